//! The ground truth written to `demo_room.expected.json`: every reflective surface's exact rectangles and area.
//!
//! Everything is computed from the data as stored in the `.glb` (vertex positions and node
//! transforms rounded to `f32`, then composed in `f64`), so an extractor that reads the
//! file carefully can match it to about 1e-6 m. Field meanings are documented on the
//! structs below and in `assets/README.md`.

use anyhow::{Context, Result, bail, ensure};
use glam::DVec3;
use serde::Serialize;

use crate::level_builder::{LevelBuilder, NodeId};
use crate::rectangle_fit::{Rectangle, minimum_area_rectangle};

/// Values in the file are rounded to this many metres (or units, for directions).
pub const ROUNDING: f64 = 1e-6;
/// `1 / ROUNDING`, exact, so `k / STEPS_PER_UNIT` is the double nearest to `k · 1e-6`.
const STEPS_PER_UNIT: f64 = 1e6;

/// How a reflector is shaded (the names `ppr-format` uses).
#[derive(Serialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ReflectorKind {
    Opaque,
    Transparent,
    Water,
}

/// A surface the level places as a reflector: one primitive of one node's mesh.
#[derive(Clone, Debug)]
pub struct ReflectorSpec {
    pub node: NodeId,
    pub primitive: usize,
    pub kind: ReflectorKind,
    /// Exact partitions of the region into rectangles, each a list of parts, each part a
    /// list of triangle indices of the primitive. The first is the preferred split; empty
    /// when the region is best fitted by its single enclosing rectangle.
    pub splits: Vec<Vec<Vec<usize>>>,
}

/// A surface that looks like a candidate but must not become a reflector.
#[derive(Clone, Debug)]
pub struct NonReflectorSpec {
    pub node: NodeId,
    pub primitive: usize,
    pub reason: &'static str,
}

/// The whole `*.expected.json` document.
#[derive(Serialize, Debug)]
pub struct ExpectedLevel {
    /// Always `ppr-demo-level-expected`.
    pub format: &'static str,
    pub version: u32,
    /// The `.glb` this describes (a sibling file).
    pub level: &'static str,
    pub conventions: Conventions,
    pub reflectors: Vec<ExpectedReflector>,
    /// Reflectors sharing one normal exactly, in order of first appearance.
    pub parallel_groups: Vec<ExpectedParallelGroup>,
    /// Surfaces for which an extractor must produce no reflector.
    pub non_reflectors: Vec<ExpectedNonReflector>,
}

/// How to read the numbers.
#[derive(Serialize, Debug)]
pub struct Conventions {
    pub units: &'static str,
    pub up: &'static str,
    pub handedness: &'static str,
    pub rectangle_axes: &'static str,
    pub rounding: f64,
    pub suggested_position_tolerance_m: f64,
    pub suggested_direction_tolerance: f64,
    pub suggested_relative_area_tolerance: f64,
}

/// One reflective surface.
#[derive(Serialize, Debug)]
pub struct ExpectedReflector {
    /// The node's name (unique in the level).
    pub name: &'static str,
    pub kind: ReflectorKind,
    pub node: &'static str,
    pub mesh: &'static str,
    /// Index of the reflective primitive within the mesh.
    pub primitive: usize,
    pub material: &'static str,
    pub triangle_count: usize,
    /// Unit normal of the reflecting side, world space.
    pub normal: [f64; 3],
    /// True reflective area (sum of the world-space triangle areas), m².
    pub area: f64,
    /// The best fit: the enclosing rectangle, or the rectangles of the best exact split.
    pub rectangles: Vec<ExpectedRectangle>,
    /// `area` / total area of `rectangles`.
    pub coverage: f64,
    /// The single minimum-area rectangle enclosing the whole surface.
    pub enclosing_rectangle: ExpectedRectangle,
    /// `area` / area of `enclosing_rectangle`.
    pub enclosing_coverage: f64,
    /// Other splits exactly as good as `rectangles` (an extractor may return any of them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub alternative_rectangles: Vec<Vec<ExpectedRectangle>>,
}

