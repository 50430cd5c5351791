//! The inspector's integration tests: state and edit logic without a GPU (`state_tests`),
//! and the application driven through egui_kittest on the wgpu software adapter
//! (`ui_tests`, with snapshots in `tests/snapshots/`).

mod demo;
mod shared_scenes;
mod state_tests;
mod ui_tests;
