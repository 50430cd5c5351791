//! The views of the exact glossy reference: per rough reflector plane, `N` eye points `E_j`
//! scattered behind the plane around the mirrored eye, each with a projection that sees the
//! plane exactly as the main view does (the same pixel shows the same plane point), clipped
//! at the plane.
//!
//! Seen from `E_j`, the main-view pixel on plane point `x` shows exactly the radiance
//! arriving at `x` from direction `normalize(x − E_j)`: every sampled ray starts on the
//! pixel's own surface point (the mirrored view is the case `E = mirror(eye)`). The points
//! are drawn from a mixture of isotropic Gaussians on the plane parallel to the reflector
//! through the mirrored eye; [`GlossyView::inv_density`] is the reciprocal of that
//! mixture's area density at `E_j`, so the accumulation can weight each view by
//! `f(ω) / p(ω)` with `p(ω) = q(E) |x − E|² / |n · ω|`.

use glam::{DMat4, DVec3, DVec4};
use ppr_runtime::{Camera, DepthMode};

use crate::mirror_camera::{MIRROR_SURFACE_MARGIN, MIRROR_SURFACE_MARGIN_PER_METRE, MirrorPlane};

/// How the glossy reference samples the reflection lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossyParams {
    /// Views (eye points) per rough reflector plane; 0 turns the glossy reference off (rough
    /// reflectors then show the mirror reference). 64 for tests, 256 for the bench.
    pub samples: u32,
    /// Gaussian components of the eye-point mixture (1 to 16; 6 covers the lobe from the
    /// nearest to the farthest reflector pixel with room for GGX's tails).
    pub components: u32,
}

impl GlossyParams {
    /// No glossy reference: every reflector shows its mirror reflection.
    pub const fn off() -> Self {
        Self { samples: 0, components: 6 }
    }

    /// 64 views per rough plane: tests on the software adapter.
    pub const fn tests() -> Self {
        Self { samples: 64, components: 6 }
    }

    /// 256 views per rough plane: the bench's reference.
    pub const fn bench() -> Self {
        Self { samples: 256, components: 6 }
    }

    /// Whether the glossy reference is rendered at all.
    pub fn enabled(&self) -> bool {
        self.samples > 0
    }
}

impl Default for GlossyParams {
    fn default() -> Self {
        Self::off()
    }
}

/// One view of the glossy reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossyView {
    /// Clip-from-relative (relative to the real camera), no mirroring: the scene seen from
    /// `eye` through the plane, depth clipped at the plane.
    pub clip_from_rel: DMat4,
    /// The eye point `E_j`, camera-relative (behind the plane).
    pub eye: DVec3,
    /// `1 / q(E_j)`: the reciprocal of the mixture's area density at the eye point, m².
    pub inv_density: f64,
}

/// Range of distances from the camera to the reflector pixels of a plane, and of the
/// alphas (`roughness²`) of its rough members: what the mixture must cover.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeRange {
    /// Nearest distance from the camera to a reflector pixel, metres (> 0).
    pub near: f64,
    /// Farthest distance, metres (≥ `near`).
    pub far: f64,
    /// Smallest GGX alpha of the plane's rough members (> 0).
    pub min_alpha: f64,
    /// Largest GGX alpha.
    pub max_alpha: f64,
}

/// Standard deviations of the mixture's components, metres, log-spaced from the lobe's
/// footprint at the nearest pixel of the smallest alpha to four times the footprint at
/// the farthest pixel of the largest alpha, stretched for grazing views (`1 / cos`, at most
/// 10): the footprint of a lobe of angular width `2α` at distance `D` is about `2αD`.
pub fn component_scales(range: &LobeRange, grazing_cos: f64, components: u32) -> Vec<f64> {
    let k = components.clamp(1, 16);
    let lo = 2.0 * range.min_alpha * range.near;
    let hi = 8.0 * range.max_alpha * range.far / grazing_cos.clamp(0.1, 1.0);
    let hi = hi.max(lo * 1.0001);
    (0..k)
        .map(|i| {
            let t = if k == 1 { 1.0 } else { f64::from(i) / f64::from(k - 1) };
            lo * (hi / lo).powf(t)
        })
        .collect()
}

