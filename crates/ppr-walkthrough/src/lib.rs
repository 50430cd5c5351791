//! The PPR walkthrough: how a game loads a reflector set and renders pixel-projected
//! reflections every frame with `ppr-runtime`.
//!
//! Start with [`walkthrough_renderer`]: the game's own forward pass, then the runtime's two
//! calls per frame (`prepare`, `encode`), then the game's composite. Around it:
//!
//! - [`gltf_level`], [`forward_pass`]: the level rendered the way a game would
//!   (camera-relative draws, one sun, a reflection weight per pixel), on `ppr-scene-gpu`'s
//!   level, GPU meshes and raster pieces (shared with the testbed);
//! - [`composite_pass`], [`intermediate_view`], [`overlay_pass`]: the image on screen, the
//!   debug view of PPR's intermediate buffer, and the status text ([`status_line`],
//!   [`overlay_text`], [`bitmap_font`]);
//! - [`hot_reload`]: the `*.ppr.json` watched on a thread, refused files reported, the last
//!   good set kept, a set of another level refused ([`level_match`]);
//! - [`window_app`] (winit) with [`surface_state`] (resize, minimise, surface loss) and
//!   [`gpu_context`] (device-lost callback, recovery); [`headless`] for tests and CI, which
//!   refuses a missing or refused set with [`bad_input::EXIT_BAD_INPUT`].
//!
//! Architecture invariant: for reflections it uses only `ppr-runtime` and `ppr-format`,
//! like a game; its level and raster pieces come from `ppr-level` and `ppr-scene-gpu`
//! (standing in for a game's own loader and renderer), never from the testbed.

pub mod bad_input;
pub mod bitmap_font;
pub mod camera_spec;
pub mod cli;
pub mod composite_pass;
pub mod controls;
pub mod fly_camera;
pub mod forward_pass;
pub mod frame_clock;
pub mod frame_targets;
pub mod fullscreen_pipeline;
pub mod gltf_level;
pub mod gpu_context;
pub mod headless;
pub mod hot_reload;
pub mod intermediate_view;
pub mod level_match;
pub mod offscreen_target;
pub mod overlay_pass;
pub mod overlay_text;
pub mod previous_frame;
pub mod reflectivity;
pub mod screen_passes;
pub mod status_line;
pub mod stereo_frame;
pub mod surface_state;
pub mod texture_readback;
pub mod view_mode;
pub mod walkthrough_renderer;
pub mod window_app;

pub use cli::Args;
pub use headless::{HeadlessFrame, run_headless};
pub use walkthrough_renderer::WalkthroughRenderer;
pub use window_app::run_window;

/// Runs the walkthrough as the command line asks: a window, or headless frames.
///
/// # Errors
/// Whatever stops the run (level, camera, GPU, screenshot).
pub fn run(args: Args) -> anyhow::Result<()> {
    if !args.headless {
        return run_window(args);
    }
    if args.frames.is_none() {
        return Err(bad_input::BadInput("--headless needs --frames N".into()).into());
    }
    let frame = run_headless(&args)?;
    println!("adapter: {}", frame.adapter);
    println!("{}", frame.plan);
    if let Some(t) = &frame.timings {
        println!("GPU: {t}");
    }
    if frame.device_recoveries > 0 {
        println!("device lost and recreated {} time(s)", frame.device_recoveries);
    }
    if let Some(path) = &args.screenshot {
        println!("wrote {}", path.display());
    }
    Ok(())
}
