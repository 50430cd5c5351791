//! The runtime's per-pass GPU times as Bevy diagnostics (`ppr/projection`, ..., `ppr/total`).

use std::sync::{Arc, Mutex};

use bevy::app::App;
use bevy::diagnostic::{Diagnostic, DiagnosticPath, Diagnostics, RegisterDiagnostic};
use bevy::ecs::prelude::*;

/// The diagnostic of each pass's GPU time in milliseconds, as `PassTimings::passes` names
/// them, and of their sum. Read them from `DiagnosticsStore`.
pub const PASS_DIAGNOSTICS: [DiagnosticPath; 8] = [
    DiagnosticPath::const_new("ppr/classify"),
    DiagnosticPath::const_new("ppr/clear"),
    DiagnosticPath::const_new("ppr/projection"),
    DiagnosticPath::const_new("ppr/reflection"),
    DiagnosticPath::const_new("ppr/layers"),
    DiagnosticPath::const_new("ppr/downsample"),
    DiagnosticPath::const_new("ppr/upsample"),
    DiagnosticPath::const_new("ppr/total"),
];

/// Timings read in the render world, waiting for the main world to record them. One value
/// shared by both worlds (render world writes, main world takes).
#[derive(Resource, Clone, Default)]
pub(crate) struct PendingTimings(Arc<Mutex<Vec<(&'static str, f64)>>>);

impl PendingTimings {
    /// Replaces what waits with a new read-out.
    pub fn put(&self, passes: Vec<(&'static str, f64)>) {
        if let Ok(mut pending) = self.0.lock() {
            *pending = passes;
        }
    }

    fn take(&self) -> Vec<(&'static str, f64)> {
        self.0.lock().map(|mut pending| std::mem::take(&mut *pending)).unwrap_or_default()
    }
}

/// Registers the diagnostics with a unit of milliseconds.
pub(crate) fn register(app: &mut App) {
    for path in PASS_DIAGNOSTICS {
        app.register_diagnostic(Diagnostic::new(path).with_suffix(" ms"));
    }
}

/// Main world: records the latest read-out.
pub(crate) fn record_timings(pending: Res<PendingTimings>, mut diagnostics: Diagnostics) {
    for (name, ms) in pending.take() {
        if let Some(path) = PASS_DIAGNOSTICS.iter().find(|p| p.as_str() == format!("ppr/{name}")) {
            diagnostics.add_measurement(path, || ms);
        }
    }
}
