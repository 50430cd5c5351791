//! The 3D viewport: the level rendered by the testbed with the PPR preview (or the
//! reference, or the difference), the rectangles overlaid with egui's painter, picking by
//! clicking, camera control, and the selected rectangle's handles.

use egui::{Color32, PointerButton, Pos2, Rect, Sense, Shape, Stroke, TextureOptions, Vec2 as EVec2};
use glam::{DVec2, DVec3, Vec2};
use ppr_format::{Reflector, ReflectorSet};

use crate::camera_control::{CameraMode, CameraRig};
use crate::commands::EditCommand;
use crate::overlay_geometry::{project_polygon, reflector_color};
use crate::picking::pick;
use crate::preview::PreviewSettings;
use crate::state::InspectorState;
use crate::viewport_handles::{Handle, dragged_placement, handle_positions, plane_hit};
use crate::viewport_renderer::{PreviewFrame, ViewportRenderer};

/// Screen distance within which a press grabs a handle, points.
const HANDLE_GRAB_RADIUS: f32 = 9.0;
/// Stroke of the selected rectangle.
const SELECTED: Color32 = Color32::WHITE;
/// Stroke of the selected rectangle's occluders.
const OCCLUDER: Color32 = Color32::from_rgb(255, 150, 40);
/// Stroke of the selected rectangle's parallel group.
const PARALLEL: Color32 = Color32::from_rgb(200, 120, 255);

/// The GPU the viewport renders on.
#[derive(Clone)]
pub struct ViewportGpu {
    /// Device (eframe's, so the runtime and the testbed share egui's wgpu).
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name and backend, for the UI.
    pub adapter: String,
}

impl ViewportGpu {
    /// The device of eframe's wgpu render state.
    pub fn from_render_state(rs: &eframe::egui_wgpu::RenderState) -> Self {
        let info = rs.adapter.get_info();
        Self {
            device: rs.device.clone(),
            queue: rs.queue.clone(),
            adapter: format!("{} ({:?})", info.name, info.backend),
        }
    }
}

#[derive(Clone, Copy, PartialEq)]
struct RenderKey {
    level_generation: u64,
    revision: u64,
    camera: CameraRig,
    size: [u32; 2],
    preview: PreviewSettings,
}

struct HandleDrag {
    handle: Handle,
    start: Reflector,
    grab: DVec2,
    gesture: u64,
}

/// The viewport and what it keeps between frames.
pub struct Viewport {
    gpu: Option<ViewportGpu>,
    renderer: Option<ViewportRenderer>,
    renderer_generation: u64,
    uploaded_revision: u64,
    texture: Option<egui::TextureHandle>,
    rendered: Option<RenderKey>,
    /// The last rendered frame (plan, timings, quality).
    pub frame: Option<PreviewFrame>,
    failed: Option<RenderKey>,
    /// (level generation, revision) for which the GPU side could not be built: not retried.
    failed_build: Option<(u64, u64)>,
    drag: Option<HandleDrag>,
}

impl Viewport {
    /// A viewport rendering on `gpu` (none: the preview is unavailable, the overlay works).
    pub fn new(gpu: Option<ViewportGpu>) -> Self {
        Self {
            gpu,
            renderer: None,
            renderer_generation: 0,
            uploaded_revision: 0,
            texture: None,
            rendered: None,
            frame: None,
            failed: None,
            failed_build: None,
            drag: None,
        }
    }

    /// The adapter's description, when there is a GPU.
    pub fn adapter(&self) -> Option<&str> {
        self.gpu.as_ref().map(|g| g.adapter.as_str())
    }

    /// Whether a preview image was rendered.
    pub fn has_frame(&self) -> bool {
        self.frame.is_some()
    }

