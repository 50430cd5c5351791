//! The reflector inspector: review, fix and preview a level's reflector set.
//!
//! `ppr-inspector [level.glb] [--set level.ppr.json]` opens a level, extracts it in the
//! background (or loads a saved set), shows it in a 3D viewport with the rectangles
//! overlaid and a live PPR preview, and lets an artist edit the reflectors with undo and
//! redo, re-extract keeping manual edits, and save.
//!
//! The state ([`state::InspectorState`]: document, history, job, settings) is apart from
//! the UI ([`app::InspectorApp`] and its panels) so it can be tested without a GPU.

pub mod app;
pub mod camera_control;
pub mod commands;
pub mod document;
pub mod edit_history;
pub mod edits_file;
pub mod error;
pub mod extraction_job;
pub mod extraction_panel;
pub mod gpu_setup;
pub mod manual_edits;
pub mod messages;
pub mod overlay_geometry;
pub mod picking;
pub mod preview;
pub mod preview_panel;
pub mod properties_panel;
pub mod reflector_geometry;
pub mod reflector_list;
pub mod reflector_table;
pub mod set_tolerances;
pub mod state;
pub mod status_bar;
pub mod toolbar;
pub mod viewport;
pub mod viewport_handles;
pub mod viewport_renderer;

pub use app::{InspectorApp, StartupOptions};
pub use error::{EditError, InspectorError};
pub use state::InspectorState;
