//! Our own buffer resolver (never `gltf::import`, which follows any path): `data:` URIs, the
//! GLB binary chunk, and relative paths confined to the scene's folder, each read no further
//! than the buffer's declared `byteLength`.

use std::collections::HashMap;
use std::fs::File;
use std::io::Read;
use std::path::{Component, Path, PathBuf};
use std::rc::Rc;

use gltf::json;

use super::error::{BufferError, GltfError};

/// The bytes of one buffer: shared with every other buffer entry naming the same file (or the
/// same GLB chunk), and seen no further than its declared `byteLength`.
#[derive(Clone, Debug)]
pub(super) struct Buffer {
    bytes: Rc<Vec<u8>>,
    len: usize,
}

impl Buffer {
    pub(super) fn as_slice(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    /// Which allocation the bytes live in (shared entries give the same).
    pub(super) fn identity(&self) -> *const u8 {
        self.bytes.as_ptr()
    }

    /// Bytes of the allocation behind this buffer.
    pub(super) fn held(&self) -> usize {
        self.bytes.len()
    }
}

/// Resolves every buffer of `root` to its bytes, trimmed to the declared `byteLength`. Each
/// distinct file is read once, the GLB chunk is shared, and the bytes held in all (files, the
/// chunk and data URIs) are at most `limit`.
pub(super) fn resolve_buffers(
    file: &Path,
    root: &json::Root,
    blob: Option<Vec<u8>>,
    limit: u64,
) -> Result<Vec<Buffer>, GltfError> {
    let folder = file
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut sources = Sources {
        folder,
        blob: blob.map(Rc::new),
        files: HashMap::new(),
        held: 0,
        limit,
    };
    let mut out = Vec::with_capacity(root.buffers.len());
    for (index, buffer) in root.buffers.iter().enumerate() {
        let declared = buffer.byte_length.0;
        let bytes = sources
            .resolve(buffer.uri.as_deref(), declared)
            .map_err(|reason| GltfError::Buffer {
                file: file.to_path_buf(),
                buffer: index,
                reason,
            })?;
        out.push(bytes);
    }
    Ok(out)
}

/// Where buffer bytes come from, each source read once, and the bytes held so far.
struct Sources<'a> {
    folder: &'a Path,
    blob: Option<Rc<Vec<u8>>>,
    /// Files already read, by canonical path.
    files: HashMap<PathBuf, Rc<Vec<u8>>>,
    held: u64,
    limit: u64,
}

impl Sources<'_> {
    fn resolve(&mut self, uri: Option<&str>, declared: u64) -> Result<Buffer, BufferError> {
        let limit = self.limit;
        if declared > limit {
            return Err(BufferError::TooLarge { declared, limit });
        }
        let bytes = match uri {
            // The chunk came with the scene file, which is bounded by the same limit.
            None => self.blob.clone().ok_or(BufferError::MissingBinChunk)?,
            Some(uri) if has_prefix_ignore_case(uri, "data:") => {
                let bytes = decode_data_uri(uri)?;
                // A base64 payload may carry up to 3 bytes of padding past byteLength.
                if bytes.len() as u64 > declared + 3 {
                    return Err(BufferError::LongerThanDeclared { declared });
                }
                self.hold(bytes.len() as u64)?;
                Rc::new(bytes)
            }
            Some(uri) => {
                let target = confined_target(self.folder, uri)?;
                match self.files.get(&target) {
                    Some(bytes) => {
                        if bytes.len() as u64 > declared {
                            return Err(BufferError::LongerThanDeclared { declared });
                        }
                        bytes.clone()
                    }
                    None => {
                        let meta = std::fs::metadata(&target).map_err(unreadable(uri))?;
                        if meta.len() <= declared {
                            self.hold(meta.len())?;
                        }
                        let bytes = Rc::new(read_regular(&target, uri, declared)?);
                        self.files.insert(target, bytes.clone());
                        bytes
                    }
                }
            }
        };
        if (bytes.len() as u64) < declared {
            return Err(BufferError::ShorterThanDeclared {
                declared,
                actual: bytes.len() as u64,
            });
        }
        Ok(Buffer {
            bytes,
            len: declared as usize,
        })
    }

    /// Counts `bytes` more held, refusing past the limit.
    fn hold(&mut self, bytes: u64) -> Result<(), BufferError> {
        self.held = self.held.saturating_add(bytes);
        if self.held > self.limit {
            return Err(BufferError::TotalTooLarge { limit: self.limit });
        }
        Ok(())
    }
}

fn unreadable(uri: &str) -> impl Fn(std::io::Error) -> BufferError + '_ {
    move |source| BufferError::Unreadable {
        uri: uri.to_owned(),
        source,
    }
}

