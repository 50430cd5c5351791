//! The wgpu device eframe creates for the inspector: the adapter's own limits (the PPR
//! compute passes need more than egui's WebGL2-level defaults on GL) and GPU timestamps
//! where the adapter has them. The viewport renders on this device.

use std::sync::Arc;

use eframe::egui_wgpu::{WgpuSetup, WgpuSetupCreateNew};

/// Features requested when the adapter has them (never required): timestamps, subgroups
/// for the projection's subgroup culling, and mapped buffers the preview's passes bind (its
/// frame upload without a copy).
const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::TIMESTAMP_QUERY
    .union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    .union(wgpu::Features::SUBGROUP)
    .union(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS);

/// The device the inspector asks `adapter` for.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some("ppr-inspector device"),
        required_features: adapter.features() & OPTIONAL_FEATURES,
        required_limits: adapter.limits(),
        ..Default::default()
    }
}

/// `setup` with the inspector's device descriptor (a setup that reuses an existing device
/// is returned as it is).
pub fn with_inspector_device(setup: WgpuSetup) -> WgpuSetup {
    match setup {
        WgpuSetup::CreateNew(mut new) => {
            new.device_descriptor = Arc::new(device_descriptor);
            WgpuSetup::CreateNew(new)
        }
        existing => existing,
    }
}

/// The setup for the application window.
pub fn wgpu_setup() -> WgpuSetup {
    with_inspector_device(WgpuSetup::CreateNew(WgpuSetupCreateNew::without_display_handle()))
}
