//! Extraction parameters and the re-extract button (manual edits are kept by id).

use egui::{DragValue, Ui};
use ppr_extract::{CandidateRule, ExtractParams};

use crate::state::InspectorState;

/// Shows the main parameters and "Re-extract".
pub fn show(ui: &mut Ui, state: &mut InspectorState) {
    ui.horizontal(|ui| {
        ui.label("Preset");
        for (name, preset) in ExtractParams::presets() {
            if ui.selectable_label(state.params == preset, name).clicked() {
                state.params = preset;
            }
        }
    });
    let p = &mut state.params;
    let mut all_planar = p.candidates == CandidateRule::AllPlanar;
    if ui.checkbox(&mut all_planar, "Every planar surface is a candidate").changed() {
        p.candidates = if all_planar { CandidateRule::AllPlanar } else { CandidateRule::Materials };
    }
    egui::Grid::new("extraction parameters").num_columns(2).show(ui, |ui| {
        number(ui, "Max roughness", &mut p.max_roughness, 0.01);
        number(ui, "Angle tolerance °", &mut p.angle_tolerance_deg, 0.05);
        number(ui, "Distance tolerance m", &mut p.distance_tolerance_m, 1e-4);
        number(ui, "Min area m²", &mut p.min_area_m2, 1e-3);
        number(ui, "Split min gain", &mut p.split_min_gain, 0.01);
        let label = ui.label("Max shapes per region");
        ui.add(DragValue::new(&mut p.max_shapes_per_region).range(1..=64)).labelled_by(label.id);
        ui.end_row();
        number(ui, "Near-planar merge °", &mut p.near_planar_angle_deg, 0.05);
        number(ui, "Max reflection error m", &mut p.max_reflection_error_m, 1e-3);
        number(ui, "Budget cube m", &mut p.budget_cube_m, 0.5);
        let label = ui.label("Max rectangles per cube");
        ui.add(DragValue::new(&mut p.max_shapes_per_cube).range(1..=100_000)).labelled_by(label.id)
            .on_hover_text("the density budget: rectangles a camera can see at once, per cube of the size above; what it merges, drops or keeps is listed in the messages");
        ui.end_row();
        let mut limited = p.reach_m.is_some();
        ui.checkbox(&mut limited, "Limit occluder reach");
        let mut reach = p.reach_m.unwrap_or(10.0);
        ui.add_enabled(limited, DragValue::new(&mut reach).speed(0.1).suffix(" m"));
        ui.end_row();
        p.reach_m = limited.then_some(reach);
    });
    if let Err(e) = p.validate() {
        ui.colored_label(egui::Color32::LIGHT_RED, e);
    }
    let can_run = state.job.is_none() && state.level.as_ref().is_some_and(|l| l.extract.is_some());
    let run = ui.add_enabled(can_run, egui::Button::new("Re-extract")).on_hover_text(
        "extract again with these parameters; manual edits are kept where their ids still exist",
    );
    if run.clicked() {
        let result = state.reextract();
        state.report(result);
    }
}

fn number(ui: &mut Ui, title: &str, value: &mut f64, speed: f64) {
    let label = ui.label(title);
    ui.add(DragValue::new(value).speed(speed).max_decimals(6)).labelled_by(label.id);
    ui.end_row();
}
