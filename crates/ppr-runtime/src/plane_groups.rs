//! Coplanar reflectors merged into one projection test: a floor of puddles, a facade of
//! windows, the floor tiles of a level.
//!
//! Shapes on one plane mirror a pixel to the same point, so their writes are the same;
//! they differ only in whether the reflection point (where the ray from the camera to the
//! mirror image crosses the plane) lies on one of them. A group is therefore tested once
//! per pixel, by the pyramid through the bounding rectangle of its members, and a pixel
//! that passes looks its reflection point up in a uniform grid over that rectangle, whose
//! cells list the members that overlap them (the seed's per-plane grid idea). A pixel's
//! cost is then one plane test, not one per member: 10 000 windows cost as much as a few.
//!
//! The grid is static (built with the table, in the group's own plane coordinates);
//! only each merged group's origin, camera-relative, is uploaded per frame
//! ([`GpuPlaneGroup`]).
//!
//! Layout of the static words (`u32`, floats as bits), per group, from `cells_start`:
//! `nu · nv + 1` cell starts (word positions of each cell's member list, from
//! `cells_start`; the next cell's start ends it), the member lists (local member indices),
//! then per member eight words from `rects_start`: centre (u, v), half extents (u, v), the
//! member's own u axis in the group's (u, v), its shape index, and its path blocker
//! ([`crate::path_blockers`], [`crate::path_blockers::NO_BLOCKER`] for none). On the GPU the
//! static words follow the headers and the frame's parallel trees; a header's
//! `cells_start` and `rects_start` count from the buffer's start.

use std::collections::HashMap;

use glam::{DVec2, DVec3, Vec3};
use ppr_format::ReflectorKind;

use crate::path_blockers::NO_BLOCKER;
use crate::shapes::ShapeSource;

/// Bit of [`crate::gpu_types::GpuShapeTest::shape`]: the test is a merged plane group's
/// (the rest of the word is its slot in the frame's group headers), not a shape's.
pub const GROUP_TEST_FLAG: u32 = 0x8000_0000;

/// Word offset of `table`'s static grid words in the GPU buffer: after one header slot per
/// group and the room of the frame's parallel trees ([`crate::parallel_trees`]).
pub fn plane_group_words_offset(table: &crate::shapes::ShapeTable) -> u32 {
    crate::parallel_trees::tree_words_start(table) + table.parallel_families.words_capacity() as u32
}

/// Words per member rectangle in the static data.
pub const RECT_WORDS: usize = 8;

/// Largest distance of a member's centre from the group's plane, metres, and smallest
/// cosine between their normals: shapes must lie on one plane to within f32 rounding of
/// the positions the projection tests (a looser tolerance would mirror a pixel against
/// the wrong plane).
const PLANE_TOLERANCE: f64 = 1e-4;
const NORMAL_COS: f32 = 1.0 - 1e-6;

/// One group of coplanar shapes (two or more).
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneGroup {
    /// Shape indices (into the table), in table order.
    pub members: Vec<u32>,
    /// World-space origin of the group's plane coordinates: the bounding rectangle's
    /// (min u, min v) corner.
    pub origin: DVec3,
    /// The first member's axes and normal: the group's plane coordinates.
    pub axis_u: Vec3,
    pub axis_v: Vec3,
    pub normal: Vec3,
    /// Size of the bounding rectangle along u and v, metres.
    pub extent: [f64; 2],
    /// Grid cells along u and v.
    pub cells: [u32; 2],
    /// Word positions in [`PlaneGroups::words`] of the cell starts and the member rects.
    pub cells_start: u32,
    pub rects_start: u32,
    /// The members' parallel group (merged shapes share it).
    pub parallel_group: u32,
    /// The largest roughness among the members.
    pub max_roughness: f32,
}