/// The `samples` eye points of one plane and their views.
///
/// Component `j mod K` of the mixture places point `j` with a Box–Muller transform of a
/// stratified radius and a van der Corput angle (deterministic: the same frame gives the
/// same image). Returns `None` when the camera is not strictly on the reflecting side.
pub fn glossy_views(
    camera: &Camera,
    aspect: f64,
    plane: &MirrorPlane,
    scales: &[f64],
    samples: u32,
) -> Option<Vec<GlossyView>> {
    let n = plane.normal;
    let d_rel = n.dot(plane.point - camera.position);
    if d_rel >= -1e-6 || scales.is_empty() {
        return None;
    }
    // The mirrored eye, camera-relative: 2 d_rel n (the camera is at the origin).
    let centre = 2.0 * d_rel * n;
    let (t, b) = n.any_orthonormal_pair();
    let k = scales.len() as u32;
    // Component c places `counts[c]` points (j mod K = c); its mixture weight is their share.
    let counts: Vec<u32> = (0..k).map(|c| samples.saturating_sub(c).div_ceil(k)).collect();
    let weights: Vec<f64> = counts.iter().map(|&m| f64::from(m) / f64::from(samples.max(1))).collect();
    let main = camera.clip_from_relative(aspect as f32).as_dmat4();
    let mut views = Vec::with_capacity(samples as usize);
    for j in 0..samples {
        let (c, i) = (j % k, j / k);
        let s = scales[c as usize];
        let u = (f64::from(i) + 0.5) / f64::from(counts[c as usize]);
        let radius = s * (-2.0 * (1.0 - u).ln()).sqrt();
        let phi = std::f64::consts::TAU * f64::from(i.reverse_bits()) / 2f64.powi(32) + f64::from(c);
        let eye = centre + radius * (phi.cos() * t + phi.sin() * b);
        let density = mixture_density(scales, &weights, (eye - centre).length());
        views.push(GlossyView {
            clip_from_rel: view_matrix(&main, camera, n, d_rel, eye),
            eye,
            inv_density: 1.0 / density.max(1e-300),
        });
    }
    Some(views)
}

/// Area density of the mixture of isotropic 2D Gaussians (standard deviations `scales`,
/// weights summing to 1) at distance `r` from their common centre, m⁻².
pub fn mixture_density(scales: &[f64], weights: &[f64], r: f64) -> f64 {
    scales
        .iter()
        .zip(weights)
        .map(|(s, w)| w * (-0.5 * r * r / (s * s)).exp() / (std::f64::consts::TAU * s * s))
        .sum()
}

