//! Render world: extract PPR cameras, run the runtime after the opaque pass, composite.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use bevy::asset::Assets;
use bevy::camera::{Camera, Camera3d};
use bevy::ecs::prelude::*;
use bevy::log::warn_once;
use bevy::render::Extract;
use bevy::render::render_resource::{
    Extent3d, LoadOp, Operations, PipelineCache, RenderPassColorAttachment, RenderPassDescriptor, StoreOp,
    TextureAspect, TextureDescriptor, TextureDimension, TextureUsages, TextureViewDescriptor,
};
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::sync_world::RenderEntity;
use bevy::render::texture::{CachedTexture, TextureCache};
use bevy::render::view::{ExtractedView, ViewDepthTexture, ViewTarget};
use ppr_format::ReflectorSet;
use ppr_runtime::ReflectionSettings;

use crate::asset::PprReflectorSet;
use crate::camera::PprCamera;
use crate::composite::{CompositePipeline, TARGET_FORMAT};
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

/// 3D cameras without PPR.
type PlainCameras = (With<Camera3d>, Without<PprCamera>);

/// Copies each active PPR camera's component (and its set, an `Arc`) to the render world.
pub(crate) fn extract_ppr_cameras(
    mut commands: Commands,
    cameras: Extract<Query<(RenderEntity, &PprCamera, &Camera)>>,
    plain: Extract<Query<RenderEntity, PlainCameras>>,
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

/// One view's runtime and how many frames it rendered.
struct ViewState {
    runtime: ViewRuntime,
    frames: u32,
}

/// Every PPR view's state, by render-world view entity. The runtime is `Send` but not
/// `Sync`, hence the mutex (never contended: one system at a time touches it).
#[derive(Resource, Default)]
pub(crate) struct PprViews(Mutex<HashMap<Entity, ViewState>>);

/// Drops the state of views that are no longer PPR cameras.
pub(crate) fn prune_views(mut state: ResMut<PprViews>, live: Query<Entity, With<ExtractedPpr>>) {
    if let Ok(views) = state.0.get_mut() {
        views.retain(|entity, _| live.contains(*entity));
    }
}

/// The runtime's output texture for a view of `size` (from Bevy's texture cache).
fn output_texture(cache: &mut TextureCache, device: &RenderDevice, size: Extent3d) -> CachedTexture {
    cache.get(
        device,
        TextureDescriptor {
            label: Some("bevy_ppr output"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: OUTPUT_FORMAT,
            usage: TextureUsages::STORAGE_BINDING
                | TextureUsages::TEXTURE_BINDING
                | TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        },
    )
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
    composite: Res<CompositePipeline>,
    pipeline_cache: Res<PipelineCache>,
    mut texture_cache: ResMut<TextureCache>,
    queue: Res<RenderQueue>,
    timings: Res<PendingTimings>,
    mut ctx: RenderContext,
) {
    let entity = view.entity();
    let (extracted, target, depth, ppr) = view.into_inner();
    let (Some(set), Some(pipeline)) = (&ppr.set, composite.get(&pipeline_cache)) else { return };
    let format = target.main_texture_format();
    if format != TARGET_FORMAT {
        warn_once!(
            "bevy_ppr: the camera's main texture is {format:?}; PPR needs an Hdr camera (Rgba16Float)"
        );
        return;
    }
    let device = ctx.render_device().clone();
    let Ok(mut views) = state.0.lock() else { return };
    let view_state = views
        .entry(entity)
        .or_insert_with(|| ViewState { runtime: ViewRuntime::new(device.wgpu_device(), &queue), frames: 0 });
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
    let size = target.main_texture().size();
    let world_from_view = dmat4(extracted.world_from_view.to_matrix());
    let clip_from_view = glam::Mat4::from_cols_array(&extracted.clip_from_view.to_cols_array());
    let plan = match view_state.runtime.prepare(
        world_from_view,
        clip_from_view,
        ppr.settings,
        [size.width, size.height],
    ) {
        Ok(plan) => plan,
        Err(e) => {
            warn_once!("bevy_ppr: camera not usable by the runtime: {e}");
            return;
        }
    };
    if plan.empty {
        return;
    }
    let output = output_texture(&mut texture_cache, &device, size);
    let bind_group = composite.bind_group(&device, &pipeline_cache, &output.default_view, ppr.reflectivity);
    let depth_view = depth.texture.create_view(&TextureViewDescriptor {
        label: Some("bevy_ppr depth"),
        aspect: TextureAspect::DepthOnly,
        ..Default::default()
    });
    let encoder = ctx.command_encoder();
    if plan.indirect {
        // Only the tiles with a visible reflector are written: clear the rest.
        encoder.begin_render_pass(&RenderPassDescriptor {
            label: Some("bevy_ppr output clear"),
            color_attachments: &[Some(RenderPassColorAttachment {
                view: &output.default_view,
                depth_slice: None,
                resolve_target: None,
                ops: Operations { load: LoadOp::Clear(Default::default()), store: StoreOp::Store },
            })],
            ..Default::default()
        });
    }
    view_state.runtime.encode(encoder, target.main_texture_view(), &depth_view, &output.default_view);
    let mut pass = ctx.begin_tracked_render_pass(RenderPassDescriptor {
        label: Some("bevy_ppr composite"),
        color_attachments: &[Some(target.get_unsampled_color_attachment())],
        ..Default::default()
    });
    pass.set_render_pipeline(pipeline);
    pass.set_bind_group(0, &bind_group, &[]);
    pass.draw(0..3, 0..1);
}
