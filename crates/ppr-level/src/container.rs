//! The two glTF containers: a `.glb` (header, JSON chunk, optional BIN chunk) or plain JSON.

use std::path::Path;

use super::LoadError;

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// The JSON text of a glTF file and, for a `.glb`, its BIN chunk.
pub(crate) struct Container<'a> {
    pub json: &'a [u8],
    pub bin: Option<&'a [u8]>,
}

/// Splits `bytes` into JSON and BIN: a `.glb` when it starts with the `glTF` magic, else JSON.
pub(crate) fn split_container<'a>(path: &Path, bytes: &'a [u8]) -> Result<Container<'a>, LoadError> {
    if bytes.starts_with(GLB_MAGIC) {
        return split_glb(path, bytes);
    }
    let first =
        bytes.iter().copied().find(|b| !b.is_ascii_whitespace() && *b != 0xEF && *b != 0xBB && *b != 0xBF);
    if first != Some(b'{') {
        let reason = if bytes.is_empty() {
            "the file is empty".to_owned()
        } else {
            "it neither starts with the .glb magic `glTF` nor is a JSON object".to_owned()
        };
        return Err(LoadError::NotGltf { path: path.to_owned(), reason });
    }
    Ok(Container { json: bytes, bin: None })
}

fn split_glb<'a>(path: &Path, bytes: &'a [u8]) -> Result<Container<'a>, LoadError> {
    let truncated = |reason: String| LoadError::TruncatedGlb { path: path.to_owned(), reason };
    if bytes.len() < 12 {
        return Err(truncated(format!("{} bytes, shorter than the 12-byte header", bytes.len())));
    }
    let word = |at: usize| -> Option<u32> {
        let b = bytes.get(at..at + 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    let version = word(4).unwrap_or(0);
    if version != 2 {
        return Err(LoadError::NotGltf {
            path: path.to_owned(),
            reason: format!(".glb container version {version}; only version 2 is glTF 2.0"),
        });
    }
    let declared = word(8).unwrap_or(0) as usize;
    if declared > bytes.len() {
        return Err(truncated(format!(
            "the header declares {declared} bytes but the file has {}",
            bytes.len()
        )));
    }
    let body = &bytes[..declared];
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    while at < body.len() {
        let (Some(len), Some(kind)) = (word(at), word(at + 4)) else {
            return Err(truncated(format!("chunk header at byte {at} is cut off")));
        };
        if at + 8 > body.len() {
            return Err(truncated(format!("chunk header at byte {at} is cut off")));
        }
        let start = at + 8;
        let end = start.checked_add(len as usize).filter(|&e| e <= body.len()).ok_or_else(|| {
            truncated(format!(
                "chunk at byte {at} declares {len} bytes but only {} remain",
                body.len().saturating_sub(start)
            ))
        })?;
        match kind {
            CHUNK_JSON if json.is_none() => json = Some(&body[start..end]),
            CHUNK_BIN if bin.is_none() => bin = Some(&body[start..end]),
            _ => {} // unknown chunks are skipped, as the specification asks
        }
        at = end;
    }
    let json = json.ok_or_else(|| truncated("no JSON chunk".to_owned()))?;
    Ok(Container { json, bin })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
        let mut out = b"glTF".to_vec();
        out.extend(2u32.to_le_bytes());
        out.extend(0u32.to_le_bytes());
        out.extend((json.len() as u32).to_le_bytes());
        out.extend(CHUNK_JSON.to_le_bytes());
        out.extend(json);
        if let Some(bin) = bin {
            out.extend((bin.len() as u32).to_le_bytes());
            out.extend(CHUNK_BIN.to_le_bytes());
            out.extend(bin);
        }
        let len = out.len() as u32;
        out[8..12].copy_from_slice(&len.to_le_bytes());
        out
    }

    #[test]
    fn splits_glb_and_json() {
        let bytes = glb(b"{}  ", Some(&[1, 2, 3, 4]));
        let c = split_container(Path::new("a.glb"), &bytes).unwrap();
        assert_eq!(c.json, b"{}  ");
        assert_eq!(c.bin, Some(&[1u8, 2, 3, 4][..]));
        let c = split_container(Path::new("a.gltf"), b" {\"asset\":{}}").unwrap();
        assert!(c.bin.is_none());
    }

    #[test]
    fn refuses_truncated_and_foreign_files() {
        let bytes = glb(b"{}  ", Some(&[1, 2, 3, 4]));
        for cut in [5, 11, 16, bytes.len() - 1] {
            let err = split_container(Path::new("t.glb"), &bytes[..cut]).err().unwrap();
            assert!(matches!(err, LoadError::TruncatedGlb { .. }), "cut at {cut}: {err}");
        }
        let err = split_container(Path::new("x.png"), b"\x89PNG\r\n").err().unwrap();
        assert!(err.to_string().contains("not a glTF file"), "{err}");
        let err = split_container(Path::new("e.glb"), b"").err().unwrap();
        assert!(err.to_string().contains("empty"), "{err}");
    }
}
