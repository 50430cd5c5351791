//! Pixel masks for comparisons: interiors of regions and edges of the exact reflection.

use crate::scene::Frame;

/// Pixels of `mask` whose whole (2r+1)² neighbourhood is in `mask`.
pub fn interior(f: &Frame, r: i32, mask: impl Fn(usize) -> bool) -> Vec<bool> {
    let [w, h] = f.size.map(|v| v as i32);
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            (-r..=r).all(|dy| {
                (-r..=r).all(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    nx >= 0 && ny >= 0 && nx < w && ny < h && mask((ny * w + nx) as usize)
                })
            })
        })
        .collect()
}

/// Mirror pixels whose reference differs from a 4-neighbour's by more than `threshold`.
pub fn reference_edges(f: &Frame, threshold: f32) -> Vec<bool> {
    let [w, h] = f.size;
    let mut edges = vec![false; f.reference.len()];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = (y * w + x) as usize;
            let c = f.reference[i];
            edges[i] = [i - 1, i + 1, i - w as usize, i + w as usize]
                .iter()
                .any(|&j| f.mirror[j].is_none() || (f.reference[j] - c).abs().max_element() > threshold);
        }
    }
    edges
}
