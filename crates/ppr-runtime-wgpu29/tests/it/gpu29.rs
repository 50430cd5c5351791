//! A wgpu-29 device and frame for the parity test: colour and raw `R32Float` depth in,
//! the runtime's output read back.

use std::sync::OnceLock;

use glam::Vec4;
use half::f16;
use ppr_runtime_wgpu29::OUTPUT_FORMAT;
use ppr_tests::scene::Frame;
use wgpu::util::DeviceExt;

/// The device the wgpu-29 build runs on; fails loudly when there is no adapter.
pub struct Gpu29 {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: String,
}

/// Created once and never dropped: wgpu 29 and wgpu 30 share the process's EGL display on
/// the GL backend, and dropping either's last device terminates it under the other.
pub fn gpu29() -> &'static Gpu29 {
    static GPU: OnceLock<Gpu29> = OnceLock::new();
    GPU.get_or_init(open)
}

fn open() -> Gpu29 {
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

/// A texture of the frame's size holding `bytes`.
fn texture(
    g: &Gpu29,
    frame: &Frame,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    bytes: &[u8],
) -> wgpu::Texture {
    let [width, height] = frame.size;
    let desc = wgpu::TextureDescriptor {
        label: Some("wgpu29 test frame"),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: usage | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    };
    g.device.create_texture_with_data(&g.queue, &desc, wgpu::util::TextureDataOrder::LayerMajor, bytes)
}

impl Frame29 {
    pub fn upload(g: &Gpu29, frame: &Frame) -> Self {
        let rgba: Vec<f16> =
            frame.color.iter().flat_map(|c| [c.x, c.y, c.z, 1.0]).map(f16::from_f32).collect();
        let (read, write) = (wgpu::TextureUsages::TEXTURE_BINDING, wgpu::TextureUsages::STORAGE_BINDING);
        let pixels = (frame.size[0] * frame.size[1]) as usize;
        Self {
            color: texture(g, frame, wgpu::TextureFormat::Rgba16Float, read, bytemuck::cast_slice(&rgba)),
            depth: texture(g, frame, wgpu::TextureFormat::R32Float, read, bytemuck::cast_slice(&frame.depth)),
            output: texture(
                g,
                frame,
                OUTPUT_FORMAT,
                write | wgpu::TextureUsages::COPY_SRC,
                &vec![0; pixels * 8],
            ),
        }
    }

    /// The output texture's pixels (rows need no padding: the width is a multiple of 32).
    pub fn read_output(&self, g: &Gpu29) -> Vec<Vec4> {
        let bytes_per_row = self.output.width() * 8;
        assert_eq!(bytes_per_row % wgpu::COPY_BYTES_PER_ROW_ALIGNMENT, 0, "width must be a multiple of 32");
        let readback = g.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("wgpu29 test readback"),
            size: u64::from(bytes_per_row * self.output.height()),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = g.device.create_command_encoder(&Default::default());
        let into = wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(bytes_per_row),
                rows_per_image: None,
            },
        };
        encoder.copy_texture_to_buffer(self.output.as_image_copy(), into, self.output.size());
        g.queue.submit([encoder.finish()]);
        readback.slice(..).map_async(wgpu::MapMode::Read, |r| r.expect("map the readback"));
        g.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        let halves: Vec<f16> = bytemuck::pod_collect_to_vec(&readback.slice(..).get_mapped_range());
        halves.chunks_exact(4).map(|c| Vec4::from_array([c[0], c[1], c[2], c[3]].map(f32::from))).collect()
    }
}
