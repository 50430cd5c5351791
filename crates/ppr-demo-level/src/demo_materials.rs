//! The materials of the demo room: the reflective ones an extractor should pick and the rough ones it should reject.

use crate::level_builder::{LevelBuilder, MaterialId, MaterialSpec};
use crate::procedural_textures;

/// Every material of the level, added to a builder.
///
/// Reflective: `mirror`, `puddle`, `glass`, `water`, `polished_marble`, and two glossy ones
/// that blur their reflection: `brushed_metal` (metallic, roughness 0.3) and `rough_water`
/// (roughness 0.15). Everything else has
/// roughness ≥ 0.5, metallic 0 and no transmission, except `lacquered_wood` (roughness
/// 0.2), whose node is marked `{"ppr": {"reflector": false}}`.
pub struct DemoMaterials {
    pub mirror: MaterialId,
    pub puddle: MaterialId,
    pub glass: MaterialId,
    pub water: MaterialId,
    pub polished_marble: MaterialId,
    pub brushed_metal: MaterialId,
    pub rough_water: MaterialId,
    pub floor_tiles: MaterialId,
    pub brick_wall: MaterialId,
    pub stone: MaterialId,
    pub frame_dark: MaterialId,
    pub lacquered_wood: MaterialId,
    pub wood_matte: MaterialId,
    pub paint_red: MaterialId,
    pub paint_blue: MaterialId,
    pub paint_yellow: MaterialId,
    pub paint_orange: MaterialId,
    pub paint_cyan: MaterialId,
    pub paint_purple: MaterialId,
    pub paint_green: MaterialId,
}

impl DemoMaterials {
    pub fn add_to(builder: &mut LevelBuilder) -> Self {
        let floor_texture = builder.add_texture("floor_tiles_checker", &procedural_textures::floor_tiles());
        let brick_texture = builder.add_texture("brick_wall_bricks", &procedural_textures::bricks());
        let mut add = |spec: MaterialSpec| builder.add_material(spec);
        let paint = |name, colour| MaterialSpec::opaque(name, colour, 0.0, 0.7);
        Self {
            mirror: add(MaterialSpec::opaque("mirror", [0.95, 0.95, 0.95], 1.0, 0.02)),
            puddle: add(MaterialSpec::opaque("puddle", [0.06, 0.07, 0.08], 0.0, 0.03)),
            glass: add(MaterialSpec {
                // BLEND with a low alpha is a fallback for renderers without the extension.
                base_color: [0.92, 0.96, 1.0, 0.25],
                transmission: Some(1.0),
                alpha_mode: gltf::json::material::AlphaMode::Blend,
                double_sided: true,
                ..MaterialSpec::opaque("glass", [1.0, 1.0, 1.0], 0.0, 0.0)
            }),
            water: add(MaterialSpec::opaque("water", [0.04, 0.12, 0.16], 0.0, 0.02)),
            polished_marble: add(MaterialSpec::opaque("polished_marble", [0.82, 0.8, 0.76], 0.0, 0.05)),
            brushed_metal: add(MaterialSpec::opaque("brushed_metal", [0.78, 0.78, 0.8], 1.0, 0.3)),
            rough_water: add(MaterialSpec::opaque("rough_water", [0.04, 0.12, 0.16], 0.0, 0.15)),
            floor_tiles: add(MaterialSpec {
                base_color_texture: Some(floor_texture),
                ..MaterialSpec::opaque("floor_tiles", [1.0, 1.0, 1.0], 0.0, 0.9)
            }),
            brick_wall: add(MaterialSpec {
                base_color_texture: Some(brick_texture),
                ..MaterialSpec::opaque("brick_wall", [1.0, 1.0, 1.0], 0.0, 0.9)
            }),
            stone: add(MaterialSpec::opaque("stone", [0.42, 0.41, 0.38], 0.0, 0.8)),
            frame_dark: add(MaterialSpec::opaque("frame_dark", [0.05, 0.05, 0.06], 0.0, 0.6)),
            lacquered_wood: add(MaterialSpec::opaque("lacquered_wood", [0.35, 0.16, 0.06], 0.0, 0.2)),
            wood_matte: add(MaterialSpec::opaque("wood_matte", [0.25, 0.13, 0.06], 0.0, 0.7)),
            paint_red: add(paint("paint_red", [0.8, 0.05, 0.04])),
            paint_blue: add(paint("paint_blue", [0.04, 0.12, 0.8])),
            paint_yellow: add(paint("paint_yellow", [0.9, 0.7, 0.05])),
            paint_orange: add(paint("paint_orange", [0.95, 0.35, 0.03])),
            paint_cyan: add(paint("paint_cyan", [0.05, 0.65, 0.7])),
            paint_purple: add(paint("paint_purple", [0.4, 0.08, 0.6])),
            paint_green: add(paint("paint_green", [0.1, 0.6, 0.08])),
        }
    }
}
