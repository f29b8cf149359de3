//! Why a cache file cannot be written, read or used: each error names the section, the byte
//! offset and the field at fault, or the identity entry that differs.

use thiserror::Error;

/// What is wrong with a cache file, and where. Offsets count bytes from the file's start.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CacheFileError {
    /// Reading or writing failed.
    #[error("{path}: {message}")]
    Io {
        /// The file (or "the reader" / "the writer").
        path: String,
        /// What failed.
        message: String,
    },
    /// The first 8 bytes are not the cache file's magic number.
    #[error(
        "not a photon cache file: its first bytes are {found:02x?}, not the magic number {expected:02x?}"
    )]
    NotACacheFile {
        /// The bytes found.
        found: Vec<u8>,
        /// The magic number.
        expected: [u8; 8],
    },
    /// A format version this build does not read.
    #[error(
        "cache file format version {found}: this build reads version {supported} only (re-save the cache)"
    )]
    UnsupportedVersion {
        /// The file's version.
        found: u32,
        /// The version read.
        supported: u32,
    },
    /// The file ends before a field, or a count or length asks for more bytes than remain
    /// (checked before anything is allocated for it).
    #[error(
        "{section} at byte {offset}: {field} needs {needed} bytes but only {remaining} remain (truncated or corrupt file)"
    )]
    Truncated {
        /// The section read.
        section: &'static str,
        /// Where the field starts.
        offset: u64,
        /// The field.
        field: &'static str,
        /// Bytes it needs (saturated at `u64::MAX`).
        needed: u64,
        /// Bytes left in the file.
        remaining: u64,
    },
    /// A count or length beyond what any cache file may hold.
    #[error("{section} at byte {offset}: {field} is {value}, more than the limit of {limit}")]
    TooLarge {
        /// The section read.
        section: &'static str,
        /// Where the field starts.
        offset: u64,
        /// The field.
        field: &'static str,
        /// Its value.
        value: u64,
        /// The limit.
        limit: u64,
    },
    /// The payload's checksum does not match the one stored.
    #[error(
        "payload checksum {computed:016x} differs from the {stored:016x} stored in the header (corrupt file)"
    )]
    ChecksumMismatch {
        /// Stored in the header.
        stored: u64,
        /// Computed from the payload.
        computed: u64,
    },
    /// Bytes after the payload's end.
    #[error("bytes after the payload's end at byte {offset} (corrupt file)")]
    TrailingBytes {
        /// Where the payload ends.
        offset: u64,
    },
    /// A field whose value is impossible (a tree that breaks its invariants, a flag that is
    /// neither 0 nor 1, a text that is not UTF-8).
    #[error("{section} at byte {offset}: {field}: {what}")]
    Invalid {
        /// The section read.
        section: &'static str,
        /// Where the field starts.
        offset: u64,
        /// The field.
        field: &'static str,
        /// What is wrong.
        what: String,
    },
    /// The cache was made for another scene or other settings: the first identity entry that
    /// differs.
    #[error(
        "the cache file was made with {key}={file}, this run has {key}={run}: refused (it would render another image)"
    )]
    IdentityMismatch {
        /// The entry (`photons`, `seed`, `k`, `geometry`, `lights`, …).
        key: String,
        /// The file's value (`(none)` when the file has no such entry).
        file: String,
        /// This run's value (`(none)` when the run has no such entry).
        run: String,
    },
}
