//! Instance, adapter, device and queue (opened by `ppr-scene-gpu`'s `request_device`), with
//! the device-lost callback and an error handler
//! that reports instead of panicking, so a lost device is recreated rather than fatal.

use std::sync::{Arc, Mutex};

use anyhow::{Result, anyhow};
use ppr_scene_gpu::{DeviceRequest, GpuDevice, GpuInitError, request_device};

/// Features used when the adapter has them (never required): per-pass GPU times, subgroup
/// culling, and the frame upload bound where it is written (no copy a frame).
const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::TIMESTAMP_QUERY
    .union(wgpu::Features::SUBGROUP)
    .union(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS);

/// What the device-lost callback and the error handler report, shared with the render loop.
#[derive(Debug, Default)]
struct DeviceReports {
    lost: Option<String>,
    errors: u64,
    last_error: Option<String>,
}

/// One device and what it takes to notice that it is gone.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    reports: Arc<Mutex<DeviceReports>>,
}

/// The wgpu instance: with the window's display handle (the GL backend needs it to present),
/// or without one for headless runs. Honours `WGPU_BACKEND` and friends.
pub fn new_instance(display: Option<Box<dyn wgpu::rwh::HasDisplayHandle + Send + Sync>>) -> wgpu::Instance {
    let desc = match display {
        Some(display) => {
            wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(DisplayHandle(display)))
        }
        None => wgpu::InstanceDescriptor::new_without_display_handle_from_env(),
    };
    wgpu::Instance::new(desc)
}

/// A display handle wgpu can keep (it wants `Debug`).
struct DisplayHandle(Box<dyn wgpu::rwh::HasDisplayHandle + Send + Sync>);

impl std::fmt::Debug for DisplayHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("DisplayHandle")
    }
}

impl wgpu::rwh::HasDisplayHandle for DisplayHandle {
    fn display_handle(&self) -> Result<wgpu::rwh::DisplayHandle<'_>, wgpu::rwh::HandleError> {
        self.0.display_handle()
    }
}

impl GpuContext {
    /// Picks an adapter (one that can present to `surface`, if given) and creates a device
    /// with the adapter's limits and timestamps where available.
    ///
    /// # Errors
    /// No adapter, or the adapter refuses the device.
    pub fn new(instance: &wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Self> {
        let request = DeviceRequest { label: "ppr-walkthrough device", optional_features: OPTIONAL_FEATURES };
        let GpuDevice { adapter, device, queue, adapter_info } = request_device(instance, surface, &request)
            .map_err(|e| match e {
                GpuInitError::NoAdapter(_) => {
                    anyhow!(
                        "no GPU adapter (on a machine without a GPU, install Mesa's llvmpipe: libegl-mesa0)"
                    )
                }
                GpuInitError::NoDevice { adapter, reason } => {
                    anyhow!("{adapter}: cannot create a device: {reason}")
                }
            })?;

        let reports = Arc::new(Mutex::new(DeviceReports::default()));
        let lost = Arc::clone(&reports);
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut r) = lost.lock() {
                r.lost = Some(format!("{reason:?}: {message}"));
            }
        });
        let errors = Arc::clone(&reports);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            if let Ok(mut r) = errors.lock() {
                r.errors += 1;
                if r.errors <= 3 {
                    eprintln!("ppr-walkthrough: wgpu error: {error}");
                }
                r.last_error = Some(error.to_string());
            }
        }));
        Ok(Self { adapter, device, queue, adapter_info, reports })
    }

    /// Why the device was lost, once its callback has run.
    pub fn lost(&self) -> Option<String> {
        self.reports.lock().ok().and_then(|r| r.lost.clone())
    }

    /// Errors reported since the device was created, and the last one.
    pub fn errors(&self) -> (u64, Option<String>) {
        self.reports.lock().map(|r| (r.errors, r.last_error.clone())).unwrap_or((0, None))
    }

    /// Loses the device on purpose (the F9 key and `--lose-device-at`): what a driver reset
    /// or an unplugged GPU does, so the recovery path can be tried.
    pub fn simulate_loss(&self) {
        self.device.destroy();
        // Drive the callbacks now rather than at the next poll.
        let _ = self.device.poll(wgpu::PollType::Poll);
    }

    /// Name and backend of the adapter, for the status line.
    pub fn describe(&self) -> String {
        format!("{} ({:?})", self.adapter_info.name, self.adapter_info.backend)
    }
}
