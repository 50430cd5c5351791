//! The materials on the GPU: each material's uniform and bind group (group 1), its base
//! colour texture uploaded as sRGB with a mip chain made on the CPU (white when it has none).

use wgpu::util::DeviceExt;

use crate::level_data::{LevelData, LevelTexture, Material};
use crate::level_meshes::MaterialUniform;
use crate::scene_layouts::SceneLayouts;

/// One bind group per material of `level`, in its order; `params` gives each material's
/// `MaterialUniform::params`.
pub fn material_bind_groups(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &SceneLayouts,
    level: &LevelData,
    params: fn(&Material) -> [f32; 4],
) -> Vec<wgpu::BindGroup> {
    let white = LevelTexture { name: "white".into(), width: 1, height: 1, rgba8: vec![255; 4] };
    let views: Vec<wgpu::TextureView> = level
        .textures
        .iter()
        .chain([&white])
        .map(|t| upload_texture(device, queue, t).create_view(&Default::default()))
        .collect();
    let white_view = views.last().expect("the white texture was just added");
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("level meshes: base colour sampler"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    level
        .materials
        .iter()
        .map(|m| {
            let uniform = MaterialUniform {
                base_color: m.base_color,
                emissive: [m.emissive[0], m.emissive[1], m.emissive[2], if m.unlit { 1.0 } else { 0.0 }],
                params: params(m),
            };
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("level meshes: material uniform"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let view = m.base_color_texture.and_then(|t| views.get(t)).unwrap_or(white_view);
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("level meshes: material bind group"),
                layout: &layouts.material,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(view) },
                    wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&sampler) },
                ],
            })
        })
        .collect()
}

/// Uploads an sRGB RGBA8 texture with a full mip chain (box-filtered on the CPU, in sRGB space).
fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, texture: &LevelTexture) -> wgpu::Texture {
    let (w, h) = (texture.width.max(1), texture.height.max(1));
    let mip_count = 32 - w.max(h).leading_zeros();
    let gpu = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("level meshes: base colour texture"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: mip_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut level_image = image::RgbaImage::from_raw(w, h, texture.rgba8.clone())
        .unwrap_or_else(|| image::RgbaImage::from_pixel(w, h, image::Rgba([255, 0, 255, 255])));
    for mip in 0..mip_count {
        let (mw, mh) = level_image.dimensions();
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &gpu,
                mip_level: mip,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            level_image.as_raw(),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * mw), rows_per_image: Some(mh) },
            wgpu::Extent3d { width: mw, height: mh, depth_or_array_layers: 1 },
        );
        let (nw, nh) = ((mw / 2).max(1), (mh / 2).max(1));
        level_image = image::imageops::resize(&level_image, nw, nh, image::imageops::FilterType::Triangle);
    }
    gpu
}
