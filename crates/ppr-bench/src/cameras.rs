//! Cameras for levels that bring none: derived deterministically from the level's bounds
//! and its largest reflectors, on the CPU only (the same cameras on every adapter).

use glam::{DVec3, Vec3};
use ppr_format::ReflectorSet;
use ppr_runtime::plan::{FramePlan, PlanParams};
use ppr_runtime::shapes::ShapeTable;
use ppr_runtime::{Camera, Projection};
use ppr_testbed::Level;

/// A camera with the name reports use.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedCamera {
    pub name: String,
    pub camera: Camera,
}

/// Reflectors (largest first) that get candidate viewpoints.
const CANDIDATE_REFLECTORS: usize = 8;
/// Aspect ratio the candidates are scored at.
const SCORE_ASPECT: [u32; 2] = [1600, 900];

/// Candidate cameras: an overview from high in one corner of the bounds, then, for each of
/// the largest reflectors, the viewpoints (of four around it, on its reflecting side at a
/// grazing angle) that have a clear line to it, best CPU score first (reflector area on
/// screen times the estimated share of its reflection on screen). [`rank_cameras`] then
/// picks among them by rendering.
pub fn derive_cameras(level: &Level, set: &ReflectorSet, count: usize) -> Vec<NamedCamera> {
    let Some((lo, hi)) = level.bounds() else {
        return Vec::new();
    };
    let size = hi - lo;
    let diag = size.length().max(1e-3);
    let projection = Projection {
        fov_y: 60f32.to_radians(),
        near: (diag * 2e-4).clamp(0.005, 0.5) as f32,
        far: Some((diag * 3.0) as f32),
        ..Projection::default()
    };
    let triangles = level_triangles(level);
    let inside = |p: DVec3| p.cmpge(lo + size * 0.02).all() && p.cmple(hi - size * 0.02).all();
    let table = ShapeTable::from_set(set);
    // Reflector area on screen, weighted by the share of its reflection that is on screen
    // (what the comparison measures best).
    let score = |camera: &Camera, r: &ppr_format::Reflector| {
        let plan = FramePlan::build(&table, camera, SCORE_ASPECT, &PlanParams::default());
        f64::from(plan.coverage) * (0.1 + reflection_on_screen_share(camera, r, &triangles, diag))
    };

    let mut cameras = Vec::new();
    let eye = lo + size * DVec3::new(0.85, 0.8, 0.85);
    let target = lo + size * DVec3::new(0.4, 0.2, 0.4);
    cameras.push(NamedCamera {
        name: "overview".into(),
        camera: Camera::look_at(eye, target, Vec3::Y, projection),
    });

    let mut order: Vec<usize> = (0..set.reflectors.len()).filter(|&i| set.reflectors[i].enabled).collect();
    order.sort_by(|&a, &b| set.reflectors[b].area().total_cmp(&set.reflectors[a].area()).then(a.cmp(&b)));
    let mut views: Vec<(f64, usize, NamedCamera)> = Vec::new();
    for &i in order.iter().take(CANDIDATE_REFLECTORS) {
        let r = &set.reflectors[i];
        let reach = (r.half_extents.max_element() * 1.2).clamp(diag * 0.05, diag * 0.3);
        for (k, dir) in [r.axis_u, -r.axis_u, r.axis_v, -r.axis_v].into_iter().enumerate() {
            // Viewpoints above a wall mirror or below a ceiling make odd pictures: prefer
            // sideways directions.
            if dir.y.abs() > 0.7 {
                continue;
            }
            let eye = r.center + r.normal * (0.5 * reach) + dir * reach;
            if !inside(eye) || segment_blocked(&triangles, eye, r.center + r.normal * (1e-3 * reach)) {
                continue;
            }
            let camera = Camera::look_at(eye, r.center, Vec3::Y, projection);
            let s = score(&camera, r);
            views.push((s, i, NamedCamera { name: format!("view-{}-{k}", sanitize(&r.name)), camera }));
        }
    }
    views.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    cameras.extend(views.into_iter().map(|(_, _, c)| c).take(count.max(1) * 4));
    cameras
}