    /// Shows the viewport in all of `ui`'s remaining space.
    pub fn show(&mut self, ui: &mut egui::Ui, state: &mut InspectorState) {
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, "3D viewport"));
        let size = Vec2::new(rect.width().max(1.0), rect.height().max(1.0));
        self.steer(ui, state, &response, rect, size);
        // While the view or a handle is dragged, at most half resolution keeps slow adapters responsive.
        let scale =
            if response.dragged() { state.preview.resolution.min(0.5) } else { state.preview.resolution };
        let ppp = ui.ctx().pixels_per_point() * scale.clamp(0.1, 1.0);
        let pixels = [(size.x * ppp).round().max(1.0) as u32, (size.y * ppp).round().max(1.0) as u32];
        self.render_if_needed(ui.ctx(), state, pixels);

        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, Color32::from_rgb(13, 18, 28));
        match (&self.texture, &state.level) {
            (Some(t), Some(_)) => {
                let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
                painter.image(t.id(), rect, uv, Color32::WHITE);
            }
            (_, level) => {
                let text = match level {
                    None => "Open a level: type its path above, or drop a .glb / .gltf / .ppr.json here",
                    Some(l) if l.render.is_none() => "Loading the level…",
                    Some(_) => "No preview (see the messages)",
                };
                painter.text(
                    rect.center(),
                    egui::Align2::CENTER_CENTER,
                    text,
                    egui::FontId::proportional(16.0),
                    Color32::GRAY,
                );
            }
        }
        if let Some(set) = state.set()
            && state.preview.overlay
        {
            draw_overlay(&painter, rect, size, state, set);
        }
        if let Some(r) = state.selected() {
            draw_handles(&painter, rect, size, &state.camera, r, self.drag.as_ref().map(|d| d.handle));
        }
    }

    /// Camera control, picking and handle drags.
    fn steer(
        &mut self,
        ui: &egui::Ui,
        state: &mut InspectorState,
        response: &egui::Response,
        rect: Rect,
        size: Vec2,
    ) {
        let local = |p: Pos2| Vec2::new(p.x - rect.min.x, p.y - rect.min.y);
        let pointer = response.interact_pointer_pos().or(response.hover_pos()).map(local);

        if response.drag_started_by(PointerButton::Primary)
            && let Some(origin) = ui.input(|i| i.pointer.press_origin()).map(local)
        {
            self.drag = self.grab_handle(state, origin, size);
        }
        if response.dragged_by(PointerButton::Primary) {
            match (&self.drag, pointer) {
                (Some(drag), Some(p)) => {
                    let (o, d) = state.camera.ray(p, size);
                    if let Some(now) = plane_hit(&drag.start, o, d) {
                        let placement = dragged_placement(&drag.start, drag.handle, drag.grab, now);
                        let command = EditCommand::Place { id: drag.start.id, placement };
                        state.apply_in_gesture(command, Some(drag.gesture));
                    }
                }
                _ => state.camera.rotate(to_vec2(response.drag_delta())),
            }
        }
        if response.dragged_by(PointerButton::Secondary) || response.dragged_by(PointerButton::Middle) {
            state.camera.pan(to_vec2(response.drag_delta()), size.y);
        }
        if response.drag_stopped() {
            self.drag = None;
        }
        if response.clicked()
            && let (Some(p), Some(set)) = (pointer, state.set())
        {
            let (o, d) = state.camera.ray(p, size);
            let hit = pick(set, o, d);
            state.select(hit);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                state.camera.zoom(scroll);
            }
        }
        if state.camera.mode == CameraMode::Fly && response.hovered() && !ui.ctx().egui_wants_keyboard_input()
        {
            let (dir, dt) = ui.input(|i| {
                let axis = |plus: egui::Key, minus: egui::Key| {
                    f64::from(u8::from(i.key_down(plus))) - f64::from(u8::from(i.key_down(minus)))
                };
                let dir = DVec3::new(
                    axis(egui::Key::D, egui::Key::A),
                    axis(egui::Key::E, egui::Key::Q),
                    axis(egui::Key::W, egui::Key::S),
                );
                (dir, f64::from(i.stable_dt.min(0.1)))
            });
            if dir != DVec3::ZERO {
                state.camera.fly(dir, dt);
                ui.ctx().request_repaint();
            }
        }
    }

    fn grab_handle(&self, state: &mut InspectorState, origin: Vec2, size: Vec2) -> Option<HandleDrag> {
        let r = state.selected()?.clone();
        let (handle, _) = handle_positions(&r)
            .into_iter()
            .filter_map(|(h, p)| state.camera.project(p, size).map(|s| (h, s.distance(origin))))
            .filter(|(_, d)| *d <= HANDLE_GRAB_RADIUS)
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let (o, d) = state.camera.ray(origin, size);
        let grab = plane_hit(&r, o, d)?;
        Some(HandleDrag { handle, start: r, grab, gesture: state.new_gesture() })
    }

    fn render_if_needed(&mut self, ctx: &egui::Context, state: &mut InspectorState, pixels: [u32; 2]) {
        let Some(level) = state.level.as_ref() else { return };
        let Some(render_level) = level.render.clone() else { return };
        let Some(gpu) = self.gpu.clone() else { return };
        let empty = ReflectorSet::new(level.path.display().to_string());
        let set = state.set().unwrap_or(&empty);
        let build = (state.level_generation, state.revision());
        if self.renderer.is_none() || self.renderer_generation != state.level_generation {
            if self.failed_build == Some(build) {
                return;
            }
            self.renderer = None;
            self.texture = None;
            self.frame = None;
            match ViewportRenderer::new(&gpu.device, &gpu.queue, &render_level, &level.path, set) {
                Ok(r) => self.renderer = Some(r),
                Err(e) => {
                    state.messages.error(format!("preview: {e}"));
                    self.failed_build = Some(build);
                }
            }
            self.renderer_generation = state.level_generation;
            self.uploaded_revision = state.revision();
        }
        let Some(renderer) = self.renderer.as_mut() else { return };
        let set = state.set().unwrap_or(&empty);
        if self.uploaded_revision != state.revision() {
            let uploaded = renderer.set_reflectors(set);
            self.uploaded_revision = state.revision();
            if let Err(e) = uploaded {
                state.messages.error(format!("preview: {e}"));
                self.failed_build = Some(build);
                self.renderer = None;
                self.texture = None;
                self.frame = None;
                return;
            }
        }
        let mut preview = state.preview;
        preview.overlay = false;
        preview.color_by = Default::default();
        let key = RenderKey {
            level_generation: state.level_generation,
            revision: state.revision(),
            camera: state.camera,
            size: pixels,
            preview,
        };
        if self.rendered == Some(key) || self.failed == Some(key) {
            return;
        }
        match renderer.render(&state.camera.camera(), pixels, &state.preview) {
            Ok(frame) => {
                match &mut self.texture {
                    Some(t) => t.set(frame.image.clone(), TextureOptions::LINEAR),
                    None => {
                        self.texture =
                            Some(ctx.load_texture("viewport", frame.image.clone(), TextureOptions::LINEAR));
                    }
                }
                self.frame = Some(frame);
                self.rendered = Some(key);
                self.failed = None;
            }
            Err(e) => {
                state.messages.error(format!("preview: {e}"));
                self.failed = Some(key);
            }
        }
    }
}

