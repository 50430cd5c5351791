//! Stable reflector ids, derived deterministically from content so that re-extraction
//! with other parameters gives the same id to the same surface (the inspector keeps manual
//! edits by id).
//!
//! The id hashes (blake3) the kind, the plane quantised to 1/1000 of the normal and to
//! [`PLANE_OFFSET_UNIT_M`], the rectangle's centre quantised to [`CENTER_UNIT_M`], and the
//! primary source node and material names. The units are physical, so a surface keeps its
//! id when the level around it grows. Collisions are resolved deterministically
//! (the next free id, in the order of the shapes' content keys).

use std::collections::BTreeSet;

use glam::DVec3;
use ppr_format::ReflectorKind;

/// Quantisation of the plane's offset from the origin, metres.
pub const PLANE_OFFSET_UNIT_M: f64 = 0.01;
/// Quantisation of the rectangle's centre, metres.
pub const CENTER_UNIT_M: f64 = 0.1;

/// The content an id is derived from.
#[derive(Clone, Debug, PartialEq)]
pub struct IdContent<'a> {
    /// Reflector kind.
    pub kind: ReflectorKind,
    /// Unit normal.
    pub normal: DVec3,
    /// Rectangle centre, world space.
    pub center: DVec3,
    /// Primary node name.
    pub node: &'a str,
    /// Primary material name.
    pub material: &'a str,
}

/// The 31-bit content hash of one shape.
pub fn content_hash(c: &IdContent) -> u32 {
    let q = |x: f64, unit: f64| (x / unit).round() as i64;
    let mut h = blake3::Hasher::new();
    h.update(c.kind.as_str().as_bytes());
    for x in c.normal.to_array() {
        h.update(&q(x, 1e-3).to_le_bytes());
    }
    h.update(&q(c.normal.dot(c.center), PLANE_OFFSET_UNIT_M).to_le_bytes());
    for x in c.center.to_array() {
        h.update(&q(x, CENTER_UNIT_M).to_le_bytes());
    }
    for s in [c.node, c.material] {
        h.update(&(s.len() as u64).to_le_bytes());
        h.update(s.as_bytes());
    }
    let bytes = h.finalize();
    let b = bytes.as_bytes();
    u32::from_le_bytes([b[0], b[1], b[2], b[3]]) & 0x7FFF_FFFF
}

/// Unique ids for hashes: each hash, or the next free value after it, taken in the order
/// given (callers pass shapes in a deterministic order).
pub fn dedupe_ids(hashes: &[u32]) -> Vec<u32> {
    let mut used = BTreeSet::new();
    hashes
        .iter()
        .map(|&h| {
            let mut id = h;
            while !used.insert(id) {
                id = (id + 1) & 0x7FFF_FFFF;
            }
            id
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn content(center: DVec3) -> IdContent<'static> {
        IdContent { kind: ReflectorKind::Opaque, normal: DVec3::Y, center, node: "Floor", material: "Marble" }
    }

    #[test]
    fn ids_are_stable_under_small_changes_and_unique() {
        let a = content_hash(&content(DVec3::new(1.0, 0.0, 2.0)));
        assert_eq!(a, content_hash(&content(DVec3::new(1.0001, 0.0, 2.0001))));
        assert_ne!(a, content_hash(&content(DVec3::new(3.0, 0.0, 2.0))));
        assert_ne!(a, content_hash(&IdContent { material: "Glass", ..content(DVec3::new(1.0, 0.0, 2.0)) }));
        assert_eq!(dedupe_ids(&[5, 5, 6, 0x7FFF_FFFF, 0x7FFF_FFFF]), vec![5, 6, 7, 0x7FFF_FFFF, 0]);
    }
}
