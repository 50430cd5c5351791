//! Reads accessors of any component type (f32, and the normalized or plain integers that
//! `KHR_mesh_quantization` allows) into `f64`, with strides, sparse substitution and
//! bounds checks that name the accessor.

use std::path::Path;

use gltf::accessor::{DataType, Dimensions};

use crate::LoadError;
use crate::buffers::BufferData;

/// Size in bytes of one component.
fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// Reads component `t` at `bytes[0..]` as f64, applying glTF's normalization rule.
fn read_component(bytes: &[u8], t: DataType, normalized: bool) -> f64 {
    match t {
        DataType::I8 => {
            let v = f64::from(bytes[0] as i8);
            if normalized { (v / 127.0).max(-1.0) } else { v }
        }
        DataType::U8 => {
            let v = f64::from(bytes[0]);
            if normalized { v / 255.0 } else { v }
        }
        DataType::I16 => {
            let v = f64::from(i16::from_le_bytes([bytes[0], bytes[1]]));
            if normalized { (v / 32767.0).max(-1.0) } else { v }
        }
        DataType::U16 => {
            let v = f64::from(u16::from_le_bytes([bytes[0], bytes[1]]));
            if normalized { v / 65535.0 } else { v }
        }
        DataType::U32 => {
            let v = f64::from(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]));
            if normalized { v / f64::from(u32::MAX) } else { v }
        }
        DataType::F32 => f64::from(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
    }
}

/// (columns, rows) of an element.
fn shape(d: Dimensions) -> (usize, usize) {
    match d {
        Dimensions::Scalar => (1, 1),
        Dimensions::Vec2 => (1, 2),
        Dimensions::Vec3 => (1, 3),
        Dimensions::Vec4 => (1, 4),
        Dimensions::Mat2 => (2, 2),
        Dimensions::Mat3 => (3, 3),
        Dimensions::Mat4 => (4, 4),
    }
}

/// An accessor read into a flat list of `count * components` values.
pub(crate) struct AccessorValues {
    pub components: usize,
    pub values: Vec<f64>,
}

impl AccessorValues {
    pub fn len(&self) -> usize {
        self.values.len() / self.components.max(1)
    }
    pub fn get(&self, i: usize) -> &[f64] {
        &self.values[i * self.components..(i + 1) * self.components]
    }
}

/// Reads `accessor` into f64 values (matrices column-major), checking every offset and
/// size before the values are allocated.
pub(crate) fn read_accessor(
    path: &Path,
    data: &BufferData,
    accessor: &gltf::Accessor,
) -> Result<AccessorValues, LoadError> {
    let field = format!("accessors[{}]", accessor.index());
    let t = accessor.data_type();
    let normalized = accessor.normalized();
    let (cols, rows) = shape(accessor.dimensions());
    let csize = component_size(t);
    // Matrix columns start on 4-byte boundaries.
    let col_stride = if cols > 1 { (rows * csize).next_multiple_of(4) } else { rows * csize };
    let elem_size = col_stride * (cols - 1) + rows * csize;
    let components = cols * rows;
    let count = accessor.count();
    let decode = |bytes: &[u8], out: &mut [f64]| {
        for c in 0..cols {
            for r in 0..rows {
                out[c * rows + r] = read_component(&bytes[c * col_stride + r * csize..], t, normalized);
            }
        }
    };
    let view = match accessor.view() {
        Some(view) => Some((data.view(&view)?, view.index())),
        None => None,
    };
    let out_of_range =
        |reason: String| LoadError::OutOfRange { path: path.to_owned(), field: field.clone(), reason };
    // Every check before the allocation below.
    let placement = match &view {
        Some((vb, view_index)) => {
            let stride = vb.stride.unwrap_or(elem_size);
            let offset = accessor.offset();
            if stride < elem_size {
                return Err(LoadError::BadAccessor {
                    path: path.to_owned(),
                    field,
                    reason: format!(
                        "byteStride {stride} of bufferViews[{view_index}] is smaller than an element ({elem_size} bytes)"
                    ),
                });
            }
            if count > 0 {
                let needed = (count - 1)
                    .checked_mul(stride)
                    .and_then(|n| n.checked_add(offset))
                    .and_then(|n| n.checked_add(elem_size));
                if needed.is_none_or(|n| n > vb.bytes.len()) {
                    return Err(out_of_range(format!(
                        "count {count} elements of {elem_size} bytes (stride {stride}) from byteOffset {offset} need {} bytes but bufferViews[{view_index}] has {}",
                        needed.map_or_else(|| "more than 2^64".to_owned(), |n| n.to_string()),
                        vb.bytes.len()
                    )));
                }
            }
            Some((vb.bytes, stride, offset))
        }
        None => {
            // Without a buffer view the values are zeros (plus sparse substitutions): the
            // count alone sets the size, so it is bounded by what the file holds.
            let limit = data.total_buffer_bytes();
            if count.checked_mul(elem_size).is_none_or(|n| n > limit) {
                return Err(out_of_range(format!(
                    "count {count} elements of {elem_size} bytes without a bufferView exceed the {limit} bytes of the file's buffers"
                )));
            }
            None
        }
    };
    let total =
        count.checked_mul(components).ok_or_else(|| out_of_range(format!("count {count} overflows")))?;
    let mut values = vec![0.0; total];
    if let Some((bytes, stride, offset)) = placement {
        for i in 0..count {
            let at = offset + i * stride;
            decode(&bytes[at..at + elem_size], &mut values[i * components..(i + 1) * components]);
        }
    }
    if let Some(sparse) = accessor.sparse() {
        apply_sparse(path, data, &field, &sparse, count, elem_size, &decode, components, &mut values)?;
    }
    Ok(AccessorValues { components, values })
}

