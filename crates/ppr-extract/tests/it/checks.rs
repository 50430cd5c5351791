//! Shared assertions: every rectangle encloses its region's vertices and is coplanar with
//! them; the set is valid and round-trips through JSON.

use ppr_extract::Extraction;
use ppr_format::ReflectorSet;

/// Asserts the set is valid, round-trips through JSON, and every reflector encloses its
/// region vertices (within 1e-7 of the diagonal) and lies within `plane_tol_m` metres of
/// them.
pub fn assert_encloses_regions(x: &Extraction, plane_tol_m: f64, what: &str) {
    let diag = x.stats.diagonal;
    x.set.validate().unwrap_or_else(|e| panic!("{what}: invalid set: {e}"));
    let json = x.set.to_json_string().unwrap();
    let back = ReflectorSet::from_json_str(&json).unwrap();
    // serde_json parses floats to within one ulp (no `float_roundtrip`), so compare closely.
    assert_eq!(back.reflectors.len(), x.set.reflectors.len(), "{what}: JSON round trip");
    for (a, b) in back.reflectors.iter().zip(&x.set.reflectors) {
        assert_eq!(
            (a.id, &a.name, a.kind, &a.occluders),
            (b.id, &b.name, b.kind, &b.occluders),
            "{what}: JSON round trip"
        );
        assert!(
            (a.center - b.center).length() <= 1e-12 * (1.0 + b.center.length()),
            "{what}: JSON round trip"
        );
    }
    assert_eq!(x.regions.len(), x.set.reflectors.len(), "{what}: one region per reflector");
    for (r, verts) in x.set.reflectors.iter().zip(&x.regions) {
        assert!(!verts.is_empty(), "{what}: {} has no region vertices", r.name);
        for v in verts {
            let l = r.local(*v);
            assert!(
                r.contains_projection(*v, 1e-7 * diag),
                "{what}: {} (id {}) does not enclose {v:?}: local {l:?}, half extents {:?}",
                r.name,
                r.id,
                r.half_extents
            );
            assert!(
                l.z.abs() <= plane_tol_m,
                "{what}: {} (id {}) is {} m off the plane of {v:?} (tolerance {})",
                r.name,
                r.id,
                l.z,
                plane_tol_m
            );
        }
    }
}
