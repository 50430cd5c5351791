//! What one `prepare` hands to the GPU, packed in one block: the frame uniforms, the
//! camera-relative shapes, the visible list, the screen rectangles, the layers, the shape
//! tests, the source boxes and the merged plane groups' headers.
//! `encode` writes it into a staging buffer (`upload_ring.rs`: reused frame after frame)
//! and records copies from there into the frame buffers before its passes.
//!
//! Why not `queue.write_buffer` into the frame buffers: those writes all land at the next
//! submit, before any command of it, so two views prepared and encoded before one submit
//! would both run with the last view's camera. A copy recorded in the encoder lands
//! where it is recorded.

use crate::frame_buffers::FrameBuffers;
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

/// One prepared frame's data, immutable once built.
pub(crate) struct FrameUpload {
    /// Every part, one after the other.
    bytes: Vec<u8>,
    /// (target, offset in `bytes`, bytes).
    parts: Vec<(UploadTarget, u64, u64)>,
}

impl FrameUpload {
    /// Packs the non-empty `parts` (each a whole number of 4-byte words, as every GPU
    /// struct of the runtime is) into `bytes` (emptied first: the last frame's, so that
    /// its memory is reused).
    pub fn new(parts: &[(UploadTarget, &[u8])], mut bytes: Vec<u8>) -> Self {
        bytes.clear();
        bytes.reserve(parts.iter().map(|(_, p)| p.len()).sum());
        let mut placed = Vec::with_capacity(parts.len());
        for &(target, data) in parts.iter().filter(|(_, p)| !p.is_empty()) {
            debug_assert_eq!(data.len() as u64 % wgpu::COPY_BUFFER_ALIGNMENT, 0, "{target:?}");
            placed.push((target, bytes.len() as u64, data.len() as u64));
            bytes.extend_from_slice(data);
        }
        Self { bytes, parts: placed }
    }

    /// The packed bytes, to be reused by the next frame's upload.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    /// Writes the bytes into a staging buffer of `ring` and records the copies from
    /// there into `buffers` (which must be the ones the frame was prepared for: every part
    /// fits its target).
    pub fn encode_copies(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        buffers: &FrameBuffers,
        ring: &mut UploadRing,
    ) {
        if self.bytes.is_empty() {
            return;
        }
        let staging = ring.stage(encoder, &self.bytes);
        for &(target, offset, size) in &self.parts {
            encoder.copy_buffer_to_buffer(&staging, offset, target.buffer(buffers), 0, size);
        }
    }
}
