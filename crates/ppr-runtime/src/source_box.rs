//! The screen box of the pixels that may reflect into a shape, for the projection pass to
//! skip a shape in the tiles outside it.
//!
//! A point `p` in front of the plane is reflected into the rectangle when the ray from the
//! camera to its mirror image crosses the rectangle, i.e. when `p` lies in the pyramid
//! from the *mirrored* camera through the rectangle, beyond it. That pyramid is the
//! positive hull, in homogeneous coordinates, of the rectangle's four corners `(r, 1)` and
//! of the four directions `(r − e', 0)` from the mirrored camera `e'` through them. Its
//! boundary is five faces (the rectangle and four unbounded sides); each is clipped
//! against the view frustum's side planes in clip space (Sutherland–Hodgman on homogeneous
//! vectors, which handles the points at infinity), and the box of what is left, projected,
//! bounds every pixel whose position can reflect into the rectangle, at any depth. The
//! near and far planes are not clipped against: the box is conservative.
//!
//! That holds while the camera is outside the pyramid (every ray through it then enters
//! through a face). A camera inside it (in front of the plane, straight over the
//! rectangle: a player standing on a mirror floor) sees the pyramid around itself, so
//! every pixel may reflect into the shape and the box is the whole screen.

use glam::{DMat4, DVec3, DVec4, Mat4, Vec3};

use crate::plan::ScreenRect;
use crate::shapes::ShapeSource;

/// Pixels added on every side, for the f32 rounding of per-pixel positions.
const MARGIN_PX: f64 = 1.0;

/// The screen box (inclusive min, exclusive max) of the pixels that may reflect into
/// `shape` for a camera at `eye` with `clip_from_rel`; empty (`min == max`) when no
/// pixel can.
pub fn source_rect(shape: &ShapeSource, eye: DVec3, clip_from_rel: &Mat4, size: [u32; 2]) -> ScreenRect {
    SourceBoxes::new(eye, clip_from_rel, size).rect(shape)
}

/// Source boxes for one view: [`source_rect`] with the view's matrix converted once, and
/// the union of many shapes' boxes (a parallel tree's members) that skips the shapes a
/// cheap bound shows cannot add to it.
pub struct SourceBoxes {
    eye: DVec3,
    m: DMat4,
    size: [u32; 2],
}

impl SourceBoxes {
    pub fn new(eye: DVec3, clip_from_rel: &Mat4, size: [u32; 2]) -> Self {
        let m = DMat4::from_cols_array(&clip_from_rel.to_cols_array().map(f64::from));
        Self { eye, m, size }
    }

    fn full(&self) -> ScreenRect {
        ScreenRect { min: [0, 0], max: self.size }
    }

    /// The pyramid's four corners (points, the rectangle's) and its four edge directions
    /// from the mirrored camera through them (points at infinity), in clip space. The
    /// matrix is linear, so four products serve the eight: the centre and the two half axes
    /// give the corners, and a direction is its corner less the mirrored camera's image
    /// (`M (r − e', 0) = M (r, 1) − M (e', 1)`).
    ///
    /// The half axes' products come from `axes` where the last shape it saw had the same
    /// axes and extents (a flight's treads, a facade's windows): the same products.
    fn pyramid(&self, shape: &ShapeSource, axes: &mut HalfAxes) -> ([DVec4; 4], [DVec4; 4]) {
        let n = shape.normal.as_dvec3();
        let mirrored_eye = 2.0 * shape.plane_dist_from(self.eye) * n;
        let centre = self.m * (shape.center - self.eye).extend(1.0);
        let key = (shape.axis_u, shape.axis_v, shape.half_extents);
        if axes.key != Some(key) {
            axes.u = self.m * (shape.axis_u.as_dvec3() * f64::from(shape.half_extents[0])).extend(0.0);
            axes.v = self.m * (shape.axis_v.as_dvec3() * f64::from(shape.half_extents[1])).extend(0.0);
            axes.key = Some(key);
        }
        let (u, v) = (axes.u, axes.v);
        // The corners in `ShapeSource::corners`' order.
        let c = [centre - u - v, centre + u - v, centre + u + v, centre - u + v];
        let e = self.m * mirrored_eye.extend(1.0);
        (c, c.map(|c| c - e))
    }

    /// [`source_rect`]. Where all eight of the pyramid's points lie in front of the camera
    /// (w > 0) the pyramid projects onto the convex hull of their projections, so the box
    /// of that hull clipped to the screen, in two dimensions, is the box (where every point
    /// lies on the screen, their own box: the hull's extreme vertices are theirs);
    /// otherwise its five faces are clipped in homogeneous coordinates (points at infinity
    /// and behind the camera included).
    pub fn rect(&self, shape: &ShapeSource) -> ScreenRect {
        self.rect_unless_inside(shape, None, &mut HalfAxes::default()).expect("no box to be inside")
    }

