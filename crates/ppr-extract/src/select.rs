//! Candidate selection: which triangles may become reflectors, and of which kind.
//!
//! The rule, in order:
//! 1. `extras.ppr.reflector` on the node, else the mesh, else the material, decides when set.
//! 2. With [`CandidateRule::AllPlanar`] every other triangle is a candidate.
//! 3. With [`CandidateRule::Materials`] a triangle is a candidate when its material has
//!    roughness ≤ `max_roughness`, or metallic ≥ `min_metallic` with roughness ≤
//!    `metallic_max_roughness`, or transmission > 0, or a clear coat ≥ 0.5 with clear-coat
//!    roughness ≤ `max_roughness`, or when its material, mesh or node name contains one of
//!    `name_patterns` (case-insensitive; default mirror, glass, water, puddle, chrome,
//!    polished).
//!
//! The kind: `extras.ppr.kind` (node, then mesh, then material) wins; else a material, mesh
//! or node name containing a `water_patterns` entry gives `water`; else transmission > 0,
//! or a name containing a `transparent_patterns` entry (default glass, window), gives
//! `transparent`; else `opaque`.
//!
//! Degenerate triangles (twice the area below 1e-10 of the longest edge squared, or a
//! longest edge below 1e-9 of the level's diagonal) are skipped and counted.

use glam::DVec3;
use ppr_format::ReflectorKind;

use crate::level::{Level, MaterialInfo, TriangleSource};
use crate::{CandidateRule, ExtractParams, SceneScale};

/// A triangle that may become part of a reflector, in local coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Index into the level's triangles.
    pub triangle: u32,
    /// Corners relative to [`SceneScale::center`].
    pub positions: [DVec3; 3],
    /// Unit front-face normal.
    pub normal: DVec3,
    /// Area, square metres.
    pub area: f64,
    /// Longest edge, metres.
    pub longest_edge: f64,
    /// The reflector kind it would give.
    pub kind: ReflectorKind,
}

/// The candidates of a level and what was skipped.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection {
    /// Candidate triangles, in level order.
    pub candidates: Vec<Candidate>,
    /// Degenerate triangles skipped (among all triangles, candidates or not).
    pub degenerate: usize,
}

/// The kind a source's triangles would give, or `None` when they are not candidates.
pub fn classify(
    source: &TriangleSource,
    material: &MaterialInfo,
    params: &ExtractParams,
) -> Option<ReflectorKind> {
    let over = source.node_extras.or(source.mesh_extras).or(material.extras);
    let names = [material.name.to_lowercase(), source.mesh.to_lowercase(), source.node.to_lowercase()];
    let named = |patterns: &[String]| {
        patterns.iter().any(|p| !p.is_empty() && names.iter().any(|n| n.contains(&p.to_lowercase())))
    };
    let candidate = over.reflector.unwrap_or_else(|| match params.candidates {
        CandidateRule::AllPlanar => true,
        CandidateRule::Materials => {
            material.roughness <= params.max_roughness
                || (material.metallic >= params.min_metallic
                    && material.roughness <= params.metallic_max_roughness)
                || material.transmission > 0.0
                || (material.clearcoat >= 0.5 && material.clearcoat_roughness <= params.max_roughness)
                || named(&params.name_patterns)
        }
    });
    if !candidate {
        return None;
    }
    Some(over.kind.unwrap_or(if named(&params.water_patterns) {
        ReflectorKind::Water
    } else if material.transmission > 0.0 || named(&params.transparent_patterns) {
        ReflectorKind::Transparent
    } else {
        ReflectorKind::Opaque
    }))
}

