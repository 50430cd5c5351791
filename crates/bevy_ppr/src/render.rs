//! Render world: extract PPR cameras, run the runtime after the opaque pass, composite.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use bevy::asset::Assets;
use bevy::camera::{Camera, Camera3d};
use bevy::ecs::prelude::*;
use bevy::log::warn_once;
use bevy::render::Extract;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::sync_world::RenderEntity;
use bevy::render::view::{ExtractedView, ViewDepthTexture, ViewTarget};
use ppr_format::ReflectorSet;
use ppr_runtime::ReflectionSettings;

use crate::asset::PprReflectorSet;
use crate::camera::PprCamera;
use crate::composite::CompositePass;
use crate::diagnostics::PendingTimings;
use crate::runtime::{OUTPUT_FORMAT, ViewRuntime};

/// Frames between two timing read-outs (each waits for the GPU).
const TIMING_INTERVAL: u32 = 30;

/// A PPR camera as the render world sees it.
#[derive(Component, Clone)]
pub(crate) struct ExtractedPpr {
    /// `None` until the set has loaded.
    pub set: Option<Arc<ReflectorSet>>,
    pub settings: ReflectionSettings,
    pub reflectivity: f32,
}

/// Copies each active PPR camera's component (and its set, an `Arc`) to the render world.
pub(crate) fn extract_ppr_cameras(
    mut commands: Commands,
    cameras: Extract<Query<(RenderEntity, &PprCamera, &Camera)>>,
    plain: Extract<Query<RenderEntity, (With<Camera3d>, Without<PprCamera>)>>,
    sets: Extract<Res<Assets<PprReflectorSet>>>,
) {
    for (entity, ppr, camera) in &cameras {
        if !camera.is_active {
            commands.entity(entity).remove::<ExtractedPpr>();
            continue;
        }
        let set = sets.get(&ppr.reflectors).map(|asset| Arc::clone(&asset.set));
        commands.entity(entity).insert(ExtractedPpr {
            set,
            settings: ppr.settings,
            reflectivity: ppr.reflectivity,
        });
    }
    for entity in &plain {
        commands.entity(entity).remove::<ExtractedPpr>();
    }
}

/// One view's runtime and output texture.
struct ViewState {
    runtime: ViewRuntime,
    output: Option<(wgpu::Texture, wgpu::TextureView)>,
    frames: u32,
}

/// Every PPR view's state, by render-world view entity. The runtime is `Send` but not
/// `Sync`, hence the mutex (never contended: one system touches it).
#[derive(Resource, Default)]
pub(crate) struct PprViews {
    views: Mutex<HashMap<Entity, ViewState>>,
    composite: Mutex<Option<CompositePass>>,
}

/// Drops the state of views that are no longer PPR cameras.
pub(crate) fn prune_views(mut state: ResMut<PprViews>, live: Query<Entity, With<ExtractedPpr>>) {
    if let Ok(views) = state.views.get_mut() {
        views.retain(|entity, _| live.contains(*entity));
    }
}

fn output_texture(device: &wgpu::Device, [width, height]: [u32; 2]) -> (wgpu::Texture, wgpu::TextureView) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("bevy_ppr output"),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: OUTPUT_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    (texture, view)
}

fn clear(encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("bevy_ppr output clear"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
        })],
        ..Default::default()
    });
}

/// Bevy's `Mat4` (its glam) as the runtime's `DMat4`.
fn dmat4(m: bevy::math::Mat4) -> glam::DMat4 {
    glam::DMat4::from_cols_array(&m.to_cols_array().map(f64::from))
}

/// `Core3d`, after the opaque pass (and so after deferred lighting): the runtime reads the
/// view's colour and depth, writes its output, and the composite blends it over the colour.
#[allow(clippy::too_many_arguments)]
pub(crate) fn ppr_pass(
    view: ViewQuery<(&ExtractedView, &ViewTarget, &ViewDepthTexture, &ExtractedPpr)>,
    state: Res<PprViews>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    timings: Res<PendingTimings>,
    mut ctx: RenderContext,
) {
    let entity = view.entity();
    let (extracted, target, depth, ppr) = view.into_inner();
    let Some(set) = &ppr.set else { return };
    let format = target.main_texture_format();
    if format != wgpu::TextureFormat::Rgba16Float {
        warn_once!("bevy_ppr: the camera's main texture is {format:?}; PPR needs an Hdr camera (Rgba16Float)");
        return;
    }
    let device = device.wgpu_device();
    let size = target.main_texture().size();
    let size = [size.width, size.height];
    let (Ok(mut views), Ok(mut composite)) = (state.views.lock(), state.composite.lock()) else { return };
    let view_state = views.entry(entity).or_insert_with(|| ViewState {
        runtime: ViewRuntime::new(device, &queue),
        output: None,
        frames: 0,
    });
    if let Err(e) = view_state.runtime.use_set(set) {
        warn_once!("bevy_ppr: the runtime refused the reflector set: {e}");
        return;
    }
    view_state.frames = view_state.frames.wrapping_add(1);
    if view_state.frames % TIMING_INTERVAL == 0
        && let Some(passes) = view_state.runtime.read_timings()
    {
        timings.put(passes);
    }
    let world_from_view = dmat4(extracted.world_from_view.to_matrix());
    let clip_from_view = glam::Mat4::from_cols_array(&extracted.clip_from_view.to_cols_array());
    let plan = match view_state.runtime.prepare(world_from_view, clip_from_view, ppr.settings, size) {
        Ok(plan) => plan,
        Err(e) => {
            warn_once!("bevy_ppr: camera not usable by the runtime: {e}");
            return;
        }
    };
    if plan.empty {
        return;
    }
    if view_state.output.as_ref().is_none_or(|(t, _)| [t.width(), t.height()] != size) {
        view_state.output = Some(output_texture(device, size));
    }
    let Some((_, output)) = &view_state.output else { return };
    let composite = match &mut *composite {
        Some(pass) if pass.format() == format => pass,
        slot => slot.insert(CompositePass::new(device, format)),
    };
    let bind_group = composite.bind_group(device, output, ppr.reflectivity);
    let depth_view = depth.texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("bevy_ppr depth"),
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    });
    let encoder = ctx.command_encoder();
    if plan.indirect {
        clear(encoder, output);
    }
    view_state.runtime.encode(encoder, target.main_texture_view(), &depth_view, output);
    composite.encode(encoder, &bind_group, target.main_texture_view());
}