impl PlaneGroup {
    /// The group's bounding rectangle as a shape (for its pyramid test and source box).
    pub fn bounding_shape(&self) -> ShapeSource {
        let half = [self.extent[0] * 0.5, self.extent[1] * 0.5];
        ShapeSource {
            id: u32::MAX,
            kind: ReflectorKind::Opaque,
            enabled: true,
            center: self.origin + self.axis_u.as_dvec3() * half[0] + self.axis_v.as_dvec3() * half[1],
            axis_u: self.axis_u,
            axis_v: self.axis_v,
            normal: self.normal,
            // Rounded up, so that the bounding pyramid holds every member's.
            half_extents: [next_up(half[0]), next_up(half[1])],
            parallel_group: self.parallel_group,
            normal_map: false,
            roughness: self.max_roughness,
        }
    }

    /// The frame's header of this group for a camera at `eye`, for static words placed at
    /// word `base` of the GPU buffer.
    pub fn gpu_header(&self, eye: DVec3, base: u32) -> GpuPlaneGroup {
        let inv = |extent: f64, cells: u32| (f64::from(cells) / extent.max(1e-9)) as f32;
        GpuPlaneGroup {
            origin: (self.origin - eye).as_vec3().to_array(),
            cells_start: base + self.cells_start,
            axis_u: self.axis_u.to_array(),
            cells_u: self.cells[0],
            axis_v: self.axis_v.to_array(),
            cells_v: self.cells[1],
            inv_cell: [inv(self.extent[0], self.cells[0]), inv(self.extent[1], self.cells[1])],
            rects_start: base + self.rects_start,
            _pad: 0,
        }
    }
}

/// A merged group's header as `group_member` of `projection.wgsl` reads it (16 words):
/// its grid, camera-relative.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuPlaneGroup {
    pub origin: [f32; 3],
    pub cells_start: u32,
    pub axis_u: [f32; 3],
    pub cells_u: u32,
    pub axis_v: [f32; 3],
    pub cells_v: u32,
    /// Cells per metre along u and v.
    pub inv_cell: [f32; 2],
    pub rects_start: u32,
    pub _pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuPlaneGroup>() == 64);

/// Every group of coplanar shapes of a table and their static grid words.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlaneGroups {
    pub groups: Vec<PlaneGroup>,
    /// Per shape of the table, its group (if any).
    pub group_of: Vec<Option<u32>>,
    /// The grids (layout in the module documentation).
    pub words: Vec<u32>,
}

impl PlaneGroups {
    /// Groups the enabled opaque shapes of `shapes` that share a plane (and a parallel
    /// group) and builds their grids.
    pub fn build(shapes: &[ShapeSource]) -> Self {
        // Candidates bucketed by parallel group and plane offset to a millimetre; each is
        // then checked against its bucket's groups (and the neighbouring offsets', so that
        // a plane at a rounding boundary still finds its group).
        let mut by_key: HashMap<(u32, i64), Vec<usize>> = HashMap::new();
        let mut draft: Vec<Vec<u32>> = Vec::new();
        for (i, s) in shapes.iter().enumerate() {
            if !s.enabled || s.kind != ReflectorKind::Opaque {
                continue;
            }
            let offset = s.center.dot(s.normal.as_dvec3());
            let key = (offset * 1e3).round() as i64;
            let found = (key - 1..=key + 1).find_map(|k| {
                by_key.get(&(s.parallel_group, k))?.iter().copied().find(|&g| {
                    let first = &shapes[draft[g][0] as usize];
                    coplanar(first, s)
                })
            });
            match found {
                Some(g) => draft[g].push(i as u32),
                None => {
                    by_key.entry((s.parallel_group, key)).or_default().push(draft.len());
                    draft.push(vec![i as u32]);
                }
            }
        }
        let mut out = Self { group_of: vec![None; shapes.len()], ..Self::default() };
        for members in draft.into_iter().filter(|m| m.len() >= 2) {
            let g = out.groups.len() as u32;
            for &m in &members {
                out.group_of[m as usize] = Some(g);
            }
            let group = build_grid(shapes, members, &mut out.words);
            out.groups.push(group);
        }
        out
    }

