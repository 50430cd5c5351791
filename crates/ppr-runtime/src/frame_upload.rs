//! What one `prepare` hands to the GPU: the frame uniforms, the camera-relative shapes,
//! the visible list, the screen rectangles, the layers, the shape tests, the source boxes
//! and the merged plane groups' headers and trees' words, in memory kept from frame to
//! frame. `encode` writes the parts into a staging buffer (`upload_ring.rs`: reused frame
//! after frame) as they lie in the frame buffers' upload buffer (`upload_layout.rs`) and
//! records one copy from there per run of parts that lie close together: one copy for a
//! level of a few hundred shapes. On devices with `MAPPABLE_PRIMARY_BUFFERS` it writes
//! them instead into a mapped buffer laid out as the upload buffer, which the passes bind
//! in its place: no copy, and no barrier between a copy and the first pass.
//!
//! Why not `queue.write_buffer` into the frame buffers: those writes all land at the next
//! submit, before any command of it, so two views prepared and encoded before one submit
//! would both run with the last view's camera. A copy recorded in the encoder lands
//! where it is recorded.

use crate::frame_buffers::FrameBuffers;
use crate::gpu_types::GpuShape;
use crate::shape_tests::FrameTests;
use crate::upload_layout::{UploadLayout, UploadTarget, copy_runs};
use crate::upload_ring::UploadRing;

/// Gap between two parts up to which one copy takes both (and the gap): a copy command
/// costs the GPU about 1.5 µs (the upload probe, `docs/perf/runtime.md`), in which the bus
/// moves tens of kilobytes.
pub(crate) const MAX_COPY_GAP: u64 = 16 << 10;

/// The memory of one view's upload, kept from frame to frame (at thousands of shapes,
/// fresh vectors of megabytes a frame cost page faults on every frame): the small parts
/// packed, and the big ones as they were built, staged from there without a packing copy.
#[derive(Default)]
pub(crate) struct UploadMemory {
    /// The small parts, one after the other.
    pub bytes: Vec<u8>,
    /// The camera-relative shapes, all of the table.
    pub shapes: Vec<GpuShape>,
    /// The tests and the plane-group words.
    pub tests: FrameTests,
}

/// Where an upload part's bytes are in its [`UploadMemory`].
#[derive(Clone, Copy, Debug)]
enum Part {
    Packed { offset: usize, len: usize },
    Shapes,
    Tests,
    GroupWords,
}

/// One prepared frame's data, immutable once built.
pub(crate) struct FrameUpload {
    memory: UploadMemory,
    /// Every non-empty part and its target.
    parts: Vec<(UploadTarget, Part)>,
}

impl FrameUpload {
    /// The upload of `memory`'s shapes (into [`UploadTarget::Shapes`]), tests
    /// ([`UploadTarget::Tests`]: the uniform tests are their first ones) and plane-group
    /// words ([`UploadTarget::PlaneGroups`]), and of the small `packed` parts, copied into
    /// its bytes (emptied first). Every part is a whole number of 4-byte words, as every GPU
    /// struct of the runtime is.
    pub fn new(packed: &[(UploadTarget, &[u8])], mut memory: UploadMemory) -> Self {
        memory.bytes.clear();
        memory.bytes.reserve(packed.iter().map(|(_, p)| p.len()).sum());
        let mut parts = Vec::with_capacity(packed.len() + 3);
        for &(target, data) in packed {
            parts.push((target, Part::Packed { offset: memory.bytes.len(), len: data.len() }));
            memory.bytes.extend_from_slice(data);
        }
        parts.extend([
            (UploadTarget::Shapes, Part::Shapes),
            (UploadTarget::Tests, Part::Tests),
            (UploadTarget::PlaneGroups, Part::GroupWords),
        ]);
        let mut upload = Self { memory, parts: Vec::new() };
        upload.parts = parts.into_iter().filter(|&(_, part)| !upload.bytes_of(part).is_empty()).collect();
        upload
    }

    /// The memory, to be refilled by the next frame's upload.
    pub fn into_memory(self) -> UploadMemory {
        self.memory
    }

    fn bytes_of(&self, part: Part) -> &[u8] {
        let m = &self.memory;
        match part {
            Part::Packed { offset, len } => &m.bytes[offset..offset + len],
            Part::Shapes => bytemuck::cast_slice(&m.shapes),
            Part::Tests => bytemuck::cast_slice(&m.tests.tests),
            Part::GroupWords => bytemuck::cast_slice(&m.tests.group_words),
        }
    }

    /// Each part's bytes and its offset in the upload buffer (which must be the one the
    /// frame was prepared for: every part fits its range), in order of offset.
    fn placed(&self, layout: &UploadLayout) -> Vec<(u64, &[u8])> {
        let mut placed: Vec<(u64, &[u8])> = self
            .parts
            .iter()
            .map(|&(target, part)| {
                let (range, data) = (layout.range(target), self.bytes_of(part));
                debug_assert_eq!(data.len() as u64 % wgpu::COPY_BUFFER_ALIGNMENT, 0, "{target:?}");
                debug_assert!(data.len() as u64 <= range.end - range.start, "{target:?} fits its part");
                (range.start, data)
            })
            .collect();
        placed.sort_by_key(|&(offset, _)| offset);
        placed
    }

    /// Writes the parts, each at its offset, into a buffer of `buffers`' bindable ring
    /// (`FrameBuffers::bindable_uploads`, which must exist), to bind in place of `buffers`'
    /// upload buffer by the commands recorded in `encoder` (none is recorded here).
    pub fn stage_bindable(&self, encoder: &wgpu::CommandEncoder, buffers: &FrameBuffers) -> wgpu::Buffer {
        let layout = &buffers.upload_layout;
        let ring = buffers.bindable_uploads.as_ref().expect("a device that maps bindable buffers");
        let placed = self.placed(layout);
        // (A mapped range is never empty: at least one word, written or not.)
        let end = placed.last().map_or(0, |&(offset, data)| offset + data.len() as u64);
        let end = end.max(wgpu::COPY_BUFFER_ALIGNMENT);
        ring.borrow_mut().stage(encoder, end, &placed)
    }

    /// Writes the parts into a staging buffer of `ring` and records the copies from
    /// there into `buffers`' upload buffer (which must be the one the frame was prepared
    /// for: every part fits its range): one per run of parts apart by at most `max_gap`
    /// bytes (`None`: one per part). Returns how many copies it recorded.
    pub fn encode_copies(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        buffers: &FrameBuffers,
        ring: &mut UploadRing,
        max_gap: Option<u64>,
    ) -> usize {
        if self.parts.is_empty() {
            return 0;
        }
        let placed = self.placed(&buffers.upload_layout);
        let ranges: Vec<_> = placed.iter().map(|&(o, d)| o..o + d.len() as u64).collect();
        let runs = copy_runs(&ranges, max_gap);
        // The runs one after the other in the staging buffer, each with its gaps.
        let mut staged = Vec::with_capacity(placed.len());
        let mut run_starts = Vec::with_capacity(runs.len());
        let mut size = 0;
        let mut next = placed.iter().peekable();
        for run in &runs {
            run_starts.push(size);
            while let Some(&&(offset, data)) = next.peek().filter(|(o, _)| *o < run.end) {
                staged.push((size + offset - run.start, data));
                next.next();
            }
            size += run.end - run.start;
        }
        let staging = ring.stage(encoder, size, &staged);
        for (run, from) in runs.iter().zip(run_starts) {
            encoder.copy_buffer_to_buffer(&staging, from, &buffers.upload, run.start, run.end - run.start);
        }
        runs.len()
    }
}