    /// [`Self::rect`], or `None` where a bound on it, a pixel wider, lies inside `known`
    /// (then the rect does too). The bounds, cheapest first: the pyramid's eight points
    /// ([`Self::points_inside`]: their box holds the box of their hull clipped to the
    /// screen), then the box of the hull clipped to the screen, which the rect widens.
    fn rect_unless_inside(
        &self,
        shape: &ShapeSource,
        known: Option<ScreenRect>,
        axes: &mut HalfAxes,
    ) -> Option<ScreenRect> {
        if eye_over_rectangle(shape, self.eye) {
            let full = self.full();
            return if known == Some(full) { None } else { Some(full) };
        }
        let (c, d) = self.pyramid(shape, axes);
        if known.is_some_and(|k| self.points_inside(&d, k) && self.points_inside(&c, k)) {
            return None;
        }
        let Some(points) = self.projected(c, d) else {
            return Some(self.rect_by_clipping(c, d));
        };
        let screen = self.size.map(f64::from);
        let inside = |(lo, hi): ([f64; 2], [f64; 2])| {
            known.is_some_and(|k| contains(k, self.widened(lo, hi, MARGIN_PX + 1.0)))
        };
        let (lo, hi) = points_box(&points);
        if (0..2).all(|a| lo[a] >= 0.0 && hi[a] <= screen[a]) {
            return Some(self.widened(lo, hi, MARGIN_PX));
        }
        if known.is_some_and(|k| self.clipped_points_inside(&points, k)) {
            return None;
        }
        match clipped_box(&convex_hull(points), screen) {
            Some(Some(b)) if inside(b) => None,
            Some(Some((lo, hi))) => Some(self.widened(lo, hi, MARGIN_PX)),
            Some(None) => Some(ScreenRect { min: [0, 0], max: [0, 0] }),
            // Rounding made the hull's clipping overflow.
            None => Some(self.rect_by_clipping(c, d)),
        }
    }

    /// Per axis, the pixel range a shape's points must keep to for its rect to lie in `k`:
    /// `MARGIN_PX + 1` inside each side of `k`, unbounded at a side that is the screen's
    /// edge (the rect is clipped to the screen there).
    fn skip_ranges(&self, k: ScreenRect) -> [[f64; 2]; 2] {
        let m = MARGIN_PX + 1.0;
        std::array::from_fn(|a| {
            let lo = if k.min[a] == 0 { f64::NEG_INFINITY } else { f64::from(k.min[a]) + m };
            let hi = if k.max[a] >= self.size[a] { f64::INFINITY } else { f64::from(k.max[a]) - m };
            [lo, hi]
        })
    }

    /// Whether every one of `points` (four of the pyramid's eight) lies in front of the
    /// camera and at least `MARGIN_PX + 1` pixels inside each side of `k` that is not the
    /// screen's edge, so that, with the other four, the rect (its hull's box clipped to the
    /// screen, `MARGIN_PX` wider) lies in `k`. Compared in clip space, without dividing by w: `x / w ≥ t ⇔ x ≥ t w` for
    /// `w > 0` (its rounding is far below the spare pixel).
    fn points_inside(&self, points: &[DVec4; 4], k: ScreenRect) -> bool {
        let size = self.size.map(f64::from);
        // Per axis, the NDC range the points must keep to; y runs up in NDC and down in
        // pixels.
        let ndc = |a: usize, px: f64| 2.0 * px / size[a] - 1.0;
        let [px, py] = self.skip_ranges(k);
        let x = [ndc(0, px[0]), ndc(0, px[1])];
        let y = [-ndc(1, py[1]), -ndc(1, py[0])];
        points.iter().all(|v| {
            v.w > 1e-9 * v.abs().max_element()
                && v.x >= x[0] * v.w
                && v.x <= x[1] * v.w
                && v.y >= y[0] * v.w
                && v.y <= y[1] * v.w
        })
    }

    /// Whether the hull of `points` (in pixels), clipped to the screen, lies at least
    /// `MARGIN_PX + 1` pixels inside each side of `k` that is not the screen's edge, found
    /// without the hull: the points are clipped by the screen's edges that `k` shares (a
    /// convex hull cut by a line is the hull of its points on the inner side and of the
    /// crossings of the segments from those to the others), then tested against the other
    /// sides. A tread seen from above has its edge directions far above the screen: only
    /// the top edge brings its hull back within the union's width.
    fn clipped_points_inside(&self, points: &[[f64; 2]; 8], k: ScreenRect) -> bool {
        // At most 8 points, then 4 + 4·4 after one edge; beyond 32 the hull is cheaper.
        const CAPACITY: usize = 32;
        let size = self.size.map(f64::from);
        let edges = [
            (0, k.min[0] == 0, 0.0, 1.0),
            (0, k.max[0] >= self.size[0], size[0], -1.0),
            (1, k.min[1] == 0, 0.0, 1.0),
            (1, k.max[1] >= self.size[1], size[1], -1.0),
        ];
        let [x, y] = self.skip_ranges(k);
        let within = |p: &[f64; 2]| p[0] >= x[0] && p[0] <= x[1] && p[1] >= y[0] && p[1] <= y[1];
        let crossing = |axis: usize, edge: f64, p: &[f64; 2], q: &[f64; 2]| {
            let other = 1 - axis;
            let t = (edge - p[axis]) / (q[axis] - p[axis]);
            let across = p[other] + (q[other] - p[other]) * t;
            if axis == 0 { [edge, across] } else { [across, edge] }
        };
        let mut shared = edges.iter().filter(|e| e.1);
        match (shared.next(), shared.next()) {
            // Nothing to clip: `points_inside` has decided.
            (None, _) => return false,
            // One edge (a flight's treads seen from above: the top): the points within it
            // and the crossings are tested as they come, without keeping them (eight points
            // give at most 20, within the capacity, so the answer is the clipping's).
            (Some(&(axis, _, edge, sign)), None) => {
                let inside = |p: &[f64; 2]| sign * (p[axis] - edge) >= 0.0;
                // A crossing lies between its segment's ends across the edge: where both
                // are within the other axis's range, so is the crossing (to its rounding,
                // far below the spare pixel), without the division.
                let other = 1 - axis;
                let range = [x, y][other];
                let within_other = |v: f64| v >= range[0] && v <= range[1];
                let mut any = false;
                for p in points.iter().filter(|p| inside(p)) {
                    any = true;
                    if !within(p)
                        || points.iter().any(|q| {
                            !inside(q) && !within_other(q[other]) && !within(&crossing(axis, edge, p, q))
                        })
                    {
                        return false;
                    }
                }
                return any;
            }
            _ => {}
        }
        let mut bufs = [[[0.0f64; 2]; CAPACITY]; 2];
        bufs[0][..8].copy_from_slice(points);
        let (mut len, mut cur) = (8, 0);
        for (axis, shared, edge, sign) in edges {
            if !shared {
                continue;
            }
            let (src, dst) = match &mut bufs {
                [a, b] if cur == 0 => (&*a, b),
                [a, b] => (&*b, a),
            };
            let src = &src[..len];
            let inside = |p: &[f64; 2]| sign * (p[axis] - edge) >= 0.0;
            let ins = src.iter().filter(|p| inside(p)).count();
            if ins == 0 || ins + ins * (len - ins) > CAPACITY {
                // Nothing within the edge (the hull decides), or too many crossings.
                return false;
            }
            let mut n = 0;
            for p in src.iter().filter(|p| inside(p)) {
                dst[n] = *p;
                n += 1;
                for q in src.iter().filter(|q| !inside(q)) {
                    dst[n] = crossing(axis, edge, p, q);
                    n += 1;
                }
            }
            (len, cur) = (n, 1 - cur);
        }
        bufs[cur][..len].iter().all(within)
    }

