//! A wgpu device for the crate's unit tests (Mesa's llvmpipe without a GPU): each call
//! makes its own instance.

/// A new instance's first adapter and its device; panics (loudly) where there is none.
pub(crate) fn device() -> wgpu::Device {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect(
        "no GPU adapter found: GPU tests need one (Mesa's llvmpipe through wgpu's GL backend works \
         without a GPU)",
    );
    pollster::block_on(adapter.request_device(&Default::default())).expect("the adapter refused a device").0
}
