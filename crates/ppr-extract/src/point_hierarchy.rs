//! A static hierarchy of points for box queries: the points in Morton order, a box over
//! every block of 8 consecutive points, a box over every 8 such boxes, and so on up to one.
//! A query visits only the blocks whose boxes overlap it, so a large, thin box (a big floor
//! triangle's) costs about the points near it, not the cells it spans.

use glam::DVec3;

/// Children per box.
const FAN_OUT: usize = 8;

/// Points in Morton order with the boxes of their blocks.
pub struct PointHierarchy<'a> {
    points: &'a [DVec3],
    /// Point indices in Morton order.
    order: Vec<u32>,
    /// `levels[0]`: boxes of blocks of points; `levels[k]`: boxes of blocks of `levels[k-1]`.
    levels: Vec<Vec<(DVec3, DVec3)>>,
}

impl<'a> PointHierarchy<'a> {
    /// The hierarchy of `points` (n log n for the sort, linear otherwise).
    pub fn new(points: &'a [DVec3]) -> Self {
        let (lo, hi) = points
            .iter()
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(l, h), &p| {
                (l.min(p), h.max(p))
            });
        let extent = (hi - lo).max(DVec3::splat(f64::MIN_POSITIVE));
        let scale = DVec3::splat(((1u32 << 21) - 1) as f64) / extent;
        let mut keyed: Vec<(u64, u32)> = points
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let q = ((p - lo) * scale).clamp(DVec3::ZERO, DVec3::splat(((1u32 << 21) - 1) as f64));
                (morton(q.x as u64, q.y as u64, q.z as u64), i as u32)
            })
            .collect();
        keyed.sort_unstable();
        let order: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();
        let mut levels = Vec::new();
        let mut boxes: Vec<(DVec3, DVec3)> = order
            .chunks(FAN_OUT)
            .map(|block| {
                block
                    .iter()
                    .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(l, h), &i| {
                        (l.min(points[i as usize]), h.max(points[i as usize]))
                    })
            })
            .collect();
        loop {
            let last = boxes.len() <= 1;
            let parents: Vec<(DVec3, DVec3)> = boxes
                .chunks(FAN_OUT)
                .map(|block| block.iter().fold(block[0], |(l, h), b| (l.min(b.0), h.max(b.1))))
                .collect();
            levels.push(boxes);
            if last {
                break;
            }
            boxes = parents;
        }
        Self { points, order, levels }
    }

    /// Appends to `out` every point inside the closed box `[lo, hi]` (in Morton order).
    pub fn query(&self, lo: DVec3, hi: DVec3, out: &mut Vec<u32>) {
        let overlaps = |b: &(DVec3, DVec3)| b.0.cmple(hi).all() && b.1.cmpge(lo).all();
        let top = self.levels.len() - 1;
        let mut stack: Vec<(usize, usize)> = (0..self.levels[top].len()).map(|i| (top, i)).collect();
        while let Some((level, i)) = stack.pop() {
            if !overlaps(&self.levels[level][i]) {
                continue;
            }
            let children = i * FAN_OUT..(i * FAN_OUT + FAN_OUT);
            if level == 0 {
                for &p in &self.order[children.start..children.end.min(self.order.len())] {
                    let q = self.points[p as usize];
                    if q.cmpge(lo).all() && q.cmple(hi).all() {
                        out.push(p);
                    }
                }
            } else {
                let below = self.levels[level - 1].len();
                stack.extend(children.filter(|&c| c < below).map(|c| (level - 1, c)));
            }
        }
    }
}

/// Interleaves the low 21 bits of `x`, `y`, `z`.
fn morton(x: u64, y: u64, z: u64) -> u64 {
    fn spread(v: u64) -> u64 {
        let mut v = v & 0x1f_ffff;
        v = (v | v << 32) & 0x1f_0000_0000_ffff;
        v = (v | v << 16) & 0x1f_0000_ff00_00ff;
        v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
        v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
        (v | v << 2) & 0x1249_2492_4924_9249
    }
    spread(x) | spread(y) << 1 | spread(z) << 2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_find_exactly_the_points_in_the_box() {
        let mut seed = 3u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let points: Vec<DVec3> = (0..1000).map(|_| DVec3::new(rnd() * 10.0, rnd(), rnd() * 5.0)).collect();
        let h = PointHierarchy::new(&points);
        for _ in 0..50 {
            let a = DVec3::new(rnd() * 10.0, rnd(), rnd() * 5.0);
            let b = DVec3::new(rnd() * 10.0, rnd(), rnd() * 5.0);
            let (lo, hi) = (a.min(b), a.max(b));
            let mut got = Vec::new();
            h.query(lo, hi, &mut got);
            got.sort_unstable();
            let want: Vec<u32> = (0..points.len() as u32)
                .filter(|&i| points[i as usize].cmpge(lo).all() && points[i as usize].cmple(hi).all())
                .collect();
            assert_eq!(got, want);
        }
        assert_eq!(morton(1, 0, 0), 1);
        assert_eq!(morton(0, 1, 0), 2);
        assert_eq!(morton(0, 0, 1), 4);
        assert_eq!(morton(3, 0, 0), 9);
    }
}