    /// The eight points in pixels, where every one lies in front of the camera (`None`
    /// otherwise, or where one is not finite).
    fn projected(&self, c: [DVec4; 4], d: [DVec4; 4]) -> Option<[[f64; 2]; 8]> {
        let [w, h] = self.size.map(f64::from);
        let mut points = [[0.0f64; 2]; 8];
        for (i, p) in points.iter_mut().enumerate() {
            let v = if i < 4 { c[i] } else { d[i - 4] };
            // On or behind the camera's plane, or NaN.
            if v.w.partial_cmp(&(1e-9 * v.abs().max_element())) != Some(std::cmp::Ordering::Greater) {
                return None;
            }
            // One division a point (x and y share it; its rounding is far below the box's
            // margin).
            let r = 1.0 / v.w;
            *p = [(v.x * r * 0.5 + 0.5) * w, (0.5 - v.y * r * 0.5) * h];
            if !(p[0].is_finite() && p[1].is_finite()) {
                return None;
            }
        }
        Some(points)
    }

    /// [`Self::rect`] by clipping the pyramid's five faces against the view's side planes
    /// in homogeneous coordinates (Sutherland–Hodgman), then projecting what is left. The
    /// side planes and the projection read x, y and w only, so the faces are clipped in
    /// those three; a plane that no point of a face lies outside of leaves the face as it
    /// is, and one that all four lie outside of leaves nothing (each point's planes found
    /// once, for every face it bounds).
    fn rect_by_clipping(&self, c: [DVec4; 4], d: [DVec4; 4]) -> ScreenRect {
        let points: [DVec3; 8] = std::array::from_fn(|i| xyw(if i < 4 { c[i] } else { d[i - 4] }));
        let outside = points.map(outside_planes);
        // The corners 0..4, the directions 4..8 (`pyramid`'s order).
        const FACES: [[usize; 4]; 5] = [[0, 1, 2, 3], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
        let [w, h] = self.size;
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        let mut bufs = [[DVec3::ZERO; CLIP_CAPACITY]; 2];
        for face in FACES {
            let codes = [outside[face[0]], outside[face[1]], outside[face[2]], outside[face[3]]];
            if codes[0] & codes[1] & codes[2] & codes[3] != 0 {
                continue;
            }
            let cut = codes[0] | codes[1] | codes[2] | codes[3];
            let quad = [points[face[0]], points[face[1]], points[face[2]], points[face[3]]];
            for &v in clip_to_view(&quad, cut, &mut bufs) {
                let scale = v.abs().max_element();
                // Only the zero vector survives the side planes with w = 0 (and NaN is skipped).
                // (The scale leaves out z: a point a hair in front of the camera's plane
                // with a large depth is kept, where the four-dimensional scale dropped it;
                // its x and y lie within ±w, on the screen, so the box only holds more.)
                if v.z.partial_cmp(&(1e-12 * scale)) != Some(std::cmp::Ordering::Greater) {
                    continue;
                }
                let px = [(v.x / v.z * 0.5 + 0.5) * f64::from(w), (0.5 - v.y / v.z * 0.5) * f64::from(h)];
                for a in 0..2 {
                    lo[a] = lo[a].min(px[a]);
                    hi[a] = hi[a].max(px[a]);
                }
            }
        }
        if lo[0] > hi[0] {
            return ScreenRect { min: [0, 0], max: [0, 0] };
        }
        if !lo.iter().chain(&hi).all(|x| x.is_finite()) {
            return self.full();
        }
        self.widened(lo, hi, MARGIN_PX)
    }

    /// The pixels of [lo, hi] widened by `margin` on every side, clamped to the screen.
    fn widened(&self, lo: [f64; 2], hi: [f64; 2], margin: f64) -> ScreenRect {
        let [w, h] = self.size;
        let clamp = |x: f64, max: u32| x.clamp(0.0, f64::from(max)) as u32;
        ScreenRect {
            min: [clamp((lo[0] - margin).floor(), w), clamp((lo[1] - margin).floor(), h)],
            max: [clamp((hi[0] + margin).ceil(), w), clamp((hi[1] + margin).ceil(), h)],
        }
    }

    /// The union of the boxes ([`Self::rect`]) of the `count` shapes `shape(0..count)`,
    /// the same rectangle as folding them in order with [`union_rect`], without computing
    /// most of them where they nest: the first and the last shape's boxes are computed
    /// first (a staircase's treads run from one end of it to the other), and a shape with a
    /// bound inside the union of the boxes computed so far cannot change the result and is
    /// skipped ([`Self::rect_unless_inside`]); the fold stops at the whole screen. The plan
    /// builds these boxes every frame, and at 10 000 treads they were most of its time.
    /// Returns the union and how many boxes it computed.
    pub fn union<'a>(&self, count: usize, shape: impl Fn(usize) -> &'a ShapeSource) -> (ScreenRect, usize) {
        let empty = ScreenRect { min: [0, 0], max: [0, 0] };
        if count == 0 {
            return (empty, 0);
        }
        let full = self.full();
        let ends = [self.rect(shape(0)), self.rect(shape(count - 1))];
        let mut computed = if count == 1 { 1 } else { 2 };
        // Every box computed so far; while it has area it stands for the final union,
        // which holds it (an empty box is never kept over a later one). The union of boxes
        // does not depend on their order (an empty one adds nothing).
        let mut known = union_rect(ends[0], ends[1]);
        let mut axes = HalfAxes::default();
        for k in 1..count.saturating_sub(1) {
            if known == full {
                break;
            }
            if let Some(r) = self.rect_unless_inside(shape(k), (known.area() > 0).then_some(known), &mut axes)
            {
                computed += 1;
                known = union_rect(known, r);
            }
        }
        (known, computed)
    }
}

