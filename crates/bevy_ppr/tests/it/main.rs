//! `bevy_ppr` in a Bevy app: the asset loader (errors, hot reload) and one headless frame of
//! the demo room against `ppr-render`.

#[path = "../../examples/demo_room/scene.rs"]
mod scene;

mod app;
mod headless;
mod loader;
