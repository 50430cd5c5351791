//! Clearing a reflection target to "no reflection" (transparent black: colour 0,
//! confidence 0) before a technique writes it: the runtime writes only where its plan's
//! passes run (active tiles, layer rectangles), so a target reused across frames or
//! techniques is cleared first.

/// Records a render pass that clears `view` to transparent black. `label` names the
/// caller's target in captures.
pub fn clear_target(encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView, label: &str) {
    let _pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
}
