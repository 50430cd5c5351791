//! Parallel reflectors at many plane offsets merged into one projection test: stair
//! treads, shelves, the floors of a many-storeyed level (the plane groups of
//! [`crate::plane_groups`] merge only shapes of one plane).
//!
//! For a pixel at camera-relative `p` and a plane of normal `n` at (camera-relative)
//! distance `d < 0`, the mirror image is `p − 2(n·p − d)n` and the ray from the camera to
//! it crosses the plane at `t` times the image, `t = d / (2d − n·p)`. In the plane's own
//! coordinates `(u, v)` (shared by parallel planes) that reflection point is `t · (u_p,
//! v_p)`: as `d` runs over the planes below the pixel, it slides along one segment from
//! the camera's foot point towards the pixel's, `t` monotone in `d`. A pixel is reflected
//! by a member exactly when its point for the member's `d` lies in the member's rectangle.
//!
//! The members visible in a frame are the leaves of a complete binary tree, in an order
//! fixed with the table: a recursive median split of the family along the longest of its
//! plane offset, u and v extents, so that a node's members lie close together in all
//! three. Each node holds, camera-relative, the range of its members' offsets, the u range
//! of their rectangles, and a slab in (offset, v): the least-squares slope `α` of their v
//! against the offset and the range of `v − α·offset` (a stairway's treads climb along v as
//! their offset grows; a plain v range would meet every pixel's segment along the whole
//! flight). A pixel walks the tree and descends only into nodes its reflection point can
//! reach (for the node's offsets), and tests each leaf it reaches with the member's own
//! test, the one the plain loop runs, so the writes are the same. On the 10 000-tread
//! stairway of the scaling suite a pixel on the treads tests about 50 nodes and 8 leaves
//! for its 4.5 reflections, not 10 000 shapes.
//!
//! Words per frame (`u32`, floats as bits), per tree: a header of
//! [`TREE_HEADER_WORDS`] (normal, node start, u axis, leaf count, v axis, member count,
//! first member test), then the nodes, [`TREE_NODE_WORDS`] each, in heap order (node 1
//! the root, children `2k` and `2k + 1`, leaves from the leaf count): lowest and highest
//! offset, u range, range of `v − α·offset`, `α`, `1/α`. Empty leaves have an offset range
//! that no pixel meets. Then the offset index (below), [`index_words`] long. They live in
//! the plane-group buffer, between the groups' headers and their static grids
//! ([`tree_words_start`]).
//!
//! **The offset index** (where the plan asks for it, [`crate::plan::FramePlan::tree_index`]):
//! a member can reflect a pixel only where its own offset passes the *root's* test at that
//! one offset, and on a flight of stairs (the root's slab as tight as a tread) few do: 4.6
//! a pixel of the scaling stairway's 1 000 treads, 10 of its 10 000, against 32 and 51
//! node tests of the walk (6.7 and 8.4 candidates with the buckets' slack, for 4.0 and 2.3
//! reflections). So the pixel solves the root's test for the offsets that pass
//! it (the u bounds are linear in the offset, the slab's quadratic: [`index_interval`]),
//! looks up the members of those offsets in an index of equal offset buckets (a quarter
//! bucket of slack on each side), and runs the member tests on them; more than
//! [`INDEX_MOST_MEMBERS`] candidates, and it walks. The index: header words 13-15 hold its
//! word position (0: none), the lowest offset and the buckets per metre; its words are the
//! bucket starts (members + 1 words) and the members' leaf positions sorted by bucket.
//! The CPU writes it only where no bucket holds more than [`INDEX_MOST_PER_BUCKET`]
//! members (a flight, not the floors of a level at a few heights).

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use ppr_format::ReflectorKind;

use crate::shapes::{ShapeSource, ShapeTable};

/// Bit of [`crate::gpu_types::GpuShapeTest::shape`]: the test stands for a parallel tree
/// (the rest of the word is its header's word position in the plane-group buffer).
pub const TREE_TEST_FLAG: u32 = 0x4000_0000;

/// Words of a tree's header.
pub const TREE_HEADER_WORDS: usize = 16;
/// Words of a tree node.
pub const TREE_NODE_WORDS: usize = 8;

/// Most candidates a pixel takes from the offset index; more and it walks the tree.
pub const INDEX_MOST_MEMBERS: u32 = 64;
/// Buckets (a share of one) by which a pixel widens each offset interval before it looks
/// up its buckets: far more than the f32 rounding of the interval's ends and of the bucket
/// arithmetic where buckets are as wide as [`offset_index`] asks.
pub const INDEX_SLACK: f32 = 0.25;
/// Most members an offset bucket of an index may hold (else the tree gets no index).
pub const INDEX_MOST_PER_BUCKET: u32 = 4;

/// Largest difference of a member's unit normal from its family's, per component: members
/// share the family's plane coordinates to within f32 rounding of the pixel positions.
const NORMAL_TOLERANCE: f32 = 1e-6;

/// Shapes of one parallel group whose normals agree (two or more), in tree order.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallelFamily {
    /// Shape indices in the leaf order of a median-split tree over their plane offsets
    /// (`center · normal`) and centres.
    pub members: Vec<u32>,
    /// The first member's frame: the family's plane coordinates.
    pub normal: Vec3,
    pub axis_u: Vec3,
    pub axis_v: Vec3,
}

/// Every family of a table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParallelFamilies {
    pub families: Vec<ParallelFamily>,
    /// Per shape of the table: its family and its rank in the family's order.
    pub family_of: Vec<Option<(u32, u32)>>,
}

impl ParallelFamilies {
    /// Groups the enabled opaque shapes of `shapes` by parallel group and normal.
    pub fn build(shapes: &[ShapeSource]) -> Self {
        let mut by_group: HashMap<u32, Vec<Vec<u32>>> = HashMap::new();
        for (i, s) in shapes.iter().enumerate() {
            if !s.enabled || s.kind != ReflectorKind::Opaque {
                continue;
            }
            let drafts = by_group.entry(s.parallel_group).or_default();
            let same = |d: &Vec<u32>| {
                (shapes[d[0] as usize].normal - s.normal).abs().max_element() <= NORMAL_TOLERANCE
            };
            match drafts.iter_mut().find(|d| same(d)) {
                Some(d) => d.push(i as u32),
                None => drafts.push(vec![i as u32]),
            }
        }
        let mut drafts: Vec<Vec<u32>> = by_group.into_values().flatten().filter(|d| d.len() >= 2).collect();
        // Deterministic family order, whatever the hash map's.
        drafts.sort_by_key(|d| d[0]);
        let mut out = Self { families: Vec::new(), family_of: vec![None; shapes.len()] };
        for mut members in drafts {
            let first = &shapes[members[0] as usize];
            let frame = [first.normal, first.axis_u, first.axis_v].map(Vec3::as_dvec3);
            let mut keyed: Vec<([f64; 3], u32)> =
                members.iter().map(|&m| (frame.map(|a| shapes[m as usize].center.dot(a)), m)).collect();
            median_split(&mut keyed);
            members = keyed.into_iter().map(|(_, m)| m).collect();
            let f = out.families.len() as u32;
            for (rank, &m) in members.iter().enumerate() {
                out.family_of[m as usize] = Some((f, rank as u32));
            }
            out.families.push(ParallelFamily {
                normal: first.normal,
                axis_u: first.axis_u,
                axis_v: first.axis_v,
                members,
            });
        }
        out
    }

    /// Words the trees of one frame may need at most (every family a tree of all its
    /// members).
    pub fn words_capacity(&self) -> usize {
        self.families.iter().map(|f| tree_words(f.members.len())).sum()
    }
}

