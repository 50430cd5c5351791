//! Each visible shape's reflection test (a plane and two axis forms), built per frame in f64 and
//! camera-relative, for the projection pass's per-pixel loop and its block culling.
//!
//! A point `p` in front of a reflector is reflected into its rectangle when the ray from
//! the camera to its mirror image crosses the plane inside the rectangle. Mirroring that
//! ray gives the segment from the mirrored camera `e'` to `p`, which crosses the plane at
//! the same point: the test is whether `p` lies in the pyramid from `e'` through the
//! rectangle. That is four half-spaces (the pyramid's sides, each through `e'` and one
//! edge) plus the reflector's own (in front of the plane). Opposite sides share their
//! terms: with `h` the camera's height over the plane and `dist` the point's, the crossing
//! lies within the half extent `a` along an axis exactly when `|L| ≤ a (dist + h)`, `L` a
//! linear form of the point (the crossing's offset along the axis times `dist + h`). So
//! the per-pixel test is three dot products and two products, without a division
//! ([`GpuShapeTest`]), and a block of pixels is culled by the five planes
//! ([`GpuShapeTest::sides`]) against the box of its positions.

use glam::{DVec3, DVec4};

use crate::gpu_types::GpuShapeTest;
use crate::parallel_trees::{TREE_TEST_FLAG, TreeScratch, tree_words_start};
use crate::path_blockers::NO_BLOCKER;
use crate::plan::{FramePlan, TestedEntry};
use crate::plane_groups::{GROUP_TEST_FLAG, plane_group_words_offset};
use crate::shapes::{ShapeSource, ShapeTable};

/// What one frame's projection reads of its tests. [`FrameTests::fill`] refills it frame
/// after frame in the same memory (at thousands of shapes, fresh vectors of megabytes a
/// frame cost more in page faults than their contents).
#[derive(Default)]
pub struct FrameTests {
    /// One test per entry of `plan.tested` (a merged plane group's is its bounding
    /// rectangle's, its `shape` the group's slot among the headers, flagged
    /// [`GROUP_TEST_FLAG`]; a parallel tree's is its lowest member's plane with sides every
    /// point passes, its `shape` the tree's header position, flagged [`TREE_TEST_FLAG`]),
    /// then one per layer, then the trees' members' own tests.
    pub tests: Vec<GpuShapeTest>,
    /// How many of `tests` the loop reads (the entries and the layers; the uniform copy).
    pub looped: usize,
    /// The start of the plane-group buffer: the merged groups' headers in slot order, then
    /// (when the frame has trees) zeros up to the trees' room and the trees' words.
    pub group_words: Vec<u32>,
    /// The trees' working memory.
    trees: TreeScratch,
}

/// A frame's projection tests for a camera at `eye`.
pub fn frame_tests(table: &ShapeTable, plan: &FramePlan, eye: DVec3) -> FrameTests {
    let mut tests = FrameTests::default();
    tests.fill(table, plan, eye);
    tests
}

impl FrameTests {
    /// Refills these with a frame's projection tests for a camera at `eye` ([`frame_tests`]).
    pub fn fill(&mut self, table: &ShapeTable, plan: &FramePlan, eye: DVec3) {
        let base = plane_group_words_offset(table);
        let entries = plan.tested.len();
        self.looped = entries + plan.layers.len();
        let tree_base = tree_words_start(table) as usize;
        let Self { tests, group_words, trees, looped } = self;
        // The entries' and layers' tests by index, the members' pushed after them; the
        // groups' headers at their slots, the trees' words from `tree_base` on: each part
        // written once where it goes.
        tests.clear();
        tests.resize(*looped, GpuShapeTest::default());
        group_words.clear();
        if !plan.trees.is_empty() {
            group_words.resize(tree_base, 0);
        }
        let mut slots = 0usize;
        for (k, e) in plan.tested.iter().enumerate() {
            tests[k] = match *e {
                TestedEntry::Shape(i) => member_test(table, plan, i, eye),
                TestedEntry::PlaneGroup(g) => {
                    let group = &table.plane_groups.groups[g as usize];
                    let slot = GROUP_TEST_FLAG | slots as u32;
                    let header = [group.gpu_header(eye, base)];
                    let words: &[u32] = bytemuck::cast_slice(&header);
                    let at = slots * words.len()..(slots + 1) * words.len();
                    if group_words.len() < at.end {
                        group_words.resize(at.end, 0);
                    }
                    group_words[at].copy_from_slice(words);
                    slots += 1;
                    shape_test(&group.bounding_shape(), slot, eye)
                }
                TestedEntry::ParallelTree(t) => {
                    let tree = &plan.trees[t as usize];
                    let start = tests.len() as u32;
                    let header = tree.append_words(table, eye, 0, start, plan.tree_index, group_words, trees);
                    tests.extend(tree.members.iter().map(|&m| member_test(table, plan, m, eye)));
                    let mut test =
                        shape_test(&table.shapes[tree.lowest(table) as usize], TREE_TEST_FLAG | header, eye);
                    // Lowered by a margin, so that no member reflects a point the entry's plane
                    // does not (their normals may differ in the last bits).
                    test.plane[3] += 1e-5 * test.plane[3].abs() + 1e-6;
                    (test.across_u, test.across_v, test.extent) = GpuShapeTest::NO_SIDES;
                    test
                }
            };
        }
        for (k, l) in plan.layers.iter().enumerate() {
            tests[entries + k] = shape_test(&table.shapes[l.shape as usize], l.shape, eye);
        }
    }
}

