//! The selected reflector's properties: enable, kind, roughness, name, placement fields, and the
//! split, merge and re-fit operations. Every change is an edit command (undoable,
//! validated; a refused one shows as an error). It also says which reflector is the
//! selection's path blocker (`ppr_runtime::path_blockers`): the runtime draws no reflection
//! whose path crosses it.

use egui::{DragValue, Ui};
use ppr_format::ReflectorKind;

use crate::commands::EditCommand;
use crate::reflector_geometry::{SplitAxis, placement_of};
use crate::set_tolerances::SetTolerances;
use crate::state::InspectorState;

/// What the panel remembers between frames.
#[derive(Clone, Debug)]
pub struct PropertiesPanel {
    /// Where a split cuts, as a fraction of the length.
    pub split_at: f64,
    /// The reflector chosen to merge with the selection.
    pub merge_with: Option<u32>,
    /// The field being edited and its undo gesture (one step per field interaction).
    field_gesture: Option<(egui::Id, u64)>,
    /// Per reflector of the set, its path blocker's index, for (level generation, revision).
    blockers: Option<((u64, u64), Vec<u32>)>,
}

impl Default for PropertiesPanel {
    fn default() -> Self {
        Self { split_at: 0.5, merge_with: None, field_gesture: None, blockers: None }
    }
}

impl PropertiesPanel {
    fn gesture(&mut self, state: &mut InspectorState, id: egui::Id) -> u64 {
        match self.field_gesture {
            Some((field, g)) if field == id => g,
            _ => {
                let g = state.new_gesture();
                self.field_gesture = Some((id, g));
                g
            }
        }
    }

    fn end_gesture(&mut self, response: &egui::Response) {
        if (response.drag_stopped() || response.lost_focus())
            && self.field_gesture.is_some_and(|(id, _)| id == response.id)
        {
            self.field_gesture = None;
        }
    }

    /// "path blocker: …" for reflector `r` of the set: the parallel reflector right in
    /// front of it whose rectangle a reflection's path may cross (then not drawn), as the
    /// runtime finds it; rebuilt after each edit.
    fn path_blocker_line(&mut self, state: &InspectorState, r: &ppr_format::Reflector) -> String {
        let Some(set) = state.set() else { return String::new() };
        let key = (state.level_generation, state.revision());
        if self.blockers.as_ref().is_none_or(|(k, _)| *k != key) {
            self.blockers = Some((key, ppr_runtime::shapes::ShapeTable::from_set(set).path_blockers));
        }
        let blockers = self.blockers.as_ref().map(|(_, b)| b.as_slice()).unwrap_or_default();
        let blocker = set
            .reflectors
            .iter()
            .position(|x| x.id == r.id)
            .and_then(|i| blockers.get(i))
            .and_then(|&b| set.reflectors.get(b as usize));
        match blocker {
            Some(b) => format!(
                "path blocker: {} (id {}), {:.3} m in front",
                b.name,
                b.id,
                (b.center - r.center).dot(r.normal)
            ),
            None => "path blocker: none".to_owned(),
        }
    }

