//! Planes and the area-weighted least-squares plane fit of a set of triangles, computed
//! relative to a local origin so that levels far from the world origin keep precision.

use glam::{DMat3, DVec2, DVec3};

/// A plane with an orthonormal in-plane frame: `u × v = normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point of the plane (the fitted centroid).
    pub origin: DVec3,
    /// Unit normal, pointing to the reflecting side.
    pub normal: DVec3,
    /// First in-plane axis.
    pub u: DVec3,
    /// Second in-plane axis.
    pub v: DVec3,
}

impl Plane {
    /// The plane through `origin` with `normal` and a deterministic in-plane frame.
    pub fn new(origin: DVec3, normal: DVec3) -> Self {
        let normal = normal.normalize();
        // Start from the world axis least aligned with the normal.
        let a = normal.abs();
        let helper = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let u = (helper - normal * helper.dot(normal)).normalize();
        let v = normal.cross(u);
        Self { origin, normal, u, v }
    }

    /// Signed distance of `p` from the plane (positive on the normal's side).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }

    /// Coordinates of `p` in the plane's frame.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.v))
    }

    /// The point of the plane with frame coordinates `q`.
    pub fn lift(&self, q: DVec2) -> DVec3 {
        self.origin + self.u * q.x + self.v * q.y
    }

    /// The in-plane direction with frame coordinates `d`.
    pub fn lift_direction(&self, d: DVec2) -> DVec3 {
        self.u * d.x + self.v * d.y
    }
}

/// Area-weighted moments of triangles, accumulated relative to a fixed local origin.
#[derive(Clone, Debug)]
pub struct PlaneAccumulator {
    origin: DVec3,
    area: f64,
    first: DVec3,
    second: DMat3,
    /// Sum of `(b - a) × (c - a)`: decides the reflecting side by area-weighted majority.
    winding: DVec3,
    /// Sum of `|(b - a) × (c - a)|`.
    winding_abs: f64,
}

impl PlaneAccumulator {
    /// An empty accumulator; `origin` should be near the triangles (e.g. the first one).
    pub fn new(origin: DVec3) -> Self {
        Self {
            origin,
            area: 0.0,
            first: DVec3::ZERO,
            second: DMat3::ZERO,
            winding: DVec3::ZERO,
            winding_abs: 0.0,
        }
    }

    /// Total area added so far.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Adds a triangle (front face counter-clockwise).
    pub fn add(&mut self, [a, b, c]: [DVec3; 3]) {
        let cross = (b - a).cross(c - a);
        let area = 0.5 * cross.length();
        let (a, b, c) = (a - self.origin, b - self.origin, c - self.origin);
        let s = a + b + c;
        // Exact second moment of a uniform triangle: A/12 (Σ vᵢvᵢᵀ + s sᵀ).
        let outer = |x: DVec3| DMat3::from_cols(x * x.x, x * x.y, x * x.z);
        self.second += (outer(a) + outer(b) + outer(c) + outer(s)) * (area / 12.0);
        self.first += s * (area / 3.0);
        self.area += area;
        self.winding += cross;
        self.winding_abs += cross.length();
    }

    /// Adds everything `other` accumulated (its moments moved to this origin).
    pub fn merge(&mut self, other: &PlaneAccumulator) {
        let d = other.origin - self.origin;
        let outer = |a: DVec3, b: DVec3| DMat3::from_cols(a * b.x, a * b.y, a * b.z);
        // Σ∫(x + d)(x + d)ᵀ = second + first dᵀ + d firstᵀ + area d dᵀ.
        self.second +=
            other.second + outer(other.first, d) + outer(d, other.first) + outer(d, d) * other.area;
        self.first += other.first + d * other.area;
        self.area += other.area;
        self.winding += other.winding;
        self.winding_abs += other.winding_abs;
    }

    /// The least-squares plane: through the area centroid, normal along the covariance's
    /// smallest eigenvector, oriented to the side most of the area faces.
    /// `None` when no area was added.
    pub fn fit(&self) -> Option<Plane> {
        if !(self.area > 0.0) {
            return None;
        }
        let c = self.first / self.area;
        let cov = self.second - DMat3::from_cols(c * c.x, c * c.y, c * c.z) * self.area;
        let mut normal = smallest_eigenvector(cov);
        let side = normal.dot(self.winding);
        if side.abs() > 1e-9 * self.winding_abs {
            if side < 0.0 {
                normal = -normal;
            }
        } else if normal.to_array().iter().fold(0.0f64, |m, &x| if x.abs() > m.abs() { x } else { m }) < 0.0 {
            // A tie (e.g. double-sided duplicates): a deterministic choice.
            normal = -normal;
        }
        Some(Plane::new(self.origin + c, normal))
    }
}

