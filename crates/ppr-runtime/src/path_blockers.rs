//! Each parallel-family member's path blocker: the member standing right in front of it
//! (the next plane offset along the family's normal, its rectangle nearest), whose
//! rectangle a reflection path into the member may cross.
//!
//! A pixel at `p` reflects in a member at its reflection point `hit`; the light travels
//! from `p` down to `hit`. Where a parallel reflector of the same family stands between
//! the two planes and the segment crosses its rectangle, the path is blocked: the mirror
//! shows that reflector's underside there, not `p` (beyond the seed: its occluder lists
//! test the camera's ray to `hit`, which the depth test already covers). On a flight of
//! mirror treads a pixel reflects in the four or five treads below its own, and every
//! reflection but the nearest tread's crosses the tread above the one it lands on: those
//! writes would lose at the `atomicMin` to the nearer tread's value anyway (the riser or
//! the tread above is seen there), but they cost their projection, load, encoding and
//! atomic first. The projection pass tests a passing member's blocker before its write
//! (`PATH_BLOCKERS`), so they cost one shape read and a few products instead.
//!
//! Blocked writes are never ones that should land: a path that crosses an opaque
//! reflector's rectangle strictly inside it (by a rounding margin) cannot reach the
//! mirror. Where nothing else is seen along the path (a floating shelf whose underside
//! no pixel shows), the pixel stays without a value instead of showing what the shelf
//! hides. Only one blocker per member is looked up (the nearest rectangle of the nearest
//! offset above that lies within reach), so some blocked paths still write: the
//! buffer may keep values the test could have spared. A reflector's rectangle encloses
//! its reflective region (the extractor's fit), so a path through a part of a blocker's
//! rectangle that is not surface (the inside corner of an L-shaped floor) is blocked too:
//! the approximation the seed's occluder lists make with the same rectangles.

use glam::{DVec3, Vec3};

use crate::gpu_types::GpuShape;
use crate::parallel_trees::ParallelFamilies;
use crate::shapes::ShapeSource;

/// A member without a blocker (and every shape outside a family).
pub const NO_BLOCKER: u32 = u32::MAX;

/// Offsets closer than this (metres) are one level: coplanar members never block each other.
const LEVEL_TOLERANCE: f64 = 1e-5;
/// Levels above a member searched for its blocker.
const LEVELS_SEARCHED: usize = 8;
/// Members of a level compared (the lowest offsets first): a level of thousands of tiles
/// is not searched whole for each member below it.
const LEVEL_MEMBERS_SEARCHED: usize = 64;
/// A candidate whose rectangle lies farther from the member's, in their plane, than this
/// many times its height above the member is not taken: paths rarely reach it.
const REACH_PER_RISE: f64 = 4.0;

/// Per shape of `shapes`, its blocker's index ([`NO_BLOCKER`] for none).
pub fn path_blockers(shapes: &[ShapeSource], families: &ParallelFamilies) -> Vec<u32> {
    let mut out = vec![NO_BLOCKER; shapes.len()];
    for f in &families.families {
        let frame = [f.normal, f.axis_u, f.axis_v].map(Vec3::as_dvec3);
        let mut members: Vec<Member> =
            f.members.iter().map(|&i| Member::new(&shapes[i as usize], frame, i)).collect();
        members.sort_by(|a, b| a.offset.total_cmp(&b.offset).then(a.index.cmp(&b.index)));
        // The start of each level, and the end.
        let mut levels = vec![0];
        for (i, m) in members.iter().enumerate().skip(1) {
            if m.offset - members[*levels.last().expect("one level")].offset > LEVEL_TOLERANCE {
                levels.push(i);
            }
        }
        levels.push(members.len());
        for (level, span) in levels.windows(2).enumerate() {
            for k in &members[span[0]..span[1]] {
                out[k.index as usize] = levels
                    .windows(2)
                    .skip(level + 1)
                    .take(LEVELS_SEARCHED)
                    .find_map(|above| {
                        let end = above[1].min(above[0] + LEVEL_MEMBERS_SEARCHED);
                        members[above[0]..end]
                            .iter()
                            .map(|b| (k.gap(b), b))
                            .filter(|(gap, b)| *gap <= REACH_PER_RISE * (b.offset - k.offset))
                            .min_by(|x, y| x.0.total_cmp(&y.0))
                            .map(|(_, b)| b.index)
                    })
                    .unwrap_or(NO_BLOCKER);
            }
        }
    }
    out
}