/// The clip-space half axes of the last pyramid built ([`SourceBoxes::pyramid`]), by the
/// shape's axes and extents.
#[derive(Default)]
struct HalfAxes {
    key: Option<(Vec3, Vec3, [f32; 2])>,
    u: DVec4,
    v: DVec4,
}

/// The box of two boxes; an empty one (no area) adds nothing.
pub fn union_rect(a: ScreenRect, b: ScreenRect) -> ScreenRect {
    if a.area() == 0 {
        return b;
    }
    if b.area() == 0 {
        return a;
    }
    ScreenRect {
        min: [a.min[0].min(b.min[0]), a.min[1].min(b.min[1])],
        max: [a.max[0].max(b.max[0]), a.max[1].max(b.max[1])],
    }
}

/// A convex polygon in pixel coordinates, on the stack: the hull of eight points (clipped
/// by four lines, at most twelve vertices).
struct ScreenPolygon {
    p: [[f64; 2]; 8],
    len: usize,
}

impl ScreenPolygon {
    fn points(&self) -> &[[f64; 2]] {
        &self.p[..self.len]
    }
}

/// The convex hull of eight points, counter-clockwise (Andrew's monotone chain; collinear
/// points dropped).
fn convex_hull(mut points: [[f64; 2]; 8]) -> ScreenPolygon {
    points.sort_unstable_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let cross =
        |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    // Lower chain then upper chain: at most 9 + 8 points on the way (the last of each chain is
    // the first of the next, dropped), 8 at the end.
    let mut p = [[0.0; 2]; 17];
    let mut len = 0;
    for pass in 0..2 {
        let start = len;
        for k in 0..8 {
            let q = if pass == 0 { points[k] } else { points[7 - k] };
            while len >= start + 2 && cross(p[len - 2], p[len - 1], q) <= 0.0 {
                len -= 1;
            }
            p[len] = q;
            len += 1;
        }
        len -= 1;
    }
    let mut hull = ScreenPolygon { p: [[0.0; 2]; 8], len: len.min(8) };
    hull.p[..hull.len].copy_from_slice(&p[..hull.len]);
    hull
}

/// The box (lo, hi) of a convex polygon clipped to the screen [0, w] × [0, h]
/// (Sutherland–Hodgman, between two buffers): `Some(None)` when nothing is left, `None`
/// when rounding made the polygon cross a line more than twice and the buffers overflow
/// (the caller then clips in four dimensions).
fn clipped_box(poly: &ScreenPolygon, [w, h]: [f64; 2]) -> Option<Option<([f64; 2], [f64; 2])>> {
    const CAPACITY: usize = 12;
    let edges: [(usize, f64, f64); 4] = [(0, 0.0, 1.0), (0, w, -1.0), (1, 0.0, 1.0), (1, h, -1.0)];
    let mut bufs = [[[0.0f64; 2]; CAPACITY]; 2];
    let mut lens = [poly.len, 0];
    bufs[0][..poly.len].copy_from_slice(poly.points());
    let mut cur = 0;
    for (axis, at, sign) in edges {
        let n = lens[cur];
        if n == 0 {
            return Some(None);
        }
        let (first, second) = bufs.split_at_mut(1);
        let (src, dst) = if cur == 0 { (&first[0], &mut second[0]) } else { (&second[0], &mut first[0]) };
        let mut len = 0;
        for i in 0..n {
            if len + 2 > CAPACITY {
                return None;
            }
            let (a, b) = (src[i], src[if i + 1 == n { 0 } else { i + 1 }]);
            let (fa, fb) = (sign * (a[axis] - at), sign * (b[axis] - at));
            if fa >= 0.0 {
                dst[len] = a;
                len += 1;
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                let t = fa / (fa - fb);
                dst[len] = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
                len += 1;
            }
        }
        cur = 1 - cur;
        lens[cur] = len;
    }
    let pts = &bufs[cur][..lens[cur]];
    if pts.is_empty() {
        return Some(None);
    }
    Some(Some(points_box(pts)))
}