pub(super) fn has_prefix_ignore_case(s: &str, prefix: &str) -> bool {
    s.len() >= prefix.len() && s.as_bytes()[..prefix.len()].eq_ignore_ascii_case(prefix.as_bytes())
}

/// True when `s` starts with a URI scheme (`file:`, `http:`, `c:` ...), RFC 3986 section 3.1.
fn has_scheme(s: &str) -> bool {
    let Some(colon) = s.find(':') else {
        return false;
    };
    let scheme = &s.as_bytes()[..colon];
    scheme.first().is_some_and(u8::is_ascii_alphabetic)
        && scheme
            .iter()
            .all(|&c| c.is_ascii_alphanumeric() || matches!(c, b'+' | b'-' | b'.'))
}

/// The canonical path of a relative, percent-encoded URI that must stay inside `folder` after
/// decoding and canonicalisation (symbolic links included).
pub(super) fn confined_target(folder: &Path, uri: &str) -> Result<PathBuf, BufferError> {
    let owned = || uri.to_owned();
    if has_scheme(uri) {
        return Err(BufferError::Scheme { uri: owned() });
    }
    let decoded = urlencoding::decode(uri).map_err(|_| BufferError::BadEscape { uri: owned() })?;
    if decoded.contains('\0') {
        return Err(BufferError::BadEscape { uri: owned() });
    }
    if has_scheme(&decoded) {
        return Err(BufferError::Scheme { uri: owned() });
    }
    let relative = Path::new(decoded.as_ref());
    if relative.has_root() || decoded.starts_with(['/', '\\']) {
        return Err(BufferError::Absolute { uri: owned() });
    }
    if escapes_lexically(relative) {
        return Err(BufferError::EscapesFolder { uri: owned() });
    }
    let unreadable = |source| BufferError::Unreadable { uri: owned(), source };
    let base = folder.canonicalize().map_err(unreadable)?;
    let target: PathBuf = base.join(relative).canonicalize().map_err(unreadable)?;
    if !target.starts_with(&base) {
        return Err(BufferError::EscapesFolder { uri: owned() });
    }
    Ok(target)
}

