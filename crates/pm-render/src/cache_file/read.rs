//! Reading a cache file's payload, field by field, from bytes already in memory: every count
//! is checked against the bytes that remain before anything is allocated for it, so a file
//! of N bytes allocates O(N) however its counts lie, and every error names where it is.

use super::error::CacheFileError;
use super::identity::CacheIdentity;
use glam::Vec3;
use pm_kdtree::{OwnedTreeArrays, PhotonTree};

/// Most identity entries, and most bytes of one key or value.
pub(crate) const MAX_ENTRIES: u32 = 256;
pub(crate) const MAX_TEXT: u32 = 4096;

/// The payload being read: its bytes, the place reached, where it starts in the file and the
/// section being read (for messages).
pub(crate) struct Fields<'a> {
    bytes: &'a [u8],
    pos: usize,
    base: u64,
    pub(crate) section: &'static str,
}

impl<'a> Fields<'a> {
    /// The payload `bytes`, which start at byte `base` of the file.
    pub(crate) fn new(bytes: &'a [u8], base: u64) -> Self {
        Fields {
            bytes,
            pos: 0,
            base,
            section: "identity",
        }
    }

    /// Where the next field starts in the file.
    pub(crate) fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// The next `count × size` bytes, refused before anything is read when fewer remain.
    fn take(&mut self, field: &'static str, count: u64, size: u64) -> Result<&'a [u8], CacheFileError> {
        self.check_room(field, count, size)?;
        let needed = count * size;
        let bytes = &self.bytes[self.pos..self.pos + needed as usize];
        self.pos += needed as usize;
        Ok(bytes)
    }

    fn array<const N: usize>(&mut self, field: &'static str) -> Result<[u8; N], CacheFileError> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(field, 1, N as u64)?);
        Ok(a)
    }

    pub(crate) fn u8(&mut self, field: &'static str) -> Result<u8, CacheFileError> {
        Ok(self.array::<1>(field)?[0])
    }

    pub(crate) fn u32(&mut self, field: &'static str) -> Result<u32, CacheFileError> {
        self.array(field).map(u32::from_le_bytes)
    }

    pub(crate) fn u64(&mut self, field: &'static str) -> Result<u64, CacheFileError> {
        self.array(field).map(u64::from_le_bytes)
    }

    pub(crate) fn f32(&mut self, field: &'static str) -> Result<f32, CacheFileError> {
        self.array(field).map(f32::from_le_bytes)
    }

    pub(crate) fn f64(&mut self, field: &'static str) -> Result<f64, CacheFileError> {
        self.array(field).map(f64::from_le_bytes)
    }

    /// `count` f32s (`count` checked against the bytes left first).
    fn f32s(&mut self, field: &'static str, count: u64) -> Result<Vec<f32>, CacheFileError> {
        let bytes = self.take(field, count, 4)?;
        Ok(bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }

    /// `count` vectors of three f32s.
    pub(crate) fn vec3s(&mut self, field: &'static str, count: u64) -> Result<Vec<Vec3>, CacheFileError> {
        let xs = self.f32s(field, count.saturating_mul(3))?;
        Ok(xs.chunks_exact(3).map(Vec3::from_slice).collect())
    }

    /// A length-prefixed UTF-8 text of at most [`MAX_TEXT`] bytes.
    fn text(&mut self, field: &'static str) -> Result<String, CacheFileError> {
        let offset = self.offset();
        let len = self.u32(field)?;
        if len > MAX_TEXT {
            return Err(self.too_large(offset, field, u64::from(len), u64::from(MAX_TEXT)));
        }
        let bytes = self.take(field, u64::from(len), 1)?;
        String::from_utf8(bytes.to_vec()).map_err(|e| self.invalid(offset, field, e.to_string()))
    }

    pub(crate) fn too_large(
        &self,
        offset: u64,
        field: &'static str,
        value: u64,
        limit: u64,
    ) -> CacheFileError {
        CacheFileError::TooLarge {
            section: self.section,
            offset,
            field,
            value,
            limit,
        }
    }

    pub(crate) fn invalid(&self, offset: u64, field: &'static str, what: String) -> CacheFileError {
        CacheFileError::Invalid {
            section: self.section,
            offset,
            field,
            what,
        }
    }

    /// The identity's entries.
    pub(crate) fn identity(&mut self) -> Result<CacheIdentity, CacheFileError> {
        self.section = "identity";
        let offset = self.offset();
        let count = self.u32("entry count")?;
        if count > MAX_ENTRIES {
            return Err(self.too_large(offset, "entry count", u64::from(count), u64::from(MAX_ENTRIES)));
        }
        // Each entry takes at least its two lengths: checked before the list is made.
        self.check_room("entries", u64::from(count), 8)?;
        let mut entries = Vec::with_capacity(count as usize);
        for _ in 0..count {
            let key = self.text("key")?;
            let value = self.text("value")?;
            entries.push((key, value));
        }
        Ok(CacheIdentity::from_entries(entries))
    }

    /// Refuses `count` items of at least `size` bytes each when fewer bytes remain.
    pub(crate) fn check_room(
        &self,
        field: &'static str,
        count: u64,
        size: u64,
    ) -> Result<(), CacheFileError> {
        let needed = count.saturating_mul(size);
        if needed > self.remaining() as u64 {
            return Err(CacheFileError::Truncated {
                section: self.section,
                offset: self.offset(),
                field,
                needed,
                remaining: self.remaining() as u64,
            });
        }
        Ok(())
    }

    /// A photon tree as `write.rs` puts it, its invariants checked ([`PhotonTree::from_arrays`]).
    pub(crate) fn tree(&mut self) -> Result<PhotonTree, CacheFileError> {
        let start = self.offset();
        let offset = self.offset();
        let n = self.u64("photon count")?;
        // 20 bytes a photon, checked before the count is used for anything else.
        self.check_room("photons", n, 20)?;
        let n_usize =
            usize::try_from(n).map_err(|_| self.too_large(offset, "photon count", n, usize::MAX as u64))?;
        let scale_watts = self.f32("power scale")?;
        let below_range = self.u64("channels below range")?;
        let xs = self.f32s("x coordinates", n)?;
        let ys = self.f32s("y coordinates", n)?;
        let zs = self.f32s("z coordinates", n)?;
        let payload_bytes = self.take("photon payloads", n, 8)?;
        let payload = payload_bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
            .collect();
        let slots = PhotonTree::inner_slots(n_usize) as u64;
        let splits = self.f32s("split values", slots)?;
        let axes = self.take("split axes", slots, 1)?.to_vec();
        let arrays = OwnedTreeArrays {
            xs,
            ys,
            zs,
            payload,
            splits,
            axes,
            scale_watts,
            below_range,
        };
        PhotonTree::from_arrays(arrays).map_err(|e| self.invalid(start, "photon tree", e.to_string()))
    }
}