/// The box (lo, hi) of `points`.
fn points_box(points: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in points {
        for a in 0..2 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    (lo, hi)
}

/// Whether `outer` holds all of `inner`.
fn contains(outer: ScreenRect, inner: ScreenRect) -> bool {
    (0..2).all(|a| outer.min[a] <= inner.min[a] && inner.max[a] <= outer.max[a])
}

/// Whether `eye` lies in the shape's mirrored pyramid: in front of the plane, its foot on
/// the plane inside the rectangle (with a relative margin, so that a camera on the
/// pyramid's boundary counts as inside).
fn eye_over_rectangle(shape: &ShapeSource, eye: DVec3) -> bool {
    let height = -shape.plane_dist_from(eye);
    let rel = eye - shape.center;
    let margin = 1e-4 * (1.0 + rel.length());
    let inside = |axis: glam::Vec3, half: f32| rel.dot(axis.as_dvec3()).abs() <= f64::from(half) + margin;
    height > 0.0 && inside(shape.axis_u, shape.half_extents[0]) && inside(shape.axis_v, shape.half_extents[1])
}

/// Most vertices of a quadrilateral clipped by four planes: a polygon of n vertices leaves a
/// plane with at most 1.5 n (half of them kept, a crossing on every edge), 4 → 6 → 9 → 13 →
/// 19, whatever the input (a convex face gains at most one a plane).
const CLIP_CAPACITY: usize = 19;

/// A clip-space vector's x, y and w (as x, y, z): what the side planes and the projection
/// to the screen read.
fn xyw(v: DVec4) -> DVec3 {
    DVec3::new(v.x, v.y, v.w)
}

/// The value of the frustum's side plane `plane` (0..4: left, right, bottom, top) at `v`
/// (x, y, w), `>= 0` inside.
fn side_value(plane: usize, v: DVec3) -> f64 {
    match plane {
        0 => v.z + v.x,
        1 => v.z - v.x,
        2 => v.z + v.y,
        _ => v.z - v.y,
    }
}

/// The side planes `v` (x, y, w) lies outside of, a bit each (bit `p` where `side_value(p)`
/// is not `>= 0`, NaN included: the clipping drops what is not).
fn outside_planes(v: DVec3) -> u8 {
    (0..4).fold(0, |m, p| m | u8::from(side_value(p, v).partial_cmp(&0.0).is_none_or(|o| o.is_lt())) << p)
}

/// Clips a quadrilateral of homogeneous vectors (x, y, w; its positive hull) against the
/// frustum's side planes whose bits are set in `cut` (Sutherland–Hodgman, in plane order),
/// in `bufs`, without allocation: the plan clips five faces for every tested shape whose
/// pyramid reaches behind the camera, every frame. Planes left out of `cut` are those no
/// vertex lies outside of, which would keep every vertex.
fn clip_to_view<'a>(quad: &'a [DVec3; 4], cut: u8, bufs: &'a mut [[DVec3; CLIP_CAPACITY]; 2]) -> &'a [DVec3] {
    let [first, second] = bufs;
    // Where the polygon is: the quadrilateral itself until a plane cuts it, then the
    // buffers in turn.
    let (mut at, mut len) = (0, 4);
    for plane in 0..4 {
        if cut & (1 << plane) == 0 {
            continue;
        }
        if len == 0 {
            break;
        }
        let (src, dst): (&[DVec3], &mut [DVec3; CLIP_CAPACITY]) = match at {
            0 => (quad, &mut *first),
            1 => (&first[..len], &mut *second),
            _ => (&second[..len], &mut *first),
        };
        let mut out = 0;
        for i in 0..len {
            let (a, b) = (src[i], src[if i + 1 == len { 0 } else { i + 1 }]);
            let (fa, fb) = (side_value(plane, a), side_value(plane, b));
            if fa >= 0.0 {
                dst[out] = a;
                out += 1;
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                dst[out] = a + (b - a) * (fa / (fa - fb));
                out += 1;
            }
        }
        (at, len) = (if at == 1 { 2 } else { 1 }, out);
    }
    match at {
        0 => quad,
        1 => &first[..len],
        _ => &second[..len],
    }
}

#[cfg(test)]
mod tests {
    use glam::{Quat, Vec3};
    use ppr_format::ReflectorKind;

    use super::*;
    use crate::camera::{Camera, Projection};

    fn floor(half: f32) -> ShapeSource {
        ShapeSource {
            id: 0,
            kind: ReflectorKind::Opaque,
            enabled: true,
            center: DVec3::ZERO,
            axis_u: Vec3::X,
            axis_v: Vec3::NEG_Z,
            normal: Vec3::Y,
            half_extents: [half, half],
            parallel_group: 0,
            normal_map: false,
            roughness: 0.0,
        }
    }

    /// Brute force: pixel centres whose ray, at some depth, holds a point that the floor
    /// reflects into its rectangle.
    fn reflecting_pixels(shape: &ShapeSource, camera: &Camera, [w, h]: [u32; 2]) -> Vec<[u32; 2]> {
        let clip_from_rel = camera.clip_from_relative(w as f32 / h as f32);
        let rel_from_clip = clip_from_rel.inverse();
        let n = shape.normal;
        let d = shape.plane_dist_from(camera.position) as f32;
        let c = (shape.center - camera.position).as_vec3();
        let mut out = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let ndc = [(x as f32 + 0.5) / w as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h as f32 * 2.0];
                let near = rel_from_clip.project_point3(Vec3::new(ndc[0], ndc[1], 0.0));
                let far = rel_from_clip.project_point3(Vec3::new(ndc[0], ndc[1], 0.5));
                let dir = (far - near).normalize();
                let hits = (0..240).any(|k| {
                    let p = near + dir * (0.05 * 1.04f32.powi(k));
                    let dist = p.dot(n) - d;
                    if dist <= 0.0 {
                        return false;
                    }
                    let m = p - 2.0 * dist * n;
                    let hit = m * (d / m.dot(n)) - c;
                    hit.dot(shape.axis_u).abs() <= shape.half_extents[0]
                        && hit.dot(shape.axis_v).abs() <= shape.half_extents[1]
                });
                if hits {
                    out.push([x, y]);
                }
            }
        }
        out
    }

    #[test]
    fn the_box_holds_every_reflecting_pixel_and_is_tight() {
        let projection = Projection::default();
        let cameras = [
            Camera::look_at(DVec3::new(0.0, 1.6, 4.0), DVec3::new(0.0, 0.5, 0.0), Vec3::Y, projection),
            Camera::look_at(DVec3::new(3.0, 0.3, 3.0), DVec3::new(-1.0, 0.8, -2.0), Vec3::Y, projection),
            Camera { position: DVec3::new(0.2, 5.0, 0.1), rotation: Quat::from_rotation_x(-1.5), projection },
        ];
        let size = [64, 40];
        for (i, camera) in cameras.iter().enumerate() {
            let shape = floor(0.8);
            let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(1.6), size);
            let pixels = reflecting_pixels(&shape, camera, size);
            assert!(!pixels.is_empty(), "camera {i}: the floor reflects something");
            for p in &pixels {
                assert!(
                    p[0] >= rect.min[0] && p[0] < rect.max[0] && p[1] >= rect.min[1] && p[1] < rect.max[1],
                    "camera {i}: pixel {p:?} outside {rect:?}"
                );
            }
            // Tight: within the margin plus one pixel of the brute-force box.
            let lo = [0, 1].map(|a| pixels.iter().map(|p| p[a]).min().unwrap_or(0));
            let hi = [0, 1].map(|a| pixels.iter().map(|p| p[a] + 1).max().unwrap_or(0));
            for a in 0..2 {
                assert!(
                    rect.min[a] + 3 >= lo[a] && rect.max[a] <= hi[a] + 3,
                    "camera {i}: {rect:?} vs {lo:?}..{hi:?}"
                );
            }
        }
    }

    /// Standing on a mirror floor (an 8 × 6 m room's), looking along it: the walls at the
    /// top of the view reflect into the floor at the camera's feet, so every row may
    /// reflect. The box from the pyramid's faces alone lost the top third of the rows.
    #[test]
    fn a_camera_over_the_rectangle_gets_the_whole_screen() {
        let projection = Projection { far: Some(60.0), ..Projection::default() };
        let camera =
            Camera::look_at(DVec3::new(0.5, 0.4, 2.5), DVec3::new(-1.0, 0.2, -3.0), Vec3::Y, projection);
        let mut shape = floor(4.0);
        shape.half_extents = [4.0, 3.0];
        let size = [160, 90];
        let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(16.0 / 9.0), size);
        let pixels = reflecting_pixels(&shape, &camera, size);
        assert!(pixels.iter().any(|p| p[1] == 0), "the top row reflects into the floor");
        for p in &pixels {
            assert!(
                p[0] >= rect.min[0] && p[0] < rect.max[0] && p[1] >= rect.min[1] && p[1] < rect.max[1],
                "pixel {p:?} outside {rect:?}"
            );
        }
    }

    /// The clipping as first written (a `Vec` a plane): what `clip_to_view` must return.
    fn clip_to_view_with_vecs(mut poly: Vec<DVec4>) -> Vec<DVec4> {
        let planes: [fn(&DVec4) -> f64; 4] = [|v| v.w + v.x, |v| v.w - v.x, |v| v.w + v.y, |v| v.w - v.y];
        for plane in planes {
            if poly.is_empty() {
                break;
            }
            let mut out = Vec::with_capacity(poly.len() + 2);
            for i in 0..poly.len() {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                let (fa, fb) = (plane(&a), plane(&b));
                if fa >= 0.0 {
                    out.push(a);
                }
                if (fa >= 0.0) != (fb >= 0.0) {
                    out.push(a + (b - a) * (fa / (fa - fb)));
                }
            }
            poly = out;
        }
        poly
    }

    /// `SourceBoxes::rect_by_clipping` as first written: the five faces clipped in four
    /// dimensions against every side plane, with vectors.
    fn rect_of_faces_clipped_with_vecs(boxes: &SourceBoxes, c: [DVec4; 4], d: [DVec4; 4]) -> ScreenRect {
        let faces = [
            c,
            [c[0], c[1], d[1], d[0]],
            [c[1], c[2], d[2], d[1]],
            [c[2], c[3], d[3], d[2]],
            [c[3], c[0], d[0], d[3]],
        ];
        let [w, h] = boxes.size.map(f64::from);
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for face in faces {
            for v in clip_to_view_with_vecs(face.to_vec()) {
                if v.w.partial_cmp(&(1e-12 * v.abs().max_element())) != Some(std::cmp::Ordering::Greater) {
                    continue;
                }
                let px = [(v.x / v.w * 0.5 + 0.5) * w, (0.5 - v.y / v.w * 0.5) * h];
                for a in 0..2 {
                    lo[a] = lo[a].min(px[a]);
                    hi[a] = hi[a].max(px[a]);
                }
            }
        }
        if lo[0] > hi[0] {
            return ScreenRect { min: [0, 0], max: [0, 0] };
        }
        if !lo.iter().chain(&hi).all(|x| x.is_finite()) {
            return boxes.full();
        }
        boxes.widened(lo, hi, MARGIN_PX)
    }

    /// `clip_to_view` of a quadrilateral given as clip-space vectors, with every plane that
    /// some vertex lies outside of.
    fn clip_quad(quad: [DVec4; 4]) -> Vec<DVec3> {
        let quad = quad.map(xyw);
        let cut = quad.iter().fold(0, |m, &v| m | outside_planes(v));
        let mut bufs = [[DVec3::ZERO; CLIP_CAPACITY]; 2];
        clip_to_view(&quad, cut, &mut bufs).to_vec()
    }

    proptest::proptest! {
        /// The stack polygon, in x, y and w, with its shortcuts (planes no vertex lies
        /// outside of left out) gives the x, y and w of the clipping with vectors in four
        /// dimensions, bit for bit (points at infinity, w = 0, included).
        #[test]
        fn the_clipping_without_allocation_matches_the_clipping_with_vectors(
            coords in proptest::collection::vec(-4.0f64..4.0, 16),
            at_infinity in proptest::collection::vec(proptest::bool::ANY, 4),
            scale in 0.01f64..100.0,
        ) {
            let quad: [DVec4; 4] = std::array::from_fn(|i| {
                let w = if at_infinity[i] { 0.0 } else { coords[4 * i + 3].abs() * scale };
                DVec4::new(coords[4 * i], coords[4 * i + 1], coords[4 * i + 2], w)
            });
            let fast = clip_quad(quad);
            let slow: Vec<DVec3> = clip_to_view_with_vecs(quad.to_vec()).into_iter().map(xyw).collect();
            proptest::prop_assert_eq!(fast, slow);
        }
    }

    #[test]
    fn a_quadrilateral_inside_the_view_is_not_clipped_and_one_outside_vanishes() {
        let inside = [
            DVec4::new(-0.5, -0.5, 0.3, 1.0),
            DVec4::new(0.5, -0.5, 0.3, 1.0),
            DVec4::new(0.5, 0.5, 0.3, 1.0),
            DVec4::new(-0.5, 0.5, 0.3, 1.0),
        ];
        assert_eq!(clip_quad(inside), inside.map(xyw).to_vec());
        let outside = inside.map(|v| v + DVec4::new(3.0, 0.0, 0.0, 0.0));
        assert!(clip_quad(outside).is_empty());
        let straddling = inside.map(|v| v + DVec4::new(1.0, 0.0, 0.0, 0.0));
        let clipped = clip_quad(straddling);
        let slow: Vec<DVec3> = clip_to_view_with_vecs(straddling.to_vec()).into_iter().map(xyw).collect();
        assert_eq!(clipped, slow);
        assert!(clipped.iter().all(|v| v.x <= v.z), "{clipped:?}");
    }

    proptest::proptest! {
        /// Where every point of the pyramid lies in front of the camera, the box of their
        /// hull clipped in two dimensions is the box of the faces clipped in four, within a
        /// pixel (their rounding differs), and the bound holds it; for rectangles of any
        /// size, orientation and place, seen from anywhere.
        #[test]
        fn the_hull_s_box_is_the_clipped_faces_box(
            centre in proptest::array::uniform3(-6.0f64..6.0),
            angles in proptest::array::uniform3(-3.2f32..3.2),
            half in proptest::array::uniform2(0.05f32..4.0),
            eye in proptest::array::uniform3(-8.0f64..8.0),
            at in proptest::array::uniform3(-8.0f64..8.0),
        ) {
            let rotation = Quat::from_euler(glam::EulerRot::XYZ, angles[0], angles[1], angles[2]);
            let mut shape = floor(1.0);
            shape.center = DVec3::from_array(centre);
            shape.axis_u = rotation * Vec3::X;
            shape.axis_v = rotation * Vec3::NEG_Z;
            shape.normal = shape.axis_u.cross(shape.axis_v);
            shape.half_extents = half;
            let (eye, at) = (DVec3::from_array(eye), DVec3::from_array(at));
            proptest::prop_assume!(eye.distance(at) > 0.1);
            let camera = Camera::look_at(eye, at, Vec3::Y, Projection::default());
            for size in [[64, 40], [3840, 2160]] {
                let clip = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
                let boxes = SourceBoxes::new(camera.position, &clip, size);
                proptest::prop_assume!(!eye_over_rectangle(&shape, boxes.eye));
                let (c, d) = boxes.pyramid(&shape, &mut HalfAxes::default());
                let clipped = boxes.rect_by_clipping(c, d);
                let rect = boxes.rect(&shape);
                if boxes.projected(c, d).is_some() {
                    // Where either is empty the other can be no more than a sliver along an
                    // edge (rounding at a tangent).
                    let thin = |r: ScreenRect| (0..2).any(|a| r.max[a].saturating_sub(r.min[a]) <= 3);
                    if clipped.area() == 0 || rect.area() == 0 {
                        proptest::prop_assert!(thin(clipped) && thin(rect), "{:?} against {:?}", rect, clipped);
                    } else {
                        for a in 0..2 {
                            let near = rect.min[a].abs_diff(clipped.min[a]) <= 1 && rect.max[a].abs_diff(clipped.max[a]) <= 1;
                            proptest::prop_assert!(near, "{:?} against {:?}", rect, clipped);
                        }
                    }
                } else {
                    proptest::prop_assert_eq!(rect, clipped);
                    // The faces clipped in x, y and w with the shortcuts: the box of the
                    // faces clipped in four dimensions, every plane, as first written.
                    let reference = rect_of_faces_clipped_with_vecs(&boxes, c, d);
                    proptest::prop_assert_eq!(clipped, reference);
                }
                // The skip is sound: a box one pixel short of the rect on any side does not
                // hold it, so the rect comes back; and tight: one a pixel wider on every side
                // holds the bound.
                if rect.area() > 0 {
                    for side in 0..4 {
                        let (a, grow) = (side % 2, side >= 2);
                        let mut short = rect;
                        if grow {
                            short.max[a] -= 1;
                        } else {
                            short.min[a] += 1;
                        }
                        let got = boxes.rect_unless_inside(&shape, Some(short), &mut HalfAxes::default());
                        proptest::prop_assert_eq!(got, Some(rect), "inside {:?}", short);
                    }
                    let wider = ScreenRect {
                        min: rect.min.map(|x| x.saturating_sub(1)),
                        max: [(rect.max[0] + 1).min(size[0]), (rect.max[1] + 1).min(size[1])],
                    };
                    if boxes.projected(c, d).is_some() && !eye_over_rectangle(&shape, boxes.eye) {
                        proptest::prop_assert_eq!(boxes.rect_unless_inside(&shape, Some(wider), &mut HalfAxes::default()), None);
                    }
                }
            }
        }
    }

    /// Tread `i` of a straight flight (0.17 m rise, 0.28 m run, 2 m wide).
    fn tread(i: usize) -> ShapeSource {
        let mut s = floor(1.0);
        s.half_extents = [1.0, 0.14];
        s.center = DVec3::new(0.0, 0.17 * i as f64, -0.28 * i as f64);
        s
    }

    /// The union that skips nested treads is the plain fold's rectangle (from below, above,
    /// beside and inside the flight, at two sizes), and skips most of a long flight's boxes.
    #[test]
    fn the_union_of_a_flights_boxes_skips_nested_treads_and_keeps_the_rectangle() {
        let projection = Projection { far: Some(200.0), ..Projection::default() };
        let treads: Vec<ShapeSource> = (0..400).map(tread).collect();
        let eyes = [
            (DVec3::new(0.3, 1.7, 3.0), DVec3::new(0.0, 8.0, -14.0)),
            (DVec3::new(-4.0, 30.0, -20.0), DVec3::new(0.0, 20.0, -40.0)),
            (DVec3::new(6.0, 10.0, -10.0), DVec3::new(0.0, 15.0, -30.0)),
            (DVec3::new(0.2, 35.0, -50.0), DVec3::new(0.0, 60.0, -100.0)),
            (DVec3::new(0.0, 80.0, -140.0), DVec3::new(0.0, 0.0, 0.0)),
        ];
        let (mut computed, mut total) = (0, 0);
        for (k, (eye, at)) in eyes.into_iter().enumerate() {
            let camera = Camera::look_at(eye, at, Vec3::Y, projection);
            for size in [[640, 360], [3840, 2160]] {
                let clip = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
                let boxes = SourceBoxes::new(camera.position, &clip, size);
                let plain = treads.iter().map(|t| boxes.rect(t)).reduce(union_rect).expect("treads");
                let (union, n) = boxes.union(treads.len(), |i| &treads[i]);
                assert_eq!(union, plain, "camera {k}, {size:?}");
                assert!(plain.area() > 0, "camera {k} sees the flight's reflections");
                computed += n;
                total += treads.len();
            }
        }
        assert!(computed * 2 < total, "{computed} of {total} boxes computed");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// The union that skips nested boxes is the plain fold's rectangle for scattered
        /// parallel shapes (any offsets, places and sizes, in a random order, in a cloud
        /// some way off) seen from around them.
        #[test]
        fn the_union_of_scattered_parallel_shapes_is_the_plain_fold(
            shapes in proptest::collection::vec(
                (proptest::array::uniform3(-3.0f64..3.0), proptest::array::uniform2(0.05f32..0.6)),
                64..160,
            ),
            tilt in proptest::array::uniform3(-0.6f32..0.6),
            eye in proptest::array::uniform3(-8.0f64..8.0),
            at in proptest::array::uniform3(-3.0f64..3.0),
        ) {
            let rotation = Quat::from_euler(glam::EulerRot::XYZ, tilt[0], tilt[1], tilt[2]);
            let shapes: Vec<ShapeSource> = shapes
                .iter()
                .map(|&(c, half)| {
                    let mut s = floor(1.0);
                    s.center = DVec3::from_array(c) + DVec3::new(0.0, 0.0, -20.0);
                    s.axis_u = rotation * Vec3::X;
                    s.axis_v = rotation * Vec3::NEG_Z;
                    s.normal = s.axis_u.cross(s.axis_v);
                    s.half_extents = half;
                    s
                })
                .collect();
            let (eye, at) = (DVec3::from_array(eye), DVec3::from_array(at) + DVec3::new(0.0, 0.0, -20.0));
            let camera = Camera::look_at(eye, at, Vec3::Y, Projection::default());
            // The plan unions the shapes in front of the camera (the others it culls).
            let front: Vec<&ShapeSource> = shapes.iter().filter(|s| s.plane_dist_from(eye) < 0.0).collect();
            for size in [[64, 40], [1920, 1080]] {
                let clip = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
                let boxes = SourceBoxes::new(camera.position, &clip, size);
                let plain = front.iter().map(|t| boxes.rect(t)).fold(ScreenRect { min: [0, 0], max: [0, 0] }, union_rect);
                let (union, _) = boxes.union(front.len(), |i| front[i]);
                proptest::prop_assert_eq!(union, plain);
            }
        }
    }

    #[test]
    fn a_reflector_whose_mirror_pyramid_leaves_the_view_has_an_empty_box() {
        // The floor lies behind a camera that looks away from it: its pyramid runs from
        // the floor away from the view.
        let camera = Camera::look_at(
            DVec3::new(0.0, 1.0, 5.0),
            DVec3::new(0.0, 1.0, 10.0),
            Vec3::Y,
            Projection::default(),
        );
        let shape = floor(0.5);
        let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(1.0), [32, 32]);
        assert_eq!(reflecting_pixels(&shape, &camera, [32, 32]), Vec::<[u32; 2]>::new());
        assert_eq!(rect.area(), 0, "{rect:?}");
    }
}
