//! Stereo: a headset's two eyes from one renderer. The set is uploaded and the pipelines
//! built once; `prepare_stereo` plans both eyes and packs both uploads, `encode_stereo`
//! records both eyes' passes into one encoder, each into its own textures (two textures,
//! or `D2` views of the two layers of array textures).

use std::sync::Arc;

use crate::camera::Camera;
use crate::plan::FramePlan;
use crate::renderer::{FrameInputs, ReflectionRenderer};

impl ReflectionRenderer {
    /// Plans the two eyes of a stereo frame, `[left, right]`, each `viewport` pixels (the
    /// per-eye size), and packs each eye's upload. Call once per frame, then
    /// [`Self::encode_stereo`].
    ///
    /// Each eye's plan is the one [`Self::prepare`] would make for that eye alone; the
    /// frame buffers are shared (sized for both plans), so a stereo frame needs no more
    /// GPU memory than a mono one.
    pub fn prepare_stereo(&mut self, eyes: [&Camera; 2], viewport: [u32; 2]) -> [Arc<FramePlan>; 2] {
        self.prepare_views(eyes, viewport)
    }

    /// Records both eyes' passes into `encoder`: the left eye's uploads and passes, then the
    /// right eye's, each with its own [`FrameInputs`] (colour, depth and outputs of that
    /// eye). Each eye's output is bit for bit what a mono frame of that eye writes.
    /// [`Self::read_timings`] then reports the right eye's passes.
    ///
    /// # Panics
    /// If the last prepare was not [`Self::prepare_stereo`].
    pub fn encode_stereo(&self, encoder: &mut wgpu::CommandEncoder, eyes: [&FrameInputs<'_>; 2]) {
        assert_eq!(self.views.len(), 2, "prepare_stereo() before encode_stereo()");
        self.dispatches.set(0);
        for (view, inputs) in self.views.iter().zip(eyes) {
            self.encode_view(encoder, view, inputs);
        }
    }
}
