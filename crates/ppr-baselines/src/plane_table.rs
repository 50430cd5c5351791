//! The reflector set as the baselines see it: each reflector's plane (grouped with the
//! coplanar ones), camera-relative per frame, and which planes get an SSPR hash layer.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::reflector_planes::{ReflectorPlane, group_by_plane, may_be_visible};

use crate::gpu_types::{GpuReflectorPlane, NO_LAYER};

/// The reflectors of a set grouped by plane.
///
/// Invariant: `group_of[i]` is the group holding reflector `i` (`None` for a disabled
/// reflector, which keeps its own plane).
#[derive(Clone, Debug)]
pub struct PlaneTable {
    set: ReflectorSet,
    groups: Vec<ReflectorPlane>,
    group_of: Vec<Option<usize>>,
}

impl PlaneTable {
    /// Groups the enabled reflectors of `set` by plane.
    pub fn new(set: &ReflectorSet) -> Self {
        let groups = group_by_plane(set);
        let mut group_of = vec![None; set.reflectors.len()];
        for (k, g) in groups.iter().enumerate() {
            for &m in &g.members {
                group_of[m] = Some(k);
            }
        }
        Self { set: set.clone(), groups, group_of }
    }

    /// Number of reflectors (the GPU table's length).
    pub fn reflector_count(&self) -> usize {
        self.set.reflectors.len()
    }

    /// The plane groups.
    pub fn groups(&self) -> &[ReflectorPlane] {
        &self.groups
    }

    /// Indices of the groups `camera` may see (in front of the plane, inside the frustum),
    /// in set order, at most `max`.
    pub fn visible_groups(&self, camera: &Camera, size: [u32; 2], max: usize) -> Vec<usize> {
        let aspect = f64::from(size[0].max(1)) / f64::from(size[1].max(1));
        (0..self.groups.len())
            .filter(|&k| may_be_visible(&self.set, &self.groups[k], camera, aspect))
            .take(max)
            .collect()
    }

    /// Each reflector's camera-relative plane (its group's plane); the reflectors of
    /// `layered[j]` get layer `j`, the others [`NO_LAYER`].
    pub fn gpu_planes(&self, camera: &Camera, layered: &[usize]) -> Vec<GpuReflectorPlane> {
        self.set
            .reflectors
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let (point, normal) = match self.group_of[i] {
                    Some(k) => (self.groups[k].plane.point, self.groups[k].plane.normal),
                    None => (r.center, r.normal),
                };
                let layer = self.group_of[i]
                    .and_then(|k| layered.iter().position(|&g| g == k))
                    .map_or(NO_LAYER, |j| u32::try_from(j).expect("fewer than 2^32 layers"));
                gpu_plane(camera, point, normal, layer)
            })
            .collect()
    }

    /// The plane of each layered group, in layer order.
    pub fn gpu_layers(&self, camera: &Camera, layered: &[usize]) -> Vec<GpuReflectorPlane> {
        layered
            .iter()
            .enumerate()
            .map(|(j, &k)| {
                let p = &self.groups[k].plane;
                gpu_plane(camera, p.point, p.normal, u32::try_from(j).expect("fewer than 2^32 layers"))
            })
            .collect()
    }
}

/// The camera-relative plane through world `point` with unit `normal` (offset in f64).
fn gpu_plane(camera: &Camera, point: glam::DVec3, normal: glam::DVec3, layer: u32) -> GpuReflectorPlane {
    let offset = normal.dot(point - camera.position);
    GpuReflectorPlane { normal: normal.as_vec3().to_array(), offset: offset as f32, layer, _pad: [0; 3] }
}