/// Unit eigenvector of the smallest eigenvalue of a symmetric 3×3 matrix (Jacobi rotations).
pub fn smallest_eigenvector(m: DMat3) -> DVec3 {
    let mut a = m.to_cols_array_2d();
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-30 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J with J the rotation in the (p, q) plane.
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * row_p[k] - s * row_q[k];
                a[q][k] = s * row_p[k] + c * row_q[k];
            }
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let k = (0..3).min_by(|&i, &j| a[i][i].total_cmp(&a[j][j])).unwrap_or(0);
    let e = DVec3::new(v[0][k], v[1][k], v[2][k]);
    e.try_normalize().unwrap_or(DVec3::Z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_right_handed() {
        for n in [DVec3::X, DVec3::NEG_Y, DVec3::new(1.0, 2.0, -3.0), DVec3::new(1e-9, 1.0, 0.0)] {
            let p = Plane::new(DVec3::ONE, n);
            assert!((p.u.length() - 1.0).abs() < 1e-12 && (p.v.length() - 1.0).abs() < 1e-12);
            assert!(p.u.dot(p.normal).abs() < 1e-12 && p.v.dot(p.normal).abs() < 1e-12);
            assert!((p.u.cross(p.v) - p.normal).length() < 1e-12);
            let q = DVec2::new(0.3, -2.0);
            assert!((p.project(p.lift(q)) - q).length() < 1e-12);
        }
    }

    #[test]
    fn eigenvector_of_known_matrices() {
        let m = DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0));
        assert!((smallest_eigenvector(m).abs() - DVec3::Y).length() < 1e-12);
        let r = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 1.1, -0.7);
        let rm = DMat3::from_quat(r);
        let m = rm * DMat3::from_diagonal(DVec3::new(5.0, 4.0, 1e-6)) * rm.transpose();
        let e = smallest_eigenvector(m);
        assert!(e.dot(rm * DVec3::Z).abs() > 1.0 - 1e-12);
    }

    #[test]
    fn fits_far_noisy_planes_and_majority_side() {
        // A tilted plane 10 km away, with 1e-4 noise, mixed windings (3 up, 1 down).
        let far = DVec3::new(1e4, -3e3, 7e3);
        let n = DVec3::new(0.2, 1.0, 0.1).normalize();
        let plane = Plane::new(far, n);
        let mut acc = PlaneAccumulator::new(far);
        let mut seed = 1u64;
        let mut noise = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2e-4
        };
        for i in 0..40 {
            let q = DVec2::new(i as f64 * 0.5, (i % 7) as f64);
            let mut t = [q, q + DVec2::X, q + DVec2::Y].map(|q| plane.lift(q) + n * noise());
            if i % 4 == 3 {
                t.swap(1, 2);
            }
            acc.add(t);
        }
        let fit = acc.fit().unwrap();
        assert!(fit.normal.dot(n) > 1.0 - 1e-6, "normal {:?}", fit.normal);
        assert!(plane.signed_distance(fit.origin).abs() < 1e-4);
    }

    #[test]
    fn merged_accumulators_fit_like_one() {
        let tris = [
            [DVec3::ZERO, DVec3::X, DVec3::Z],
            [DVec3::new(3.0, 0.1, 1.0), DVec3::new(4.0, 0.0, 1.0), DVec3::new(3.0, 0.0, 2.0)],
            [DVec3::new(-2.0, 0.05, 5.0), DVec3::new(-1.0, 0.0, 5.0), DVec3::new(-2.0, 0.0, 6.0)],
        ];
        let mut all = PlaneAccumulator::new(DVec3::ZERO);
        let (mut a, mut b) =
            (PlaneAccumulator::new(DVec3::ONE), PlaneAccumulator::new(DVec3::new(9.0, -4.0, 2.0)));
        for (k, t) in tris.iter().enumerate() {
            all.add(*t);
            if k == 0 { a.add(*t) } else { b.add(*t) }
        }
        a.merge(&b);
        let (p, q) = (all.fit().unwrap(), a.fit().unwrap());
        assert!(p.normal.dot(q.normal) > 1.0 - 1e-12 && (p.origin - q.origin).length() < 1e-9);
    }
}