/// The projection with centre `eye` (camera-relative, behind the plane `n · X = d_rel`)
/// that agrees with `main` on the plane, its depth row clipping at the plane (with the
/// mirrored view's margin) and growing along every ray: `depth = k σ / w` (standard) or
/// `1 − k σ / w` (reversed), `σ` the distance beyond the plane, `k` small enough that
/// everything in front of the camera's near plane stays below 1.
fn view_matrix(main: &DMat4, camera: &Camera, n: DVec3, d_rel: f64, eye: DVec3) -> DMat4 {
    let plane = DVec4::new(n.x, n.y, n.z, -d_rel);
    let e = eye.extend(1.0);
    let sigma_e = plane.dot(e);
    let rows = main.transpose();
    let bend = |row: DVec4| row - plane * (row.dot(e) / sigma_e);
    let (x, y, w) = (bend(rows.x_axis), bend(rows.y_axis), bend(rows.w_axis));
    let margin = MIRROR_SURFACE_MARGIN + MIRROR_SURFACE_MARGIN_PER_METRE * -d_rel;
    let k = 0.999 * f64::from(camera.projection.near) / (-sigma_e + margin);
    let clip = (plane - DVec4::new(0.0, 0.0, 0.0, margin)) * k;
    let z = match camera.projection.depth {
        DepthMode::Standard => clip,
        DepthMode::Reversed => w - clip,
    };
    DMat4::from_cols(x, y, z, w).transpose()
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use ppr_runtime::Projection;

    use super::*;
    use crate::mirror_camera::{MirrorClipping, mirrored_view};

    fn camera(depth: DepthMode) -> Camera {
        let projection = Projection { depth, far: Some(100.0), ..Projection::default() };
        Camera::look_at(DVec3::new(3.0, 2.0, 5.0), DVec3::new(3.0, 0.0, 0.0), Vec3::Y, projection)
    }

    fn floor() -> MirrorPlane {
        MirrorPlane { point: DVec3::new(0.0, 0.0, 0.0), normal: DVec3::Y }
    }

    fn ndc(m: &DMat4, p: DVec3) -> DVec3 {
        let c = *m * p.extend(1.0);
        c.truncate() / c.w
    }

    #[test]
    fn plane_points_land_where_the_main_view_sees_them_and_depth_clips_at_the_plane() {
        for depth in [DepthMode::Standard, DepthMode::Reversed] {
            let cam = camera(depth);
            let main = cam.clip_from_relative(1.5).as_dmat4();
            let scales = [0.05, 0.5];
            let views = glossy_views(&cam, 1.5, &floor(), &scales, 8).expect("floor is below the camera");
            let near = if depth == DepthMode::Standard { 0.0 } else { 1.0 };
            for v in &views {
                assert!(v.eye.y + cam.position.y < 0.0, "eye behind the floor: {:?}", v.eye);
                for p in [DVec3::new(3.3, 0.0, -1.0), DVec3::new(2.0, 0.0, 1.0)] {
                    let rel = p - cam.position;
                    let (a, b) = (ndc(&main, rel), ndc(&v.clip_from_rel, rel));
                    assert!((a.truncate() - b.truncate()).length() < 1e-6, "{depth:?}: {a} vs {b}");
                    assert!((b.z - near).abs() < 1e-3, "{depth:?}: plane depth {}", b.z);
                }
                // Along the ray from the eye through a plane point, depth grows away from
                // the plane and stays inside [0, 1]; the eye's side is clipped.
                let x = DVec3::new(3.3, 0.0, -1.0) - cam.position;
                let dir = (x - v.eye).normalize();
                let zs: Vec<f64> =
                    [0.5, 2.0, 50.0, 1e4].iter().map(|t| ndc(&v.clip_from_rel, x + dir * t).z).collect();
                for pair in zs.windows(2) {
                    let grows =
                        if depth == DepthMode::Standard { pair[1] > pair[0] } else { pair[1] < pair[0] };
                    assert!(grows && (0.0..=1.0).contains(&pair[1]), "{depth:?}: {zs:?}");
                }
                let behind = ndc(&v.clip_from_rel, x - dir * 0.1).z;
                assert!(if depth == DepthMode::Standard { behind < 0.0 } else { behind > 1.0 }, "{behind}");
            }
        }
    }

    #[test]
    fn the_mirrored_eye_gives_the_mirrored_view() {
        let cam = camera(DepthMode::Standard);
        let mirrored = mirrored_view(&cam, 1.5, &floor(), MirrorClipping::Oblique).expect("visible");
        let main = cam.clip_from_relative(1.5).as_dmat4();
        let d_rel = floor().normal.dot(floor().point - cam.position);
        let m = view_matrix(&main, &cam, DVec3::Y, d_rel, 2.0 * d_rel * DVec3::Y);
        for p in [DVec3::new(1.0, 0.7, -2.0), DVec3::new(4.0, 2.5, 0.5)] {
            let rel = p - cam.position;
            let (a, b) = (ndc(&mirrored.clip_from_rel, rel), ndc(&m, rel));
            assert!((a.truncate() - b.truncate()).length() < 1e-6, "{a} vs {b}");
        }
    }

    #[test]
    fn the_mixture_density_integrates_to_one_and_scales_cover_the_range() {
        let scales =
            component_scales(&LobeRange { near: 1.0, far: 20.0, min_alpha: 0.04, max_alpha: 0.04 }, 0.5, 6);
        assert_eq!(scales.len(), 6);
        assert!((scales[0] - 0.08).abs() < 1e-12 && (scales[5] - 12.8).abs() < 1e-9, "{scales:?}");
        let dr = 1e-3;
        let total: f64 = (0..200_000)
            .map(|i| {
                let r = (f64::from(i) + 0.5) * dr;
                mixture_density(&scales, &[1.0 / 6.0; 6], r) * std::f64::consts::TAU * r * dr
            })
            .sum();
        assert!((total - 1.0).abs() < 1e-3, "{total}");
    }
}
