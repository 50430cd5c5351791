//! The reflector set as the runtime holds it: static shape data on the CPU, written
//! camera-relative into GPU shapes each frame.

use glam::{DVec3, Vec3};
use ppr_format::{ReflectorKind, ReflectorSet};

use crate::gpu_types::{GpuShape, SHAPE_OCCLUDES};
use crate::parallel_trees::ParallelFamilies;
use crate::path_blockers::path_blockers;
use crate::plane_groups::PlaneGroups;

/// One reflector as the runtime needs it (f64 centre, f32 frame).
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeSource {
    /// Stable id from the set.
    pub id: u32,
    /// Kind from the set.
    pub kind: ReflectorKind,
    /// Disabled shapes stay in the table (occluder indices refer to them) but never render.
    pub enabled: bool,
    /// World-space centre.
    pub center: DVec3,
    /// Unit axes and normal.
    pub axis_u: Vec3,
    pub axis_v: Vec3,
    pub normal: Vec3,
    /// Half extents along u and v, metres.
    pub half_extents: [f32; 2],
    /// Parallel group from the set.
    pub parallel_group: u32,
    /// The surface has a normal map.
    pub normal_map: bool,
    /// Perceptual roughness from the set (0: a mirror).
    pub roughness: f32,
}

impl ShapeSource {
    /// The four corners, world space.
    pub fn corners(&self) -> [DVec3; 4] {
        let u = self.axis_u.as_dvec3() * f64::from(self.half_extents[0]);
        let v = self.axis_v.as_dvec3() * f64::from(self.half_extents[1]);
        let c = self.center;
        [c - u - v, c + u - v, c + u + v, c - u + v]
    }

    /// `dot(center − eye, normal)` in f64: negative when `eye` is on the reflecting side.
    pub fn plane_dist_from(&self, eye: DVec3) -> f64 {
        (self.center - eye).dot(self.normal.as_dvec3())
    }
}

/// Every reflector of a set plus the flattened occluder lists.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShapeTable {
    /// Shapes in set order (occluder indices refer to this order).
    pub shapes: Vec<ShapeSource>,
    /// Per shape, the range of its occluders in `occluder_indices`.
    pub occluder_ranges: Vec<std::ops::Range<u32>>,
    /// All occluder lists, concatenated.
    pub occluder_indices: Vec<u32>,
    /// The groups of coplanar shapes and their grids (built with the table).
    pub plane_groups: PlaneGroups,
    /// The families of parallel shapes with one normal, in tree order (built with
    /// the table; a frame merges a family's visible members into a parallel tree).
    pub parallel_families: ParallelFamilies,
    /// Per shape, its family's member right in front of it ([`crate::path_blockers`]).
    pub path_blockers: Vec<u32>,
}

impl ShapeTable {
    /// Builds the table of a (validated) set.
    pub fn from_set(set: &ReflectorSet) -> Self {
        let mut table = Self::default();
        for r in &set.reflectors {
            table.shapes.push(ShapeSource {
                id: r.id,
                kind: r.kind,
                enabled: r.enabled,
                center: r.center,
                axis_u: r.axis_u.as_vec3(),
                axis_v: r.axis_v.as_vec3(),
                normal: r.normal.as_vec3(),
                half_extents: [r.half_extents.x as f32, r.half_extents.y as f32],
                parallel_group: r.parallel_group,
                normal_map: r.normal_map,
                roughness: r.roughness as f32,
            });
            let start = table.occluder_indices.len() as u32;
            table.occluder_indices.extend(&r.occluders);
            table.occluder_ranges.push(start..table.occluder_indices.len() as u32);
        }
        table.plane_groups = PlaneGroups::build(&table.shapes);
        table.parallel_families = ParallelFamilies::build(&table.shapes);
        table.path_blockers = path_blockers(&table.shapes, &table.parallel_families);
        table.plane_groups.set_blockers(&table.path_blockers);
        table
    }

    /// Whether shape `i` has an occluder that blocks reflections of the main buffer.
    pub fn has_blocking_occluders(&self, i: usize) -> bool {
        let range = self.occluder_ranges[i].clone();
        self.occluder_indices[range.start as usize..range.end as usize].iter().any(|&o| {
            let o = &self.shapes[o as usize];
            o.enabled && blocks_main_buffer(o.kind)
        })
    }

    /// All shapes relative to a camera at `eye`, as the GPU reads them, into `out`
    /// (emptied first, its memory reused frame after frame).
    pub fn gpu_shapes_into(&self, eye: DVec3, out: &mut Vec<GpuShape>) {
        out.clear();
        out.extend(self.shapes.iter().zip(&self.occluder_ranges).map(|(s, range)| {
            let rel = s.center - eye;
            GpuShape {
                center: rel.as_vec3().to_array(),
                half_u: s.half_extents[0],
                axis_u: s.axis_u.to_array(),
                half_v: s.half_extents[1],
                axis_v: s.axis_v.to_array(),
                plane_dist: s.plane_dist_from(eye) as f32,
                normal: s.normal.to_array(),
                flags: if s.enabled && blocks_main_buffer(s.kind) { SHAPE_OCCLUDES } else { 0 },
                occluder_start: range.start,
                occluder_count: range.end - range.start,
                parallel_group: s.parallel_group,
                center_u: rel.dot(s.axis_u.as_dvec3()) as f32,
                center_v: rel.dot(s.axis_v.as_dvec3()) as f32,
                _pad: [0; 3],
            }
        }));
    }
}

/// Whether a shape of this kind is opaque to reflections written into the main buffer.
pub fn blocks_main_buffer(kind: ReflectorKind) -> bool {
    !matches!(kind, ReflectorKind::Transparent)
}

/// A mirror of the unit tests: facing +y, u along +x, v along −z.
#[cfg(test)]
pub(crate) fn floor_mirror(
    id: u32,
    center: DVec3,
    half_extents: [f32; 2],
    parallel_group: u32,
) -> ShapeSource {
    ShapeSource {
        id,
        kind: ReflectorKind::Opaque,
        enabled: true,
        center,
        axis_u: Vec3::X,
        axis_v: Vec3::NEG_Z,
        normal: Vec3::Y,
        half_extents,
        parallel_group,
        normal_map: false,
        roughness: 0.0,
    }
}
