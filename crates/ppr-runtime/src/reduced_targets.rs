//! The textures of the reduced-resolution tiers: depth and the reflection outputs at
//! the reduced size, reallocated only when that size changes.

use crate::passes::downsample::REDUCED_DEPTH_FORMAT;
use crate::passes::reflection::OUTPUT_FORMAT;

/// One reduced-size texture and its view.
pub(crate) struct ReducedTexture {
    _texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl ReducedTexture {
    fn new(device: &wgpu::Device, label: &str, [w, h]: [u32; 2], format: wgpu::TextureFormat) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        Self { _texture: texture, view }
    }
}

/// Depth, reflection and layer reflection at the reduced size.
pub(crate) struct ReducedTargets {
    pub size: [u32; 2],
    pub depth: ReducedTexture,
    pub output: ReducedTexture,
    pub layer_output: ReducedTexture,
}

impl ReducedTargets {
    pub fn new(device: &wgpu::Device, size: [u32; 2]) -> Self {
        Self {
            size,
            depth: ReducedTexture::new(device, "ppr reduced depth", size, REDUCED_DEPTH_FORMAT),
            output: ReducedTexture::new(device, "ppr reduced output", size, OUTPUT_FORMAT),
            layer_output: ReducedTexture::new(device, "ppr reduced layer output", size, OUTPUT_FORMAT),
        }
    }
}
