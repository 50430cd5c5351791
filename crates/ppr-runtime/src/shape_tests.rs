//! Each visible shape's reflection test as five planes, built per frame in f64 and
//! camera-relative, for the projection pass's per-pixel loop and its block culling.
//!
//! A point `p` in front of a reflector is reflected into its rectangle when the ray from
//! the camera to its mirror image crosses the plane inside the rectangle. Mirroring that
//! ray gives the segment from the mirrored camera `e'` to `p`, which crosses the plane at
//! the same point: the test is whether `p` lies in the pyramid from `e'` through the
//! rectangle. That is four half-spaces (the pyramid's sides, each through `e'` and one
//! edge) plus the reflector's own (in front of the plane), so the per-pixel test is five
//! dot products, without a division, and a block of pixels is culled by the same five
//! planes against the box of its positions.

use glam::{DVec3, DVec4};

use crate::gpu_types::GpuShapeTest;
use crate::parallel_trees::{TREE_TEST_FLAG, tree_words_start};
use crate::plan::{FramePlan, TestedEntry};
use crate::plane_groups::{GROUP_TEST_FLAG, GpuPlaneGroup, plane_group_words_offset};
use crate::shapes::{ShapeSource, ShapeTable};

/// What one frame's projection reads of its tests.
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
}

/// A frame's projection tests for a camera at `eye`.
pub fn frame_tests(table: &ShapeTable, plan: &FramePlan, eye: DVec3) -> FrameTests {
    let base = plane_group_words_offset(table);
    let mut headers: Vec<GpuPlaneGroup> = Vec::new();
    let looped = plan.tested.len() + plan.layers.len();
    let tree_base = tree_words_start(table);
    let mut tree_words = Vec::new();
    let mut member_tests = Vec::new();
    let mut tests: Vec<GpuShapeTest> = plan
        .tested
        .iter()
        .map(|e| match *e {
            TestedEntry::Shape(i) => shape_test(&table.shapes[i as usize], i, eye),
            TestedEntry::PlaneGroup(g) => {
                let group = &table.plane_groups.groups[g as usize];
                let slot = GROUP_TEST_FLAG | headers.len() as u32;
                headers.push(group.gpu_header(eye, base));
                shape_test(&group.bounding_shape(), slot, eye)
            }
            TestedEntry::ParallelTree(t) => {
                let tree = &plan.trees[t as usize];
                let start = (looped + member_tests.len()) as u32;
                let header = tree.append_words(table, eye, tree_base, start, &mut tree_words);
                member_tests
                    .extend(tree.members.iter().map(|&m| shape_test(&table.shapes[m as usize], m, eye)));
                let mut test =
                    shape_test(&table.shapes[tree.lowest(table) as usize], TREE_TEST_FLAG | header, eye);
                // Lowered by a margin, so that no member reflects a point the entry's plane
                // does not (their normals may differ in the last bits).
                test.plane[3] += 1e-5 * test.plane[3].abs() + 1e-6;
                test.sides = [[0.0, 0.0, 0.0, 1.0]; 4];
                test
            }
        })
        .collect();
    tests.extend(plan.layers.iter().map(|l| shape_test(&table.shapes[l.shape as usize], l.shape, eye)));
    tests.extend(member_tests);
    let mut group_words: Vec<u32> = bytemuck::cast_slice(&headers).to_vec();
    if !tree_words.is_empty() {
        group_words.resize(tree_base as usize, 0);
        group_words.extend(tree_words);
    }
    FrameTests { tests, looped, group_words }
}

/// The test of one shape (index `index` in its table).
pub fn shape_test(shape: &ShapeSource, index: u32, eye: DVec3) -> GpuShapeTest {
    let n = shape.normal.as_dvec3();
    let d = shape.plane_dist_from(eye);
    let plane = n.extend(-d);
    let sides = pyramid_sides(shape, eye);
    GpuShapeTest {
        plane: plane.as_vec4().to_array(),
        sides: sides.map(|s| s.as_vec4().to_array()),
        shape: index,
        group: shape.parallel_group,
        _pad: [0; 2],
    }
}

/// The four sides of the pyramid from the mirrored camera through the rectangle, as unit
/// normals and offsets (`xyz · p + w ≥ 0` inside), camera-relative. A degenerate side (the
/// camera on the plane, which the plan culls) is a plane every point passes.
pub fn pyramid_sides(shape: &ShapeSource, eye: DVec3) -> [DVec4; 4] {
    let n = shape.normal.as_dvec3();
    let apex = 2.0 * shape.plane_dist_from(eye) * n;
    let corners = shape.corners().map(|c| c - eye);
    let center = shape.center - eye;
    std::array::from_fn(|i| {
        let (a, b) = (corners[i] - apex, corners[(i + 1) % 4] - apex);
        let mut normal = a.cross(b);
        let len = normal.length();
        if !(len > 0.0 && len.is_finite()) {
            return DVec4::new(0.0, 0.0, 0.0, 1.0);
        }
        normal /= len;
        if normal.dot(center - apex) < 0.0 {
            normal = -normal;
        }
        normal.extend(-normal.dot(apex))
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use ppr_format::ReflectorKind;

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

    #[test]
    fn five_planes_agree_with_mirroring_and_casting() {
        let shape = mirror();
        let eye = DVec3::new(9.0, 1.7, 2.0);
        let t = shape_test(&shape, 7, eye);
        assert_eq!((t.shape, t.group), (7, 3));
        let planes: Vec<DVec4> =
            std::iter::once(t.plane).chain(t.sides).map(|a| DVec4::from(a.map(f64::from))).collect();
        let mut state = 0x1234_5678_u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut inside, mut disagree) = (0, 0);
        for _ in 0..20_000 {
            let p = DVec3::new(next() * 8.0 - 3.0, next() * 4.0 - 1.0, next() * 10.0 - 12.0);
            let values: Vec<f64> = planes.iter().map(|pl| pl.truncate().dot(p) + pl.w).collect();
            let by_planes = values[0] > 0.0 && values[1..].iter().all(|&v| v >= 0.0);
            let by_reference = reflects(&shape, eye, p);
            inside += usize::from(by_reference);
            // Points within f32 rounding of a side may go either way.
            let margin = values[1..].iter().map(|v| v.abs()).fold(f64::MAX, f64::min);
            if by_planes != by_reference && margin > 1e-5 {
                disagree += 1;
            }
        }
        assert!(inside > 500, "the sample must hit the pyramid: {inside}");
        assert_eq!(disagree, 0);
    }
}
