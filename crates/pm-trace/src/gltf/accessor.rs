//! Checked accessor reading: every accessor, buffer view and sparse block is bounds-checked
//! against the resolved buffers before a byte is read, so a lying count or offset is an error
//! naming the accessor, never a panic or an unbounded allocation.

use std::path::Path;

use glam::Vec3;
use gltf::json;
use json::accessor::{ComponentType, GenericComponentType, IndexComponentType, Type};
use json::validation::Checked;

use super::buffers::Buffer;
use super::error::GltfError;

/// Reads accessors of one document against its resolved buffers.
pub(super) struct AccessorReader<'a> {
    file: &'a Path,
    root: &'a json::Root,
    buffers: &'a [Buffer],
    /// Total bytes of all buffers: no accessor may describe more data than the file holds.
    total_bytes: u64,
}

impl<'a> AccessorReader<'a> {
    pub(super) fn new(file: &'a Path, root: &'a json::Root, buffers: &'a [Buffer]) -> Self {
        let total_bytes = buffers.iter().map(|b| b.as_slice().len() as u64).sum();
        Self {
            file,
            root,
            buffers,
            total_bytes,
        }
    }

    fn error(&self, accessor: usize, reason: impl Into<String>) -> GltfError {
        GltfError::Accessor {
            file: self.file.to_path_buf(),
            accessor,
            reason: reason.into(),
        }
    }

    /// Reads a `VEC3` accessor of floats (or, as `KHR_mesh_quantization` allows, of
    /// normalized or plain integers) as `Vec3`s.
    pub(super) fn read_vec3(&self, index: usize) -> Result<Vec<Vec3>, GltfError> {
        let accessor = self.get(index)?;
        let (ty, component) = self.types(index, accessor)?;
        if ty != Type::Vec3 {
            return Err(self.error(index, format!("type {ty:?}, expected VEC3")));
        }
        if component == ComponentType::U32 {
            return Err(self.error(index, "component type UNSIGNED_INT is not allowed here"));
        }
        let normalized = accessor.normalized;
        let size = component.size();
        self.read(index, accessor, component.size() * 3, Vec3::ZERO, |b| {
            Vec3::new(
                scalar_to_f32(component, normalized, &b[..size]),
                scalar_to_f32(component, normalized, &b[size..2 * size]),
                scalar_to_f32(component, normalized, &b[2 * size..]),
            )
        })
    }

    /// Reads a `VEC2`, `VEC3` or `VEC4` accessor (as `allowed` says) of floats or normalized
    /// integers as `Vec4`s, missing components zero (texture coordinates, colours).
    pub(super) fn read_vec(&self, index: usize, allowed: &[Type]) -> Result<Vec<glam::Vec4>, GltfError> {
        let accessor = self.get(index)?;
        let (ty, component) = self.types(index, accessor)?;
        let n = match ty {
            Type::Vec2 => 2,
            Type::Vec3 => 3,
            Type::Vec4 => 4,
            _ => 0,
        };
        if n == 0 || !allowed.contains(&ty) {
            return Err(self.error(index, format!("type {ty:?}, expected one of {allowed:?}")));
        }
        if component == ComponentType::U32 {
            return Err(self.error(index, "component type UNSIGNED_INT is not allowed here"));
        }
        let normalized = accessor.normalized;
        let size = component.size();
        self.read(index, accessor, size * n, glam::Vec4::ZERO, |b| {
            let mut v = [0.0f32; 4];
            for (i, c) in v.iter_mut().enumerate().take(n) {
                *c = scalar_to_f32(component, normalized, &b[i * size..(i + 1) * size]);
            }
            glam::Vec4::from(v)
        })
    }

