//! Splitting non-convex regions (L, U, ring shapes) into several rectangles.
//!
//! A region's polygons are rasterised (conservatively) into an occupancy grid aligned with
//! its minimum-area rectangle. The largest empty grid rectangle is the biggest hole or
//! notch; the region is cut along that hole's sides into up to four bands (two layouts are
//! tried: full-width bands above and below the hole, or full-height bands left and right of
//! it), every polygon is clipped exactly along the cuts, and each non-empty band gets its
//! own minimum-area rectangle. The split is kept when every extra shape saves at least
//! `split_min_gain` of the *region's* rectangle area (not the piece's: a triangle gets the
//! two or three rectangles that pay, not a staircase of ever smaller ones). Pieces are
//! split again, most wasteful first, until no split pays or `max_shapes_per_region` is
//! reached. Each accepted split is recorded ([`SplitStep`]) so the density budget
//! ([`crate::budget`]) can keep only the steps it can afford.

use std::borrow::Cow;

use glam::DVec2;

use crate::polygon::Polygon;
use crate::rect_fit::{Rect2, min_area_rect};

/// Part of a region with its rectangle.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The (clipped) polygons of the part.
    pub polygons: Vec<Polygon>,
    /// Minimum-area rectangle enclosing every vertex of `polygons`.
    pub rect: Rect2,
    /// Reflective area (sum of polygon areas, duplicates removed by the caller).
    pub area: f64,
}

impl Piece {
    /// Fits the rectangle of `polygons`; `None` when they have no vertex.
    pub fn new(polygons: Vec<Polygon>) -> Option<Piece> {
        let points: Vec<DVec2> = polygons.iter().flat_map(|p| p.flat.iter().copied()).collect();
        let rect = min_area_rect(&points)?;
        let area = polygons.iter().map(Polygon::area).sum();
        Some(Piece { polygons, rect, area })
    }

    /// Rectangle area not covered by the region.
    pub fn waste(&self) -> f64 {
        (self.rect.area() - self.area).max(0.0)
    }
}

/// Splitting settings (from [`crate::ExtractParams`]).
#[derive(Clone, Copy, Debug)]
pub struct SplitSettings {
    /// Least area saved per extra shape, as a fraction of the parent rectangle's area.
    pub min_gain: f64,
    /// Most pieces per region.
    pub max_pieces: usize,
    /// Occupancy grid size (cells).
    pub grid_cells: usize,
}

/// One accepted split: the shapes it added and the rectangle area it saved, m².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitStep {
    /// Extra rectangles (parts − 1).
    pub extra_shapes: usize,
    /// Rectangle area saved (parent rectangle − parts' rectangles), m².
    pub area_saved: f64,
}

/// Splits `piece` while it pays; returns the pieces in a deterministic order.
pub fn split_region(piece: Piece, s: &SplitSettings) -> Vec<Piece> {
    split_region_steps(piece, s, usize::MAX).0
}

/// Splits `piece` while it pays, at most `max_steps` times; returns the pieces in a
/// deterministic order and the splits made, in order. The first `k` steps do not depend on
/// `max_steps >= k`, so a caller can replay a prefix of the steps.
pub fn split_region_steps(piece: Piece, s: &SplitSettings, max_steps: usize) -> (Vec<Piece>, Vec<SplitStep>) {
    let root = piece.rect.area();
    let mut done: Vec<Piece> = Vec::new();
    let mut open: Vec<Piece> = vec![piece];
    let mut steps = Vec::new();
    while let Some(idx) = most_wasteful(&open) {
        let p = open.swap_remove(idx);
        let budget = s.max_pieces.saturating_sub(done.len() + open.len());
        match (steps.len() < max_steps).then(|| try_split(&p, s, budget, root)).flatten() {
            Some(parts) => {
                let area_saved = p.rect.area() - parts.iter().map(|q| q.rect.area()).sum::<f64>();
                steps.push(SplitStep { extra_shapes: parts.len() - 1, area_saved });
                open.extend(parts);
            }
            None => done.push(p),
        }
    }
    done.sort_by(|a, b| {
        b.rect.area().total_cmp(&a.rect.area()).then(a.rect.center.x.total_cmp(&b.rect.center.x))
    });
    (done, steps)
}

