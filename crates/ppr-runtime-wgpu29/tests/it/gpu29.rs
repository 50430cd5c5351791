//! A wgpu-29 device and frame for the parity test: colour and raw `R32Float` depth in,
//! the runtime's output read back.

use glam::Vec4;
use half::f16;
use ppr_tests::scene::Frame;

/// The device the wgpu-29 build runs on; fails loudly when there is no adapter.
pub struct Gpu29 {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: String,
}

pub fn gpu29() -> Gpu29 {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .expect("no GPU adapter for wgpu 29 (llvmpipe through the GL backend works without a GPU)");
    let info = adapter.get_info();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("ppr-runtime-wgpu29 tests"),
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .expect("the adapter refused a device");
    Gpu29 { device, queue, adapter: format!("{} ({:?})", info.name, info.backend) }
}

/// Colour (`Rgba16Float`), raw depth (`R32Float`, as `GpuFrame::upload_raw_depth` gives
/// the wgpu-30 build) and the output texture.
pub struct Frame29 {
    pub color: wgpu::Texture,
    pub depth: wgpu::Texture,
    pub output: wgpu::Texture,
}

fn texture(g: &Gpu29, frame: &Frame, format: wgpu::TextureFormat, usage: wgpu::TextureUsages) -> wgpu::Texture {
    g.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("wgpu29 test frame"),
        size: wgpu::Extent3d { width: frame.size[0], height: frame.size[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

fn write(g: &Gpu29, t: &wgpu::Texture, bytes: &[u8], bytes_per_pixel: u32) {
    let layout = wgpu::TexelCopyBufferLayout {
        offset: 0,
        bytes_per_row: Some(t.width() * bytes_per_pixel),
        rows_per_image: None,
    };
    g.queue.write_texture(t.as_image_copy(), bytes, layout, t.size());
}

impl Frame29 {
    pub fn upload(g: &Gpu29, frame: &Frame) -> Self {
        let read = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let color = texture(g, frame, wgpu::TextureFormat::Rgba16Float, read);
        let rgba: Vec<f16> = frame.color.iter().flat_map(|c| [c.x, c.y, c.z, 1.0]).map(f16::from_f32).collect();
        write(g, &color, bytemuck::cast_slice(&rgba), 8);
        let depth = texture(g, frame, wgpu::TextureFormat::R32Float, read);
        write(g, &depth, bytemuck::cast_slice(&frame.depth), 4);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
        let output = texture(g, frame, ppr_runtime_wgpu29::OUTPUT_FORMAT, usage);
        write(g, &output, &vec![0; (frame.size[0] * frame.size[1] * 8) as usize], 8);
        Self { color, depth, output }
    }

    /// The output texture's pixels.
    pub fn read_output(&self, g: &Gpu29) -> Vec<Vec4> {
        let (w, h) = (self.output.width(), self.output.height());
        let row = (w * 8).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = g.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("wgpu29 test readback"),
            size: u64::from(row * h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = g.device.create_command_encoder(&Default::default());
        let layout = wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None };
        encoder.copy_texture_to_buffer(
            self.output.as_image_copy(),
            wgpu::TexelCopyBufferInfo { buffer: &buffer, layout },
            self.output.size(),
        );
        g.queue.submit([encoder.finish()]);
        buffer.slice(..).map_async(wgpu::MapMode::Read, |r| r.expect("map the readback"));
        g.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        let bytes = buffer.slice(..).get_mapped_range().to_vec();
        (0..h as usize)
            .flat_map(|y| {
                let line: &[f16] = bytemuck::cast_slice(&bytes[y * row as usize..][..(w * 8) as usize]);
                line.chunks_exact(4).map(|c| Vec4::new(c[0].into(), c[1].into(), c[2].into(), c[3].into())).collect::<Vec<_>>()
            })
            .collect()
    }
}