/// Reads `target`, which must be a regular file (checked before opening: a FIFO would block)
/// holding no more than `declared` bytes. At most `declared + 1` bytes are read.
pub(super) fn read_regular(target: &Path, uri: &str, declared: u64) -> Result<Vec<u8>, BufferError> {
    let owned = || uri.to_owned();
    let unreadable = unreadable(uri);
    let meta = std::fs::metadata(target).map_err(&unreadable)?;
    if !meta.is_file() {
        return Err(BufferError::NotRegularFile { uri: owned() });
    }
    if meta.len() > declared {
        return Err(BufferError::LongerThanDeclared { declared });
    }
    let file = File::open(target).map_err(&unreadable)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(declared.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(&unreadable)?;
    if bytes.len() as u64 > declared {
        return Err(BufferError::LongerThanDeclared { declared });
    }
    Ok(bytes)
}

/// True when the `..` components of a relative path climb above its start.
fn escapes_lexically(relative: &Path) -> bool {
    let mut depth = 0i64;
    for component in relative.components() {
        match component {
            Component::ParentDir => {
                depth -= 1;
                if depth < 0 {
                    return true;
                }
            }
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return true,
        }
    }
    false
}

/// Decodes `data:[<media type>][;base64],<data>`.
pub(super) fn decode_data_uri(uri: &str) -> Result<Vec<u8>, BufferError> {
    let bad = |reason: &str| BufferError::BadDataUri {
        reason: reason.to_owned(),
    };
    let (header, payload) = uri["data:".len()..]
        .split_once(',')
        .ok_or_else(|| bad("no comma before the payload"))?;
    if has_suffix_ignore_case(header, ";base64") {
        decode_base64(payload).ok_or_else(|| bad("invalid base64"))
    } else {
        Ok(urlencoding::decode_binary(payload.as_bytes()).into_owned())
    }
}

fn has_suffix_ignore_case(s: &str, suffix: &str) -> bool {
    s.len() >= suffix.len() && s.as_bytes()[s.len() - suffix.len()..].eq_ignore_ascii_case(suffix.as_bytes())
}

/// Each byte's base64 value (standard and URL-safe alphabets alike), or [`NOT_BASE64`].
const BASE64_VALUES: [u8; 256] = {
    let mut values = [NOT_BASE64; 256];
    let mut i = 0;
    while i < 26 {
        values[b'A' as usize + i] = i as u8;
        values[b'a' as usize + i] = 26 + i as u8;
        if i < 10 {
            values[b'0' as usize + i] = 52 + i as u8;
        }
        i += 1;
    }
    values[b'+' as usize] = 62;
    values[b'-' as usize] = 62;
    values[b'/' as usize] = 63;
    values[b'_' as usize] = 63;
    values
};

/// Marks a byte that is no base64 digit (any value of 64 or more would do).
const NOT_BASE64: u8 = 0xFF;

/// Standard or URL-safe base64, padding optional; `None` on any other character. Four digits
/// at a time by table (an embedded glTF buffer is megabytes of them), any invalid digit
/// noticed once at the end.
pub(super) fn decode_base64(text: &str) -> Option<Vec<u8>> {
    let text = text.trim_end_matches('=').as_bytes();
    if text.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let value = |c: u8| BASE64_VALUES[c as usize];
    let mut seen = 0u8;
    let mut chunks = text.chunks_exact(4);
    for chunk in &mut chunks {
        let [a, b, c, d] = [chunk[0], chunk[1], chunk[2], chunk[3]].map(value);
        seen |= a | b | c | d;
        let acc = (u32::from(a) << 18) | (u32::from(b) << 12) | (u32::from(c) << 6) | u32::from(d);
        out.extend_from_slice(&acc.to_be_bytes()[1..]);
    }
    let rest = chunks.remainder();
    if !rest.is_empty() {
        let mut acc = 0u32;
        for &c in rest {
            seen |= value(c);
            acc = (acc << 6) | u32::from(value(c) & 63);
        }
        acc <<= 6 * (4 - rest.len() as u32);
        out.extend_from_slice(&acc.to_be_bytes()[1..rest.len()]);
    }
    (seen < 64).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        // RFC 4648 section 10 test vectors: an independent truth.
        for (plain, encoded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(decode_base64(encoded).as_deref(), Some(plain.as_bytes()));
        }
        assert_eq!(decode_base64("Zm9v!"), None);
        assert_eq!(decode_base64("Z"), None);
    }

    /// Base64 the slow way, six bits at a time off a bit string: the independent encoder the
    /// table decoder is checked against.
    fn encode(bytes: &[u8], alphabet: &[u8; 64], pad: bool) -> String {
        let bits: Vec<u8> = bytes
            .iter()
            .flat_map(|b| (0..8).rev().map(move |i| (b >> i) & 1))
            .collect();
        let mut out: String = bits
            .chunks(6)
            .map(|six| {
                let v = (0..6).fold(0usize, |v, i| {
                    (v << 1) | usize::from(six.get(i).copied().unwrap_or(0))
                });
                alphabet[v] as char
            })
            .collect();
        while pad && !out.len().is_multiple_of(4) {
            out.push('=');
        }
        out
    }

    proptest::proptest! {
        /// Every byte string, in either alphabet, padded or not, decodes to itself; one byte
        /// that is no base64 digit, anywhere, makes it invalid.
        #[test]
        fn base64_decodes_what_it_encodes(
            bytes in proptest::collection::vec(proptest::num::u8::ANY, 0..100),
            url_safe: bool,
            pad: bool,
            bad_at in 0usize..200,
            bad in proptest::sample::select(vec![b'!', b'.', b' ', b'\n', 0x80u8, b'*']),
        ) {
            let mut alphabet = *b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
            if url_safe {
                alphabet[62] = b'-';
                alphabet[63] = b'_';
            }
            let text = encode(&bytes, &alphabet, pad);
            proptest::prop_assert_eq!(decode_base64(&text), Some(bytes.clone()));
            let digits = text.trim_end_matches('=').len();
            if digits > 0 {
                let mut broken = text.into_bytes();
                broken[bad_at % digits] = bad;
                let broken = String::from_utf8_lossy(&broken).into_owned();
                proptest::prop_assert_eq!(decode_base64(&broken), None);
            }
        }
    }

    #[test]
    fn schemes_are_recognised() {
        assert!(has_scheme("file:///etc/passwd"));
        assert!(has_scheme("http://x"));
        assert!(has_scheme("C:\\x"));
        assert!(!has_scheme("a/b:c.bin"));
        assert!(!has_scheme("../x.bin"));
        assert!(!has_scheme("1abc:x"));
    }

    #[test]
    fn lexical_escape_counts_parent_components() {
        assert!(escapes_lexically(Path::new("../x")));
        assert!(escapes_lexically(Path::new("a/../../x")));
        assert!(!escapes_lexically(Path::new("a/../x")));
        assert!(!escapes_lexically(Path::new("./a/b")));
    }
}
