//! `ppr-demo-level`: writes the demo level `assets/demo_room.glb` and its ground truth `assets/demo_room.expected.json`.
//!
//! Usage: `cargo run -p ppr-demo-level [-- OUTPUT_DIR]` (default: the workspace's `assets/`).
//! The output is deterministic: same bytes on every run (a test holds the committed files
//! equal to a fresh run).
//!
//! # The room (metres, +Y up, right-handed; looking down, x to the right, z towards you)
//!
//! Interior x ∈ [-8, 8], z ∈ [-6, 6], walls 5 m high, no ceiling. Floor: rough tiles
//! (1 m checker); walls: rough bricks.
//!
//! ```text
//!  z=-6  +------------------[ mirror wall x∈[-3,3] ]----------------------------+
//!        |      (red pillar -4,-4.2)  orange box -1.6,-4.9  green box 3.2,-4.8   |
//!        |  purple box                              (blue pillar 4.5,-4.6)       |
//!  z=-3.5|  [pond -4.6,-2.35] puddle_c (-2.2,-2.6)   [ glass x∈[0,3] ]          |
//!        |S5 z∈[-1.5,-0.5] y=1.25          puddle_b (1.9,-1.6)  tilted mirror   |
//!        |S4 y=1.0      +--+                                    (5,-2)   table   |
//!        |S3 y=0.75     |L | puddle_a (-0.6,0.6)   cyan box (2,0.8)     (6.3,-0.2)|
//!        |S2 y=0.5      |  +------------+                 +-------------+       |
//!        |S1 z∈[2.5,3.5]|   L floor     |                 | water basin |       |
//!        |  y=0.25      +---------------+                 +-------------+       |
//!        |   (yellow pillar -5.2,5)          cameras near z≈5                   |
//!  z=+6  +-----------------------------------------------------------------------+
//!       x=-8                                                                   x=8
//! ```
//!
//! - Mirror wall: 6 × 3 m, centre (0, 2, -5.95), facing +Z, dark frame.
//! - Glass pane: 3 × 2.5 m, centre (1.5, 1.33, -3.5), facing +Z (double-sided), framed.
//! - Mirror stairs `step_1..5` against the left wall, x ∈ [-8, -6], 1 m deep each, tops at
//!   y = 0.25 … 1.25 for z centres 3, 2, 1, 0, -1 (one mesh, five instances).
//! - Tilted mirror (`tilted_mirror`): 1.5 × 2 m on a stone stand at (5, 0, -2), turned
//!   -30° about Y, leaning back 20°; centre ≈ (5.18, 1.15, -2.31).
//! - Stone basin: centred (4.5, 0, 3), rim 0.5 m; `water_surface` 3 × 2 m at y = 0.4.
//! - Pond: centred (-4.6, 0, -2.35), rim 0.18 m; `pond_water` 2 × 1.4 m at y = 0.12.
//! - L floor (polished marble, y = 0.001): x ∈ [-4.5, 1.5] × z ∈ [2.5, 4.5] plus
//!   x ∈ [-4.5, -2.5] × z ∈ [-0.5, 2.5].
//! - Puddles (y = 0.002): `puddle_a` (-0.6, 0.6), `puddle_b` (1.9, -1.6), `puddle_c`
//!   (-2.2, -2.6) under a node with scale x = -1.
//! - Table at (6.3, 0, -0.2): glossy top marked `{"ppr": {"reflector": false}}`.
//! - Cameras `cam_overview` (0, 2, 5), `cam_mirror` (-1.2, 0.5, 5.6), `cam_steps`
//!   (-2.5, 2.3, 5.2).

mod demo_materials;
mod demo_room;
mod exact_trig;
mod generated_level;
mod ground_truth;
mod json_layout;
mod level_builder;
mod mesh_data;
mod png_encoder;
mod ppr_extras;
mod procedural_textures;
mod rectangle_fit;

#[cfg(test)]
mod level_checks;

use std::path::PathBuf;

use anyhow::{Result, bail};

use generated_level::{EXPECTED_FILE, GeneratedLevel, LEVEL_FILE};

/// The workspace's `assets/` folder.
fn default_assets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

fn main() -> Result<()> {
    let mut args = std::env::args_os().skip(1);
    let directory = args.next().map_or_else(default_assets_dir, PathBuf::from);
    if args.next().is_some() {
        bail!("usage: ppr-demo-level [OUTPUT_DIR]");
    }
    let level = GeneratedLevel::generate()?;
    level.write_to(&directory)?;
    println!(
        "wrote {} ({} bytes) and {} ({} bytes) to {}",
        LEVEL_FILE,
        level.glb.len(),
        EXPECTED_FILE,
        level.expected_json.len(),
        directory.display()
    );
    Ok(())
}