fn most_wasteful(pieces: &[Piece]) -> Option<usize> {
    (0..pieces.len()).max_by(|&a, &b| pieces[a].waste().total_cmp(&pieces[b].waste()).then(b.cmp(&a)))
}

/// The best band split of `p` into at most `budget` pieces, if every extra piece saves at
/// least `min_gain` of the region's whole rectangle (`root`, m²).
fn try_split(p: &Piece, s: &SplitSettings, budget: usize, root: f64) -> Option<Vec<Piece>> {
    let parent = p.rect.area();
    let least = s.min_gain * root;
    if budget < 2 || !(parent > 0.0) || p.waste() < least {
        return None;
    }
    let grid = OccupancyGrid::rasterise(p, s.grid_cells);
    let hole = grid.largest_empty()?;
    if (hole.area_cells() as f64) * grid.cell_area() < least {
        return None;
    }
    let bounds = grid.hole_bounds(&hole, &p.polygons);
    let mut best: Option<(f64, Vec<Piece>)> = None;
    for layout in [Layout::Rows, Layout::Columns] {
        let parts: Vec<Piece> = grid
            .bands(bounds, layout)
            .into_iter()
            .filter_map(|cuts| {
                let polys: Vec<Polygon> = p.polygons.iter().filter_map(|poly| cuts.clip(poly)).collect();
                let piece = Piece::new(polys)?;
                (piece.area > 1e-12 * parent).then_some(piece)
            })
            .collect();
        if parts.len() < 2 || parts.len() > budget {
            continue;
        }
        let total: f64 = parts.iter().map(|q| q.rect.area()).sum();
        let gain = parent - total;
        if gain >= least * (parts.len() - 1) as f64 && best.as_ref().is_none_or(|(t, _)| total < *t) {
            best = Some((total, parts));
        }
    }
    best.map(|(_, parts)| parts)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Layout {
    /// Full-width bands below and above the hole, side bands beside it.
    Rows,
    /// Full-height bands left and right of the hole, short bands below and above it.
    Columns,
}

/// Cell ranges `[i0, i1) × [j0, j1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct CellRect {
    i0: usize,
    i1: usize,
    j0: usize,
    j1: usize,
}

impl CellRect {
    fn area_cells(&self) -> usize {
        (self.i1 - self.i0) * (self.j1 - self.j0)
    }
}

/// A band: the intersection of up to four half-planes of the rectangle's frame.
struct Band {
    rect: Rect2,
    /// (axis index 0 = x / 1 = y, limit in local coordinates, keep_below).
    limits: Vec<(usize, f64, bool)>,
}

impl Band {
    fn clip(&self, poly: &Polygon) -> Option<Polygon> {
        clip_all(poly, &self.rect, &self.limits).map(Cow::into_owned)
    }
}

/// `poly` clipped by each of `cuts` in turn, copied only when a cut changes it; `None` when
/// nothing is left. A cut `(axis, limit, below)` keeps `local(axis) <= limit` (`below`) or
/// `>= limit` in `rect`'s centred frame (axis 0: along `rect.axis`, 1: across).
fn clip_all<'a>(poly: &'a Polygon, rect: &Rect2, cuts: &[(usize, f64, bool)]) -> Option<Cow<'a, Polygon>> {
    let mut out = Cow::Borrowed(poly);
    for &(axis, limit, below) in cuts {
        let dir = if axis == 0 { rect.axis } else { rect.perp() };
        let limit = dir.dot(rect.center) + limit;
        if !out.keeps_all(dir, limit, below) {
            out = Cow::Owned(out.clip(dir, limit, below)?);
        }
    }
    Some(out)
}

/// Which cells of the rectangle's grid any polygon touches.
struct OccupancyGrid {
    rect: Rect2,
    nu: usize,
    nv: usize,
    cell: DVec2,
    occupied: Vec<bool>,
}

