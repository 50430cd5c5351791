//! A headless device for tests: fails loudly when no adapter exists.

use std::sync::OnceLock;

pub struct TestGpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
}

/// Backends a test binary asks for instead of `WGPU_BACKEND` (set before the first [`gpu`]).
static BACKENDS: OnceLock<wgpu::Backends> = OnceLock::new();

/// Makes this test binary's device come from `backends` (every test of the binary calls it
/// before [`gpu`]; the first call wins).
pub fn use_backends(backends: wgpu::Backends) {
    let _ = BACKENDS.set(backends);
}

/// The shared test device (created once per test binary), with timestamps, subgroups and
/// bindable mapped buffers where the adapter has them.
pub fn gpu() -> &'static TestGpu {
    static GPU: OnceLock<TestGpu> = OnceLock::new();
    GPU.get_or_init(|| {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if let Some(&b) = BACKENDS.get() {
            desc.backends = b;
        }
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
            .expect(
                "no GPU adapter found: GPU tests need one (Mesa's llvmpipe through wgpu's GL backend \
                 works without a GPU; install libegl-mesa0 / mesa-vulkan-drivers)",
            );
        let info = adapter.get_info();
        eprintln!("test adapter: {} ({:?}, {:?})", info.name, info.backend, info.device_type);
        // Where the adapter maps bindable buffers (Vulkan, not GL), the renderer binds the
        // frame upload it writes instead of copying it (`it/bound_upload.rs`).
        let wanted = wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::SUBGROUP
            | wgpu::Features::MAPPABLE_PRIMARY_BUFFERS;
        let features = adapter.features() & wanted;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("ppr-runtime tests"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .expect("the adapter refused a device");
        TestGpu { device, queue, info }
    })
}

/// Copies a buffer to the CPU.
pub fn read_buffer(buffer: &wgpu::Buffer) -> Vec<u8> {
    let g = gpu();
    let staging = g.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = g.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    g.queue.submit([encoder.finish()]);
    staging.slice(..).map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    g.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let bytes = staging.slice(..).get_mapped_range().expect("mapped").to_vec();
    staging.unmap();
    bytes
}
