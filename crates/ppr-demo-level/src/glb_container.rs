//! Packing a glTF JSON document and its binary buffer into one `.glb` file (glTF 2.0 binary container).

/// The GLB file: 12-byte header, a JSON chunk padded with spaces and a BIN chunk padded
/// with zeros (both to 4 bytes), all little-endian.
pub fn pack_glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    const MAGIC: &[u8; 4] = b"glTF";
    const CHUNK_JSON: &[u8; 4] = b"JSON";
    const CHUNK_BIN: &[u8; 4] = b"BIN\0";

    let json_padded = json.len().next_multiple_of(4);
    let bin_padded = bin.len().next_multiple_of(4);
    let total = 12 + 8 + json_padded + 8 + bin_padded;

    let mut glb = Vec::with_capacity(total);
    glb.extend_from_slice(MAGIC);
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&byte_length(total).to_le_bytes());

    glb.extend_from_slice(&byte_length(json_padded).to_le_bytes());
    glb.extend_from_slice(CHUNK_JSON);
    glb.extend_from_slice(json);
    glb.resize(glb.len() + json_padded - json.len(), b' ');

    glb.extend_from_slice(&byte_length(bin_padded).to_le_bytes());
    glb.extend_from_slice(CHUNK_BIN);
    glb.extend_from_slice(bin);
    glb.resize(glb.len() + bin_padded - bin.len(), 0);
    glb
}

fn byte_length(length: usize) -> u32 {
    u32::try_from(length).expect("the demo level is far below 4 GiB")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_are_padded_to_four_bytes() {
        let glb = pack_glb(b"{}", &[1, 2, 3, 4, 5]);
        assert_eq!(glb.len(), 12 + 8 + 4 + 8 + 8);
        assert_eq!(&glb[20..24], b"{}  ");
        assert_eq!(&glb[32..40], &[1, 2, 3, 4, 5, 0, 0, 0]);
        assert_eq!(u32::from_le_bytes([glb[8], glb[9], glb[10], glb[11]]) as usize, glb.len());
    }
}
