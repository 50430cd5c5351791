//! Which views the exact glossy reference renders in a frame: for each rendered plane
//! with rough members, the lobe's range of distances and alphas and the eye points of
//! [`crate::glossy_views`]; and the per-reflector table the accumulation reads.

use glam::{DVec3, DVec4};
use ppr_format::ReflectorSet;
use ppr_runtime::Camera;

use crate::glossy_accumulate::{GlossySampleUniform, RoughReflector};
use crate::glossy_views::{GlossyParams, GlossyView, LobeRange, component_scales, glossy_views};
use crate::reflector_planes::ReflectorPlane;

/// The views of one rough plane.
#[derive(Clone, Debug, PartialEq)]
pub struct GlossyPlane {
    /// Index of the plane group.
    pub plane: usize,
    /// Index of the first view among all glossy views of the frame.
    pub first: u32,
    /// The views.
    pub views: Vec<GlossyView>,
}

/// The glossy views of a frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GlossyPlan {
    /// One entry per rendered plane with rough members.
    pub planes: Vec<GlossyPlane>,
    /// Per reflector: its plane slot and GGX alpha (0 for mirrors and disabled ones).
    pub reflectors: Vec<RoughReflector>,
    /// The scene raster's view slot of the first view (the renderer's to set).
    pub first_view_slot: u32,
}

impl GlossyPlan {
    /// Views of every plane together.
    pub fn view_count(&self) -> u32 {
        self.planes.iter().map(|p| p.views.len() as u32).sum()
    }
}

/// The GGX alpha (`roughness²`) of reflector `i`; 0 for mirrors and disabled reflectors.
fn alpha(set: &ReflectorSet, i: usize) -> f64 {
    let r = &set.reflectors[i];
    if r.enabled { r.roughness * r.roughness } else { 0.0 }
}

/// Planes with at least one rough member (an upper bound on the planes of a plan).
pub fn rough_plane_count(set: &ReflectorSet, planes: &[ReflectorPlane]) -> usize {
    planes.iter().filter(|g| g.members.iter().any(|&m| alpha(set, m) > 0.0)).count()
}

/// Grid points per side over the screen where [`lobe_range`] looks at the plane.
pub const RANGE_GRID: u32 = 33;

/// The lobe's range over the rough members of `group` seen from `camera`, and the cosine
/// of the most grazing view of them: from a [`RANGE_GRID`]² grid of main-view rays that hit
/// a rough member (what is on screen), else from the members' corners. `None` when no
/// member is rough.
pub fn lobe_range(
    set: &ReflectorSet,
    group: &ReflectorPlane,
    camera: &Camera,
    aspect: f64,
) -> Option<(LobeRange, f64)> {
    let rough: Vec<usize> = group.members.iter().copied().filter(|&m| alpha(set, m) > 0.0).collect();
    if rough.is_empty() {
        return None;
    }
    let min_alpha = rough.iter().map(|&m| alpha(set, m)).fold(f64::INFINITY, f64::min);
    let max_alpha = rough.iter().map(|&m| alpha(set, m)).fold(0.0, f64::max);
    let n = group.plane.normal;
    let d_rel = n.dot(group.plane.point - camera.position);
    let height = d_rel.abs();
    let near_plane = f64::from(camera.projection.near);
    let far_plane = camera.projection.far.map_or(1e4, f64::from);
    let inside = |p: DVec3| {
        rough.iter().any(|&m| {
            let r = &set.reflectors[m];
            let l = p - r.center;
            let v = r.normal.cross(r.axis_u);
            l.dot(r.axis_u).abs() <= r.half_extents.x && l.dot(v).abs() <= r.half_extents.y
        })
    };
    let rel_from_clip = camera.clip_from_relative(aspect as f32).as_dmat4().inverse();
    let (mut near, mut far, mut grazing) = (f64::INFINITY, 0.0f64, 1.0f64);
    for j in 0..RANGE_GRID {
        for i in 0..RANGE_GRID {
            let k = |a: u32| f64::from(a) / f64::from(RANGE_GRID - 1) * 2.0 - 1.0;
            let h = rel_from_clip * DVec4::new(k(i), k(j), 0.5, 1.0);
            let dir = (h.truncate() / h.w).normalize();
            let dn = n.dot(dir);
            if dn >= -1e-9 {
                continue;
            }
            let t = d_rel / dn;
            if t <= near_plane || t > far_plane || !inside(camera.position + dir * t) {
                continue;
            }
            near = near.min(t);
            far = far.max(t);
            grazing = grazing.min(-dn);
        }
    }
    if far == 0.0 {
        // Smaller than the grid's spacing: the members' corners.
        near = height.max(near_plane);
        far = near;
        for &m in &rough {
            let r = &set.reflectors[m];
            let v = r.normal.cross(r.axis_u);
            for (su, sv) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
                let corner: DVec3 =
                    r.center + r.axis_u * (su * r.half_extents.x) + v * (sv * r.half_extents.y);
                far = far.max((corner - camera.position).length());
            }
        }
        far = far.min(far_plane).max(near);
        grazing = height / far;
    }
    Some((LobeRange { near, far, min_alpha, max_alpha }, grazing))
}

/// The glossy views of the `rendered` planes and the reflector table.
pub fn plan_glossy(
    set: &ReflectorSet,
    planes: &[ReflectorPlane],
    rendered: &[usize],
    camera: &Camera,
    aspect: f64,
    params: &GlossyParams,
) -> GlossyPlan {
    let mut plan = GlossyPlan {
        planes: Vec::new(),
        reflectors: vec![RoughReflector { plane: u32::MAX, alpha: 0.0 }; set.reflectors.len()],
        first_view_slot: 0,
    };
    if !params.enabled() {
        return plan;
    }
    for &k in rendered {
        let group = &planes[k];
        let Some((range, grazing)) = lobe_range(set, group, camera, aspect) else { continue };
        let scales = component_scales(&range, grazing, params.components);
        let Some(views) = glossy_views(camera, aspect, &group.plane, &scales, params.samples) else {
            continue;
        };
        let slot = u32::try_from(k).expect("fewer than 2^32 planes");
        for &m in &group.members {
            plan.reflectors[m] = RoughReflector { plane: slot, alpha: alpha(set, m) as f32 };
        }
        let first = plan.view_count();
        plan.planes.push(GlossyPlane { plane: k, first, views });
    }
    plan
}

/// The accumulation uniform of `view` of the plane in slot `slot`.
pub fn sample_uniform(
    camera: &Camera,
    aspect: f64,
    group: &ReflectorPlane,
    slot: u32,
    view: &GlossyView,
) -> GlossySampleUniform {
    let main = camera.clip_from_relative(aspect as f32).as_dmat4();
    let n = group.plane.normal;
    let d_rel = n.dot(group.plane.point - camera.position);
    let e = view.eye;
    GlossySampleUniform {
        rel_from_main_clip: main.inverse().as_mat4().to_cols_array_2d(),
        plane: [n.x as f32, n.y as f32, n.z as f32, d_rel as f32],
        eye: [e.x as f32, e.y as f32, e.z as f32, view.inv_density as f32],
        slot: [slot, 0, 0, 0],
    }
}
