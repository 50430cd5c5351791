//! The status bar: job progress with a cancel button, the latest message, and the log.

use egui::{Color32, RichText, Ui};

use crate::messages::{Message, Severity};
use crate::state::InspectorState;

fn color(severity: Severity) -> Color32 {
    match severity {
        Severity::Info => Color32::GRAY,
        Severity::Warning => Color32::from_rgb(240, 200, 80),
        Severity::Error => Color32::from_rgb(255, 110, 100),
    }
}

fn message_text(m: &Message) -> RichText {
    let prefix = match m.severity {
        Severity::Info => "",
        Severity::Warning => "warning: ",
        Severity::Error => "error: ",
    };
    RichText::new(format!("{prefix}{}", m.text)).color(color(m.severity))
}

/// Shows the bar; `log_open` toggles the message window.
pub fn show(ui: &mut Ui, state: &mut InspectorState, log_open: &mut bool) {
    ui.horizontal(|ui| {
        if let Some(job) = &state.job {
            let progress = job.progress;
            ui.add(egui::ProgressBar::new(progress.overall()).desired_width(220.0).text(format!(
                "{}: {}",
                job.description,
                progress.stage.name()
            )));
            if ui.button("Cancel").clicked() {
                state.cancel_job();
            }
        }
        let count = state.messages.entries().len();
        if ui.selectable_label(*log_open, format!("Messages ({count})")).clicked() {
            *log_open = !*log_open;
        }
        if state.is_dirty() {
            ui.label(RichText::new("unsaved changes").italics());
        }
        if let Some(m) = state.messages.latest() {
            ui.label(message_text(m));
        }
    });
}

/// The message window (all messages, newest last).
pub fn log_window(ctx: &egui::Context, state: &mut InspectorState, open: &mut bool) {
    let mut clear = false;
    egui::Window::new("Messages").open(open).default_size([560.0, 260.0]).show(ctx, |ui| {
        if ui.button("Clear").clicked() {
            clear = true;
        }
        egui::ScrollArea::vertical().stick_to_bottom(true).show(ui, |ui| {
            for m in state.messages.entries() {
                ui.label(message_text(m));
            }
        });
    });
    if clear {
        state.messages.clear();
    }
}