/// A rectangle in world space (the fields of a `ppr-format` reflector).
#[derive(Serialize, Debug, Clone)]
pub struct ExpectedRectangle {
    pub center: [f64; 3],
    /// Along the longer side; `axis_u × axis_v = normal`.
    pub axis_u: [f64; 3],
    pub axis_v: [f64; 3],
    /// Half size along `axis_u` and `axis_v` (`[0] >= [1]`).
    pub half_extents: [f64; 2],
    pub normal: [f64; 3],
    /// `4 · hu · hv`.
    pub area: f64,
    /// Reflective area inside this rectangle / its area.
    pub coverage: f64,
    /// Counter-clockwise seen from the reflecting side: `c-u-v, c+u-v, c+u+v, c-u+v`.
    pub corners: [[f64; 3]; 4],
}

#[derive(Serialize, Debug)]
pub struct ExpectedParallelGroup {
    pub normal: [f64; 3],
    pub members: Vec<&'static str>,
}

#[derive(Serialize, Debug)]
pub struct ExpectedNonReflector {
    pub name: &'static str,
    pub node: &'static str,
    pub mesh: &'static str,
    pub material: &'static str,
    pub roughness: f32,
    pub reason: &'static str,
    pub expected: &'static str,
}

/// Computes the ground truth of `reflectors` and `non_reflectors` in `builder`'s level.
pub fn expected_level(
    builder: &LevelBuilder,
    level: &'static str,
    reflectors: &[ReflectorSpec],
    non_reflectors: &[NonReflectorSpec],
) -> Result<ExpectedLevel> {
    let reflectors =
        reflectors.iter().map(|spec| expected_reflector(builder, spec)).collect::<Result<Vec<_>>>()?;

    let mut parallel_groups: Vec<ExpectedParallelGroup> = Vec::new();
    for reflector in &reflectors {
        match parallel_groups.iter_mut().find(|group| group.normal == reflector.normal) {
            Some(group) => group.members.push(reflector.name),
            None => parallel_groups
                .push(ExpectedParallelGroup { normal: reflector.normal, members: vec![reflector.name] }),
        }
    }

    let non_reflectors = non_reflectors
        .iter()
        .map(|spec| {
            let mesh = builder.node_mesh(spec.node).context("a non-reflector node has no mesh")?;
            let (_, material) = builder.primitive(mesh, spec.primitive).context("no such primitive")?;
            Ok(ExpectedNonReflector {
                name: builder.node_name(spec.node),
                node: builder.node_name(spec.node),
                mesh: builder.mesh_name(mesh),
                material: material.name,
                roughness: material.roughness,
                reason: spec.reason,
                expected: "no reflector",
            })
        })
        .collect::<Result<Vec<_>>>()?;

    Ok(ExpectedLevel {
        format: "ppr-demo-level-expected",
        version: 1,
        level,
        conventions: Conventions {
            units: "metres",
            up: "+Y",
            handedness: "right",
            rectangle_axes: "axis_u along the longer side with its largest component positive; \
                             axis_v = normal × axis_u; any rectangle with the same centre, normal and \
                             corner set is the same rectangle",
            rounding: ROUNDING,
            suggested_position_tolerance_m: 1e-4,
            suggested_direction_tolerance: 1e-4,
            suggested_relative_area_tolerance: 1e-4,
        },
        reflectors,
        parallel_groups,
        non_reflectors,
    })
}