    /// Writes each member's path blocker (`blockers`: per shape of the table) into its
    /// rectangle's last word.
    pub fn set_blockers(&mut self, blockers: &[u32]) {
        for g in &self.groups {
            for (j, &m) in g.members.iter().enumerate() {
                let r = g.rects_start as usize + RECT_WORDS * j;
                debug_assert_eq!(self.words[r + 6], m);
                self.words[r + 7] = blockers[m as usize];
            }
        }
    }
}

/// Whether `s` lies on `first`'s plane, facing the same way.
fn coplanar(first: &ShapeSource, s: &ShapeSource) -> bool {
    let n = first.normal.as_dvec3();
    first.normal.dot(s.normal) >= NORMAL_COS
        && s.corners().iter().all(|&c| (c - first.center).dot(n).abs() <= PLANE_TOLERANCE)
}

/// The group of `members` with its grid appended to `words`.
fn build_grid(shapes: &[ShapeSource], members: Vec<u32>, words: &mut Vec<u32>) -> PlaneGroup {
    let first = &shapes[members[0] as usize];
    let (au, av) = (first.axis_u.as_dvec3(), first.axis_v.as_dvec3());
    let base = first.center;
    let plane = |p: DVec3| DVec2::new((p - base).dot(au), (p - base).dot(av));
    let (mut lo, mut hi) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
    // Per member: its corners' box in the group's coordinates.
    let boxes: Vec<(DVec2, DVec2)> = members
        .iter()
        .map(|&m| {
            let corners = shapes[m as usize].corners().map(plane);
            let b = corners
                .iter()
                .fold((DVec2::splat(f64::MAX), DVec2::splat(f64::MIN)), |(l, h), &c| (l.min(c), h.max(c)));
            lo = lo.min(b.0);
            hi = hi.max(b.1);
            b
        })
        .collect();
    let extent = (hi - lo).max(DVec2::splat(1e-6));
    // About one member per cell, cells as square as the rectangle allows.
    let n = members.len() as f64;
    let cu = ((n * extent.x / extent.y).sqrt().ceil() as u32).clamp(1, 1024);
    let cv = ((n / f64::from(cu)).ceil() as u32).clamp(1, 1024);
    let cell_size = DVec2::new(extent.x / f64::from(cu), extent.y / f64::from(cv));
    let mut cell_members: Vec<Vec<u32>> = vec![Vec::new(); (cu * cv) as usize];
    for (local, (blo, bhi)) in boxes.iter().enumerate() {
        // Cells the member's box overlaps, widened by a cell's rounding margin.
        let cell = |p: DVec2, a: usize, cells: u32| {
            let v = (p[a] - lo[a]) / cell_size[a];
            (v.floor().max(0.0) as u32).min(cells - 1)
        };
        let margin = cell_size * 1e-4;
        let (u0, u1) = (cell(*blo - margin, 0, cu), cell(*bhi + margin, 0, cu));
        let (v0, v1) = (cell(*blo - margin, 1, cv), cell(*bhi + margin, 1, cv));
        for v in v0..=v1 {
            for u in u0..=u1 {
                cell_members[(u + v * cu) as usize].push(local as u32);
            }
        }
    }
    let cells_start = words.len() as u32;
    // Relative to `cells_start`: the lists follow the cell starts.
    let mut next = cell_members.len() + 1;
    for list in &cell_members {
        words.push(next as u32);
        next += list.len();
    }
    words.push(next as u32);
    for list in &cell_members {
        words.extend(list);
    }
    let rects_start = words.len() as u32;
    let origin = base + au * lo.x + av * lo.y;
    for &m in &members {
        let s = &shapes[m as usize];
        let c = plane(s.center) - lo;
        let axis =
            DVec2::new(s.axis_u.as_dvec3().dot(au), s.axis_u.as_dvec3().dot(av)).normalize_or(DVec2::X);
        let f = [c.x as f32, c.y as f32, s.half_extents[0], s.half_extents[1], axis.x as f32, axis.y as f32];
        words.extend(f.map(f32::to_bits));
        words.extend([m, NO_BLOCKER]);
    }
    debug_assert_eq!(words.len(), rects_start as usize + RECT_WORDS * members.len());
    PlaneGroup {
        max_roughness: members.iter().map(|&m| shapes[m as usize].roughness).fold(0.0, f32::max),
        parallel_group: first.parallel_group,
        members,
        origin,
        axis_u: first.axis_u,
        axis_v: first.axis_v,
        normal: first.normal,
        extent: [extent.x, extent.y],
        cells: [cu, cv],
        cells_start,
        rects_start,
    }
}

