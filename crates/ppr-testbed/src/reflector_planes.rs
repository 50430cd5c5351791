//! Reflectors grouped by plane: one mirrored view serves every reflector of a plane.

use glam::{DMat4, DVec3};
use ppr_format::ReflectorSet;
use ppr_runtime::Camera;

use crate::mirror_camera::MirrorPlane;

/// Largest angle between two normals of one plane group (as `1 − cos`).
pub const PLANE_NORMAL_TOLERANCE: f64 = 1e-6;
/// Largest distance between two reflectors' planes of one group, metres.
pub const PLANE_DISTANCE_TOLERANCE: f64 = 1e-4;

/// Enabled reflectors that share a plane.
#[derive(Clone, Debug, PartialEq)]
pub struct ReflectorPlane {
    /// The plane (through the first member's centre, with its normal).
    pub plane: MirrorPlane,
    /// Indices into the set's reflectors.
    pub members: Vec<usize>,
}

/// Groups the enabled reflectors of `set` by plane (normal and offset within
/// [`PLANE_NORMAL_TOLERANCE`] and [`PLANE_DISTANCE_TOLERANCE`]), in set order.
pub fn group_by_plane(set: &ReflectorSet) -> Vec<ReflectorPlane> {
    let mut groups: Vec<ReflectorPlane> = Vec::new();
    for (i, r) in set.reflectors.iter().enumerate().filter(|(_, r)| r.enabled) {
        let found = groups.iter_mut().find(|g| {
            1.0 - g.plane.normal.dot(r.normal) <= PLANE_NORMAL_TOLERANCE
                && g.plane.signed_distance(r.center).abs() <= PLANE_DISTANCE_TOLERANCE
        });
        match found {
            Some(g) => g.members.push(i),
            None => groups.push(ReflectorPlane {
                plane: MirrorPlane { point: r.center, normal: r.normal },
                members: vec![i],
            }),
        }
    }
    groups
}

/// Whether some member of `group` may be seen by `camera` (conservative: `false` only when
/// the camera is behind the plane or every member's rectangle is outside one frustum plane).
pub fn may_be_visible(set: &ReflectorSet, group: &ReflectorPlane, camera: &Camera, aspect: f64) -> bool {
    if group.plane.signed_distance(camera.position) <= 0.0 {
        return false;
    }
    let clip_from_rel: DMat4 = camera.clip_from_relative(aspect as f32).as_dmat4();
    group.members.iter().any(|&i| {
        let corners =
            set.reflectors[i].corners().map(|c: DVec3| clip_from_rel * (c - camera.position).extend(1.0));
        let all = |f: &dyn Fn(&glam::DVec4) -> bool| corners.iter().all(f);
        !(all(&|c| c.w <= 0.0)
            || all(&|c| c.x > c.w)
            || all(&|c| c.x < -c.w)
            || all(&|c| c.y > c.w)
            || all(&|c| c.y < -c.w))
    })
}
