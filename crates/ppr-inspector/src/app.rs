//! `InspectorApp`: the eframe application. Lays out the panels, routes dropped files and
//! shortcuts to the state, guards unsaved changes, and takes the `--screenshot` picture.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use egui::{Key, KeyboardShortcut, Modifiers, ViewportCommand};

use crate::error::InspectorError;
use crate::properties_panel::PropertiesPanel;
use crate::state::{InspectorState, PendingAction};
use crate::toolbar::Toolbar;
use crate::viewport::{Viewport, ViewportGpu};
use crate::{extraction_panel, preview_panel, reflector_list, status_bar};

/// What the command line asked for.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StartupOptions {
    /// A level to open.
    pub level: Option<PathBuf>,
    /// A saved set to load instead of extracting.
    pub set: Option<PathBuf>,
    /// Take a screenshot of the window once everything is loaded, write it here and quit.
    pub screenshot: Option<PathBuf>,
}

/// Where the window's picture arrives.
type ScreenshotSlot = Arc<Mutex<Option<Arc<egui::ColorImage>>>>;

/// The screenshot mode's progress.
enum Screenshot {
    /// Waiting for the level, the set and a preview.
    Waiting { path: PathBuf, frames: u32 },
    /// Asked the window for its picture.
    Requested { path: PathBuf, image: ScreenshotSlot },
}

/// The inspector application.
pub struct InspectorApp {
    /// Everything but the UI.
    pub state: InspectorState,
    /// The 3D viewport.
    pub viewport: Viewport,
    toolbar: Toolbar,
    properties: PropertiesPanel,
    log_open: bool,
    screenshot: Option<Screenshot>,
}

impl InspectorApp {
    /// The application for eframe (or egui_kittest): renders on the creation context's
    /// wgpu device, opens what `options` name.
    pub fn new(cc: &eframe::CreationContext<'_>, options: StartupOptions) -> Self {
        let ctx = cc.egui_ctx.clone();
        let state = InspectorState::new(Arc::new(move || ctx.request_repaint()));
        let gpu = cc.wgpu_render_state.as_ref().map(ViewportGpu::from_render_state);
        let mut app = Self::with_state(state, gpu);
        if app.viewport.adapter().is_none() {
            app.state
                .messages
                .error("no wgpu render state: the preview is unavailable (eframe runs without wgpu?)");
        }
        app.open(options);
        app
    }

    /// The application around `state`, rendering on `gpu`.
    pub fn with_state(state: InspectorState, gpu: Option<ViewportGpu>) -> Self {
        Self {
            state,
            viewport: Viewport::new(gpu),
            toolbar: Toolbar::default(),
            properties: PropertiesPanel::default(),
            log_open: false,
            screenshot: None,
        }
    }

    fn open(&mut self, options: StartupOptions) {
        match (&options.level, &options.set) {
            (Some(level), set) => {
                self.toolbar.path = level.display().to_string();
                self.state.open_level(level, set.as_deref());
            }
            (None, Some(set)) => self.state.open_set(set),
            (None, None) => {}
        }
        self.screenshot = options.screenshot.map(|path| Screenshot::Waiting { path, frames: 0 });
    }

    fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.clone());
        for file in dropped {
            let path = file.path().to_owned();
            self.toolbar.path = path.display().to_string();
            self.state.request(open_action(&path));
        }
    }

    fn shortcuts(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let pressed =
            |m: Modifiers, k: Key| ctx.input_mut(|i| i.consume_shortcut(&KeyboardShortcut::new(m, k)));
        if pressed(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z) || pressed(Modifiers::COMMAND, Key::Y) {
            self.state.redo();
        } else if pressed(Modifiers::COMMAND, Key::Z) {
            self.state.undo();
        }
        if pressed(Modifiers::COMMAND, Key::S) {
            let result = self.state.save();
            self.state.report(result);
        }
        if pressed(Modifiers::NONE, Key::F) {
            self.state.frame_selected();
        }
    }

    fn close_guard(&mut self, ctx: &egui::Context) {
        if ctx.input(|i| i.viewport().close_requested())
            && !self.state.quit_confirmed
            && self.state.is_dirty()
        {
            ctx.send_viewport_cmd(ViewportCommand::CancelClose);
            self.state.request(PendingAction::Quit);
        }
        if self.state.quit_confirmed {
            ctx.send_viewport_cmd(ViewportCommand::Close);
        }
    }

    fn unsaved_changes_dialog(&mut self, ctx: &egui::Context) {
        let Some(action) = self.state.pending.clone() else { return };
        let what = match &action {
            PendingAction::OpenLevel(p) => format!("open {}", p.display()),
            PendingAction::OpenSet(p) => format!("open {}", p.display()),
            PendingAction::Quit => "quit".to_owned(),
        };
        egui::Modal::new(egui::Id::unique("unsaved changes")).show(ctx, |ui| {
            ui.heading("Unsaved changes");
            ui.label(format!("The reflector set has changes that are not saved. {what} anyway?"));
            ui.horizontal(|ui| {
                if ui.button("Save first").clicked() {
                    let result = self.state.save();
                    if self.state.report(result).is_some() {
                        self.state.confirm_pending();
                    }
                }
                if ui.button("Discard changes").clicked() {
                    self.state.confirm_pending();
                }
                if ui.button("Cancel").clicked() {
                    self.state.cancel_pending();
                }
            });
        });
    }

    fn screenshot_step(&mut self, ctx: &egui::Context) {
        let Some(shot) = self.screenshot.take() else { return };
        self.screenshot = match shot {
            Screenshot::Waiting { path, frames } => {
                // Ready once nothing loads any more and the preview shows (or cannot show:
                // then the picture shows the error).
                let loaded = self.state.level.as_ref().is_some_and(|l| l.render.is_some());
                let ready = self.state.job.is_none() && (self.viewport.has_frame() || !loaded);
                if ready && self.state.selection.is_none() {
                    let first = self.state.set().and_then(|s| s.reflectors.first()).map(|r| r.id);
                    self.state.select(first);
                }
                if ready && frames >= 3 {
                    let image: ScreenshotSlot = Arc::new(Mutex::new(None));
                    let slot = image.clone();
                    let repaint = ctx.clone();
                    ctx.send_viewport_cmd(ViewportCommand::Screenshot(egui::ScreenshotCallback::new(
                        move |img| {
                            if let Ok(mut s) = slot.lock() {
                                *s = Some(img);
                            }
                            repaint.request_repaint();
                        },
                    )));
                    Some(Screenshot::Requested { path, image })
                } else {
                    Some(Screenshot::Waiting { path, frames: if ready { frames + 1 } else { 0 } })
                }
            }
            Screenshot::Requested { path, image } => {
                let taken = image.lock().ok().and_then(|mut s| s.take());
                match taken {
                    Some(img) => {
                        let result = write_png(&path, &img);
                        if self.state.report(result).is_some() {
                            self.state.messages.info(format!("screenshot written to {}", path.display()));
                        }
                        // The extracted set is not saved on purpose: close without asking.
                        self.state.quit_confirmed = true;
                        ctx.send_viewport_cmd(ViewportCommand::Close);
                        ctx.request_repaint();
                        None
                    }
                    None => Some(Screenshot::Requested { path, image }),
                }
            }
        };
        if self.screenshot.is_some() {
            ctx.request_repaint();
        }
    }

    /// Lays out every panel in `ui` (the whole window).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar.show(ui, &mut self.state));
        egui::Panel::bottom("status")
            .show(ui, |ui| status_bar::show(ui, &mut self.state, &mut self.log_open));
        egui::Panel::left("reflectors").resizable(true).default_size(300.0).show(ui, |ui| {
            ui.heading("Reflectors");
            reflector_list::show(ui, &mut self.state);
        });
        egui::Panel::right("inspector").resizable(true).default_size(310.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                egui::CollapsingHeader::new("Selected reflector")
                    .default_open(true)
                    .show(ui, |ui| self.properties.show(ui, &mut self.state));
                egui::CollapsingHeader::new("Preview").default_open(true).show(ui, |ui| {
                    preview_panel::show(
                        ui,
                        &mut self.state,
                        self.viewport.frame.as_ref(),
                        self.viewport.adapter(),
                    );
                });
                egui::CollapsingHeader::new("Extraction")
                    .default_open(false)
                    .show(ui, |ui| extraction_panel::show(ui, &mut self.state));
            });
        });
        egui::CentralPanel::default().show(ui, |ui| self.viewport.show(ui, &mut self.state));
        status_bar::log_window(&ctx, &mut self.state, &mut self.log_open);
        self.unsaved_changes_dialog(&ctx);
        if ctx.input(|i| !i.raw.hovered_files.is_empty()) {
            let painter = ctx
                .layer_painter(egui::LayerId::new(egui::Order::Foreground, egui::Id::unique("drop overlay")));
            let rect = ctx.content_rect();
            painter.rect_filled(rect, 0.0, egui::Color32::from_black_alpha(160));
            painter.text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "Drop a level (.glb, .gltf) or a set (.ppr.json)",
                egui::FontId::proportional(22.0),
                egui::Color32::WHITE,
            );
        }
    }

    /// One frame's logic: the background job, dropped files, shortcuts, closing.
    pub fn step(&mut self, ctx: &egui::Context) {
        self.state.poll_job();
        self.dropped_files(ctx);
        self.shortcuts(ctx);
        self.close_guard(ctx);
        self.screenshot_step(ctx);
    }
}

/// Opening a dropped or typed file: a set for `.json`, a level otherwise.
pub fn open_action(path: &Path) -> PendingAction {
    let is_set = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_set { PendingAction::OpenSet(path.to_owned()) } else { PendingAction::OpenLevel(path.to_owned()) }
}

fn write_png(path: &Path, image: &egui::ColorImage) -> Result<(), InspectorError> {
    let [w, h] = image.size;
    let fail = |reason: String| InspectorError::Image { path: path.to_owned(), reason };
    let rgba: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_srgba_unmultiplied()).collect();
    let buffer =
        image::RgbaImage::from_raw(w as u32, h as u32, rgba).ok_or_else(|| fail("bad size".into()))?;
    buffer.save(path).map_err(|e| fail(e.to_string()))
}

impl eframe::App for InspectorApp {
    fn logic(&mut self, ctx: &egui::Context, _frame: &mut eframe::Frame) {
        self.step(ctx);
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}