impl OccupancyGrid {
    fn rasterise(p: &Piece, cells: usize) -> Self {
        let rect = p.rect;
        let aspect = (rect.half.x / rect.half.y.max(1e-300)).clamp(1.0 / cells as f64, cells as f64);
        let nu = ((cells as f64 * aspect).sqrt().round() as usize).clamp(1, cells);
        let nv = (cells / nu).max(1);
        let cell = DVec2::new(2.0 * rect.half.x / nu as f64, 2.0 * rect.half.y / nv as f64);
        let mut grid = Self { rect, nu, nv, cell, occupied: vec![false; nu * nv] };
        // Conservative: a cell counts as touched when the polygon comes within `eps` of it.
        let eps = 1e-9 * (rect.half.x + rect.half.y);
        let mut local: Vec<DVec2> = Vec::new();
        for poly in &p.polygons {
            // Local coordinates with the rectangle's corner at the origin.
            local.clear();
            local.extend(poly.flat.iter().map(|&q| rect.local(q) + rect.half));
            let (lo, hi) =
                local.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| (l.min(q.y), h.max(q.y)));
            let j_lo = grid.row_of(lo - eps);
            let j_hi = grid.row_of(hi + eps);
            for j in j_lo..=j_hi {
                let y0 = j as f64 * cell.y - eps;
                let y1 = (j + 1) as f64 * cell.y + eps;
                let Some((xl, xh)) = strip_x_range(&local, y0, y1) else { continue };
                for i in grid.col_of(xl - eps)..=grid.col_of(xh + eps) {
                    grid.occupied[j * nu + i] = true;
                }
            }
        }
        grid
    }

    fn col_of(&self, x: f64) -> usize {
        ((x / self.cell.x).floor().max(0.0) as usize).min(self.nu - 1)
    }

    fn row_of(&self, y: f64) -> usize {
        if !(self.cell.y > 0.0) {
            return 0;
        }
        ((y / self.cell.y).floor().max(0.0) as usize).min(self.nv - 1)
    }

    fn cell_area(&self) -> f64 {
        self.cell.x * self.cell.y
    }

    /// The largest all-empty rectangle of cells (maximal rectangle in a histogram).
    fn largest_empty(&self) -> Option<CellRect> {
        let mut heights = vec![0usize; self.nu];
        let mut best: Option<CellRect> = None;
        for j in 0..self.nv {
            for (i, h) in heights.iter_mut().enumerate() {
                *h = if self.occupied[j * self.nu + i] { 0 } else { *h + 1 };
            }
            // Largest rectangle under the histogram, stack-based.
            let mut stack: Vec<usize> = Vec::new();
            for i in 0..=self.nu {
                let h = if i < self.nu { heights[i] } else { 0 };
                while let Some(&top) = stack.last() {
                    if heights[top] < h {
                        break;
                    }
                    stack.pop();
                    let height = heights[top];
                    let left = stack.last().map_or(0, |&s| s + 1);
                    let r = CellRect { i0: left, i1: i, j0: j + 1 - height, j1: j + 1 };
                    if height > 0 && best.is_none_or(|b| r.area_cells() > b.area_cells()) {
                        best = Some(r);
                    }
                }
                stack.push(i);
            }
        }
        best
    }

    /// The hole in local coordinates (relative to the rectangle's centre), grown from cell
    /// boundaries to the geometry around it so that the cuts fall exactly on its edges.
    fn hole_bounds(&self, hole: &CellRect, polygons: &[Polygon]) -> [f64; 4] {
        let (hx, hy) = (self.rect.half.x, self.rect.half.y);
        let y0 = hole.j0 as f64 * self.cell.y - hy;
        let y1 = hole.j1 as f64 * self.cell.y - hy;
        let x0 = hole.i0 as f64 * self.cell.x - hx;
        let x1 = hole.i1 as f64 * self.cell.x - hx;
        let x0 = extreme(polygons, &self.rect, 0, (y0, y1), x0, true).unwrap_or(-hx);
        let x1 = extreme(polygons, &self.rect, 0, (y0, y1), x1, false).unwrap_or(hx);
        let y0 = extreme(polygons, &self.rect, 1, (x0, x1), y0, true).unwrap_or(-hy);
        let y1 = extreme(polygons, &self.rect, 1, (x0, x1), y1, false).unwrap_or(hy);
        [x0, x1, y0, y1]
    }

    /// The bands around `hole` for `layout`, as clipping limits in the rectangle's frame.
    fn bands(&self, [x0, x1, y0, y1]: [f64; 4], layout: Layout) -> Vec<Band> {
        let hx = self.rect.half.x;
        let hy = self.rect.half.y;
        let band = |limits: Vec<(usize, f64, bool)>| Band { rect: self.rect, limits };
        let (across, along) = match layout {
            Layout::Rows => (1, 0),
            Layout::Columns => (0, 1),
        };
        let (a0, a1, b0, b1) = if layout == Layout::Rows { (y0, y1, x0, x1) } else { (x0, x1, y0, y1) };
        let mut out = Vec::new();
        if hole_edge_inside(a0, across, hx, hy) {
            out.push(band(vec![(across, a0, true)]));
        }
        if hole_edge_inside(a1, across, hx, hy) {
            out.push(band(vec![(across, a1, false)]));
        }
        if hole_edge_inside(b0, along, hx, hy) {
            out.push(band(vec![(across, a0, false), (across, a1, true), (along, b0, true)]));
        }
        if hole_edge_inside(b1, along, hx, hy) {
            out.push(band(vec![(across, a0, false), (across, a1, true), (along, b1, false)]));
        }
        out
    }
}

