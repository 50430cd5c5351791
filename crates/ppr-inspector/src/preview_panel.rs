//! Preview controls: what the viewport shows (scene, PPR, reference, difference), the
//! reflection-pass toggles, the overlay, and what the last frame did (plan, GPU times).

use egui::{RichText, Ui};

use crate::overlay_geometry::ColorBy;
use crate::preview::PreviewMode;
use crate::state::InspectorState;
use crate::viewport_renderer::PreviewFrame;

/// Shows the controls and, when a frame was rendered, its plan, timings and quality.
pub fn show(ui: &mut Ui, state: &mut InspectorState, frame: Option<&PreviewFrame>, adapter: Option<&str>) {
    let p = &mut state.preview;
    ui.horizontal(|ui| {
        for mode in PreviewMode::ALL {
            ui.selectable_value(&mut p.mode, mode, mode.label());
        }
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut p.reflection.holes, "Holes");
        ui.checkbox(&mut p.reflection.filtering, "Filtering");
        ui.add_enabled(
            p.reflection.filtering,
            egui::Checkbox::new(&mut p.reflection.anti_bleeding, "Anti-bleeding"),
        );
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut p.overlay, "Overlay");
        ui.selectable_value(&mut p.color_by, ColorBy::Kind, "Colour by kind");
        ui.selectable_value(&mut p.color_by, ColorBy::Coverage, "Colour by coverage");
    });
    ui.horizontal(|ui| {
        ui.label("Resolution");
        for (scale, name) in [(1.0, "Full"), (0.5, "Half"), (0.25, "Quarter")] {
            ui.selectable_value(&mut p.resolution, scale, name);
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label("Reflectivity");
        ui.add(egui::Slider::new(&mut p.reflectivity, 0.0..=1.0)).labelled_by(label.id);
    });
    if let Some(adapter) = adapter {
        ui.label(RichText::new(format!("GPU: {adapter}")).small());
    }
    let Some(frame) = frame else { return };
    ui.label(RichText::new("Frame plan").strong());
    ui.label(RichText::new(&frame.plan).monospace().small());
    ui.label(RichText::new("GPU time per pass").strong());
    match (&frame.timings, frame.timestamps) {
        (Some(t), _) => {
            for ((name, ms), ran) in t.passes().into_iter().zip(frame.passes_recorded) {
                // A pass that ran keeps its line when the adapter's timestamps for it were
                // unusable (llvmpipe's GL timer queries, now and then).
                let text = match ms {
                    Some(ms) => format!("{name:<11} {ms:8.3} ms"),
                    None if ran => format!("{name:<11} {:>8} ms", "–"),
                    None => continue,
                };
                ui.label(RichText::new(text).monospace().small());
            }
            ui.label(RichText::new(format!("{:<11} {:8.3} ms", "total", t.total_ms())).monospace().small());
        }
        (None, true) => {
            ui.label("(no passes ran this frame)");
        }
        (None, false) => {
            ui.label("(this adapter has no GPU timestamps)");
        }
    }
    if let Some(q) = &frame.quality {
        ui.label(RichText::new("PPR vs reference (on-screen reflector pixels)").strong());
        ui.label(RichText::new(q.comparison.to_string()).small());
        ui.label(RichText::new(format!("holes: {:.2}%", 100.0 * q.holes)).small());
    }
}