/// Share of a 5 × 5 grid of points on `r` that the camera sees and whose reflection (the
/// first triangle the mirrored ray meets) the camera sees too: a CPU estimate of how much
/// of the reflection is on screen.
fn reflection_on_screen_share(
    camera: &Camera,
    r: &ppr_format::Reflector,
    triangles: &[[DVec3; 3]],
    diag: f64,
) -> f64 {
    let aspect = SCORE_ASPECT[0] as f32 / SCORE_ASPECT[1] as f32;
    let clip = camera.clip_from_relative(aspect).as_dmat4();
    let eye = camera.position;
    let mirrored_eye = eye - 2.0 * (eye - r.center).dot(r.normal) * r.normal;
    let eps = diag * 1e-5;
    let on_screen = |p: DVec3| {
        let c = clip * (p - eye).extend(1.0);
        c.w > 0.0 && c.x.abs() < c.w && c.y.abs() < c.w
    };
    let mut hits = 0;
    for i in 0..5 {
        for j in 0..5 {
            let a = (f64::from(i) + 0.5) / 2.5 - 1.0;
            let b = (f64::from(j) + 0.5) / 2.5 - 1.0;
            let s = r.center + r.axis_u * (a * r.half_extents.x) + r.axis_v * (b * r.half_extents.y);
            let start = s + r.normal * eps;
            if !on_screen(s) || segment_blocked(triangles, eye, start) {
                continue;
            }
            let dir = (s - mirrored_eye).normalize();
            if let Some(t) = first_hit(triangles, start, dir, diag * 2.0) {
                let hit = start + dir * t;
                if on_screen(hit) && !segment_blocked(triangles, eye, hit - dir * eps) {
                    hits += 1;
                }
            }
        }
    }
    f64::from(hits) / 25.0
}

/// Distance along the ray to the nearest triangle, within `max`.
fn first_hit(triangles: &[[DVec3; 3]], origin: DVec3, dir: DVec3, max: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    for [p0, p1, p2] in triangles {
        let e1 = *p1 - *p0;
        let e2 = *p2 - *p0;
        let h = dir.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-12 {
            continue;
        }
        let f = 1.0 / det;
        let s = origin - *p0;
        let u = f * s.dot(h);
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = s.cross(e1);
        let v = f * dir.dot(q);
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let t = f * e2.dot(q);
        if t > 1e-9 && t < max && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    }
    best
}

/// Lower-case letters, digits and dashes only.
fn sanitize(name: &str) -> String {
    let s: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '-' }).collect();
    let s = s.trim_matches('-').to_string();
    if s.is_empty() { "reflector".into() } else { s }
}

/// Every placed triangle of the level, world space.
pub fn level_triangles(level: &Level) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for inst in &level.instances {
        for prim in &level.meshes[inst.mesh].primitives {
            let p = |k: u32| {
                inst.world.transform_point3(Vec3::from(prim.vertices[k as usize].position).as_dvec3())
            };
            for t in prim.indices.chunks_exact(3) {
                out.push([p(t[0]), p(t[1]), p(t[2])]);
            }
        }
    }
    out
}

/// Whether some triangle crosses the open segment from `a` to `b` (Möller–Trumbore).
pub fn segment_blocked(triangles: &[[DVec3; 3]], a: DVec3, b: DVec3) -> bool {
    let d = b - a;
    triangles.iter().any(|[p0, p1, p2]| {
        let e1 = *p1 - *p0;
        let e2 = *p2 - *p0;
        let h = d.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-12 {
            return false;
        }
        let f = 1.0 / det;
        let s = a - *p0;
        let u = f * s.dot(h);
        if !(0.0..=1.0).contains(&u) {
            return false;
        }
        let q = s.cross(e1);
        let v = f * d.dot(q);
        if v < 0.0 || u + v > 1.0 {
            return false;
        }
        let t = f * e2.dot(q);
        t > 1e-6 && t < 1.0 - 1e-6
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_test_sees_a_triangle_between_and_not_beside() {
        let tri = [[DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)]];
        assert!(segment_blocked(&tri, DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, 1.0)));
        assert!(!segment_blocked(&tri, DVec3::new(0.0, 0.0, 0.5), DVec3::new(0.0, 0.0, 1.0)));
        assert!(!segment_blocked(&tri, DVec3::new(5.0, 0.0, -1.0), DVec3::new(5.0, 0.0, 1.0)));
    }
}
