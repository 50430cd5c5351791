//! Convex polygons of a region, in the plane's 2-D frame and in 3-D (local coordinates),
//! clipped by lines of that frame.

use glam::{DVec2, DVec3};

/// A convex polygon (a triangle, or a triangle clipped by cut lines). Each vertex has its
/// 2-D frame coordinates and its 3-D position (interpolated when created by a clip).
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Vertices in the plane's frame.
    pub flat: Vec<DVec2>,
    /// The same vertices in 3-D.
    pub spatial: Vec<DVec3>,
    /// Perceptual roughness of the triangle it came from (kept by clips; see
    /// `roughness.rs`).
    pub roughness: f64,
}

impl Polygon {
    /// Absolute area in the plane's frame (shoelace).
    pub fn area(&self) -> f64 {
        let n = self.flat.len();
        let mut twice = 0.0;
        for i in 0..n {
            twice += self.flat[i].perp_dot(self.flat[(i + 1) % n]);
        }
        0.5 * twice.abs()
    }

    /// Whether every vertex is on the kept side of the cut of [`Polygon::clip`] (which then
    /// returns the polygon unchanged).
    pub fn keeps_all(&self, dir: DVec2, limit: f64, keep_below: bool) -> bool {
        let side = |p: DVec2| if keep_below { limit - dir.dot(p) } else { dir.dot(p) - limit };
        self.flat.iter().all(|&p| side(p) >= 0.0)
    }

    /// The part where `dir · p <= limit` (`keep_below`) or `>= limit`; `None` when empty.
    pub fn clip(&self, dir: DVec2, limit: f64, keep_below: bool) -> Option<Polygon> {
        let side = |p: DVec2| if keep_below { limit - dir.dot(p) } else { dir.dot(p) - limit };
        let n = self.flat.len();
        if self.keeps_all(dir, limit, keep_below) {
            return Some(self.clone());
        }
        let mut out = Polygon {
            flat: Vec::with_capacity(n + 1),
            spatial: Vec::with_capacity(n + 1),
            roughness: self.roughness,
        };
        for i in 0..n {
            let j = (i + 1) % n;
            let (si, sj) = (side(self.flat[i]), side(self.flat[j]));
            if si >= 0.0 {
                out.flat.push(self.flat[i]);
                out.spatial.push(self.spatial[i]);
            }
            if (si >= 0.0) != (sj >= 0.0) {
                let t = si / (si - sj);
                out.flat.push(self.flat[i].lerp(self.flat[j], t));
                out.spatial.push(self.spatial[i].lerp(self.spatial[j], t));
            }
        }
        (out.flat.len() >= 3).then_some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polygon {
        let flat = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let spatial = flat.iter().map(|p| DVec3::new(p.x, 5.0, p.y)).collect();
        Polygon { flat, spatial, roughness: 0.5 }
    }

    #[test]
    fn clips_keep_area_and_lift_points() {
        let s = square();
        assert_eq!(s.area(), 1.0);
        let below = s.clip(DVec2::X, 0.25, true).unwrap();
        let above = s.clip(DVec2::X, 0.25, false).unwrap();
        assert!((below.area() - 0.25).abs() < 1e-12 && (above.area() - 0.75).abs() < 1e-12);
        for (f, p) in below.flat.iter().zip(&below.spatial) {
            assert!((DVec3::new(f.x, 5.0, f.y) - *p).length() < 1e-12);
        }
        assert!(s.clip(DVec2::X, -1.0, true).is_none());
        assert_eq!(s.clip(DVec2::X, 2.0, true).unwrap(), s);
        let diag = DVec2::ONE.normalize();
        assert!((s.clip(diag, diag.dot(DVec2::splat(0.5)), true).unwrap().area() - 0.5).abs() < 1e-12);
    }
}