/// The smallest f32 above `x` (as f64): a half extent rounded up.
fn next_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) >= x { f } else { f32::from_bits(f.to_bits() + 1) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tile(i: u32, center: DVec3, half: [f32; 2], group: u32) -> ShapeSource {
        crate::shapes::floor_mirror(i, center, half, group)
    }

    /// The CPU model of the shader's lookup: the member whose rectangle holds `p` (a
    /// point on the plane), through the grid.
    fn lookup(groups: &PlaneGroups, g: usize, p: DVec3) -> Option<u32> {
        let group = &groups.groups[g];
        let w = &groups.words;
        let l = p - group.origin;
        let (u, v) = (l.dot(group.axis_u.as_dvec3()), l.dot(group.axis_v.as_dvec3()));
        let (cu, cv) = (
            (u / group.extent[0] * f64::from(group.cells[0])).floor(),
            (v / group.extent[1] * f64::from(group.cells[1])).floor(),
        );
        if cu < 0.0 || cv < 0.0 || cu >= f64::from(group.cells[0]) || cv >= f64::from(group.cells[1]) {
            return None;
        }
        let start = group.cells_start as usize;
        let cell = start + cu as usize + cv as usize * group.cells[0] as usize;
        (w[cell]..w[cell + 1]).find_map(|i| {
            let r = group.rects_start as usize + RECT_WORDS * w[start + i as usize] as usize;
            let f = |k: usize| f64::from(f32::from_bits(w[r + k]));
            let (du, dv) = (u - f(0), v - f(1));
            let (lu, lv) = (du * f(4) + dv * f(5), dv * f(4) - du * f(5));
            (lu.abs() <= f(2) && lv.abs() <= f(3)).then_some(w[r + 6])
        })
    }

    #[test]
    fn coplanar_shapes_share_a_group_and_the_grid_finds_each() {
        // A 7 × 5 floor of tiles, a raised tile (another plane), one of another parallel
        // group, a disabled one and a glass panel: only the 35 floor tiles merge.
        let mut shapes: Vec<ShapeSource> = (0..35)
            .map(|i| tile(i, DVec3::new(f64::from(i % 7) * 1.5, 0.0, -f64::from(i / 7) * 1.2), [0.5, 0.4], 0))
            .collect();
        shapes.push(tile(35, DVec3::new(0.0, 0.3, 0.0), [0.5, 0.4], 0));
        shapes.push(tile(36, DVec3::new(3.0, 0.0, 0.0), [0.5, 0.4], 1));
        let mut off = tile(37, DVec3::new(4.5, 0.0, 0.0), [0.5, 0.4], 0);
        off.enabled = false;
        shapes.push(off);
        let mut glass = tile(38, DVec3::new(6.0, 0.0, 0.0), [0.5, 0.4], 0);
        glass.kind = ReflectorKind::Transparent;
        shapes.push(glass);
        let groups = PlaneGroups::build(&shapes);
        assert_eq!(groups.groups.len(), 1);
        assert_eq!(groups.groups[0].members, (0..35).collect::<Vec<u32>>());
        assert!(groups.group_of[35..].iter().all(Option::is_none));
        let [cu, cv] = groups.groups[0].cells;
        assert!(cu * cv >= 20 && cu * cv <= 70, "{cu} x {cv} cells for 35 members");
        // Every member is found at points inside it, none at points between them.
        for (i, s) in shapes[..35].iter().enumerate() {
            for (du, dv) in [(0.0, 0.0), (0.49, 0.39), (-0.49, -0.39), (0.3, -0.2)] {
                let p = s.center + DVec3::new(du, 0.0, -dv);
                assert_eq!(lookup(&groups, 0, p), Some(i as u32), "tile {i} at ({du}, {dv})");
            }
            assert_eq!(lookup(&groups, 0, s.center + DVec3::new(0.6, 0.0, 0.0)), None);
            assert_eq!(lookup(&groups, 0, s.center + DVec3::new(0.0, 0.0, 0.55)), None);
        }
    }

    #[test]
    fn rotated_and_overlapping_members_are_found_by_their_own_axes() {
        // Members turned in the plane, one overlapping another: a point is found in a
        // member exactly when it lies in its rotated rectangle.
        let mut shapes = Vec::new();
        for i in 0..6u32 {
            let a = f64::from(i) * 0.4;
            let mut s = tile(i, DVec3::new(f64::from(i) * 0.9, 2.0, 0.3 * f64::from(i)), [0.8, 0.3], 0);
            s.axis_u = Vec3::new(a.cos() as f32, 0.0, a.sin() as f32);
            s.axis_v = s.normal.cross(s.axis_u);
            shapes.push(s);
        }
        let groups = PlaneGroups::build(&shapes);
        assert_eq!(groups.groups.len(), 1);
        let mut state = 7u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut inside, mut checked) = (0, 0);
        for _ in 0..20_000 {
            let p = DVec3::new(next() * 7.0 - 1.0, 2.0, next() * 3.5 - 1.0);
            let holders: Vec<u32> = shapes
                .iter()
                .filter(|s| {
                    let l = p - s.center;
                    l.dot(s.axis_u.as_dvec3()).abs() <= f64::from(s.half_extents[0]) - 1e-5
                        && l.dot(s.axis_v.as_dvec3()).abs() <= f64::from(s.half_extents[1]) - 1e-5
                })
                .map(|s| s.id)
                .collect();
            let outside_all = shapes.iter().all(|s| {
                let l = p - s.center;
                l.dot(s.axis_u.as_dvec3()).abs() > f64::from(s.half_extents[0]) + 1e-5
                    || l.dot(s.axis_v.as_dvec3()).abs() > f64::from(s.half_extents[1]) + 1e-5
            });
            let found = lookup(&groups, 0, p);
            if !holders.is_empty() {
                inside += 1;
                assert!(found.is_some_and(|f| holders.contains(&f)), "{p} in {holders:?}, found {found:?}");
            }
            if outside_all {
                checked += 1;
                assert_eq!(found, None, "{p} lies on no member");
            }
        }
        assert!(inside > 2000 && checked > 2000, "{inside} inside, {checked} outside");
    }

    #[test]
    fn the_bounding_shape_holds_every_member() {
        let shapes: Vec<ShapeSource> = (0..12)
            .map(|i| tile(i, DVec3::new(f64::from(i % 4) * 2.0, 1.0, -f64::from(i / 4)), [0.7, 0.3], 2))
            .collect();
        let groups = PlaneGroups::build(&shapes);
        let b = groups.groups[0].bounding_shape();
        assert_eq!(b.parallel_group, 2);
        for s in &shapes {
            for c in s.corners() {
                let l = c - b.center;
                assert!(l.dot(b.axis_u.as_dvec3()).abs() <= f64::from(b.half_extents[0]));
                assert!(l.dot(b.axis_v.as_dvec3()).abs() <= f64::from(b.half_extents[1]));
                assert!(l.dot(b.normal.as_dvec3()).abs() < 1e-9);
            }
        }
    }
}