    /// Reads a `COLOR_n` accessor as linear RGB (alpha dropped): `VEC3` or `VEC4` of floats, or
    /// of unsigned bytes or shorts marked normalized, as the glTF specification allows (a
    /// plain integer colour would read 255 or 65,535 times too bright: refused). A NaN or
    /// infinite component is refused naming the accessor and vertex; finite components are
    /// clamped to [0, 1], the range of a colour that multiplies an albedo.
    pub(super) fn read_colors(&self, index: usize) -> Result<Vec<Vec3>, GltfError> {
        let accessor = self.get(index)?;
        let (_, component) = self.types(index, accessor)?;
        let integer = matches!(component, ComponentType::U8 | ComponentType::U16);
        if !(component == ComponentType::F32 || integer && accessor.normalized) {
            return Err(self.error(
                index,
                format!(
                    "COLOR_n of component type {component:?}{}: the specification allows floats or normalized unsigned bytes or shorts",
                    if integer { " not marked normalized" } else { "" }
                ),
            ));
        }
        let colours = self.read_vec(index, &[Type::Vec3, Type::Vec4])?;
        if let Some(vertex) = colours.iter().position(|c| !c.is_finite()) {
            return Err(self.error(
                index,
                format!("colour of vertex {vertex} is {} (not finite)", colours[vertex]),
            ));
        }
        Ok(colours
            .iter()
            .map(|c| c.truncate().clamp(Vec3::ZERO, Vec3::ONE))
            .collect())
    }

    /// Reads a `SCALAR` accessor of unsigned bytes, shorts or ints as vertex indices.
    pub(super) fn read_indices(&self, index: usize) -> Result<Vec<u32>, GltfError> {
        let accessor = self.get(index)?;
        let (ty, component) = self.types(index, accessor)?;
        if ty != Type::Scalar {
            return Err(self.error(index, format!("type {ty:?}, expected SCALAR indices")));
        }
        if !matches!(
            component,
            ComponentType::U8 | ComponentType::U16 | ComponentType::U32
        ) {
            return Err(self.error(
                index,
                format!("component type {component:?}, expected an unsigned integer"),
            ));
        }
        self.read(index, accessor, component.size(), 0, |b| {
            unsigned_at(component, b)
        })
    }

