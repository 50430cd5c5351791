//! The headless GPU context: instance, adapter, device and queue (opened by
//! `ppr-scene-gpu`'s `request_device`), with the adapter recorded.

use ppr_scene_gpu::{DeviceRequest, GpuDevice, request_device};

use crate::TestbedError;

/// Everything needed to talk to one GPU, created without a window.
///
/// On machines without a GPU this is Mesa's llvmpipe reached through wgpu's GL backend
/// (EGL); [`GpuContext::describe`] says which adapter and backend were picked.
pub struct GpuContext {
    /// The wgpu instance the adapter came from.
    pub instance: wgpu::Instance,
    /// The adapter (physical device or software rasteriser).
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
    /// Name, backend, driver and type of the adapter.
    pub adapter_info: wgpu::AdapterInfo,
}

/// Optional features requested when the adapter has them (never required): timestamps,
/// subgroups for the projection's subgroup culling, and mapped buffers the passes may bind
/// (the renderer then binds the frame upload where it writes it, without a copy).
const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::TIMESTAMP_QUERY
    .union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    .union(wgpu::Features::SUBGROUP)
    .union(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS);

impl GpuContext {
    /// Creates a headless context on the adapter wgpu picks (honouring `WGPU_BACKEND`,
    /// `WGPU_ADAPTER_NAME` and `WGPU_POWER_PREF`), with the adapter's own limits and the
    /// timestamp-query features where the adapter has them.
    ///
    /// # Errors
    /// [`TestbedError::NoAdapter`] when no adapter exists (tests must fail, not skip), or
    /// [`TestbedError::NoDevice`] when the adapter refuses the device.
    pub fn new_headless() -> Result<Self, TestbedError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let request = DeviceRequest { label: "ppr-testbed device", optional_features: OPTIONAL_FEATURES };
        let GpuDevice { adapter, device, queue, adapter_info } = request_device(&instance, None, &request)?;
        Ok(Self { instance, adapter, device, queue, adapter_info })
    }

    /// One line naming the adapter, its backend, type and driver, for logs and test output.
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!(
            "{} ({:?} backend, {:?}, driver {} {})",
            i.name, i.backend, i.device_type, i.driver, i.driver_info
        )
    }

    /// Whether the device can write GPU timestamps.
    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// Blocks until every submitted command has finished.
    ///
    /// # Errors
    /// [`TestbedError::Readback`] if the device was lost or the wait failed.
    pub fn wait_idle(&self) -> Result<(), TestbedError> {
        wait_idle(&self.device)
    }
}

/// Blocks until every command submitted to `device` has finished.
///
/// # Errors
/// [`TestbedError::Readback`] if the wait failed.
pub fn wait_idle(device: &wgpu::Device) -> Result<(), TestbedError> {
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map(|_| ())
        .map_err(|e| TestbedError::Readback { what: "device poll".into(), reason: e.to_string() })
}