/// Orders `items` (keys: plane offset, u, v) as the leaves of a left-filled complete binary
/// tree: the first half of the leaf slots (a power of two) gets the items below the median
/// along the longest extent, recursively.
fn median_split(items: &mut [([f64; 3], u32)]) {
    if items.len() <= 1 {
        return;
    }
    let (lo, hi) = items.iter().fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), (k, _)| {
        (std::array::from_fn(|a| lo[a].min(k[a])), std::array::from_fn(|a| hi[a].max(k[a])))
    });
    let axis = (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
    let left = items.len().next_power_of_two() / 2;
    items.select_nth_unstable_by(left - 1, |x, y| x.0[axis].total_cmp(&y.0[axis]).then(x.1.cmp(&y.1)));
    let (a, b) = items.split_at_mut(left);
    median_split(a);
    median_split(b);
}

/// Words of a tree over `members` leaves.
fn tree_words(members: usize) -> usize {
    TREE_HEADER_WORDS + TREE_NODE_WORDS * (2 * members.next_power_of_two() - 1) + index_words(members)
}

/// Words of a tree's offset index over `members` members: the bucket starts (one bucket a
/// member, and the end) and the members' leaf positions, rounded up to whole nodes (the
/// next tree's header stays 32-byte aligned).
pub fn index_words(members: usize) -> usize {
    (2 * members + 1).next_multiple_of(TREE_NODE_WORDS)
}

/// Word position of the trees in the plane-group buffer: after the groups' headers.
pub fn tree_words_start(table: &ShapeTable) -> u32 {
    (table.plane_groups.groups.len() * std::mem::size_of::<crate::plane_groups::GpuPlaneGroup>() / 4) as u32
}

/// One frame's tree: visible members of a family, in the family's order.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FrameTree {
    /// Index into [`ParallelFamilies::families`].
    pub family: u32,
    /// Shape indices, in the family's order.
    pub members: Vec<u32>,
}

impl FrameTree {
    /// The member with the lowest plane (its plane bounds every member's from below).
    pub fn lowest(&self, table: &ShapeTable) -> u32 {
        let n = table.parallel_families.families[self.family as usize].normal.as_dvec3();
        let offset = |m: &u32| table.shapes[*m as usize].center.dot(n);
        *self.members.iter().min_by(|a, b| offset(a).total_cmp(&offset(b))).expect("a tree has members")
    }

    /// Appends this tree's words for a camera at `eye` to `words` (whose first word sits at
    /// word `base` of the buffer), its members' tests starting at `tests_start`, with its
    /// offset index where `index` asks for one and the members allow it; returns the
    /// header's word position in the buffer. `scratch`: working memory, reused.
    #[allow(clippy::too_many_arguments)]
    pub fn append_words(
        &self,
        table: &ShapeTable,
        eye: DVec3,
        base: u32,
        tests_start: u32,
        index: bool,
        words: &mut Vec<u32>,
        scratch: &mut TreeScratch,
    ) -> u32 {
        let family = &table.parallel_families.families[self.family as usize];
        let header = base + words.len() as u32;
        let leaves = self.members.len().next_power_of_two();
        let node_start = header + TREE_HEADER_WORDS as u32;
        // The shader loads a node as two vec4s: every node 32-byte aligned (group headers
        // and tree headers are 16 words, trees a multiple of 8).
        debug_assert_eq!(node_start % TREE_NODE_WORDS as u32, 0, "tree nodes must be 32-byte aligned");
        let f = |v: f32| v.to_bits();
        let [nx, ny, nz] = family.normal.to_array();
        let [ux, uy, uz] = family.axis_u.to_array();
        let [vx, vy, vz] = family.axis_v.to_array();
        words.extend([f(nx), f(ny), f(nz), node_start]);
        words.extend([f(ux), f(uy), f(uz), leaves as u32]);
        words.extend([f(vx), f(vy), f(vz), self.members.len() as u32]);
        words.extend([tests_start, 0, 0, 0]);
        let (au, av) = (family.axis_u.as_dvec3(), family.axis_v.as_dvec3());
        let TreeScratch { spans: geometry, stats, buckets, member_buckets } = scratch;
        geometry.clear();
        geometry.extend(self.members.iter().map(|&m| {
            let s = &table.shapes[m as usize];
            let corners = s.corners().map(|c| [(c - eye).dot(au), (c - eye).dot(av)]);
            MemberSpan::new(s.plane_dist_from(eye), (s.center - eye).dot(av), corners)
        }));
        // Every node's statistics, in heap order, merged from its children's: the slopes
        // and the offset and u ranges without a pass over the members per node (one pass
        // is left, for the range of v − α·offset).
        // (Every entry is written below: no clearing of the last frame's.)
        stats.resize(2 * leaves, NodeStats::EMPTY);
        for (k, leaf) in stats[leaves..2 * leaves].iter_mut().enumerate() {
            *leaf = geometry.get(k).map_or(NodeStats::EMPTY, NodeStats::of);
        }
        for k in (1..leaves).rev() {
            stats[k] = stats[2 * k].merge(&stats[2 * k + 1]);
        }
        let depth = leaves.trailing_zeros();
        for (k, m) in stats.iter().enumerate().skip(1) {
            let level = usize::BITS - 1 - k.leading_zeros();
            let span = 1 << (depth - level);
            let first = (k - (1 << level)) * span;
            let range = first.min(geometry.len())..(first + span).min(geometry.len());
            words.extend(node_words(&geometry[range], m));
        }
        let index_at = base + words.len() as u32;
        let room = index_words(self.members.len());
        match index.then(|| offset_index(geometry, stats[1].d, buckets, member_buckets)).flatten() {
            Some((d0, per_metre)) => {
                let at = (header - base) as usize;
                words[at + 13..at + 16].copy_from_slice(&[index_at, d0.to_bits(), per_metre.to_bits()]);
                words.extend_from_slice(buckets);
                words.resize(words.len() + room - buckets.len(), 0);
            }
            None => words.resize(words.len() + room, 0),
        }
        debug_assert_eq!(words.len() as u32 + base - header, tree_words(self.members.len()) as u32);
        header
    }
}

/// Working memory of [`FrameTree::append_words`], kept from frame to frame.
#[derive(Clone, Debug, Default)]
pub struct TreeScratch {
    spans: Vec<MemberSpan>,
    stats: Vec<NodeStats>,
    buckets: Vec<u32>,
    member_buckets: Vec<u32>,
}

/// The offset index of members `spans` (in leaf order) whose offsets span `range`: fills
/// `out` with the bucket starts (`spans.len() + 1` of them) and the leaf positions sorted
/// by bucket, and returns the lowest offset and the buckets per metre as the shader gets
/// them; `None` where the offsets do not spread (a bucket with more than
/// [`INDEX_MOST_PER_BUCKET`] members, or buckets too narrow for f32 at these offsets).
fn offset_index(
    spans: &[MemberSpan],
    range: [f64; 2],
    out: &mut Vec<u32>,
    member_buckets: &mut Vec<u32>,
) -> Option<(f32, f32)> {
    let n = spans.len();
    let width = range[1] - range[0];
    // A bucket must stay wide against the f32 rounding of the pixels' offsets and of the
    // intervals' ends: a quarter of one (INDEX_SLACK) some 40 f32 steps at these offsets.
    let least = 1e-5 * range[0].abs().max(range[1].abs());
    if n < 2 || (width / n as f64).partial_cmp(&least) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let d0 = down(range[0]);
    let per_metre = (n as f64 / width) as f32;
    let bucket =
        |d: f64| ((d - f64::from(d0)) * f64::from(per_metre)).floor().clamp(0.0, (n - 1) as f64) as usize;
    out.clear();
    out.resize(2 * n + 1, 0);
    let (starts, order) = out.split_at_mut(n + 1);
    member_buckets.clear();
    member_buckets.extend(spans.iter().map(|s| bucket(s.offset) as u32));
    for &b in member_buckets.iter() {
        starts[b as usize + 1] += 1;
    }
    if starts.iter().any(|&c| c > INDEX_MOST_PER_BUCKET) {
        return None;
    }
    for b in 1..=n {
        starts[b] += starts[b - 1];
    }
    // Each member to the next free slot of its bucket (its start counted up, then back).
    for (leaf, &b) in member_buckets.iter().enumerate() {
        order[starts[b as usize] as usize] = leaf as u32;
        starts[b as usize] += 1;
    }
    for b in (1..=n).rev() {
        starts[b] = starts[b - 1];
    }
    starts[0] = 0;
    Some((d0, per_metre))
}