    fn get(&self, index: usize) -> Result<&'a json::Accessor, GltfError> {
        self.root.accessors.get(index).ok_or_else(|| {
            self.error(
                index,
                format!("does not exist (the file has {})", self.root.accessors.len()),
            )
        })
    }

    fn types(&self, index: usize, accessor: &json::Accessor) -> Result<(Type, ComponentType), GltfError> {
        match (&accessor.type_, &accessor.component_type) {
            (Checked::Valid(ty), Checked::Valid(GenericComponentType(component))) => Ok((*ty, *component)),
            _ => Err(self.error(index, "invalid type or component type")),
        }
    }

    /// Reads `count` elements of `element_size` bytes: the base view (zeros without one),
    /// then the sparse substitutions.
    fn read<T: Copy>(
        &self,
        index: usize,
        accessor: &json::Accessor,
        element_size: usize,
        zero: T,
        decode: impl Fn(&[u8]) -> T,
    ) -> Result<Vec<T>, GltfError> {
        let count = accessor.count.0;
        let needed = count.saturating_mul(element_size as u64);
        if needed > self.total_bytes {
            return Err(self.error(
                index,
                format!(
                    "count {count} needs {needed} bytes, more than the file's buffers hold ({})",
                    self.total_bytes
                ),
            ));
        }
        let count = count as usize; // <= total_bytes, which fits in memory
        let mut out = Vec::with_capacity(count);
        match accessor.buffer_view {
            Some(view) => {
                let offset = accessor.byte_offset.map_or(0, |o| o.0);
                let (data, stride) = self.view_slice(index, view.value(), offset, count, element_size)?;
                out.extend((0..count).map(|i| decode(&data[i * stride..][..element_size])));
            }
            None => out.resize(count, zero),
        }
        if let Some(sparse) = &accessor.sparse {
            self.apply_sparse(index, sparse, &mut out, element_size, &decode)?;
        }
        Ok(out)
    }

    fn apply_sparse<T>(
        &self,
        index: usize,
        sparse: &json::accessor::sparse::Sparse,
        out: &mut [T],
        element_size: usize,
        decode: &impl Fn(&[u8]) -> T,
    ) -> Result<(), GltfError> {
        let count = sparse.count.0;
        if count > out.len() as u64 {
            return Err(self.error(
                index,
                format!("sparse count {count} exceeds the accessor count {}", out.len()),
            ));
        }
        let count = count as usize;
        let Checked::Valid(IndexComponentType(index_type)) = sparse.indices.component_type else {
            return Err(self.error(index, "sparse indices have an invalid component type"));
        };
        if !matches!(
            index_type,
            ComponentType::U8 | ComponentType::U16 | ComponentType::U32
        ) {
            return Err(self.error(index, "sparse indices are not unsigned integers"));
        }
        let index_size = index_type.size();
        let (indices, index_stride) = self.view_slice(
            index,
            sparse.indices.buffer_view.value(),
            sparse.indices.byte_offset.0,
            count,
            index_size,
        )?;
        let (values, value_stride) = self.view_slice(
            index,
            sparse.values.buffer_view.value(),
            sparse.values.byte_offset.0,
            count,
            element_size,
        )?;
        for k in 0..count {
            let target = unsigned_at(index_type, &indices[k * index_stride..]) as usize;
            let len = out.len();
            let slot = out.get_mut(target).ok_or_else(|| {
                self.error(
                    index,
                    format!("sparse index {target} out of range for {len} elements"),
                )
            })?;
            *slot = decode(&values[k * value_stride..][..element_size]);
        }
        Ok(())
    }

    /// The bytes of buffer view `view` from `offset` on, checked to hold `count` elements
    /// of `element_size` bytes at the view's stride; returns the slice and the stride.
    fn view_slice(
        &self,
        index: usize,
        view: usize,
        offset: u64,
        count: usize,
        element_size: usize,
    ) -> Result<(&'a [u8], usize), GltfError> {
        let v = self
            .root
            .buffer_views
            .get(view)
            .ok_or_else(|| self.error(index, format!("buffer view {view} does not exist")))?;
        let buffer = self
            .buffers
            .get(v.buffer.value())
            .map(Buffer::as_slice)
            .ok_or_else(|| {
                self.error(
                    index,
                    format!("buffer view {view}: buffer {} does not exist", v.buffer.value()),
                )
            })?;
        let start = v.byte_offset.map_or(0, |o| o.0);
        let length = v.byte_length.0;
        let end = start.checked_add(length).filter(|&e| e <= buffer.len() as u64);
        let Some(end) = end else {
            return Err(self.error(
                index,
                format!(
                    "buffer view {view} (offset {start}, length {length}) overruns buffer {} of {} bytes",
                    v.buffer.value(),
                    buffer.len()
                ),
            ));
        };
        let view_bytes = &buffer[start as usize..end as usize];
        let stride = v.byte_stride.map_or(element_size, |s| s.0);
        if stride < element_size {
            return Err(self.error(
                index,
                format!(
                    "buffer view {view}: stride {stride} is smaller than the element size {element_size}"
                ),
            ));
        }
        let span = if count == 0 {
            Some(0)
        } else {
            (stride as u64)
                .checked_mul(count as u64 - 1)
                .and_then(|s| s.checked_add(element_size as u64))
        };
        match span.and_then(|s| s.checked_add(offset)) {
            Some(needed) if needed <= length => Ok((&view_bytes[offset.min(length) as usize..], stride)),
            _ => Err(self.error(
                index,
                format!(
                    "{count} elements of {element_size} bytes at offset {offset}, stride {stride} overrun buffer view {view} of {length} bytes"
                ),
            )),
        }
    }
}

fn unsigned_at(component: ComponentType, b: &[u8]) -> u32 {
    match component {
        ComponentType::U8 => u32::from(b[0]),
        ComponentType::U16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
        _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    }
}

/// One component as f32, following the glTF rules for normalized integers.
fn scalar_to_f32(component: ComponentType, normalized: bool, b: &[u8]) -> f32 {
    match (component, normalized) {
        (ComponentType::F32, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        (ComponentType::I8, false) => f32::from(b[0] as i8),
        (ComponentType::I8, true) => (f32::from(b[0] as i8) / 127.0).max(-1.0),
        (ComponentType::U8, false) => f32::from(b[0]),
        (ComponentType::U8, true) => f32::from(b[0]) / 255.0,
        (ComponentType::I16, false) => f32::from(i16::from_le_bytes([b[0], b[1]])),
        (ComponentType::I16, true) => (f32::from(i16::from_le_bytes([b[0], b[1]])) / 32767.0).max(-1.0),
        (ComponentType::U16, false) => f32::from(u16::from_le_bytes([b[0], b[1]])),
        (ComponentType::U16, true) => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
        (ComponentType::U32, _) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}
