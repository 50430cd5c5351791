//! The headless GPU context: instance, adapter, device and queue, with the adapter recorded.

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

/// Optional features requested when the adapter has them (never required).
const OPTIONAL_FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);

impl GpuContext {
    /// Creates a headless context on the adapter wgpu picks (honouring `WGPU_BACKEND`,
    /// `WGPU_ADAPTER_NAME` and `WGPU_POWER_PREF`), with the adapter's own limits and the
    /// timestamp-query features where the adapter has them.
    ///
    /// # Errors
    /// [`TestbedError::NoAdapter`] when no adapter exists (tests must fail, not skip), or
    /// [`TestbedError::NoDevice`] when the adapter refuses the device.
    pub fn new_headless() -> Result<Self, TestbedError> {
        pollster::block_on(Self::new_headless_async())
    }

    async fn new_headless_async() -> Result<Self, TestbedError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let power_preference =
            wgpu::PowerPreference::from_env().unwrap_or(wgpu::PowerPreference::HighPerformance);
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference,
                force_fallback_adapter: false,
                compatible_surface: None,
                apply_limit_buckets: false,
            })
            .await
            .map_err(|e| TestbedError::NoAdapter(e.to_string()))?;
        let adapter_info = adapter.get_info();
        let required_features = adapter.features() & OPTIONAL_FEATURES;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("ppr-testbed device"),
                required_features,
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|e| TestbedError::NoDevice {
                adapter: adapter_info.name.clone(),
                reason: e.to_string(),
            })?;
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