/// What a node needs of a member: its plane offset, its centre's v, and its corners' u
/// and v ranges (the corners themselves are not needed: `v - α·offset` is monotone in v,
/// in f64 rounding too, so its range over the corners is that of the corners' v range).
#[derive(Clone, Copy, Debug, PartialEq)]
struct MemberSpan {
    offset: f64,
    centre_v: f64,
    u: [f64; 2],
    v: [f64; 2],
}

impl MemberSpan {
    fn new(offset: f64, centre_v: f64, corners: [[f64; 2]; 4]) -> Self {
        let (mut u, mut v) = ([f64::MAX, f64::MIN], [f64::MAX, f64::MIN]);
        for [cu, cv] in corners {
            u = [u[0].min(cu), u[1].max(cu)];
            v = [v[0].min(cv), v[1].max(cv)];
        }
        Self { offset, centre_v, u, v }
    }
}

/// What a node's words need of its members but the range of `v − α·offset`, merged from
/// its children's: the least-squares moments of their centres in (offset, v) (count,
/// means and centred sums; Chan, Golub and LeVeque's pairwise update), and the ranges of
/// their offsets and of their corners' u.
#[derive(Clone, Copy, Debug, PartialEq)]
struct NodeStats {
    n: f64,
    mean_d: f64,
    mean_v: f64,
    sdd: f64,
    sdv: f64,
    d: [f64; 2],
    u: [f64; 2],
}

impl NodeStats {
    /// No members.
    const EMPTY: Self = Self {
        n: 0.0,
        mean_d: 0.0,
        mean_v: 0.0,
        sdd: 0.0,
        sdv: 0.0,
        d: [f64::MAX, f64::MIN],
        u: [f64::MAX, f64::MIN],
    };

    fn of(m: &MemberSpan) -> Self {
        Self { n: 1.0, mean_d: m.offset, mean_v: m.centre_v, sdd: 0.0, sdv: 0.0, d: [m.offset; 2], u: m.u }
    }

    fn merge(&self, other: &Self) -> Self {
        if other.n == 0.0 {
            return *self;
        }
        if self.n == 0.0 {
            return *other;
        }
        let n = self.n + other.n;
        let (dd, dv) = (other.mean_d - self.mean_d, other.mean_v - self.mean_v);
        let w = self.n * other.n / n;
        Self {
            n,
            mean_d: self.mean_d + dd * (other.n / n),
            mean_v: self.mean_v + dv * (other.n / n),
            sdd: self.sdd + other.sdd + dd * dd * w,
            sdv: self.sdv + other.sdv + dd * dv * w,
            d: [self.d[0].min(other.d[0]), self.d[1].max(other.d[1])],
            u: [self.u[0].min(other.u[0]), self.u[1].max(other.u[1])],
        }
    }

    /// The slope of v against the offset; 0 where the offsets (nearly) agree.
    fn slope(&self) -> f64 {
        if self.sdd > 1e-12 * self.n { (self.sdv / self.sdd).clamp(-1e4, 1e4) } else { 0.0 }
    }
}

/// A node's words: the range of its members' plane offsets, the u range of their corners,
/// the slope `α` of their centres' v against the offset (their least-squares slope: a
/// stairway's treads climb along v) and the range of `v − α·offset` over their corners,
/// all rounded outwards to f32, and `1/α` (0 for α = 0); `stats` are the members' (the
/// offset and u ranges and the slope from there, the last range from the members). No
/// members: a lowest offset of f32::MAX, which no pixel lies above.
fn node_words(members: &[MemberSpan], stats: &NodeStats) -> [u32; TREE_NODE_WORDS] {
    if members.is_empty() {
        return [f32::MAX, f32::MAX, f32::MAX, f32::MIN, f32::MAX, f32::MIN, 0.0, 0.0].map(f32::to_bits);
    }
    // The slope the GPU multiplies by, so that the slab is computed with it.
    let alpha = stats.slope() as f32;
    let a = f64::from(alpha);
    // The range of v − α·offset over the members, in four interleaved minimums and
    // maximums (a chain of one each waits on the last one's latency every member; the
    // extremes are the same whatever the order).
    let (mut lo, mut hi) = ([f64::MAX; 4], [f64::MIN; 4]);
    let chunks = members.chunks_exact(4);
    let rest = chunks.remainder();
    for chunk in chunks {
        for (j, m) in chunk.iter().enumerate() {
            let shift = a * m.offset;
            lo[j] = lo[j].min(m.v[0] - shift);
            hi[j] = hi[j].max(m.v[1] - shift);
        }
    }
    for (j, m) in rest.iter().enumerate() {
        let shift = a * m.offset;
        lo[j] = lo[j].min(m.v[0] - shift);
        hi[j] = hi[j].max(m.v[1] - shift);
    }
    let w = [lo.into_iter().fold(f64::MAX, f64::min), hi.into_iter().fold(f64::MIN, f64::max)];
    let (d, u) = (stats.d, stats.u);
    let inv_alpha = if alpha == 0.0 { 0.0 } else { 1.0 / alpha };
    [down(d[0]), up(d[1]), down(u[0]), up(u[1]), down(w[0]), up(w[1]), alpha, inv_alpha].map(f32::to_bits)
}

/// The largest f32 at or below `x`.
fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) <= x { f } else { f.next_down() }
}

/// The smallest f32 at or above `x`.
fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) >= x { f } else { f.next_up() }
}

/// The CPU model of `tree_pixel` in `projection.wgsl`: the leaves (member positions) a
/// pixel at camera-relative `p` with on-plane tolerance `tol` reaches, in walk order, and
/// how many nodes it tests. `header` is the tree's header position in `words` (counted
/// from the buffer's start at `base`).
pub fn reached_leaves(words: &[u32], base: u32, header: u32, p: glam::Vec3, tol: f32) -> (Vec<u32>, usize) {
    reached_leaves_from(words, base, header, p, tol, 1)
}

/// [`reached_leaves`] for a walk that starts at node `start` (1: the root) and ends when it
/// leaves `start`'s subtree.
pub fn reached_leaves_from(
    words: &[u32],
    base: u32,
    header: u32,
    p: glam::Vec3,
    tol: f32,
    start: u32,
) -> (Vec<u32>, usize) {
    let w = |i: u32| words[(i - base) as usize];
    let f = |i: u32| f32::from_bits(w(i));
    let v3 = |i: u32| Vec3::new(f(i), f(i + 1), f(i + 2));
    let (n, au, av) = (v3(header), v3(header + 4), v3(header + 8));
    let (node_start, leaves) = (w(header + 3), w(header + 7));
    let zp = p.dot(n);
    let uv = [p.dot(au), p.dot(av)];
    let reach = zp - 0.5 * tol;
    let margin = node_margin(uv, zp);
    let mut out = Vec::new();
    let mut node = start;
    let mut tested = 0;
    loop {
        tested += 1;
        let at = node_start + (node - 1) * TREE_NODE_WORDS as u32;
        let lim: [f32; 8] = std::array::from_fn(|i| f(at + i as u32));
        if node_meets(lim, zp, uv, reach, margin) {
            if node >= leaves {
                out.push(node - leaves);
            } else {
                node *= 2;
                continue;
            }
        }
        while node != start && node & 1 == 1 {
            node >>= 1;
        }
        if node == start {
            break;
        }
        node += 1;
    }
    (out, tested)
}

