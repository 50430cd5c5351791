//! Adapter, device and queue from an instance: the one place the tools open a GPU.

use crate::error::GpuInitError;

/// What to ask the adapter for.
#[derive(Clone, Copy, Debug)]
pub struct DeviceRequest<'a> {
    /// The device's label (captures and validation messages name it).
    pub label: &'a str,
    /// Features requested when the adapter has them (never required).
    pub optional_features: wgpu::Features,
}

/// One adapter and the device opened on it.
pub struct GpuDevice {
    /// The adapter (physical device or software rasteriser).
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
    /// Name, backend, driver and type of the adapter.
    pub adapter_info: wgpu::AdapterInfo,
}

/// Picks the adapter wgpu prefers (honouring `WGPU_ADAPTER_NAME` and `WGPU_POWER_PREF`,
/// high performance by default; one that can present to `surface` when given) and opens a
/// device with the adapter's own limits and whichever of `request.optional_features` it has.
///
/// # Errors
/// [`GpuInitError::NoAdapter`] when no adapter fits, [`GpuInitError::NoDevice`] when the
/// adapter refuses the device.
pub fn request_device(
    instance: &wgpu::Instance,
    surface: Option<&wgpu::Surface<'_>>,
    request: &DeviceRequest<'_>,
) -> Result<GpuDevice, GpuInitError> {
    pollster::block_on(request_device_async(instance, surface, request))
}

async fn request_device_async(
    instance: &wgpu::Instance,
    surface: Option<&wgpu::Surface<'_>>,
    request: &DeviceRequest<'_>,
) -> Result<GpuDevice, GpuInitError> {
    let power_preference =
        wgpu::PowerPreference::from_env().unwrap_or(wgpu::PowerPreference::HighPerformance);
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference,
            force_fallback_adapter: false,
            compatible_surface: surface,
            apply_limit_buckets: false,
        })
        .await
        .map_err(|e| GpuInitError::NoAdapter(e.to_string()))?;
    let adapter_info = adapter.get_info();
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some(request.label),
            required_features: adapter.features() & request.optional_features,
            required_limits: adapter.limits(),
            ..Default::default()
        })
        .await
        .map_err(|e| GpuInitError::NoDevice { adapter: adapter_info.name.clone(), reason: e.to_string() })?;
    Ok(GpuDevice { adapter, device, queue, adapter_info })
}
