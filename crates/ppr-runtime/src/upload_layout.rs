//! Where each part of a frame's upload lies in the one buffer that holds them all: the
//! frame uniforms, the glossy reflectors, the layers, the shapes, the lists, the tests and
//! the plane groups' words. The passes bind each part as a range of that buffer, and the
//! upload fills the parts a frame uses with one copy where they lie close together
//! (`frame_upload.rs`): every copy command costs the GPU about 1.5 µs, whatever its size
//! (`docs/perf/runtime.md`, the upload probe).
//!
//! The parts lie in the order of [`UploadTarget::ALL`]: first those a frame fills whole or
//! nearly (uniforms, glossy reflectors, layers, shapes), then those whose use grows with the
//! visible shapes, and the plane groups last, since their buffer ends in static words
//! written once (`crate::plane_groups`) that no copy may run over.

use std::ops::Range;

/// A part of the frame upload: the binding it serves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum UploadTarget {
    Uniforms,
    Glossy,
    Layers,
    Shapes,
    Visible,
    ScreenRects,
    SourceRects,
    /// The shape tests; their first [`crate::plan::UNIFORM_TESTS_CAPACITY`] are also bound
    /// as a uniform array ([`UploadLayout::uniform_tests`]).
    Tests,
    PlaneGroups,
}

impl UploadTarget {
    /// Every part, in the order they lie in the buffer.
    pub const ALL: [Self; 9] = [
        Self::Uniforms,
        Self::Glossy,
        Self::Layers,
        Self::Shapes,
        Self::Visible,
        Self::ScreenRects,
        Self::SourceRects,
        Self::Tests,
        Self::PlaneGroups,
    ];
}

/// The ranges of the parts in the upload buffer, fixed for a shape table and viewport.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct UploadLayout {
    ranges: [Range<u64>; 9],
    uniform_tests: Range<u64>,
    size: u64,
}

impl UploadLayout {
    /// Parts of `capacity(target)` bytes (each rounded up to a whole 16 bytes), each
    /// starting at a multiple of `alignment` (the device's binding offset alignment), and
    /// the uniform tests' `uniform_tests_bytes` from the tests' start.
    pub fn new(capacity: impl Fn(UploadTarget) -> u64, alignment: u64, uniform_tests_bytes: u64) -> Self {
        let alignment = alignment.max(wgpu::COPY_BUFFER_ALIGNMENT);
        let mut offset = 0u64;
        let ranges = UploadTarget::ALL.map(|target| {
            let start = offset.next_multiple_of(alignment);
            let end = start + capacity(target).max(16).next_multiple_of(16);
            offset = end;
            start..end
        });
        let tests = ranges[UploadTarget::Tests as usize].start;
        let uniform_tests = tests..tests + uniform_tests_bytes;
        let size = offset.max(uniform_tests.end);
        Self { ranges, uniform_tests, size }
    }

    /// The bytes `target` may fill, as bound.
    pub fn range(&self, target: UploadTarget) -> Range<u64> {
        self.ranges[target as usize].clone()
    }

    /// The uniform array of the loop's tests: the tests' first bytes (past their part where
    /// the table has few shapes: the shader reads only the frame's looped tests).
    pub fn uniform_tests(&self) -> Range<u64> {
        self.uniform_tests.clone()
    }

    /// The buffer's size.
    pub fn size(&self) -> u64 {
        self.size
    }
}

/// The copies that fill `parts` (byte ranges of the upload buffer, in any order, each a
/// whole number of 4-byte words): one per run of parts whose gaps are at most `max_gap`
/// bytes, each as the range of the buffer it covers (the parts and the gaps between them),
/// in buffer order.
pub(crate) fn copy_runs(parts: &[Range<u64>], max_gap: Option<u64>) -> Vec<Range<u64>> {
    let mut sorted: Vec<Range<u64>> = parts.iter().filter(|r| !r.is_empty()).cloned().collect();
    sorted.sort_by_key(|r| r.start);
    let mut runs: Vec<Range<u64>> = Vec::with_capacity(sorted.len());
    for part in sorted {
        match (runs.last_mut(), max_gap) {
            (Some(run), Some(gap)) if part.start >= run.end && part.start - run.end <= gap => {
                run.end = part.end
            }
            _ => runs.push(part),
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_are_aligned_apart_in_order_and_the_uniform_tests_start_with_the_tests() {
        let layout = UploadLayout::new(
            |t| match t {
                UploadTarget::Uniforms => 200,
                UploadTarget::Shapes => 1000,
                UploadTarget::Visible => 0,
                _ => 20,
            },
            256,
            4096,
        );
        let mut end = 0;
        for t in UploadTarget::ALL {
            let r = layout.range(t);
            assert_eq!(r.start % 256, 0, "{t:?} at {r:?}");
            assert!(r.start >= end, "{t:?} overlaps the part before it");
            assert!(r.end - r.start >= 16 && (r.end - r.start).is_multiple_of(16), "{t:?}: {r:?}");
            end = r.end;
        }
        assert_eq!(layout.range(UploadTarget::Shapes), 768..1776, "1000 bytes round up to 1008");
        assert_eq!(layout.range(UploadTarget::Glossy), 256..288, "20 bytes round up to 32");
        let tests = layout.range(UploadTarget::Tests);
        assert_eq!(layout.uniform_tests(), tests.start..tests.start + 4096);
        assert_eq!(layout.size(), (tests.start + 4096).max(end), "room for the uniform tests");
        assert!(layout.size() > layout.range(UploadTarget::PlaneGroups).end, "they reach past the last part");
    }

    #[test]
    fn parts_close_together_share_a_copy_and_far_ones_do_not() {
        let parts = [512..520, 0..64, 256..300, 40_000..40_004, 300..320];
        assert_eq!(copy_runs(&parts, Some(256)), vec![0..520, 40_000..40_004]);
        assert_eq!(copy_runs(&parts, Some(1 << 20)), vec![0..40_004]);
        assert_eq!(
            copy_runs(&parts, Some(0)),
            vec![0..64, 256..320, 512..520, 40_000..40_004],
            "touching parts"
        );
        assert_eq!(copy_runs(&parts, None), vec![0..64, 256..300, 300..320, 512..520, 40_000..40_004]);
        assert_eq!(copy_runs(&[0..0, 8..16], Some(256)), vec![8..16], "empty parts copy nothing");
    }
}