/// The slack of a pixel's node tests (`m` of `tree_pixel` in the shader): a box is widened
/// by 1e-5 of the pixel's coordinates, ten times the f32 rounding of the member tests and of
/// normals that differ by [`NORMAL_TOLERANCE`].
fn node_margin(uv: [f32; 2], zp: f32) -> f32 {
    1e-5 * (uv[0].abs() + uv[1].abs() + zp.abs())
}

/// `tree_node_meets` of the shader: may a member of the node reflect the pixel? The
/// reflection point for offset `d` is `t(d) · uv`, `t(d) = d / (2d − zp)`, monotone in `d`
/// over the node's offsets below `reach`: its u over the node's range is a segment; its
/// `v − α·d` is the sum of a hyperbola and a line in `d`, whose range is its values at the
/// ends and, where it turns inside, at its one stationary point.
fn node_meets(lim: [f32; 8], zp: f32, uv: [f32; 2], reach: f32, margin: f32) -> bool {
    // NaN (a broken pixel) meets nothing.
    if lim[0].partial_cmp(&reach) != Some(std::cmp::Ordering::Less) {
        return false;
    }
    let (lo, hi) = (lim[0], lim[1].min(reach));
    let ta = lo / (2.0 * lo - zp);
    let tb = hi / (2.0 * hi - zp);
    let (ua, ub) = (ta * uv[0], tb * uv[0]);
    if ua.max(ub) + margin < lim[2] || ua.min(ub) - margin > lim[3] {
        return false;
    }
    let alpha = lim[6];
    let wa = ta * uv[1] - alpha * lo;
    let wb = tb * uv[1] - alpha * hi;
    let (mut w0, mut w1) = (wa.min(wb), wa.max(wb));
    // The stationary point: (2d − zp)² = −v·zp/α (lim[7] holds 1/α, 0 for α = 0).
    let q = -uv[1] * zp * lim[7];
    if q > 0.0 {
        let d = 0.5 * (zp - q.sqrt());
        if lo < d && d < hi {
            let w = d / (2.0 * d - zp) * uv[1] - alpha * d;
            w0 = w0.min(w);
            w1 = w1.max(w);
        }
    }
    let m = margin + 1e-5 * alpha.abs() * (lo.abs() + zp.abs());
    w1 + m >= lim[4] && w0 - m <= lim[5]
}

/// `{d ∈ [a, b] : qa·d² + qb·d + qc ≥ 0}` as two intervals (empty where the first end is
/// above the second), in f32 as `quadratic_set` of the shader computes it: a superset
/// (a negative discriminant counts as a double root).
fn quadratic_set(qa: f32, qb: f32, qc: f32, a: f32, b: f32) -> [[f32; 2]; 2] {
    const NONE: [f32; 2] = [1.0, 0.0];
    if qa == 0.0 {
        if qb == 0.0 {
            return [if qc >= 0.0 { [a, b] } else { NONE }, NONE];
        }
        let r = -qc / qb;
        return [if qb > 0.0 { [a.max(r), b] } else { [a, b.min(r)] }, NONE];
    }
    let disc = qb * qb - 4.0 * qa * qc;
    let s = disc.max(0.0).sqrt();
    let q = -0.5 * (qb + if qb < 0.0 { -s } else { s });
    let r1 = q / qa;
    // No real roots (or one): the vertex twice.
    let r2 = if disc <= 0.0 || q == 0.0 { r1 } else { qc / q };
    let (lo, hi) = (r1.min(r2), r1.max(r2));
    if qa > 0.0 { [[a, b.min(lo)], [a.max(hi), b]] } else { [[a.max(lo), b.min(hi)], NONE] }
}

/// The offsets `d` at which the root node `lim` (its words) may hold a member that reflects
/// a pixel at `zp`, `uv` (`reach`, `margin` as for [`node_meets`]), as two intervals in
/// ascending order (each empty where its first end is above its second): `index_interval`
/// of the shader. Below the camera (`d < 0`, where a member faces it) `2d − zp < 0`, so
/// each bound, multiplied by it, is a polynomial in `d`: `t·u ≥ U` ⇔ `(2U − u)·d − U·zp ≥
/// 0`, `t·u ≤ U` ⇔ `(u − 2U)·d + U·zp ≥ 0`; `t·v − α·d ≥ W` ⇔ `2α·d² − (v + α·zp −
/// 2W)·d − W·zp ≥ 0` and `≤ W` the same negated. `t·v − α·d` has one stationary point
/// at most, so at most one of the slab's two bounds passes in two pieces, and what passes
/// every bound is two intervals at most (one hull would join the two ends of a flight a
/// grazing pixel meets: tens of treads between them).
pub fn index_interval(lim: [f32; 8], zp: f32, uv: [f32; 2], reach: f32, margin: f32) -> [[f32; 2]; 2] {
    let a = lim[0];
    let b = lim[1].min(reach).min(0.0);
    let (u0, u1) = (lim[2] - margin, lim[3] + margin);
    let [a, b] = quadratic_set(0.0, 2.0 * u0 - uv[0], -u0 * zp, a, b)[0];
    let [a, b] = quadratic_set(0.0, uv[0] - 2.0 * u1, u1 * zp, a, b)[0];
    let alpha = lim[6];
    let m = margin + 1e-5 * alpha.abs() * (lim[0].abs() + zp.abs());
    let (w0, w1) = (lim[4] - m, lim[5] + m);
    let above = quadratic_set(2.0 * alpha, -(uv[1] + alpha * zp - 2.0 * w0), -w0 * zp, a, b);
    let below = quadratic_set(-2.0 * alpha, uv[1] + alpha * zp - 2.0 * w1, w1 * zp, a, b);
    let cut = |x: [f32; 2], y: [f32; 2]| [x[0].max(y[0]), x[1].min(y[1])];
    let hull = |s: [[f32; 2]; 2]| match (s[0][0] <= s[0][1], s[1][0] <= s[1][1]) {
        (true, true) => [s[0][0], s[1][1]],
        (false, true) => s[1],
        _ => s[0],
    };
    if above[1][0] <= above[1][1] {
        let below = hull(below);
        [cut(above[0], below), cut(above[1], below)]
    } else {
        [cut(above[0], below[0]), cut(above[0], below[1])]
    }
}