/// A member's plane offset and the box of its rectangle in the family's plane frame.
struct Member {
    index: u32,
    offset: f64,
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Member {
    fn new(s: &ShapeSource, [n, u, v]: [DVec3; 3], index: u32) -> Self {
        let corners = s.corners().map(|c| [c.dot(u), c.dot(v)]);
        let lo = std::array::from_fn(|a| corners.iter().map(|c| c[a]).fold(f64::MAX, f64::min));
        let hi = std::array::from_fn(|a| corners.iter().map(|c| c[a]).fold(f64::MIN, f64::max));
        Self { index, offset: s.center.dot(n), lo, hi }
    }

    /// The distance between the two rectangles' boxes in the plane (0 where they touch).
    fn gap(&self, other: &Self) -> f64 {
        let along = |a: usize| (other.lo[a] - self.hi[a]).max(self.lo[a] - other.hi[a]).max(0.0);
        along(0).hypot(along(1))
    }
}

/// `projection.wgsl`'s `path_blocked`, in the same f32 operations: whether the path from
/// the pixel's camera-relative position `p` (at `dist` in front of the plane `plane`,
/// normal and minus its camera-relative offset) to its reflection point, `mirrored` its
/// mirror image, crosses the blocker `b`'s rectangle strictly inside.
pub fn path_blocked(p: Vec3, mirrored: Vec3, dist: f32, plane: [f32; 4], b: &GpuShape) -> bool {
    let n = Vec3::new(plane[0], plane[1], plane[2]);
    let rise = b.plane_dist + plane[3];
    let margin = PATH_MARGIN * (p.length() + dist);
    if !(rise > margin && rise < dist - margin) {
        return false;
    }
    let hit = mirrored * (-plane[3] / mirrored.dot(n));
    let x = hit + (p - hit) * (rise / dist);
    let lu = x.dot(Vec3::from(b.axis_u)) - b.center_u;
    let lv = x.dot(Vec3::from(b.axis_v)) - b.center_v;
    lu.abs() < b.half_u - margin && lv.abs() < b.half_v - margin
}

/// The rounding margin of [`path_blocked`], per metre of the magnitudes it sums (f32's
/// rounding of the mirror image, the reflection point and the crossing, with room).
pub const PATH_MARGIN: f32 = 4e-6;

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};

    use super::*;
    use crate::gpu_types::GpuShape;
    use crate::shape_tests::shape_test;
    use crate::shapes::{ShapeTable, floor_mirror};

    fn table(shapes: Vec<ShapeSource>) -> ShapeTable {
        let mut t = ShapeTable { occluder_ranges: vec![0..0; shapes.len()], shapes, ..ShapeTable::default() };
        t.parallel_families = ParallelFamilies::build(&t.shapes);
        t.path_blockers = path_blockers(&t.shapes, &t.parallel_families);
        t
    }

    /// The scaling suite's stairway of `count` mirror treads (6 m rise over a 12 m run, 6 m
    /// wide), listed bottom up.
    fn stairway(count: u32) -> ShapeTable {
        let (rise, run) = (6.0 / f64::from(count), 12.0 / f64::from(count));
        table(
            (0..count)
                .map(|k| {
                    let c = DVec3::new(0.0, f64::from(k + 1) * rise, -(f64::from(k) + 0.5) * run);
                    floor_mirror(k, c, [3.0, (run * 0.5) as f32], 0)
                })
                .collect(),
        )
    }

    #[test]
    fn each_tread_is_blocked_by_the_one_above_and_the_top_by_none() {
        let t = stairway(50);
        for k in 0..49 {
            assert_eq!(t.path_blockers[k], k as u32 + 1, "tread {k}");
        }
        assert_eq!(t.path_blockers[49], NO_BLOCKER);
    }

    #[test]
    fn blockers_stand_in_front_within_reach_and_never_share_the_plane() {
        // A floor of 3 × 3 tiles, a shelf 1 m over its middle, a shelf 0.5 m up but 100 m
        // away, and a wall (another family).
        let mut shapes: Vec<ShapeSource> = (0..9)
            .map(|i| {
                floor_mirror(i, DVec3::new(f64::from(i % 3) - 1.0, 0.0, f64::from(i / 3) - 1.0), [0.45; 2], 0)
            })
            .collect();
        shapes.push(floor_mirror(9, DVec3::new(0.0, 1.0, 0.0), [0.5; 2], 0));
        shapes.push(floor_mirror(10, DVec3::new(100.0, 0.5, 0.0), [0.5; 2], 0));
        let mut wall = floor_mirror(11, DVec3::new(0.0, 1.0, -3.0), [2.0; 2], 1);
        (wall.normal, wall.axis_v) = (Vec3::Z, Vec3::Y);
        shapes.push(wall);
        let t = table(shapes);
        // Every tile's is the near shelf (the far one is out of reach: 4 × 0.5 m), never a
        // tile beside it.
        assert_eq!(&t.path_blockers[..9], &[9; 9]);
        // Nothing stands in front of the shelves within reach, nor of the wall.
        assert_eq!(&t.path_blockers[9..], &[NO_BLOCKER; 3]);
    }

    fn gpu_shapes(t: &ShapeTable, eye: DVec3) -> Vec<GpuShape> {
        let mut gpu = Vec::new();
        t.gpu_shapes_into(eye, &mut gpu);
        gpu
    }

    /// For a pixel at `p` (world) seen from `eye`: `None` where shape `k` of `t` does not
    /// reflect it, else whether the path is blocked (`gpu`: the camera-relative shapes).
    fn blocked(t: &ShapeTable, gpu: &[GpuShape], eye: DVec3, k: usize, p: DVec3) -> Option<bool> {
        let test = shape_test(&t.shapes[k], k as u32, eye);
        let p = (p - eye).as_vec3();
        let dist = test.reflects(p, 1e-4 * p.length())?;
        let n = Vec3::from_slice(&test.plane[..3]);
        let b = t.path_blockers[k];
        Some(b != NO_BLOCKER && path_blocked(p, p - 2.0 * dist * n, dist, test.plane, &gpu[b as usize]))
    }

    #[test]
    fn a_path_through_the_shelf_is_blocked_one_beside_or_below_it_is_not() {
        let t = table(vec![
            floor_mirror(0, DVec3::ZERO, [3.0; 2], 0),
            floor_mirror(1, DVec3::new(0.0, 1.0, 0.0), [0.5; 2], 0),
        ]);
        let eye = DVec3::new(0.0, 2.5, 4.0);
        assert_eq!(t.path_blockers, [1, NO_BLOCKER]);
        let gpu = gpu_shapes(&t, eye);
        // Above the shelf, reflected in the floor below it: the path crosses the shelf.
        assert_eq!(blocked(&t, &gpu, eye, 0, DVec3::new(0.0, 2.0, -0.6)), Some(true));
        // Beside it, the path passes the shelf's edge by a metre.
        assert_eq!(blocked(&t, &gpu, eye, 0, DVec3::new(2.0, 2.0, -1.0)), Some(false));
        // Below the shelf's plane: nothing stands between.
        assert_eq!(blocked(&t, &gpu, eye, 0, DVec3::new(0.0, 0.5, -0.6)), Some(false));
    }

    /// On the scaling suite's 1 000-tread stairway seen from its camera, a pixel on the
    /// treads reflects in four or five treads below its own; all but at most one of those
    /// paths cross the tread above the one they land on (the one below its own tread, for
    /// three quarters of a tread's pixels: the rest of that tread shows the riser).
    #[test]
    fn most_reflections_of_a_long_flight_are_blocked() {
        let t = stairway(1000);
        let eye = DVec3::new(-7.0, 11.0, 8.0);
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let gpu = gpu_shapes(&t, eye);
        let (mut reflections, mut open, n) = (0usize, 0usize, 400);
        for _ in 0..n {
            let s = &t.shapes[(next() * 1000.0) as usize];
            let p = s.center + DVec3::new((next() - 0.5) * 6.0, 0.0, (next() - 0.5) * 0.012);
            for k in 0..t.shapes.len() {
                if let Some(b) = blocked(&t, &gpu, eye, k, p) {
                    reflections += 1;
                    open += usize::from(!b);
                }
            }
        }
        let per = |x: usize| x as f64 / f64::from(n);
        eprintln!("{:.2} reflections a pixel, {:.2} of them open", per(reflections), per(open));
        assert!(per(reflections) > 3.0, "{:.2} reflections a pixel", per(reflections));
        assert!(per(open) < 0.4 * per(reflections), "{:.2} of {:.2} open", per(open), per(reflections));
        assert!(
            per(open) > 0.5 && per(open) <= 1.0,
            "the nearest tread's reflection stays: {:.2} a pixel",
            per(open)
        );
    }
}
