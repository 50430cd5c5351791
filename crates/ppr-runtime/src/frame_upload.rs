//! What one `prepare` hands to the GPU: the frame uniforms, the camera-relative shapes,
//! the visible list, the screen rectangles, the layers, the shape tests, the source boxes
//! and the merged plane groups' headers and trees' words, in memory kept from frame to
//! frame. `encode` writes the parts one after the other into a staging buffer
//! (`upload_ring.rs`: reused frame after frame) and records copies from there into the
//! frame buffers before its passes.
//!
//! Why not `queue.write_buffer` into the frame buffers: those writes all land at the next
//! submit, before any command of it, so two views prepared and encoded before one submit
//! would both run with the last view's camera. A copy recorded in the encoder lands
//! where it is recorded.

use crate::frame_buffers::FrameBuffers;
use crate::gpu_types::GpuShape;
use crate::shape_tests::FrameTests;
use crate::upload_ring::UploadRing;

/// The frame buffer a part of the upload is copied into (at offset 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum UploadTarget {
    Uniforms,
    Shapes,
    Visible,
    ScreenRects,
    Layers,
    Tests,
    UniformTests,
    SourceRects,
    PlaneGroups,
    Glossy,
}

impl UploadTarget {
    fn buffer(self, b: &FrameBuffers) -> &wgpu::Buffer {
        match self {
            Self::Uniforms => &b.uniforms,
            Self::Shapes => &b.shapes,
            Self::Visible => &b.visible,
            Self::ScreenRects => &b.screen_rects,
            Self::Layers => &b.layers,
            Self::Tests => &b.tests,
            Self::UniformTests => &b.uniform_tests,
            Self::SourceRects => &b.source_rects,
            Self::PlaneGroups => &b.plane_groups,
            Self::Glossy => &b.glossy,
        }
    }
}

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
    Packed {
        offset: usize,
        len: usize,
    },
    Shapes,
    Tests,
    /// The tests the loop reads (for the uniform copy).
    LoopedTests,
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
    /// ([`UploadTarget::Tests`], and those the loop reads into
    /// [`UploadTarget::UniformTests`] where `uniform_tests`) and plane-group words
    /// ([`UploadTarget::PlaneGroups`]), and of the small `packed` parts, copied into its
    /// bytes (emptied first). Every part is a whole number of 4-byte words, as every GPU
    /// struct of the runtime is.
    pub fn new(packed: &[(UploadTarget, &[u8])], mut memory: UploadMemory, uniform_tests: bool) -> Self {
        memory.bytes.clear();
        memory.bytes.reserve(packed.iter().map(|(_, p)| p.len()).sum());
        let mut parts = Vec::with_capacity(packed.len() + 4);
        for &(target, data) in packed {
            parts.push((target, Part::Packed { offset: memory.bytes.len(), len: data.len() }));
            memory.bytes.extend_from_slice(data);
        }
        parts.extend([
            (UploadTarget::Shapes, Part::Shapes),
            (UploadTarget::Tests, Part::Tests),
            (UploadTarget::PlaneGroups, Part::GroupWords),
        ]);
        if uniform_tests {
            parts.push((UploadTarget::UniformTests, Part::LoopedTests));
        }
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
            Part::LoopedTests => bytemuck::cast_slice(&m.tests.tests[..m.tests.looped]),
            Part::GroupWords => bytemuck::cast_slice(&m.tests.group_words),
        }
    }

    /// Writes the parts into a staging buffer of `ring` and records the copies from
    /// there into `buffers` (which must be the ones the frame was prepared for: every part
    /// fits its target).
    pub fn encode_copies(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        buffers: &FrameBuffers,
        ring: &mut UploadRing,
    ) {
        if self.parts.is_empty() {
            return;
        }
        let slices: Vec<&[u8]> = self.parts.iter().map(|&(_, part)| self.bytes_of(part)).collect();
        for (&(target, _), data) in self.parts.iter().zip(&slices) {
            debug_assert_eq!(data.len() as u64 % wgpu::COPY_BUFFER_ALIGNMENT, 0, "{target:?}");
        }
        let staging = ring.stage(encoder, &slices);
        let mut offset = 0;
        for (&(target, _), data) in self.parts.iter().zip(&slices) {
            let size = data.len() as u64;
            encoder.copy_buffer_to_buffer(&staging, offset, target.buffer(buffers), 0, size);
            offset += size;
        }
    }
}
