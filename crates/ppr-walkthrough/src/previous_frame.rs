//! The previous frame's composited image as PPR's colour input (key P,
//! `--feed-previous-frame`): a mirror seen in a mirror then shows that mirror's reflection,
//! one more bounce per frame.
//!
//! After PPR, the frame is composited once more in linear HDR (the tone-mapped composite
//! on the swapchain cannot be read back as scene colour) and copied into `previous`, which
//! the next frame hands PPR instead of the forward pass's colour. A game whose composite
//! already writes linear HDR pays only the copy. The previous frame is not reprojected:
//! while the camera moves, the bounce is seen from where the camera was a frame ago.

use crate::composite_pass::{CompositeMode, CompositePass};
use crate::frame_targets::{COLOR_FORMAT, FrameTargets};

/// The linear composite, and its copy that the next frame's PPR reads.
pub struct PreviousFrame {
    size: [u32; 2],
    composite: CompositePass,
    composited: wgpu::Texture,
    previous: wgpu::Texture,
    previous_view: wgpu::TextureView,
    /// Whether `previous` holds a frame (false until the first [`Self::encode`]).
    written: bool,
}

impl PreviousFrame {
    /// Textures for frames of `size`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, size: [u32; 2]) -> Self {
        let texture = |label, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: COLOR_FORMAT,
                usage,
                view_formats: &[],
            })
        };
        use wgpu::TextureUsages as U;
        let composited = texture("walkthrough linear composite", U::RENDER_ATTACHMENT | U::COPY_SRC);
        let previous = texture("walkthrough previous frame", U::TEXTURE_BINDING | U::COPY_DST);
        let previous_view = previous.create_view(&Default::default());
        Self {
            size,
            composite: CompositePass::new(device, queue, COLOR_FORMAT),
            composited,
            previous,
            previous_view,
            written: false,
        }
    }

    /// The frame size these textures serve.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// The previous frame's composite, once one was recorded.
    pub fn color_input(&self) -> Option<&wgpu::TextureView> {
        self.written.then_some(&self.previous_view)
    }

    /// Records this frame's linear composite and its copy into the next frame's input.
    /// `reflections` says whether `targets.reflection` holds this frame's PPR output.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, targets: &FrameTargets, reflections: bool) {
        let view = self.composited.create_view(&Default::default());
        self.composite.encode(encoder, targets, &view, CompositeMode::FinalLinear, reflections);
        encoder.copy_texture_to_texture(
            self.composited.as_image_copy(),
            self.previous.as_image_copy(),
            self.composited.size(),
        );
        self.written = true;
    }
}