/// The test of shape `index` of `table` as a tested entry or a tree's member: with its
/// path blocker where the frame tests them ([`FramePlan::path_blockers`]).
pub fn member_test(table: &ShapeTable, plan: &FramePlan, index: u32, eye: DVec3) -> GpuShapeTest {
    let mut test = shape_test(&table.shapes[index as usize], index, eye);
    if plan.path_blockers {
        test.blocker = table.path_blockers.get(index as usize).copied().unwrap_or(NO_BLOCKER);
    }
    test
}

/// The test of one shape (index `index` in its table).
pub fn shape_test(shape: &ShapeSource, index: u32, eye: DVec3) -> GpuShapeTest {
    let n = shape.normal.as_dvec3();
    let d = shape.plane_dist_from(eye);
    let plane = n.extend(-d);
    let [(across_u, ku, mu), (across_v, kv, mv)] = axis_forms(shape, eye);
    GpuShapeTest {
        plane: plane.as_vec4().to_array(),
        across_u: across_u.as_vec4().to_array(),
        across_v: across_v.as_vec4().to_array(),
        extent: [ku, mu, kv, mv].map(|x| x as f32),
        shape: index,
        group: shape.parallel_group,
        blocker: NO_BLOCKER,
        _pad: 0,
    }
}

/// Per rectangle axis, the form `L` and the bound's `k`, `m` of [`GpuShapeTest`]: a point
/// `p` at distance `dist` in front of the plane is reflected within the rectangle's extent
/// along the axis when `|L · (p, 1)| ≤ k · dist + m`, camera-relative.
///
/// With `h` the camera's height over the plane (`-plane_dist`), `c` the centre's
/// coordinate along the axis and `a` the half extent: the segment from the mirrored camera
/// (coordinate `-c` from the centre, `h` behind the plane) to `p` crosses the plane at the
/// offset `(h · (p · axis - c) - c · dist) / (dist + h)` from the centre, so
/// `L = (h · axis - c · n) · p - 2 c h` and the bound is `a · (dist + h)`; both are divided
/// by `|h · axis - c · n|` (a unit normal, as the sides had). A camera on or behind the
/// plane (which the plan culls) gets a test no point passes.
pub fn axis_forms(shape: &ShapeSource, eye: DVec3) -> [(DVec4, f64, f64); 2] {
    let n = shape.normal.as_dvec3();
    let h = -shape.plane_dist_from(eye);
    let center = shape.center - eye;
    let axes = [shape.axis_u.as_dvec3(), shape.axis_v.as_dvec3()];
    std::array::from_fn(|i| {
        let (axis, half) = (axes[i], f64::from(shape.half_extents[i]));
        let c = center.dot(axis);
        let normal = h * axis - c * n;
        let len = normal.length();
        if !(h > 0.0 && len > 0.0 && len.is_finite()) {
            return (DVec4::ZERO, 0.0, -1.0);
        }
        ((normal / len).extend(-2.0 * c * h / len), half / len, half * h / len)
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use ppr_format::ReflectorKind;

    use crate::camera::{Camera, Projection};

    use super::*;

    fn mirror() -> ShapeSource {
        ShapeSource {
            id: 0,
            kind: ReflectorKind::Opaque,
            enabled: true,
            center: DVec3::new(10.0, 0.0, -3.0),
            axis_u: Vec3::X,
            axis_v: Vec3::NEG_Z,
            normal: Vec3::Y,
            half_extents: [1.5, 0.5],
            parallel_group: 3,
            normal_map: false,
            roughness: 0.0,
        }
    }

    /// The reference: mirror the point, cast from the camera, test the hit in f64.
    fn reflects(shape: &ShapeSource, eye: DVec3, p: DVec3) -> bool {
        let n = shape.normal.as_dvec3();
        let rel_center = shape.center - eye;
        let d = rel_center.dot(n);
        let dist = p.dot(n) - d;
        if dist <= 0.0 {
            return false;
        }
        let m = p - 2.0 * dist * n;
        let hit = m * (d / m.dot(n)) - rel_center;
        hit.dot(shape.axis_u.as_dvec3()).abs() <= f64::from(shape.half_extents[0])
            && hit.dot(shape.axis_v.as_dvec3()).abs() <= f64::from(shape.half_extents[1])
    }

    /// The tests and plane-group words of a frame with merged plane groups and a parallel
    /// tree, written in place, are what building each part apart and joining them gives:
    /// the entries' tests, the layers', then the members'; the groups' headers in slot
    /// order, zeros up to the trees' room, the trees' words. And a refill in the same
    /// memory gives the same again.
    #[test]
    fn a_frame_s_tests_and_words_are_the_parts_joined() {
        use crate::parallel_trees::{ParallelFamilies, TreeScratch};
        use crate::plan::{Choice, PlanParams};
        use crate::plane_groups::PlaneGroups;
        use crate::shapes::floor_mirror;

        let mut shapes = Vec::new();
        // Two floors of four tiles each (two plane groups), then a flight of 40 treads.
        for (floor, y) in [(0u32, 0.0), (1, -2.0)] {
            for k in 0..4 {
                let c = DVec3::new(f64::from(k % 2) * 2.5 - 1.25, y, f64::from(k / 2) * 2.5 - 1.25);
                shapes.push(floor_mirror(shapes.len() as u32, c, [1.0, 1.0], 10 + floor));
            }
        }
        for k in 0..40 {
            let c = DVec3::new(6.0, 1.0 + 0.17 * f64::from(k), -0.28 * f64::from(k));
            shapes.push(floor_mirror(shapes.len() as u32, c, [1.0, 0.14], 1));
        }
        let mut table =
            ShapeTable { occluder_ranges: vec![0..0; shapes.len()], shapes, ..ShapeTable::default() };
        table.plane_groups = PlaneGroups::build(&table.shapes);
        table.parallel_families = ParallelFamilies::build(&table.shapes);
        let camera = Camera::look_at(
            DVec3::new(2.0, 30.0, 12.0),
            DVec3::new(2.0, 0.0, -4.0),
            Vec3::Y,
            Projection::default(),
        );
        let params = PlanParams {
            plane_groups: Choice::On,
            parallel_trees: Choice::On,
            tree_index: Choice::On,
            ..PlanParams::default()
        };
        let plan = FramePlan::build(&table, &camera, [320, 180], &params);
        let groups = plan.tested.iter().filter(|e| matches!(e, TestedEntry::PlaneGroup(_))).count();
        assert_eq!((groups, plan.trees.len()), (2, 1), "{:?}", plan.tested);
        let eye = camera.position;

        // Each part apart, joined.
        let base = plane_group_words_offset(&table);
        let looped = plan.tested.len() + plan.layers.len();
        let (mut headers, mut tree_words, mut members) = (Vec::new(), Vec::new(), Vec::new());
        let mut tests: Vec<GpuShapeTest> = Vec::new();
        for e in &plan.tested {
            tests.push(match *e {
                TestedEntry::Shape(i) => member_test(&table, &plan, i, eye),
                TestedEntry::PlaneGroup(g) => {
                    let group = &table.plane_groups.groups[g as usize];
                    headers.push(group.gpu_header(eye, base));
                    shape_test(&group.bounding_shape(), GROUP_TEST_FLAG | (headers.len() as u32 - 1), eye)
                }
                TestedEntry::ParallelTree(t) => {
                    let tree = &plan.trees[t as usize];
                    let start = (looped + members.len()) as u32;
                    let tree_base = tree_words_start(&table);
                    let header = tree.append_words(
                        &table,
                        eye,
                        tree_base,
                        start,
                        plan.tree_index,
                        &mut tree_words,
                        &mut TreeScratch::default(),
                    );
                    members.extend(tree.members.iter().map(|&m| member_test(&table, &plan, m, eye)));
                    let mut test =
                        shape_test(&table.shapes[tree.lowest(&table) as usize], TREE_TEST_FLAG | header, eye);
                    test.plane[3] += 1e-5 * test.plane[3].abs() + 1e-6;
                    (test.across_u, test.across_v, test.extent) = GpuShapeTest::NO_SIDES;
                    test
                }
            });
        }
        tests.extend(plan.layers.iter().map(|l| shape_test(&table.shapes[l.shape as usize], l.shape, eye)));
        tests.extend(members);
        let mut words: Vec<u32> = bytemuck::cast_slice(&headers).to_vec();
        words.resize(tree_words_start(&table) as usize, 0);
        words.extend(tree_words);

        let mut got = frame_tests(&table, &plan, eye);
        assert_eq!(got.looped, looped);
        assert_eq!(got.tests, tests);
        assert_eq!(got.group_words, words);
        // Refilled for another camera, then for the first again: the same words.
        let other = Camera::look_at(
            DVec3::new(-3.0, 25.0, 8.0),
            DVec3::new(3.0, 0.0, -6.0),
            Vec3::Y,
            Projection::default(),
        );
        got.fill(&table, &FramePlan::build(&table, &other, [320, 180], &params), other.position);
        got.fill(&table, &plan, eye);
        assert_eq!((got.tests, got.group_words), (tests, words));
    }

    #[test]
    fn the_axis_forms_and_the_sides_agree_with_mirroring_and_casting() {
        let shape = mirror();
        let mut state = 0x1234_5678_u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        // Above the mirror, grazing it from afar, and off to one side of it.
        for eye in [DVec3::new(9.0, 1.7, 2.0), DVec3::new(9.5, 0.05, 6.0), DVec3::new(16.0, 0.6, -3.5)] {
            let t = shape_test(&shape, 7, eye);
            assert_eq!((t.shape, t.group), (7, 3));
            let planes: Vec<DVec4> =
                std::iter::once(t.plane).chain(t.sides()).map(|a| DVec4::from(a.map(f64::from))).collect();
            let (mut inside, mut disagree) = (0, 0);
            for k in 0..20_000 {
                // Half anywhere near the mirror, half along reflected rays through a
                // rectangle 1.3 times the mirror's (in and out of the pyramid, close to its
                // sides from every camera).
                let p = if k % 2 == 0 {
                    DVec3::new(next() * 8.0 - 3.0, next() * 4.0 - 1.0, next() * 10.0 - 12.0)
                } else {
                    let [a, b] = shape.half_extents.map(|x| 1.3 * f64::from(x));
                    let hit = shape.center
                        + shape.axis_u.as_dvec3() * (next() * 2.0 - 1.0) * a
                        + shape.axis_v.as_dvec3() * (next() * 2.0 - 1.0) * b;
                    let n = shape.normal.as_dvec3();
                    let ray = (hit - eye).normalize();
                    hit + (ray - 2.0 * ray.dot(n) * n) * (0.1 + 5.0 * next()) - eye
                };
                let values: Vec<f64> = planes.iter().map(|pl| pl.truncate().dot(p) + pl.w).collect();
                let by_planes = values[0] > 0.0 && values[1..].iter().all(|&v| v >= 0.0);
                let by_forms = t.reflects(p.as_vec3(), 1e-30).is_some();
                let by_reference = reflects(&shape, eye, p);
                inside += usize::from(by_reference);
                // Points within f32 rounding of a side may go either way.
                let margin = values.iter().map(|v| v.abs()).fold(f64::MAX, f64::min);
                if (by_planes != by_reference || by_forms != by_reference) && margin > 1e-5 {
                    disagree += 1;
                }
            }
            assert!(inside > 200, "the sample must hit the pyramid from {eye}: {inside}");
            assert_eq!(disagree, 0, "from {eye}");
        }
    }

    #[test]
    fn a_camera_behind_the_plane_gets_a_test_no_point_passes() {
        let t = shape_test(&mirror(), 0, DVec3::new(9.0, -1.0, 2.0));
        for p in [glam::Vec3::new(1.0, 1.5, -5.0), glam::Vec3::new(1.0, -1.5, -5.0), glam::Vec3::ZERO] {
            assert_eq!(t.reflects(p, 1e-30), None, "{p}");
        }
    }
}
