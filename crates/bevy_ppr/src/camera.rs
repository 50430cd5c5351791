//! `PprCamera`: the component that turns pixel-projected reflections on for one camera.

use bevy::asset::Handle;
use bevy::camera::{Camera3d, Hdr};
use bevy::ecs::prelude::*;
use bevy::render::render_resource::TextureUsages;
use bevy::render::view::Msaa;
use ppr_runtime::ReflectionSettings;

use crate::asset::PprReflectorSet;

/// Put this on a `Camera3d` to render PPR for it: after the opaque pass, the runtime reads
/// the camera's colour and depth and the reflection is blended over the reflector pixels,
/// its confidence (the output's alpha) times [`PprCamera::reflectivity`] as the weight.
///
/// The camera renders in HDR (`Hdr` is required: the runtime reads linear `Rgba16Float`
/// colour) and without MSAA (PPR reads one depth per pixel; the plugin sets `Msaa::Off`)
/// and its depth texture gains `TEXTURE_BINDING`. Forward and deferred cameras both work.
#[derive(Component, Clone, Debug)]
#[require(Hdr)]
pub struct PprCamera {
    /// The reflector set (`*.ppr.json`); until it has loaded, nothing is drawn.
    pub reflectors: Handle<PprReflectorSet>,
    /// The runtime's settings (hole filling, filtering, anti-bleeding, border fade,
    /// resolution tier), handed to it every frame.
    pub settings: ReflectionSettings,
    /// How much of the reflection replaces the scene colour where PPR is fully confident,
    /// in `[0, 1]` (`ppr-render`'s default composite uses 0.8).
    pub reflectivity: f32,
}

impl PprCamera {
    /// PPR with the runtime's default settings and `ppr-render`'s reflectivity.
    pub fn new(reflectors: Handle<PprReflectorSet>) -> Self {
        Self { reflectors, settings: ReflectionSettings::default(), reflectivity: 0.8 }
    }
}

/// Makes every PPR camera's targets readable by the runtime: depth as a texture, one sample.
pub(crate) fn configure_ppr_cameras(mut cameras: Query<(&mut Camera3d, &mut Msaa), With<PprCamera>>) {
    for (mut camera_3d, mut msaa) in &mut cameras {
        let usages = TextureUsages::from(camera_3d.depth_texture_usages);
        if !usages.contains(TextureUsages::TEXTURE_BINDING) {
            camera_3d.depth_texture_usages = (usages | TextureUsages::TEXTURE_BINDING).into();
        }
        if *msaa != Msaa::Off {
            *msaa = Msaa::Off;
        }
    }
}
