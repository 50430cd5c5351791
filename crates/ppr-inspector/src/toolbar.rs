//! The toolbar: a path field with open and save buttons (plus native dialogs with the
//! `file-dialog` feature), undo and redo, and the camera mode.

use std::path::PathBuf;

use egui::Ui;

use crate::camera_control::CameraMode;
use crate::state::{InspectorState, PendingAction};

/// What the toolbar remembers between frames.
#[derive(Clone, Debug, Default)]
pub struct Toolbar {
    /// The path typed (or chosen) for opening and "Save as".
    pub path: String,
}

impl Toolbar {
    /// Shows the toolbar.
    pub fn show(&mut self, ui: &mut Ui, state: &mut InspectorState) {
        ui.horizontal_wrapped(|ui| {
            let label = ui.label("Path");
            ui.add(
                egui::TextEdit::singleline(&mut self.path)
                    .desired_width(260.0)
                    .hint_text("level.glb or level.ppr.json"),
            )
            .labelled_by(label.id);
            #[cfg(feature = "file-dialog")]
            if ui.button("Browse…").clicked()
                && let Some(path) =
                    rfd::FileDialog::new().add_filter("levels and sets", &["glb", "gltf", "json"]).pick_file()
            {
                self.path = path.display().to_string();
            }
            let typed = self.typed_path();
            if ui.add_enabled(typed.is_some(), egui::Button::new("Open level")).clicked()
                && let Some(path) = typed.clone()
            {
                state.request(PendingAction::OpenLevel(path));
            }
            if ui.add_enabled(typed.is_some(), egui::Button::new("Open set")).clicked()
                && let Some(path) = typed.clone()
            {
                state.request(PendingAction::OpenSet(path));
            }
            ui.separator();
            let has_doc = state.doc.is_some();
            let save = ui.add_enabled(has_doc, egui::Button::new("Save"));
            let save = match state.default_set_path() {
                Some(p) => save.on_hover_text(format!("save to {}", p.display())),
                None => save,
            };
            if save.clicked() {
                let result = state.save();
                state.report(result);
            }
            if ui.add_enabled(has_doc && typed.is_some(), egui::Button::new("Save as")).clicked()
                && let Some(path) = typed
            {
                let result = state.save_as(&path);
                state.report(result);
            }
            ui.separator();
            let undo_tip = state
                .history
                .undo_label()
                .map_or_else(|| "nothing to undo".to_owned(), |l| format!("undo {l}"));
            let undo = ui
                .add_enabled(state.history.undo_label().is_some(), egui::Button::new("Undo"))
                .on_hover_text(undo_tip);
            if undo.clicked() {
                state.undo();
            }
            let redo_tip = state
                .history
                .redo_label()
                .map_or_else(|| "nothing to redo".to_owned(), |l| format!("redo {l}"));
            let redo = ui
                .add_enabled(state.history.redo_label().is_some(), egui::Button::new("Redo"))
                .on_hover_text(redo_tip);
            if redo.clicked() {
                state.redo();
            }
            ui.separator();
            let mut mode = state.camera.mode;
            ui.selectable_value(&mut mode, CameraMode::Orbit, "Orbit");
            ui.selectable_value(&mut mode, CameraMode::Fly, "Fly");
            state.camera.set_mode(mode);
            let cameras: Vec<ppr_testbed::LevelCamera> = state
                .level
                .as_ref()
                .and_then(|l| l.render.as_ref())
                .map(|l| l.cameras.clone())
                .unwrap_or_default();
            if !cameras.is_empty() {
                egui::ComboBox::from_label("View").selected_text("level camera").show_ui(ui, |ui| {
                    for camera in &cameras {
                        if ui.selectable_label(false, &camera.name).clicked() {
                            state.view_from(camera);
                        }
                    }
                });
            }
            if ui.button("Frame level").clicked() {
                state.frame_level();
            }
            if ui.add_enabled(state.selection.is_some(), egui::Button::new("Frame selected")).clicked() {
                state.frame_selected();
            }
        });
    }

    fn typed_path(&self) -> Option<PathBuf> {
        let t = self.path.trim();
        (!t.is_empty()).then(|| PathBuf::from(t))
    }
}
