//! `EXT_meshopt_compression`: decodes a compressed buffer view into plain bytes with the
//! meshoptimizer decoders (vertex, index buffer, index sequence) and filters.

use std::path::Path;

use crate::LoadError;

/// At most this many decoded bytes per compressed byte. Meshoptimizer's vertex codec (v0,
/// what `EXT_meshopt_compression` specifies) spends at least 2 header bits per 16 bytes of
/// a byte channel (64×, reached only by constant data); its index codecs at least one byte
/// per triangle (12×) or per index (4×). A larger ratio cannot be the encoder's output,
/// so the view is refused before its output is allocated.
const MAX_EXPANSION: usize = 64;

/// Decodes the buffer view `view` described by the extension object `ext`.
/// `buffer(i)` gives the bytes of buffer `i`.
pub(crate) fn decode_meshopt_view<'a>(
    path: &Path,
    view: usize,
    ext: &serde_json::Value,
    buffer: impl Fn(usize) -> Result<&'a [u8], LoadError>,
) -> Result<Vec<u8>, LoadError> {
    let fail = |reason: String| LoadError::Meshopt { path: path.to_owned(), view, reason };
    let field = |name: &str| ext.get(name).and_then(serde_json::Value::as_u64).map(|v| v as usize);
    let need = |name: &str| field(name).ok_or_else(|| fail(format!("missing or invalid `{name}`")));
    let source_buffer = need("buffer")?;
    let offset = field("byteOffset").unwrap_or(0);
    let length = need("byteLength")?;
    let stride = need("byteStride")?;
    let count = need("count")?;
    let mode = ext.get("mode").and_then(serde_json::Value::as_str).unwrap_or("");
    let filter = ext.get("filter").and_then(serde_json::Value::as_str).unwrap_or("NONE");

    let data = buffer(source_buffer)?;
    let src = offset.checked_add(length).and_then(|end| data.get(offset..end)).ok_or_else(|| {
        fail(format!(
            "byteOffset {offset} + byteLength {length} exceeds buffers[{source_buffer}] ({} bytes)",
            data.len()
        ))
    })?;
    let size = count
        .checked_mul(stride)
        .filter(|&s| s <= 1 << 31)
        .ok_or_else(|| fail(format!("count {count} × byteStride {stride} is too large")))?;
    if size > src.len().saturating_mul(MAX_EXPANSION).saturating_add(256) {
        return Err(fail(format!(
            "count {count} × byteStride {stride} = {size} bytes cannot come from {} compressed bytes (at most {MAX_EXPANSION}× expansion)",
            src.len()
        )));
    }
    // u32 storage keeps the output 4-byte aligned, as the filters require.
    let mut words = vec![0u32; size.div_ceil(4)];
    let dst = words.as_mut_ptr().cast::<std::ffi::c_void>();
    let code = match mode {
        "ATTRIBUTES" => {
            if stride % 4 != 0 || stride > 256 || stride == 0 {
                return Err(fail(format!(
                    "ATTRIBUTES byteStride {stride} is not a multiple of 4 in 4..=256"
                )));
            }
            // SAFETY: `dst` holds `count * stride` bytes; the decoder reads `src.len()` bytes of `src`.
            unsafe { meshopt::ffi::meshopt_decodeVertexBuffer(dst, count, stride, src.as_ptr(), src.len()) }
        }
        "TRIANGLES" | "INDICES" => {
            if stride != 2 && stride != 4 {
                return Err(fail(format!("{mode} byteStride {stride} is not 2 or 4")));
            }
            if mode == "TRIANGLES" && count % 3 != 0 {
                return Err(fail(format!("TRIANGLES count {count} is not a multiple of 3")));
            }
            // SAFETY: as above; index size is 2 or 4 bytes.
            unsafe {
                if mode == "TRIANGLES" {
                    meshopt::ffi::meshopt_decodeIndexBuffer(dst, count, stride, src.as_ptr(), src.len())
                } else {
                    meshopt::ffi::meshopt_decodeIndexSequence(dst, count, stride, src.as_ptr(), src.len())
                }
            }
        }
        other => return Err(fail(format!("unknown mode `{other}`"))),
    };
    if code != 0 {
        return Err(fail(format!(
            "the {mode} decoder refused the data (code {code}); corrupted or truncated"
        )));
    }
    match (filter, mode) {
        ("NONE", _) => {}
        ("OCTAHEDRAL", "ATTRIBUTES") if stride == 4 || stride == 8 => {
            // SAFETY: `count` elements of `stride` bytes, 4-byte aligned.
            unsafe { meshopt::ffi::meshopt_decodeFilterOct(dst, count, stride) }
        }
        ("QUATERNION", "ATTRIBUTES") if stride == 8 => {
            // SAFETY: as above.
            unsafe { meshopt::ffi::meshopt_decodeFilterQuat(dst, count, stride) }
        }
        ("EXPONENTIAL", "ATTRIBUTES") => {
            // SAFETY: as above; stride is a multiple of 4.
            unsafe { meshopt::ffi::meshopt_decodeFilterExp(dst, count, stride) }
        }
        ("COLOR", "ATTRIBUTES") if stride == 4 || stride == 8 => {
            // SAFETY: as above.
            unsafe { meshopt::ffi::meshopt_decodeFilterColor(dst, count, stride) }
        }
        (f, m) => {
            return Err(fail(format!("filter `{f}` is not valid for mode {m} with byteStride {stride}")));
        }
    }
    let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_ne_bytes()).collect();
    bytes.truncate(size);
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_vertices_and_indices() {
        let vertices: Vec<[f32; 3]> = (0..100).map(|i| [i as f32, (i * 2) as f32, 0.5]).collect();
        let encoded = meshopt::encode_vertex_buffer(&vertices).unwrap();
        let ext = serde_json::json!({"buffer": 0, "byteLength": encoded.len(), "byteStride": 12, "count": 100, "mode": "ATTRIBUTES"});
        let bytes = decode_meshopt_view(Path::new("m.glb"), 0, &ext, |_| Ok(&encoded[..])).unwrap();
        assert_eq!(bytes.len(), 1200);
        assert_eq!(
            &bytes[12..24],
            [1.0f32, 2.0, 0.5].iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<_>>()
        );

        let indices: Vec<u32> = vec![0, 1, 2, 2, 1, 3, 3, 1, 4];
        let encoded = meshopt::encode_index_buffer(&indices, 5).unwrap();
        let ext = serde_json::json!({"buffer": 0, "byteLength": encoded.len(), "byteStride": 4, "count": 9, "mode": "TRIANGLES"});
        let bytes = decode_meshopt_view(Path::new("m.glb"), 1, &ext, |_| Ok(&encoded[..])).unwrap();
        let back: Vec<u32> = bytes.chunks(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        assert_eq!(back, indices);
    }

    #[test]
    fn refuses_garbage_with_the_view_named() {
        let garbage = [0u8; 7];
        let ext = serde_json::json!({"buffer": 0, "byteLength": 7, "byteStride": 12, "count": 10, "mode": "ATTRIBUTES"});
        let err = decode_meshopt_view(Path::new("m.glb"), 4, &ext, |_| Ok(&garbage[..])).unwrap_err();
        assert!(err.to_string().contains("bufferViews[4]"), "{err}");
        let ext = serde_json::json!({"buffer": 0, "byteLength": 70, "byteStride": 12, "count": 10, "mode": "ATTRIBUTES"});
        let err = decode_meshopt_view(Path::new("m.glb"), 4, &ext, |_| Ok(&garbage[..])).unwrap_err();
        assert!(err.to_string().contains("exceeds"), "{err}");
    }
}