/// The x-range of the convex polygon `flat` within the strip `y0 <= y <= y1` (its vertices
/// there and its edges' crossings of the two lines), or `None` when it misses the strip.
fn strip_x_range(flat: &[DVec2], y0: f64, y1: f64) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let n = flat.len();
    for k in 0..n {
        let (p, q) = (flat[k], flat[(k + 1) % n]);
        if p.y >= y0 && p.y <= y1 {
            lo = lo.min(p.x);
            hi = hi.max(p.x);
        }
        for line in [y0, y1] {
            let (sp, sq) = (p.y - line, q.y - line);
            if (sp >= 0.0) != (sq >= 0.0) {
                let x = p.lerp(q, sp / (sp - sq)).x;
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The largest (`below`) or smallest local coordinate along `axis` of the geometry that lies
/// on that side of `cut`, within the open window `other` on the other axis.
fn extreme(
    polygons: &[Polygon],
    rect: &Rect2,
    axis: usize,
    other: (f64, f64),
    cut: f64,
    below: bool,
) -> Option<f64> {
    let eps = 1e-9 * (rect.half.x + rect.half.y);
    let mut best: Option<f64> = None;
    for poly in polygons {
        let cuts = [(1 - axis, other.0 + eps, false), (1 - axis, other.1 - eps, true), (axis, cut, below)];
        let Some(part) = clip_all(poly, rect, &cuts) else {
            continue;
        };
        for &v in &part.flat {
            let l = rect.local(v);
            let c = if axis == 0 { l.x } else { l.y };
            best = Some(match best {
                None => c,
                Some(b) if below => b.max(c),
                Some(b) => b.min(c),
            });
        }
    }
    best
}

/// Whether a hole side at `limit` on `axis` is strictly inside the rectangle (else the band
/// beyond it is empty).
fn hole_edge_inside(limit: f64, axis: usize, hx: f64, hy: f64) -> bool {
    let h = if axis == 0 { hx } else { hy };
    limit.abs() < h * (1.0 - 1e-12)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Unit-square cells `(x, y)` as two triangles each, rotated by `angle`.
    fn region(cells: &[(i32, i32)], angle: f64) -> Piece {
        let rot = DVec2::from_angle(angle);
        let mut polys = Vec::new();
        for &(x, y) in cells {
            let c = [(0, 0), (1, 0), (1, 1), (0, 1)]
                .map(|(dx, dy)| rot.rotate(DVec2::new((x + dx) as f64, (y + dy) as f64)));
            for tri in [[c[0], c[1], c[2]], [c[0], c[2], c[3]]] {
                polys.push(Polygon {
                    flat: tri.to_vec(),
                    spatial: tri.iter().map(|p| DVec3::new(p.x, 0.0, p.y)).collect(),
                    roughness: 0.0,
                });
            }
        }
        Piece::new(polys).unwrap()
    }

    fn settings() -> SplitSettings {
        SplitSettings { min_gain: 0.1, max_pieces: 8, grid_cells: 4096 }
    }

    /// Splits the region of `cells` at several angles: `expected_pieces` rectangles whose
    /// areas add up to `expected_total`.
    fn check(cells: &[(i32, i32)], expected_pieces: usize, expected_total: f64) {
        for angle in [0.0, 0.3, 1.0, 2.5] {
            let p = region(cells, angle);
            let pieces = split_region(p.clone(), &settings());
            assert_eq!(pieces.len(), expected_pieces, "angle {angle}: {pieces:#?}");
            let covered: f64 = pieces.iter().map(|q| q.area).sum();
            assert!((covered - p.area).abs() < 1e-9 * p.area, "area lost: {covered} vs {}", p.area);
            let total: f64 = pieces.iter().map(|q| q.rect.area()).sum();
            assert!(
                (total - expected_total).abs() < 1e-6 * p.area,
                "rectangle area {total}, expected {expected_total}"
            );
            for q in &pieces {
                for poly in &q.polygons {
                    for v in &poly.flat {
                        assert!(q.rect.contains(*v, 1e-9));
                    }
                }
            }
        }
    }

    #[test]
    fn splits_l_u_and_ring_shapes_into_tight_rectangles() {
        let l: Vec<(i32, i32)> = (0..4).map(|x| (x, 0)).chain((1..4).map(|y| (0, y))).collect();
        check(&l, 2, 7.0);
        let u: Vec<(i32, i32)> =
            (0..5).map(|x| (x, 0)).chain((1..4).flat_map(|y| [(0, y), (4, y)])).collect();
        check(&u, 3, 11.0);
        let ring: Vec<(i32, i32)> = (0..6)
            .flat_map(|x| (0..6).map(move |y| (x, y)))
            .filter(|&(x, y)| !(1..5).contains(&x) || !(1..5).contains(&y))
            .collect();
        check(&ring, 4, 20.0);
        let full: Vec<(i32, i32)> = (0..3).flat_map(|x| (0..2).map(move |y| (x, y))).collect();
        check(&full, 1, 6.0);
    }

    #[test]
    fn small_notches_are_not_worth_a_shape() {
        // A 10×10 square missing one corner cell: 1% waste.
        let cells: Vec<(i32, i32)> =
            (0..10).flat_map(|x| (0..10).map(move |y| (x, y))).filter(|&c| c != (9, 9)).collect();
        check(&cells, 1, 100.0);
    }

    #[test]
    fn respects_the_shape_budget() {
        let ring: Vec<(i32, i32)> = (0..6)
            .flat_map(|x| (0..6).map(move |y| (x, y)))
            .filter(|&(x, y)| !(1..5).contains(&x) || !(1..5).contains(&y))
            .collect();
        let s = SplitSettings { max_pieces: 3, ..settings() };
        let pieces = split_region(region(&ring, 0.0), &s);
        assert!(pieces.len() <= 3, "{}", pieces.len());
        let s = SplitSettings { max_pieces: 1, ..settings() };
        assert_eq!(split_region(region(&ring, 0.0), &s).len(), 1);
    }

    #[test]
    fn a_triangle_gets_the_few_rectangles_that_pay() {
        // Each further split of a triangle saves a quarter of the last one: with the gain
        // measured against the region (not the piece) it stops after two or three shapes.
        let tri = [DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::new(0.0, 10.0)];
        let poly = Polygon {
            flat: tri.to_vec(),
            spatial: tri.iter().map(|p| DVec3::new(p.x, 0.0, p.y)).collect(),
            roughness: 0.0,
        };
        let piece = Piece::new(vec![poly]).unwrap();
        let (pieces, steps) = split_region_steps(piece.clone(), &settings(), usize::MAX);
        assert!((2..=3).contains(&pieces.len()), "{} pieces: a staircase", pieces.len());
        let total: f64 = pieces.iter().map(|q| q.rect.area()).sum();
        assert!(total <= 0.8 * piece.rect.area(), "{total}");
        for st in &steps {
            assert!(st.area_saved >= 0.1 * piece.rect.area() * st.extra_shapes as f64, "{st:?}");
        }
        // A prefix of the steps replays exactly.
        let (one, first) = split_region_steps(piece, &settings(), 1);
        assert_eq!(first, steps[..1]);
        assert_eq!(one.len(), 1 + steps[0].extra_shapes);
    }
}