    /// Shows the panel for the selected reflector.
    pub fn show(&mut self, ui: &mut Ui, state: &mut InspectorState) {
        let Some(r) = state.selected().cloned() else {
            ui.label("Select a reflector in the list or the viewport.");
            return;
        };
        let id = r.id;
        ui.label(format!("id {id}, parallel group {}", r.parallel_group));
        if !r.source.nodes.is_empty() {
            ui.label(format!("nodes: {}", r.source.nodes.join(", ")));
        }
        if !r.source.materials.is_empty() {
            ui.label(format!("materials: {}", r.source.materials.join(", ")));
        }
        ui.label(format!(
            "area {:.3} m², coverage {:.1}%, {} occluders",
            r.area(),
            100.0 * r.coverage,
            r.occluders.len()
        ));
        ui.label(self.path_blocker_line(state, &r));

        let mut enabled = r.enabled;
        if ui.checkbox(&mut enabled, "Enabled").changed() {
            state.apply(EditCommand::SetEnabled { id, enabled });
        }

        ui.horizontal(|ui| {
            let label = ui.label("Reflector name");
            let mut name = r.name.clone();
            let response =
                ui.add(egui::TextEdit::singleline(&mut name).desired_width(200.0)).labelled_by(label.id);
            if response.changed() {
                let g = self.gesture(state, response.id);
                state.apply_in_gesture(EditCommand::Rename { id, name }, Some(g));
            }
            self.end_gesture(&response);
        });

        ui.horizontal(|ui| {
            ui.label("Kind");
            for kind in ReflectorKind::ALL {
                let title = match kind {
                    ReflectorKind::Opaque => "Opaque",
                    ReflectorKind::Transparent => "Transparent",
                    ReflectorKind::Water => "Water",
                };
                if ui.selectable_label(r.kind == kind, title).clicked() && r.kind != kind {
                    state.apply(EditCommand::SetKind { id, kind });
                }
            }
        });

        ui.horizontal(|ui| {
            let label = ui.label("Roughness");
            let mut roughness = r.roughness;
            let response = ui
                .add(DragValue::new(&mut roughness).speed(0.005).range(0.0..=1.0).max_decimals(3))
                .labelled_by(label.id)
                .on_hover_text("perceptual roughness, as glTF's: 0 is a mirror, 1 fully rough");
            if response.changed() && roughness != r.roughness {
                let g = self.gesture(state, response.id);
                state.apply_in_gesture(EditCommand::SetRoughness { id, roughness }, Some(g));
            }
            self.end_gesture(&response);
        });

        ui.separator();
        ui.label("Rectangle (in its plane)");
        let placement = placement_of(&r);
        let mut edited = placement;
        let size_speed = (r.half_extents.max_element() * 0.01).max(1e-3);
        let responses = egui::Grid::new("placement")
            .num_columns(2)
            .show(ui, |ui| {
                vec![
                    number_row(ui, "Centre X", &mut edited.center.x, size_speed, " m"),
                    number_row(ui, "Centre Y", &mut edited.center.y, size_speed, " m"),
                    number_row(ui, "Centre Z", &mut edited.center.z, size_speed, " m"),
                    number_row(ui, "Half width", &mut edited.half_extents.x, size_speed, " m"),
                    number_row(ui, "Half height", &mut edited.half_extents.y, size_speed, " m"),
                    number_row(ui, "Angle", &mut edited.angle_deg, 0.5, "°"),
                ]
            })
            .inner;
        if let Some(changed) = responses.iter().find(|r| r.changed())
            && edited != placement
        {
            let g = self.gesture(state, changed.id);
            state.apply_in_gesture(EditCommand::Place { id, placement: edited }, Some(g));
        }
        for response in &responses {
            self.end_gesture(response);
        }

        ui.separator();
        self.operations(ui, state, &r);
    }

    fn operations(&mut self, ui: &mut Ui, state: &mut InspectorState, r: &ppr_format::Reflector) {
        let id = r.id;
        ui.horizontal(|ui| {
            let label = ui.label("Cut at");
            ui.add(DragValue::new(&mut self.split_at).speed(0.01).range(0.01..=0.99).max_decimals(3))
                .labelled_by(label.id);
            if ui.button("Split across U").clicked() {
                state.apply(EditCommand::Split { id, axis: SplitAxis::U, at: self.split_at });
            }
            if ui.button("Split across V").clicked() {
                state.apply(EditCommand::Split { id, axis: SplitAxis::V, at: self.split_at });
            }
        });
        let has_region = state.doc.as_ref().is_some_and(|d| d.regions.contains_key(&id));
        let refit = ui
            .add_enabled(has_region, egui::Button::new("Re-fit to region"))
            .on_disabled_hover_text("regions come from an extraction: re-run it to re-fit");
        if refit.clicked() {
            state.apply(EditCommand::Refit { id });
        }

        let Some(set) = state.set() else { return };
        let tolerance = SetTolerances::of(set).coplanar();
        let candidates: Vec<(u32, String)> = set
            .reflectors
            .iter()
            .filter(|o| {
                o.id != id
                    && o.normal.dot(r.normal) >= tolerance.cos_angle
                    && r.signed_distance(o.center).abs() <= tolerance.distance
            })
            .map(|o| (o.id, o.name.clone()))
            .collect();
        if self.merge_with.is_some_and(|m| !candidates.iter().any(|(c, _)| *c == m)) {
            self.merge_with = None;
        }
        ui.horizontal(|ui| {
            let chosen = self
                .merge_with
                .and_then(|m| candidates.iter().find(|(c, _)| *c == m))
                .map_or_else(|| "(coplanar reflector)".to_owned(), |(_, n)| n.clone());
            egui::ComboBox::from_label("Merge with").selected_text(chosen).show_ui(ui, |ui| {
                for (cid, name) in &candidates {
                    ui.selectable_value(&mut self.merge_with, Some(*cid), name);
                }
            });
            if ui.add_enabled(self.merge_with.is_some(), egui::Button::new("Merge")).clicked()
                && let Some(other) = self.merge_with.take()
            {
                state.apply(EditCommand::Merge { id, other });
            }
        });
        if candidates.is_empty() {
            ui.label("(no coplanar reflector to merge with)");
        }
    }
}

/// A labelled number field in a two-column grid.
fn number_row(ui: &mut Ui, title: &str, value: &mut f64, speed: f64, suffix: &str) -> egui::Response {
    let label = ui.label(title);
    let response =
        ui.add(DragValue::new(value).speed(speed).max_decimals(4).suffix(suffix)).labelled_by(label.id);
    ui.end_row();
    response
}