/// Picks the candidate triangles of `level`.
pub fn select(level: &Level, params: &ExtractParams, scale: &SceneScale) -> Selection {
    let kinds: Vec<Option<ReflectorKind>> =
        level.sources.iter().map(|s| classify(s, &level.materials[s.material as usize], params)).collect();
    let mut out = Selection { candidates: Vec::with_capacity(level.triangles.len()), degenerate: 0 };
    let tiny_edge = 1e-9 * scale.diagonal;
    for (i, t) in level.triangles.iter().enumerate() {
        let p = t.positions.map(|p| p - scale.center);
        let cross = (p[1] - p[0]).cross(p[2] - p[0]);
        let longest = (p[1] - p[0]).length().max((p[2] - p[1]).length()).max((p[0] - p[2]).length());
        let twice_area = cross.length();
        if !(longest > tiny_edge) || !(twice_area > 1e-10 * longest * longest) {
            out.degenerate += 1;
            continue;
        }
        let Some(kind) = kinds[t.source as usize] else { continue };
        out.candidates.push(Candidate {
            triangle: i as u32,
            positions: p,
            normal: cross / twice_area,
            area: 0.5 * twice_area,
            longest_edge: longest,
            kind,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::ReflectorOverride;

    fn source(node: &str, node_extras: ReflectorOverride) -> TriangleSource {
        TriangleSource {
            node: node.into(),
            mesh: "m".into(),
            material: 0,
            node_extras,
            mesh_extras: ReflectorOverride::default(),
        }
    }

    fn material(name: &str, roughness: f64, metallic: f64, transmission: f64) -> MaterialInfo {
        MaterialInfo { name: name.into(), roughness, metallic, transmission, ..MaterialInfo::gltf_default() }
    }

    fn check(
        src: TriangleSource,
        mat: MaterialInfo,
        params: &ExtractParams,
        expected: Option<ReflectorKind>,
    ) {
        assert_eq!(classify(&src, &mat, params), expected, "{src:?} {mat:?}");
    }

    #[test]
    fn material_rule_kinds_and_overrides() {
        use ReflectorKind::*;
        let p = ExtractParams::default();
        let none = ReflectorOverride::default();
        check(source("n", none), material("Wall", 0.8, 0.0, 0.0), &p, None);
        check(source("n", none), material("Floor", 0.2, 0.0, 0.0), &p, Some(Opaque));
        check(source("n", none), material("Steel", 0.45, 0.9, 0.0), &p, Some(Opaque));
        check(source("n", none), material("Steel", 0.6, 0.9, 0.0), &p, None);
        check(source("n", none), material("Pane", 0.9, 0.0, 1.0), &p, Some(Transparent));
        check(source("n", none), material("Big MIRROR", 0.9, 0.0, 0.0), &p, Some(Opaque));
        check(source("n", none), material("Red Glass", 0.5, 0.0, 0.0), &p, Some(Transparent));
        check(source("Pool_Water", none), material("Tiles", 0.9, 0.0, 0.0), &p, Some(Water));
        check(source("n", none), material("Water", 0.0, 0.0, 1.0), &p, Some(Water));
        let veto = ReflectorOverride { reflector: Some(false), kind: None };
        check(source("n", veto), material("Floor", 0.1, 0.0, 0.0), &p, None);
        let force = ReflectorOverride { reflector: Some(true), kind: Some(Water) };
        check(source("n", force), material("Wall", 0.9, 0.0, 0.0), &p, Some(Water));
        let all = ExtractParams::all_planar();
        check(source("n", none), material("Wall", 0.9, 0.0, 0.0), &all, Some(Opaque));
        check(source("n", veto), material("Wall", 0.9, 0.0, 0.0), &all, None);
        // The node's override beats the material's.
        let mut m = material("Floor", 0.1, 0.0, 0.0);
        m.extras = ReflectorOverride { reflector: Some(false), kind: None };
        check(source("n", none), m.clone(), &p, None);
        check(source("n", ReflectorOverride { reflector: Some(true), kind: None }), m, &p, Some(Opaque));
    }

    #[test]
    fn degenerate_triangles_are_counted_not_kept() {
        let good = [DVec3::ZERO, DVec3::X, DVec3::Z];
        let collinear = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let point = [DVec3::ONE; 3];
        let sliver = [DVec3::ZERO, DVec3::X * 10.0, DVec3::new(5.0, 0.0, 1e-3)];
        let level =
            Level::from_triangles("t", &[good, collinear, point, sliver], material("m", 0.0, 0.0, 0.0));
        let p = ExtractParams::default();
        let s = select(&level, &p, &SceneScale::new(&level, &p));
        assert_eq!(s.degenerate, 2);
        assert_eq!(s.candidates.iter().map(|c| c.triangle).collect::<Vec<_>>(), vec![0, 3]);
        assert!((s.candidates[0].normal - DVec3::NEG_Y).length() < 1e-12);
    }
}