fn expected_reflector(builder: &LevelBuilder, spec: &ReflectorSpec) -> Result<ExpectedReflector> {
    let name = builder.node_name(spec.node);
    let mesh = builder.node_mesh(spec.node).with_context(|| format!("reflector node {name} has no mesh"))?;
    let (geometry, material) = builder
        .primitive(mesh, spec.primitive)
        .with_context(|| format!("reflector {name}: mesh has no primitive {}", spec.primitive))?;

    let world = builder.world_matrix(spec.node);
    let flips_winding = world.determinant() < 0.0;
    let triangles: Vec<[DVec3; 3]> = geometry
        .indices
        .chunks_exact(3)
        .map(|t| {
            [t[0], t[1], t[2]].map(|i| {
                world.transform_point3(DVec3::from_array(geometry.positions[i as usize].map(f64::from)))
            })
        })
        .collect();

    // Front faces are counter-clockwise in world space, clockwise under a mirroring transform.
    let front_normal = |[a, b, c]: &[DVec3; 3]| {
        let n = (*b - *a).cross(*c - *a);
        if flips_winding { -n } else { n }
    };
    let normal = triangles.iter().map(front_normal).sum::<DVec3>().normalize();
    for (index, triangle) in triangles.iter().enumerate() {
        let n = front_normal(triangle).normalize();
        ensure!(
            n.dot(normal) > 1.0 - 1e-9,
            "reflector {name}: triangle {index} is not coplanar ({n:?} vs {normal:?})"
        );
    }
    let area_of = |indices: &mut dyn Iterator<Item = usize>| -> f64 {
        indices.map(|i| front_normal(&triangles[i]).length() * 0.5).sum()
    };
    let area = area_of(&mut (0..triangles.len()));

    // Each fit is the rectangle and the reflective area it holds (unrounded).
    let fit = |indices: &[usize]| -> Result<(Rectangle, f64)> {
        let points: Vec<DVec3> = indices.iter().flat_map(|&i| triangles[i]).collect();
        let rectangle = minimum_area_rectangle(&points, normal)
            .with_context(|| format!("reflector {name}: degenerate region"))?;
        Ok((rectangle, area_of(&mut indices.iter().copied())))
    };
    let all: Vec<usize> = (0..triangles.len()).collect();
    let enclosing = fit(&all)?;

    let mut splits = spec
        .splits
        .iter()
        .map(|split| {
            let covered: usize = split.iter().map(Vec::len).sum();
            if covered != triangles.len() {
                bail!("reflector {name}: a split covers {covered} of {} triangles", triangles.len());
            }
            split.iter().map(|part| fit(part)).collect::<Result<Vec<_>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let best = if splits.is_empty() { vec![enclosing] } else { splits.remove(0) };
    let best_area: f64 = best.iter().map(|(rectangle, _)| rectangle.area()).sum();
    let to_expected = |fits: &[(Rectangle, f64)]| fits.iter().map(expected_rectangle).collect::<Vec<_>>();

    Ok(ExpectedReflector {
        name,
        kind: spec.kind,
        node: name,
        mesh: builder.mesh_name(mesh),
        primitive: spec.primitive,
        material: material.name,
        triangle_count: triangles.len(),
        normal: rounded(normal),
        area: round(area),
        rectangles: to_expected(&best),
        coverage: round(area / best_area),
        enclosing_rectangle: expected_rectangle(&enclosing),
        enclosing_coverage: round(area / enclosing.0.area()),
        alternative_rectangles: splits.iter().map(|split| to_expected(split)).collect(),
    })
}

fn expected_rectangle((rectangle, part_area): &(Rectangle, f64)) -> ExpectedRectangle {
    ExpectedRectangle {
        center: rounded(rectangle.center),
        axis_u: rounded(rectangle.axis_u),
        axis_v: rounded(rectangle.axis_v),
        half_extents: [round(rectangle.half_extents.x), round(rectangle.half_extents.y)],
        normal: rounded(rectangle.normal),
        area: round(rectangle.area()),
        coverage: round(part_area / rectangle.area()),
        corners: rectangle.corners().map(rounded),
    }
}

fn round(value: f64) -> f64 {
    // `+ 0.0` turns -0.0 into 0.0.
    (value * STEPS_PER_UNIT).round() / STEPS_PER_UNIT + 0.0
}

fn rounded(v: DVec3) -> [f64; 3] {
    v.to_array().map(round)
}