/// The CPU model of `tree_index_pixel` in `projection.wgsl`: the leaves (member positions)
/// a pixel takes from the tree's offset index, or `None` where the tree has no index or the
/// pixel walks it instead (more than [`INDEX_MOST_MEMBERS`] candidates, or an interval
/// that is not a number). Arguments as for [`reached_leaves`].
pub fn indexed_leaves(words: &[u32], base: u32, header: u32, p: glam::Vec3, tol: f32) -> Option<Vec<u32>> {
    let w = |i: u32| words[(i - base) as usize];
    let f = |i: u32| f32::from_bits(w(i));
    let index = w(header + 13);
    if index == 0 {
        return None;
    }
    let v3 = |i: u32| Vec3::new(f(i), f(i + 1), f(i + 2));
    let (n, au, av) = (v3(header), v3(header + 4), v3(header + 8));
    let (node_start, count) = (w(header + 3), w(header + 11));
    let zp = p.dot(n);
    let uv = [p.dot(au), p.dot(av)];
    let lim: [f32; 8] = std::array::from_fn(|i| f(node_start + i as u32));
    let (d0, per_metre) = (f(header + 14), f(header + 15));
    let last = (count - 1) as f32;
    // Each piece's members: its buckets, widened by INDEX_SLACK; the second from where the
    // first's end, so that none is tested twice.
    let mut ranges = [(0u32, 0u32); 2];
    let mut from = 0;
    for (k, [lo, hi]) in
        index_interval(lim, zp, uv, zp - 0.5 * tol, node_margin(uv, zp)).into_iter().enumerate()
    {
        if lo > hi {
            continue;
        }
        if lo.is_nan() || hi.is_nan() || lo.abs() >= 1e30 || hi.abs() >= 1e30 {
            return None;
        }
        let b0 = ((lo - d0) * per_metre - INDEX_SLACK).floor().clamp(0.0, last) as u32;
        let b1 = ((hi - d0) * per_metre + INDEX_SLACK).floor().clamp(0.0, last) as u32;
        let (first, end) = (w(index + b0).max(from), w(index + b1 + 1));
        ranges[k] = (first, end.max(first));
        from = from.max(end);
    }
    if ranges.iter().map(|r| r.1 - r.0).sum::<u32>() > INDEX_MOST_MEMBERS {
        return None;
    }
    Some(ranges.into_iter().flat_map(|(a, b)| a..b).map(|i| w(index + count + 1 + i)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape_tests::shape_test;

    /// The least-squares slope of `(offset, v)` in two passes (how the nodes first got it).
    fn two_pass_slope(members: &[(f64, f64)]) -> f64 {
        let n = members.len() as f64;
        let (mean_d, mean_v) = members.iter().fold((0.0, 0.0), |(a, b), m| (a + m.0 / n, b + m.1 / n));
        let (mut sdd, mut sdv) = (0.0, 0.0);
        for m in members {
            sdd += (m.0 - mean_d) * (m.0 - mean_d);
            sdv += (m.0 - mean_d) * (m.1 - mean_v);
        }
        if sdd > 1e-12 * n { (sdv / sdd).clamp(-1e4, 1e4) } else { 0.0 }
    }

    /// The node words from every corner of every member (how they were first computed).
    fn node_words_from_corners(members: &[(f64, f64, [[f64; 2]; 4])], slope: f64) -> [u32; TREE_NODE_WORDS] {
        if members.is_empty() {
            return [f32::MAX, f32::MAX, f32::MAX, f32::MIN, f32::MAX, f32::MIN, 0.0, 0.0].map(f32::to_bits);
        }
        let alpha = slope as f32;
        let a = f64::from(alpha);
        let (mut d, mut u, mut w) = ([f64::MAX, f64::MIN], [f64::MAX, f64::MIN], [f64::MAX, f64::MIN]);
        for &(offset, _, corners) in members {
            d = [d[0].min(offset), d[1].max(offset)];
            for [cu, cv] in corners {
                u = [u[0].min(cu), u[1].max(cu)];
                w = [w[0].min(cv - a * offset), w[1].max(cv - a * offset)];
            }
        }
        let inv_alpha = if alpha == 0.0 { 0.0 } else { 1.0 / alpha };
        [down(d[0]), up(d[1]), down(u[0]), up(u[1]), down(w[0]), up(w[1]), alpha, inv_alpha].map(f32::to_bits)
    }

    proptest::proptest! {
        /// A node's words from its members' statistics merged from two halves' and their v
        /// ranges are the words from all their corners, bit for bit; and the merged slope
        /// is the two-pass slope of all of them within rounding (exactly 0 where every
        /// offset agrees).
        #[test]
        fn node_words_from_member_ranges_match_the_corners(
            members in proptest::collection::vec(
                (-50.0f64..50.0, -50.0f64..50.0, proptest::array::uniform4(proptest::array::uniform2(-60.0f64..60.0))),
                0..12,
            ),
            split in 0usize..12,
            flat in proptest::bool::ANY,
        ) {
            let mut members = members;
            if flat {
                for m in &mut members {
                    m.0 = 7.25;
                }
            }
            let spans: Vec<MemberSpan> = members.iter().map(|&(d, v, c)| MemberSpan::new(d, v, c)).collect();
            let dv: Vec<(f64, f64)> = members.iter().map(|m| (m.0, m.1)).collect();
            let reference = two_pass_slope(&dv);
            let fold = |s: &[MemberSpan]| s.iter().fold(NodeStats::EMPTY, |acc, m| acc.merge(&NodeStats::of(m)));
            let split = split.min(spans.len());
            let stats = fold(&spans[..split]).merge(&fold(&spans[split..]));
            let merged = stats.slope();
            if flat {
                proptest::prop_assert_eq!(merged, 0.0);
            }
            proptest::prop_assert!((merged - reference).abs() <= 1e-9 * (1.0 + reference.abs()), "{} against {}", merged, reference);
            proptest::prop_assert_eq!(node_words(&spans, &stats), node_words_from_corners(&members, merged));
        }
    }

    fn tread(i: u32, center: DVec3, half: [f32; 2]) -> ShapeSource {
        crate::shapes::floor_mirror(i, center, half, 0)
    }

    fn table(shapes: Vec<ShapeSource>) -> ShapeTable {
        let mut t = ShapeTable { occluder_ranges: vec![0..0; shapes.len()], shapes, ..ShapeTable::default() };
        t.parallel_families = ParallelFamilies::build(&t.shapes);
        t
    }

    /// A stairway of `n` treads rising away along −z, plus scattered shelves.
    fn stairs_and_shelves(n: u32) -> Vec<ShapeSource> {
        let mut shapes: Vec<ShapeSource> = (0..n)
            .map(|i| {
                let (rise, run) = (2.0 / f64::from(n), 4.0 / f64::from(n));
                tread(
                    i,
                    DVec3::new(0.0, f64::from(i) * rise, -(f64::from(i) + 0.5) * run),
                    [1.5, (run * 0.5) as f32],
                )
            })
            .collect();
        for k in 0..12u32 {
            let x = f64::from(k % 4) * 1.1 - 2.0;
            shapes.push(tread(
                n + k,
                DVec3::new(x, 0.4 + 0.13 * f64::from(k), -1.0 - 0.3 * f64::from(k)),
                [0.3, 0.2],
            ));
        }
        shapes
    }

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The scaling suite's stairway of `count` mirror treads (6 m rise over a 12 m run, 6 m
    /// wide) seen from its camera, as one tree's words.
    struct ScalingStairway {
        table: ShapeTable,
        eye: DVec3,
        tree: FrameTree,
        words: Vec<u32>,
        header: u32,
        /// Depth of a tread.
        run: f64,
    }

    impl ScalingStairway {
        fn new(count: u32) -> Self {
            let (rise, run) = (6.0 / f64::from(count), 12.0 / f64::from(count));
            let shapes: Vec<ShapeSource> = (0..count)
                .map(|k| {
                    let c = DVec3::new(0.0, f64::from(k + 1) * rise, -(f64::from(k) + 0.5) * run);
                    tread(k, c, [3.0, (run * 0.5) as f32])
                })
                .collect();
            let table = table(shapes);
            let eye = DVec3::new(-7.0, 11.0, 8.0);
            let tree = FrameTree { family: 0, members: table.parallel_families.families[0].members.clone() };
            let mut words = Vec::new();
            let header = tree.append_words(&table, eye, 0, 0, true, &mut words, &mut TreeScratch::default());
            Self { table, eye, tree, words, header, run }
        }
    }

    /// On the scaling suite's stairways (1 000 and 10 000 treads, its camera), a pixel on
    /// the treads tests a few dozen nodes and reaches few leaves beyond those that reflect
    /// it: the slab per node follows the flight.
    #[test]
    fn a_pixel_on_a_long_flight_walks_a_few_paths() {
        for (count, max_nodes) in [(1000u32, 45.0), (10_000, 70.0)] {
            let ScalingStairway { table: t, eye, tree, words, header, run } = ScalingStairway::new(count);
            let mut next = rng(5);
            let (mut nodes, mut leaves, mut hits, n) = (0usize, 0usize, 0usize, 4000);
            for _ in 0..n {
                let s = &t.shapes[(next() * f64::from(count)) as usize];
                let on = s.center + DVec3::new((next() - 0.5) * 6.0, 0.0, (next() - 0.5) * run);
                let p = (on - eye).as_vec3();
                let tol = 1e-4 * p.length();
                let (reached, tested) = reached_leaves(&words, 0, header, p, tol);
                for &leaf in &reached {
                    let m = tree.members[leaf as usize];
                    let test = shape_test(&t.shapes[m as usize], m, eye);
                    hits += usize::from(test.reflects(p, tol).is_some());
                }
                nodes += tested;
                leaves += reached.len();
            }
            let per = |x: usize| x as f64 / f64::from(n);
            assert!(per(hits) > 1.0, "{count} treads: the treads reflect their pixels ({:.2})", per(hits));
            assert!(per(nodes) < max_nodes, "{count} treads: {:.1} nodes per pixel", per(nodes));
            assert!(leaves <= 2 * hits, "{count} treads: {leaves} leaves reached for {hits} reflections");
        }
    }

    /// The offset index of the scaling suite's stairways hands a pixel on the treads every
    /// member that reflects it, and few others: far fewer members than the walk tests
    /// nodes; a pixel walks instead only now and then.
    #[test]
    fn the_offset_index_hands_a_pixel_its_reflecting_treads_and_few_others() {
        for (count, most_mean) in [(1000u32, 9.0), (10_000, 16.0)] {
            let ScalingStairway { table: t, eye, tree, words, header, run } = ScalingStairway::new(count);
            assert_ne!(words[header as usize + 13], 0, "{count} treads: a flight gets an index");
            let mut next = rng(9);
            let (mut candidates, mut walked, mut nodes, mut hits, n) = (0usize, 0usize, 0usize, 0usize, 4000);
            for _ in 0..n {
                let s = &t.shapes[(next() * f64::from(count)) as usize];
                let on = s.center + DVec3::new((next() - 0.5) * 6.0, 0.0, (next() - 0.5) * run);
                let p = (on - eye).as_vec3();
                let tol = 1e-4 * p.length();
                nodes += reached_leaves(&words, 0, header, p, tol).1;
                let Some(given) = indexed_leaves(&words, 0, header, p, tol) else {
                    walked += 1;
                    continue;
                };
                candidates += given.len();
                for (leaf, &m) in tree.members.iter().enumerate() {
                    if shape_test(&t.shapes[m as usize], m, eye).reflects(p, tol).is_some() {
                        hits += 1;
                        assert!(
                            given.contains(&(leaf as u32)),
                            "{count} treads: member {m} reflects {p} but is not handed"
                        );
                    }
                }
            }
            let per = |x: usize| x as f64 / n as f64;
            eprintln!(
                "{count} treads: {:.2} candidates, {:.2} reflections, {:.1} walked nodes a pixel; {} of {n} walk",
                per(candidates),
                per(hits),
                per(nodes),
                walked
            );
            assert!(per(hits) > 1.0, "{count} treads: the treads reflect their pixels ({:.2})", per(hits));
            assert!(per(candidates) < most_mean, "{count} treads: {:.2} candidates a pixel", per(candidates));
            assert!(walked * 20 < n, "{count} treads: {walked} of {n} pixels walk");
        }
    }

    /// Around stairs and shelves, from random cameras, wherever a pixel takes the index's
    /// candidates they hold every member that reflects it; a family at a few offsets
    /// (floors of a level, many a storey) gets no index, and none is written unasked.
    #[test]
    fn the_offset_index_misses_no_reflecting_member_and_stays_off_where_offsets_cluster() {
        let t = table(stairs_and_shelves(300));
        let family = &t.parallel_families.families[0];
        let tree = FrameTree { family: 0, members: family.members.clone() };
        let mut next = rng(17);
        let (mut indexed, mut hits) = (0usize, 0usize);
        for _ in 0..8 {
            let eye = DVec3::new(next() * 4.0 - 2.0, 2.5 + next() * 2.0, 1.0 + next() * 3.0);
            let mut words = Vec::new();
            let header = tree.append_words(&t, eye, 24, 0, true, &mut words, &mut TreeScratch::default());
            assert_ne!(words[header as usize - 24 + 13], 0);
            let tests: Vec<_> =
                tree.members.iter().map(|&m| shape_test(&t.shapes[m as usize], m, eye)).collect();
            for _ in 0..2000 {
                let p = (DVec3::new(next() * 5.0 - 2.5, next() * 3.0, -next() * 5.0) - eye).as_vec3();
                let tol = 1e-4 * p.length();
                let Some(given) = indexed_leaves(&words, 24, header, p, tol) else { continue };
                indexed += 1;
                for (k, test) in tests.iter().enumerate() {
                    if test.reflects(p, tol).is_some() {
                        hits += 1;
                        assert!(given.contains(&(k as u32)), "member {k} reflects {p} but is not handed");
                    }
                }
            }
        }
        assert!(indexed > 10_000 && hits > 500, "{indexed} pixels indexed, {hits} reflections");

        // Ten storeys of forty floor tiles each: buckets of forty.
        let floors: Vec<ShapeSource> = (0..400u32)
            .map(|i| tread(i, DVec3::new(f64::from(i % 40) * 2.0, f64::from(i / 40) * 3.0, 0.0), [0.9, 0.9]))
            .collect();
        let t = table(floors);
        let tree = FrameTree { family: 0, members: t.parallel_families.families[0].members.clone() };
        let eye = DVec3::new(10.0, 40.0, 10.0);
        for index in [true, false] {
            let mut words = Vec::new();
            let header = tree.append_words(&t, eye, 0, 0, index, &mut words, &mut TreeScratch::default());
            assert_eq!(words[header as usize + 13], 0, "index {index}: clustered offsets get none");
            assert_eq!(words.len(), tree_words(400));
            assert_eq!(indexed_leaves(&words, 0, header, Vec3::new(0.0, -45.0, -10.0), 1e-3), None);
        }
    }

    proptest::proptest! {
        /// An offset index lists every member once, bucket by bucket: the starts climb from
        /// 0 to the member count, and the members between two starts are those whose offset
        /// falls in that bucket (as the shader's lowest offset and buckets per metre place
        /// it, within f32 rounding at a bucket's edge).
        #[test]
        fn the_offset_index_lists_every_member_once_in_its_bucket(
            steps in proptest::collection::vec(0.1f64..0.3, 2..200),
            start in -40.0f64..-1.0,
            shuffle in proptest::num::u64::ANY,
        ) {
            let mut offsets: Vec<f64> = steps.iter().scan(start, |d, s| { *d += s; Some(*d) }).collect();
            // Leaf order is not offset order.
            let mut next = rng(shuffle);
            for i in (1..offsets.len()).rev() {
                offsets.swap(i, (next() * (i + 1) as f64) as usize);
            }
            let spans: Vec<MemberSpan> = offsets.iter().map(|&d| MemberSpan::new(d, 0.0, [[0.0; 2]; 4])).collect();
            let range = [offsets.iter().copied().fold(f64::MAX, f64::min), offsets.iter().copied().fold(f64::MIN, f64::max)];
            let mut out = Vec::new();
            // Steps within a factor 3 of each other: no bucket (the mean step wide) holds
            // more than 3, so the offsets always get an index.
            let Some((d0, per_metre)) = offset_index(&spans, range, &mut out, &mut Vec::new()) else {
                return Err(proptest::test_runner::TestCaseError::fail("spread offsets get an index"));
            };
            let n = spans.len();
            let (starts, order) = out.split_at(n + 1);
            proptest::prop_assert_eq!(starts[0], 0);
            proptest::prop_assert_eq!(starts[n] as usize, n);
            proptest::prop_assert!(starts.windows(2).all(|w| w[0] <= w[1]));
            let mut seen = order.to_vec();
            seen.sort_unstable();
            proptest::prop_assert_eq!(seen, (0..n as u32).collect::<Vec<_>>());
            for b in 0..n {
                for &leaf in &order[starts[b] as usize..starts[b + 1] as usize] {
                    let x = ((offsets[leaf as usize] as f32 - d0) * per_metre).floor().clamp(0.0, (n - 1) as f32);
                    proptest::prop_assert!((x - b as f32).abs() <= 1.0, "member {} in bucket {} placed at {}", leaf, b, x);
                }
            }
        }

        /// `quadratic_set` holds every point of [a, b] where the quadratic is clearly
        /// non-negative (by more than f32 rounding), whatever its coefficients.
        #[test]
        fn quadratic_set_holds_every_point_where_the_quadratic_is_non_negative(
            qa in proptest::prop_oneof![proptest::strategy::Just(0.0f32), -10.0f32..10.0],
            qb in -100.0f32..100.0,
            qc in -100.0f32..100.0,
            a in -20.0f32..0.0,
            len in 0.0f32..20.0,
            x in 0.0f64..=1.0,
        ) {
            let b = a + len;
            let d = f64::from(a) + x * f64::from(len);
            let (qa64, qb64, qc64) = (f64::from(qa), f64::from(qb), f64::from(qc));
            let value = qa64 * d * d + qb64 * d + qc64;
            let scale = qa64.abs() * d * d + qb64.abs() * d.abs() + qc64.abs();
            let set = quadratic_set(qa, qb, qc, a, b);
            if value > 1e-4 * scale + 1e-6 {
                let slack = 1e-3 * (1.0 + d.abs());
                let inside = set.iter().any(|s| f64::from(s[0]) - slack <= d && d <= f64::from(s[1]) + slack);
                proptest::prop_assert!(inside, "q({}) = {} but the set is {:?}", d, value, set);
            }
        }
    }

    #[test]
    fn families_split_parallel_groups_by_normal_in_median_split_order() {
        let mut shapes = stairs_and_shelves(8);
        // A ceiling of the same parallel group facing down, a disabled tread, glass.
        let mut ceiling = tread(100, DVec3::new(0.0, 3.0, 0.0), [1.0, 1.0]);
        ceiling.normal = Vec3::NEG_Y;
        ceiling.axis_v = Vec3::Z;
        let mut ceiling2 = ceiling.clone();
        ceiling2.center.y = 3.5;
        let mut off = tread(102, DVec3::new(0.0, 9.0, 0.0), [1.0, 1.0]);
        off.enabled = false;
        let mut glass = tread(103, DVec3::new(0.0, 9.5, 0.0), [1.0, 1.0]);
        glass.kind = ReflectorKind::Transparent;
        shapes.extend([ceiling, ceiling2, off, glass]);
        let t = table(shapes);
        let fams = &t.parallel_families.families;
        assert_eq!(fams.len(), 2);
        assert_eq!(fams[0].members.len(), 20);
        let mut ceilings = fams[1].members.clone();
        ceilings.sort_unstable();
        assert_eq!(ceilings, vec![20, 21]);
        let mut stairs = fams[0].members.clone();
        stairs.sort_unstable();
        assert_eq!(stairs, (0..20).collect::<Vec<u32>>());
        // The median split: the first 16 leaves (the left subtree) hold the 16 centres lowest
        // along the longest extent (v = −z: 4.05 m, against 1.8 m of height and 3.3 m along x).
        let z = |m: &u32| -t.shapes[*m as usize].center.z;
        let left_max = fams[0].members[..16].iter().map(z).fold(f64::MIN, f64::max);
        let right_min = fams[0].members[16..].iter().map(z).fold(f64::MAX, f64::min);
        assert!(left_max <= right_min, "{left_max} > {right_min}");
        let tree = FrameTree { family: 1, members: fams[1].members.clone() };
        assert_eq!(tree.lowest(&t), 21, "facing down: the higher ceiling is the lowest plane");
        assert!(t.parallel_families.family_of[22..].iter().all(Option::is_none));
        let (f, rank) = t.parallel_families.family_of[7].unwrap();
        assert_eq!(fams[f as usize].members[rank as usize], 7);
    }

    /// Every member whose five-plane test (the plain loop's, in f32 as the shader runs it)
    /// passes for a pixel is reached by the walk, from cameras around stairs and shelves.
    #[test]
    fn the_walk_reaches_every_member_that_reflects_the_pixel() {
        for n in [3u32, 64, 1000] {
            let t = table(stairs_and_shelves(n));
            let family = &t.parallel_families.families[0];
            let mut next = rng(u64::from(n));
            let (mut hits, mut reached_total, mut pixels) = (0usize, 0usize, 0usize);
            for cam in 0..6 {
                let eye = DVec3::new(
                    next() * 4.0 - 2.0,
                    2.5 + next() * 2.0,
                    1.0 + next() * 3.0 - f64::from(cam) * 0.4,
                );
                let tree = FrameTree { family: 0, members: family.members.clone() };
                let mut words = Vec::new();
                let base = 40;
                let header =
                    tree.append_words(&t, eye, base, 0, true, &mut words, &mut TreeScratch::default());
                assert_eq!(words.len(), tree_words(tree.members.len()));
                let tests: Vec<_> =
                    tree.members.iter().map(|&m| shape_test(&t.shapes[m as usize], m, eye)).collect();
                for _ in 0..3000 {
                    let p = (DVec3::new(next() * 5.0 - 2.5, next() * 3.0, -next() * 5.0) - eye).as_vec3();
                    let tol = 1e-4 * p.length();
                    let (reached, _) = reached_leaves(&words, base, header, p, tol);
                    pixels += 1;
                    reached_total += reached.len();
                    for (k, test) in tests.iter().enumerate() {
                        if test.reflects(p, tol).is_some() {
                            hits += 1;
                            assert!(
                                reached.contains(&(k as u32)),
                                "{n} treads: member {k} reflects {p} but is not reached"
                            );
                        }
                    }
                }
            }
            assert!(hits > 100, "{n} treads: the sample must hit members ({hits})");
            // The walk prunes: far fewer leaves reached than members.
            let per_pixel = reached_total as f64 / pixels as f64;
            assert!(per_pixel < 3.0, "{n} treads: {per_pixel:.1} leaves reached per pixel");
        }
    }

    /// What a walk shared by a block of pixels could save at most (an idea for the
    /// 10 000-tread stairway, not built): the pixels of a patch of the flight about a 4K
    /// block wide (0.2 m at the scaling suite's camera) start their walks at the lowest
    /// common ancestor of every leaf any of them reaches, and reach the same leaves. With
    /// the ancestor known exactly (a real pass would find a higher one from the block's
    /// box) the pixels test 16-17 % fewer nodes: the reached leaves of a patch often
    /// straddle a high split, so the ancestor sits only 3-5 levels below the root.
    #[test]
    fn a_walk_from_a_patch_s_common_subtree_reaches_the_same_leaves() {
        for (count, patch) in [(1000u32, 0.2f64), (10_000, 0.2)] {
            let ScalingStairway { table: t, eye, words, header, run, .. } = ScalingStairway::new(count);
            let leaves = words[(header + 7) as usize];
            let mut next = rng(7);
            let span = ((patch / 12.0) * f64::from(count)).max(1.0) as u32;
            let (mut full, mut shared, mut depth, mut patches) = (0usize, 0usize, 0u32, 0u32);
            for _ in 0..300 {
                let (k0, x0) = ((next() * f64::from(count - span)) as u32, (next() - 0.5) * 5.0);
                let walks: Vec<(glam::Vec3, f32, Vec<u32>, usize)> = (0..64)
                    .map(|_| {
                        let s = &t.shapes[(k0 + (next() * f64::from(span)) as u32) as usize];
                        let x = x0 - s.center.x + (next() - 0.5) * patch;
                        let p = (s.center + DVec3::new(x, 0.0, (next() - 0.5) * run) - eye).as_vec3();
                        let tol = 1e-4 * p.length();
                        let (reached, tested) = reached_leaves(&words, 0, header, p, tol);
                        (p, tol, reached, tested)
                    })
                    .collect();
                // A patch nothing reflects (the flight's far end) has no subtree to start from.
                let reached = || walks.iter().flat_map(|w| w.2.iter().copied());
                let (Some(lo), Some(hi)) = (reached().min(), reached().max()) else { continue };
                full += walks.iter().map(|w| w.3).sum::<usize>();
                let (mut a, mut b) = (lo + leaves, hi + leaves);
                while a != b {
                    (a, b) = (a >> 1, b >> 1);
                }
                depth += 31 - a.leading_zeros();
                patches += 1;
                for (p, tol, reached, _) in walks {
                    let (again, tested) = reached_leaves_from(&words, 0, header, p, tol, a);
                    assert_eq!(again, reached, "{count} treads: a walk from node {a} reaches other leaves");
                    shared += tested;
                }
            }
            let saved = 1.0 - shared as f64 / full as f64;
            eprintln!(
                "{count} treads, {span}-tread patches: start {:.1} levels below the root of {}, {:.1} -> {:.1} node tests a pixel ({:.0} % fewer)",
                f64::from(depth) / f64::from(patches),
                leaves.trailing_zeros(),
                full as f64 / (64.0 * f64::from(patches)),
                shared as f64 / (64.0 * f64::from(patches)),
                100.0 * saved
            );
            assert!((0.05..0.4).contains(&saved), "{count} treads: {:.0} % fewer node tests", 100.0 * saved);
        }
    }

    /// A walk shared by a subgroup (an idea the model rejects, not built: see the test
    /// below): the pixels of one subgroup walk the tree together, descending into a node
    /// when any of them meets it, and each reaches the leaves it meets itself, in walk
    /// order (the leaves [`reached_leaves`] gives it alone). Also how many nodes the
    /// subgroup tests: what each of its invocations pays.
    fn reached_leaves_shared(
        words: &[u32],
        base: u32,
        header: u32,
        pixels: &[(glam::Vec3, f32)],
    ) -> (Vec<Vec<u32>>, usize) {
        let w = |i: u32| words[(i - base) as usize];
        let f = |i: u32| f32::from_bits(w(i));
        let v3 = |i: u32| Vec3::new(f(i), f(i + 1), f(i + 2));
        let (n, au, av) = (v3(header), v3(header + 4), v3(header + 8));
        let (node_start, leaves) = (w(header + 3), w(header + 7));
        let lanes: Vec<(f32, [f32; 2], f32, f32)> = pixels
            .iter()
            .map(|&(p, tol)| {
                let zp = p.dot(n);
                let uv = [p.dot(au), p.dot(av)];
                (zp, uv, zp - 0.5 * tol, node_margin(uv, zp))
            })
            .collect();
        let mut out = vec![Vec::new(); pixels.len()];
        let mut node = 1u32;
        let mut tested = 0;
        loop {
            tested += 1;
            let at = node_start + (node - 1) * TREE_NODE_WORDS as u32;
            let lim: [f32; 8] = std::array::from_fn(|i| f(at + i as u32));
            let meets: Vec<bool> =
                lanes.iter().map(|&(zp, uv, reach, m)| node_meets(lim, zp, uv, reach, m)).collect();
            if meets.iter().any(|&m| m) {
                if node >= leaves {
                    for (o, _) in out.iter_mut().zip(&meets).filter(|(_, m)| **m) {
                        o.push(node - leaves);
                    }
                } else {
                    node *= 2;
                    continue;
                }
            }
            while node & 1 == 1 {
                node >>= 1;
            }
            if node == 0 {
                break;
            }
            node += 1;
        }
        (out, tested)
    }

    /// What a walk shared by a subgroup costs against one walk per pixel, on the scaling
    /// suite's stairway seen through its camera at 3840x2160: 16 x 2 neighbouring pixels (a
    /// subgroup of 32 of the projection's thread layout) walk the union of their paths, each
    /// reaching the same leaves as alone. One walk per pixel costs a subgroup its slowest
    /// pixel's walk (the loop runs until every invocation is done); the shared walk the
    /// union's length, with every node load the same for all. The union is longer than
    /// the slowest walk: 41.7 node tests against 36.2 at 1 000 treads, 120 against 56 at
    /// 10 000 (the paths of pixels 16 apart part high in the tree), so the shared walk is
    /// not built.
    #[test]
    fn a_subgroup_s_shared_walk_reaches_each_pixel_s_leaves() {
        let (eye, look) = (DVec3::new(-7.0, 11.0, 8.0), DVec3::new(0.5, 2.5, -6.0));
        let fwd = (look - eye).normalize();
        let right = fwd.cross(DVec3::Y).normalize();
        let up = right.cross(fwd);
        let (width, height) = (3840.0, 2160.0);
        let th = (30f64).to_radians().tan();
        for count in [1000u32, 10_000] {
            let st = ScalingStairway::new(count);
            let rise = 6.0 / f64::from(count);
            // The pixel's point on the flight: the ray meets the slope y = -z / 2, lifted to
            // the tread there.
            let on_flight = |px: f64, py: f64| -> Option<glam::Vec3> {
                let x = ((px + 0.5) / width * 2.0 - 1.0) * th * width / height;
                let y = (1.0 - (py + 0.5) / height * 2.0) * th;
                let d = fwd + right * x + up * y;
                let s = -(eye.y + eye.z * 0.5) / (d.y + d.z * 0.5);
                let q = eye + d * s;
                if s <= 0.0 || q.x.abs() > 2.9 || !(-11.9..-0.1).contains(&q.z) {
                    return None;
                }
                let k = (-q.z / st.run).floor();
                Some((DVec3::new(q.x, (k + 1.0) * rise, q.z) - eye).as_vec3())
            };
            let mut next = rng(11);
            let (mut alone_sum, mut alone_max, mut shared, mut groups) = (0usize, 0usize, 0usize, 0usize);
            while groups < 400 {
                let (px0, py0) = ((next() * 240.0).floor() * 16.0, (next() * 1080.0).floor() * 2.0);
                let pixels: Option<Vec<(glam::Vec3, f32)>> = (0..32)
                    .map(|i| on_flight(px0 + f64::from(i % 16), py0 + f64::from(i / 16)))
                    .map(|p| p.map(|p| (p, 1e-4 * p.length())))
                    .collect();
                let Some(pixels) = pixels else { continue };
                groups += 1;
                let alone: Vec<(Vec<u32>, usize)> =
                    pixels.iter().map(|&(p, tol)| reached_leaves(&st.words, 0, st.header, p, tol)).collect();
                let (together, tested) = reached_leaves_shared(&st.words, 0, st.header, &pixels);
                for (a, t) in alone.iter().zip(&together) {
                    assert_eq!(&a.0, t, "{count} treads: the shared walk reaches other leaves");
                }
                alone_sum += alone.iter().map(|a| a.1).sum::<usize>();
                alone_max += alone.iter().map(|a| a.1).max().unwrap_or(0);
                shared += tested;
            }
            let g = groups as f64;
            eprintln!(
                "{count} treads: node tests a pixel alone {:.1} (the subgroup's slowest {:.1}), shared {:.1}",
                alone_sum as f64 / (32.0 * g),
                alone_max as f64 / g,
                shared as f64 / g
            );
            assert!(
                shared as f64 > 1.1 * alone_max as f64,
                "{count} treads: the shared walk ({shared}) would pay against the slowest pixel's ({alone_max})"
            );
        }
    }
}