fn to_vec2(v: EVec2) -> Vec2 {
    Vec2::new(v.x, v.y)
}

fn to_pos(rect: Rect, p: Vec2) -> Pos2 {
    Pos2::new(rect.min.x + p.x, rect.min.y + p.y)
}

fn draw_overlay(painter: &egui::Painter, rect: Rect, size: Vec2, state: &InspectorState, set: &ReflectorSet) {
    let selected = state.selected();
    for (index, r) in set.reflectors.iter().enumerate() {
        let poly: Vec<Pos2> =
            project_polygon(&state.camera, &r.corners(), size).into_iter().map(|p| to_pos(rect, p)).collect();
        if poly.len() < 3 {
            continue;
        }
        let base = reflector_color(r, state.preview.color_by);
        let is_selected = selected.is_some_and(|s| s.id == r.id);
        let is_occluder = selected.is_some_and(|s| s.occluders.contains(&(index as u32)));
        let in_group = selected.is_some_and(|s| s.parallel_group == r.parallel_group && s.id != r.id);
        let (stroke_color, width) = if is_selected {
            (SELECTED, 2.5)
        } else if is_occluder {
            (OCCLUDER, 2.0)
        } else if in_group {
            (PARALLEL, 1.5)
        } else {
            (base, 1.2)
        };
        let fill = if r.enabled {
            base.gamma_multiply(if is_selected { 0.30 } else { 0.16 })
        } else {
            Color32::TRANSPARENT
        };
        painter.add(Shape::convex_polygon(poly.clone(), fill, Stroke::NONE));
        let mut outline = poly;
        outline.push(outline[0]);
        let stroke = Stroke::new(width, stroke_color);
        if r.enabled {
            painter.add(Shape::line(outline, stroke));
        } else {
            painter.extend(Shape::dashed_line(&outline, stroke, 6.0, 4.0));
        }
    }
    if selected.is_some() {
        let legend = [(SELECTED, "selected"), (OCCLUDER, "its occluders"), (PARALLEL, "its parallel group")];
        let mut at = rect.min + EVec2::new(8.0, 8.0);
        for (color, text) in legend {
            painter.text(at, egui::Align2::LEFT_TOP, text, egui::FontId::proportional(12.0), color);
            at.y += 15.0;
        }
    }
}

fn draw_handles(
    painter: &egui::Painter,
    rect: Rect,
    size: Vec2,
    camera: &CameraRig,
    r: &Reflector,
    active: Option<Handle>,
) {
    for (handle, world) in handle_positions(r) {
        let Some(p) = camera.project(world, size) else { continue };
        let p = to_pos(rect, p);
        let radius = if Some(handle) == active { 6.0 } else { 4.5 };
        let fill = match handle {
            Handle::Center => Color32::from_rgb(255, 255, 255),
            Handle::Rotate => Color32::from_rgb(120, 220, 120),
            _ => Color32::from_rgb(255, 220, 90),
        };
        if handle == Handle::Rotate
            && let Some(c) = camera.project(r.center, size)
        {
            painter.line_segment([to_pos(rect, c), p], Stroke::new(1.0, fill));
        }
        painter.circle(p, radius, fill, Stroke::new(1.0, Color32::BLACK));
    }
}