#[allow(clippy::too_many_arguments)]
fn apply_sparse(
    path: &Path,
    data: &BufferData,
    field: &str,
    sparse: &gltf::accessor::sparse::Sparse,
    count: usize,
    elem_size: usize,
    decode: &dyn Fn(&[u8], &mut [f64]),
    components: usize,
    values: &mut [f64],
) -> Result<(), LoadError> {
    let n = sparse.count();
    let out_of_range = |what: &str| LoadError::OutOfRange {
        path: path.to_owned(),
        field: format!("{field}.sparse.{what}"),
        reason: format!("{n} entries do not fit in their buffer view"),
    };
    let idx = sparse.indices();
    let ivb = data.view(&idx.view())?;
    let isize = match idx.index_type() {
        gltf::accessor::sparse::IndexType::U8 => 1,
        gltf::accessor::sparse::IndexType::U16 => 2,
        gltf::accessor::sparse::IndexType::U32 => 4,
    };
    let ioff = idx.offset();
    if n.checked_mul(isize).and_then(|b| b.checked_add(ioff)).is_none_or(|end| end > ivb.bytes.len()) {
        return Err(out_of_range("indices"));
    }
    let vals = sparse.values();
    let vvb = data.view(&vals.view())?;
    let voff = vals.offset();
    if n.checked_mul(elem_size).and_then(|b| b.checked_add(voff)).is_none_or(|end| end > vvb.bytes.len()) {
        return Err(out_of_range("values"));
    }
    for k in 0..n {
        let b = &ivb.bytes[ioff + k * isize..];
        let target = match isize {
            1 => usize::from(b[0]),
            2 => usize::from(u16::from_le_bytes([b[0], b[1]])),
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
        };
        if target >= count {
            return Err(LoadError::OutOfRange {
                path: path.to_owned(),
                field: format!("{field}.sparse.indices[{k}]"),
                reason: format!("index {target} is not below the accessor's count {count}"),
            });
        }
        let at = voff + k * elem_size;
        decode(&vvb.bytes[at..at + elem_size], &mut values[target * components..(target + 1) * components]);
    }
    Ok(())
}

/// Reads an index accessor (unsigned integer scalars) as u32, checking each is below `vertex_count`.
pub(crate) fn read_indices(
    path: &Path,
    data: &BufferData,
    accessor: &gltf::Accessor,
    vertex_count: usize,
) -> Result<Vec<u32>, LoadError> {
    let field = format!("accessors[{}]", accessor.index());
    if accessor.dimensions() != Dimensions::Scalar
        || !matches!(accessor.data_type(), DataType::U8 | DataType::U16 | DataType::U32)
        || accessor.normalized()
    {
        return Err(LoadError::BadAccessor {
            path: path.to_owned(),
            field,
            reason: "indices must be unsigned integer scalars".into(),
        });
    }
    let values = read_accessor(path, data, accessor)?;
    values
        .values
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            if (v as usize) < vertex_count {
                Ok(v as u32)
            } else {
                Err(LoadError::OutOfRange {
                    path: path.to_owned(),
                    field: field.clone(),
                    reason: format!("index [{i}] = {v} is not below the vertex count {vertex_count}"),
                })
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalizes_integers_as_gltf_says() {
        assert_eq!(read_component(&[127], DataType::I8, true), 1.0);
        assert_eq!(read_component(&[0x80], DataType::I8, true), -1.0);
        assert_eq!(read_component(&[255], DataType::U8, true), 1.0);
        assert_eq!(read_component(&[0xFF, 0x7F], DataType::I16, true), 1.0);
        assert_eq!(read_component(&[0x00, 0x80], DataType::I16, true), -1.0);
        assert_eq!(read_component(&[0xFF, 0xFF], DataType::U16, true), 1.0);
        assert_eq!(read_component(&[0xFF, 0xFF], DataType::U16, false), 65535.0);
        assert_eq!(read_component(&[0xFE], DataType::I8, false), -2.0);
        assert_eq!(read_component(&1.5f32.to_le_bytes(), DataType::F32, false), 1.5);
    }
}
