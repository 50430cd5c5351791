//! The reflector list: one row per reflector (name, kind, area, coverage, occluders),
//! sortable by clicking a header, selecting by clicking a name.

use egui::{Color32, RichText, ScrollArea};

use crate::overlay_geometry::{coverage_color, kind_color};
use crate::reflector_table::SortColumn;
use crate::state::InspectorState;

/// Shows the list; clicking a name selects that reflector.
pub fn show(ui: &mut egui::Ui, state: &mut InspectorState) {
    let Some(set) = state.set() else {
        ui.label("No reflectors yet: open a level (it is extracted) or a set.");
        return;
    };
    let rows = state.sort.rows(set);
    let count = set.reflectors.len();
    let total_area: f64 = set.reflectors.iter().map(|r| r.area()).sum();
    ui.label(format!("{count} reflectors, {total_area:.2} m²"));
    let mut clicked_header = None;
    let mut clicked_row = None;
    ScrollArea::both().auto_shrink([false, false]).show(ui, |ui| {
        egui::Grid::new("reflector list").striped(true).num_columns(SortColumn::ALL.len()).show(ui, |ui| {
            for column in SortColumn::ALL {
                let arrow = match (state.sort.column == column, state.sort.descending) {
                    (true, false) => " ^",
                    (true, true) => " v",
                    _ => "",
                };
                let header = ui
                    .add(
                        egui::Button::new(RichText::new(format!("{}{arrow}", column.title())).strong())
                            .frame(false),
                    )
                    .on_hover_text(format!("sort by {}", column.title()));
                if header.clicked() {
                    clicked_header = Some(column);
                }
            }
            ui.end_row();
            for index in rows {
                let r = &set.reflectors[index];
                let selected = state.selection == Some(r.id);
                let dim = |text: String| {
                    if r.enabled {
                        RichText::new(text)
                    } else {
                        RichText::new(text).color(Color32::GRAY).italics()
                    }
                };
                ui.label(dim(index.to_string()));
                if ui.selectable_label(selected, dim(r.name.clone())).clicked() {
                    clicked_row = Some(r.id);
                }
                ui.colored_label(kind_color(r.kind), r.kind.as_str());
                ui.label(dim(format!("{:.3}", r.area())));
                ui.colored_label(coverage_color(r.coverage), format!("{:.1}%", 100.0 * r.coverage));
                ui.label(dim(r.occluders.len().to_string()));
                ui.end_row();
            }
        });
    });
    if let Some(column) = clicked_header {
        state.sort.click(column);
    }
    if let Some(id) = clicked_row {
        state.select(Some(id));
    }
}
