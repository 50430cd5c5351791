//! The application driven through egui_kittest on wgpu's software adapter (llvmpipe here):
//! open the demo level, select a reflector, edit it, undo, redo, save, reload, compare.
//! Snapshots are in `tests/snapshots/inspector/`; regenerate them with `UPDATE_SNAPSHOTS=1`.
//! Without an adapter the harness panics: the test fails, it never skips.

use std::time::Duration;

use egui_kittest::kittest::Queryable as _;
use egui_kittest::wgpu::WgpuTestRenderer;
use egui_kittest::{Harness, SnapshotResults};
use ppr_format::{ReflectorKind, ReflectorSet};
use ppr_inspector::gpu_setup::with_inspector_device;
use ppr_inspector::viewport::ViewportGpu;
use ppr_inspector::{InspectorApp, InspectorState};

/// Window size of the snapshots, points.
const SIZE: egui::Vec2 = egui::Vec2::new(1000.0, 620.0);

/// The demo level, relative to the crate (tests run there), so snapshots show one path.
const DEMO_LEVEL: &str = "../../assets/demo_room.glb";

/// The app on a harness whose wgpu renderer and the app's viewport share one device, as
/// eframe gives them one (the inspector's device descriptor, the software adapter first).
fn harness() -> Harness<'static, InspectorApp> {
    let setup = with_inspector_device(egui_kittest::wgpu::default_wgpu_setup());
    let render_state =
        egui_kittest::wgpu::create_render_state(setup, eframe::egui_wgpu::RendererOptions::PREDICTABLE);
    let app = InspectorApp::with_state(
        InspectorState::default(),
        Some(ViewportGpu::from_render_state(&render_state)),
    );
    Harness::builder()
        .with_size(SIZE)
        .with_max_steps(20)
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .build_ui_state(
            |ui, app: &mut InspectorApp| {
                let ctx = ui.ctx().clone();
                app.step(&ctx);
                app.show(ui);
            },
            app,
        )
}

/// Takes a snapshot with `masks` and the GPU times (they vary from frame to frame) masked.
fn snapshot(
    harness: &mut Harness<'_, InspectorApp>,
    results: &mut SnapshotResults,
    name: &str,
    masks: &[egui::Rect],
) {
    let mut rects: Vec<egui::Rect> = harness
        .query_all_by_label_contains(" ms")
        .map(|n| {
            let r = n.rect();
            egui::Rect::from_min_max(r.min, egui::pos2(SIZE.x, r.max.y))
        })
        .collect();
    rects.extend_from_slice(masks);
    for r in rects {
        harness.mask(r);
    }
    results.add(harness.try_snapshot(name));
}

fn wait_for_extraction(harness: &mut Harness<'_, InspectorApp>) {
    assert!(harness.state_mut().state.wait_for_job(Duration::from_secs(120)), "extraction finished in time");
    harness.run();
}

/// Types the demo level's path (relative to the crate: the same on every machine), opens it
/// and waits for its extraction.
fn open_demo_level(harness: &mut Harness<'_, InspectorApp>) {
    harness.get_by_label("Path").set_text_value_accesskit(DEMO_LEVEL);
    harness.run();
    harness.get_by_label("Open level").click();
    harness.run_ok();
    wait_for_extraction(harness);
}

fn selected(harness: &Harness<'_, InspectorApp>) -> ppr_format::Reflector {
    harness.state().state.selected().cloned().expect("a reflector is selected")
}

#[test]
fn open_select_edit_undo_redo_save_reload() {
    let mut snapshots = SnapshotResults::new();
    let mut harness = harness();
    assert!(harness.state().viewport.adapter().is_some(), "the app renders on the harness's wgpu device");

    open_demo_level(&mut harness);
    assert_eq!(harness.state().state.set().map(|s| s.reflectors.len()), Some(16));
    assert!(harness.state().viewport.has_frame(), "a preview was rendered");
    snapshot(&mut harness, &mut snapshots, "inspector/opened", &[]);

    // Select the mirror in the list.
    harness.get_by_label("mirror on mirror_wall").click();
    harness.run();
    let mirror = selected(&harness);
    assert_eq!(mirror.name, "mirror on mirror_wall");
    snapshot(&mut harness, &mut snapshots, "inspector/selected", &[]);

    // Edit name, kind and extent.
    harness.get_by_label("Reflector name").set_text_value_accesskit("hero mirror");
    harness.run();
    harness.get_by_label("Water").click();
    harness.run();
    harness.get_by_label("Half width").set_value_accesskit(2.25);
    harness.run();
    let edited = selected(&harness);
    assert_eq!(edited.id, mirror.id);
    assert_eq!(edited.name, "hero mirror");
    assert_eq!(edited.kind, ReflectorKind::Water);
    assert!((edited.half_extents.x - 2.25).abs() < 1e-9, "{:?}", edited.half_extents);
    assert!((edited.half_extents.y - mirror.half_extents.y).abs() < 1e-12);
    snapshot(&mut harness, &mut snapshots, "inspector/edited", &[]);

    // Undo the extent, then the kind; redo both.
    harness.get_by_label("Undo").click();
    harness.run();
    assert!((selected(&harness).half_extents.x - mirror.half_extents.x).abs() < 1e-12);
    harness.get_by_label("Undo").click();
    harness.run();
    assert_eq!(selected(&harness).kind, mirror.kind);
    assert_eq!(selected(&harness).name, "hero mirror");
    harness.get_by_label("Redo").click();
    harness.run();
    harness.get_by_label("Redo").click();
    harness.run();
    assert_eq!(selected(&harness), edited);

    // A refused edit shows an error and changes nothing.
    harness.get_by_label("Half height").set_value_accesskit(-1.0);
    harness.run();
    assert_eq!(selected(&harness), edited);
    let error = harness.state().state.messages.latest_error().map(|m| m.text.clone()).unwrap_or_default();
    assert!(error.contains("half_extents"), "{error}");

    // Save to a temporary directory, reload, compare.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("demo_room.ppr.json");
    harness.get_by_label("Path").set_text_value_accesskit(&path.display().to_string());
    harness.run();
    harness.get_by_label("Save as").click();
    harness.run();
    assert!(!harness.state().state.is_dirty());
    let saved = ReflectorSet::load(&path).expect("the saved file loads");
    let text = std::fs::read_to_string(&path).expect("read");
    let in_memory = harness.state().state.set().map(|s| s.to_json_string().expect("valid"));
    assert_eq!(in_memory, Some(text), "the file holds the edited set");
    assert_eq!(saved.by_id(mirror.id).map(|r| r.name.as_str()), Some("hero mirror"));

    harness.get_by_label("Open set").click();
    harness.run();
    assert_eq!(harness.state().state.set_path.as_deref(), Some(path.as_path()));
    assert_eq!(harness.state().state.set(), Some(&saved), "reloaded equals saved");
    harness.get_by_label("hero mirror").click();
    harness.get_by_label("Path").set_text_value_accesskit("demo_room.ppr.json");
    harness.run();
    assert_eq!(selected(&harness).id, mirror.id);
    // The temporary directory's name is in the status line: mask it.
    let status = harness.get_by_label_contains("loaded 16 reflectors from").rect();
    let status = egui::Rect::from_min_max(status.min, egui::pos2(SIZE.x, status.max.y));
    snapshot(&mut harness, &mut snapshots, "inspector/reloaded", &[status]);
    snapshots.unwrap();
}

#[test]
fn unsaved_changes_guard_asks_before_opening() {
    let mut harness = harness();
    open_demo_level(&mut harness);
    // A fresh extraction is unsaved: opening again asks.
    harness.get_by_label("Open level").click();
    harness.run();
    assert!(harness.state().state.pending.is_some());
    harness.get_by_label("Cancel").click();
    harness.run();
    assert!(harness.state().state.pending.is_none());
    assert!(harness.state().state.job.is_none(), "nothing was opened");
    harness.get_by_label("Open level").click();
    harness.run();
    harness.get_by_label("Discard changes").click();
    harness.run_ok();
    assert!(harness.state().state.job.is_some() || harness.state().state.doc.is_some());
    wait_for_extraction(&mut harness);
    assert_eq!(harness.state().state.set().map(|s| s.reflectors.len()), Some(16));
}

/// A file dropped on the window (what eframe hands the app).
#[derive(Debug)]
struct DroppedPath(std::path::PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &std::path::Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn dropping_a_level_then_a_set_opens_them() {
    let mut harness = harness();
    harness.input_mut().dropped_files.push(std::sync::Arc::new(DroppedPath(DEMO_LEVEL.into())));
    harness.step();
    wait_for_extraction(&mut harness);
    assert_eq!(harness.state().state.set().map(|s| s.reflectors.len()), Some(16));

    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("dropped.ppr.json");
    let state = &mut harness.state_mut().state;
    state.save_as(&path).expect("saved");
    let first = state.set().and_then(|s| s.reflectors.first()).map(|r| r.id).expect("a reflector");
    assert!(state.apply(ppr_inspector::commands::EditCommand::SetEnabled { id: first, enabled: false }));

    // Dropping the set with unsaved changes asks first.
    harness.input_mut().dropped_files.push(std::sync::Arc::new(DroppedPath(path.clone())));
    harness.run();
    assert!(harness.state().state.pending.is_some());
    harness.get_by_label("Discard changes").click();
    harness.run();
    assert_eq!(harness.state().state.set_path.as_deref(), Some(path.as_path()));
    assert_eq!(harness.state().state.set(), Some(&ReflectorSet::load(&path).expect("loads")));
    assert!(!harness.state().state.is_dirty());
}

#[test]
fn clicking_in_the_viewport_selects_and_a_corner_drag_resizes() {
    let mut harness = harness();
    harness.state_mut().state.open_level(std::path::Path::new(DEMO_LEVEL), None);
    wait_for_extraction(&mut harness);
    let viewport = harness.get_by_label("3D viewport").rect();
    let size = glam::Vec2::new(viewport.width(), viewport.height());
    let screen = |harness: &Harness<'_, InspectorApp>, world: glam::DVec3| {
        let p = harness.state().state.camera.project(world, size).expect("in front of the camera");
        egui::pos2(viewport.min.x + p.x, viewport.min.y + p.y)
    };
    let glass = harness
        .state()
        .state
        .set()
        .and_then(|s| s.reflectors.iter().find(|r| r.name == "glass on glass_panel"))
        .cloned()
        .expect("the glass panel");

    // Click on the glass panel (in front of the mirror wall): it is picked.
    let at = screen(&harness, glass.center + glass.axis_u * 0.3);
    harness.hover_at(at);
    harness.drag_at(at);
    harness.drop_at(at);
    harness.run();
    assert_eq!(harness.state().state.selection, Some(glass.id), "the click picked the glass panel");

    // Drag its (+u, +v) corner handle outwards: that corner follows, the opposite one stays.
    let (u, v, h) = (glass.axis_u, glass.axis_v, glass.half_extents);
    let from = screen(&harness, glass.center + u * h.x + v * h.y);
    let to = screen(&harness, glass.center + u * (h.x + 0.5) + v * (h.y + 0.3));
    harness.hover_at(from);
    harness.drag_at(from);
    harness.step();
    for k in 1..=4 {
        harness.hover_at(from + (to - from) * (k as f32 / 4.0));
        harness.step();
    }
    harness.drop_at(to);
    harness.run();
    let resized = selected(&harness);
    assert!((resized.half_extents.x - (h.x + 0.25)).abs() < 0.03, "{:?}", resized.half_extents);
    assert!((resized.half_extents.y - (h.y + 0.15)).abs() < 0.03, "{:?}", resized.half_extents);
    let fixed =
        |r: &ppr_format::Reflector| r.center - r.axis_u * r.half_extents.x - r.axis_v * r.half_extents.y;
    assert!((fixed(&resized) - fixed(&glass)).length() < 1e-6, "the opposite corner stays");
    assert_eq!(harness.state().state.history.undo_len(), 1, "one drag is one undo step");
    harness.get_by_label("Undo").click();
    harness.run();
    assert_eq!(selected(&harness), glass);
}

#[test]
fn every_preview_mode_renders() {
    let mut harness = harness();
    harness.state_mut().state.open_level(std::path::Path::new(DEMO_LEVEL), None);
    wait_for_extraction(&mut harness);
    harness.get_by_label("Quarter").click();
    harness.run();
    for mode in ["Scene", "Reference", "Difference", "PPR"] {
        harness.get_by_label(mode).click();
        harness.run();
        let frame = harness.state().viewport.frame.clone().expect("a frame");
        assert_eq!(frame.quality.is_some(), mode == "Difference", "{mode}");
        assert!(frame.plan.contains("visible"), "{mode}: {}", frame.plan);
        assert!(frame.image.size[0] > 10 && frame.image.size[1] > 10);
    }
    let quality = {
        harness.get_by_label("Difference").click();
        harness.run();
        harness.state().viewport.frame.clone().and_then(|f| f.quality).expect("quality")
    };
    assert!(quality.comparison.pixels > 0 && quality.comparison.psnr_db > 10.0, "{:?}", quality);
    // Toggles re-render without errors.
    harness.get_by_label("Holes").click();
    harness.run();
    harness.get_by_label("Filtering").click();
    harness.run();
    assert!(
        !harness.state().state.preview.reflection.holes
            && !harness.state().state.preview.reflection.filtering
    );
    assert!(harness.state().state.messages.latest_error().is_none());
}

#[test]
fn reextract_from_the_panel_keeps_a_rename() {
    let mut harness = harness();
    harness.state_mut().state.open_level(std::path::Path::new(DEMO_LEVEL), None);
    wait_for_extraction(&mut harness);
    harness.get_by_label("water on water_surface").click();
    harness.run();
    let water = selected(&harness).id;
    harness.get_by_label("Reflector name").set_text_value_accesskit("pond");
    harness.run();
    // Make room in the right panel: fold the other sections, open Extraction.
    for section in ["Preview", "Selected reflector", "Extraction"] {
        harness.get_by_label(section).click();
        harness.run();
    }
    harness.get_by_label("no_split").click();
    harness.run();
    harness.get_by_label("Re-extract").click();
    harness.run_ok();
    wait_for_extraction(&mut harness);
    let state = &harness.state().state;
    let set = state.set().expect("set");
    assert_eq!(set.reflectors.len(), 15, "without splits the floor is one rectangle");
    assert_eq!(set.by_id(water).map(|r| r.name.as_str()), Some("pond"), "the rename was kept");
    assert_eq!(state.selection, Some(water));
    assert_eq!(state.history.undo_len(), 2, "rename, re-extract");
}

#[test]
fn the_panel_shows_and_edits_the_roughness() {
    let mut snapshots = SnapshotResults::new();
    let mut harness = harness();
    harness.state_mut().state.open_level(std::path::Path::new(DEMO_LEVEL), None);
    wait_for_extraction(&mut harness);
    harness.get_by_label("mirror on mirror_wall").click();
    harness.run();
    let mirror = selected(&harness);
    // The extractor took the demo mirror's roughness from its material (factor 0.02).
    assert_eq!(mirror.roughness, f64::from(0.02f32));
    assert!(harness.query_by_label("Roughness").is_some(), "a roughness field in the panel");

    harness.get_by_label("Roughness").set_value_accesskit(0.35);
    harness.run();
    let rough = selected(&harness);
    assert_eq!((rough.id, rough.roughness), (mirror.id, 0.35));
    assert!(harness.state().state.is_dirty());
    let recorded = harness.state().state.doc.as_ref().is_some_and(|d| d.edits.edited.contains(&mirror.id));
    assert!(recorded, "recorded in the edits, so that a re-extraction keeps it");
    snapshot(&mut harness, &mut snapshots, "inspector/roughness", &[]);

    // Out of range is clamped by the field. Both values were set in one interaction with
    // the field (it kept the focus): one undo step gives the mirror back, redo the edit.
    harness.get_by_label("Roughness").set_value_accesskit(3.0);
    harness.run();
    assert_eq!(selected(&harness).roughness, 1.0);
    assert_eq!(harness.state().state.history.undo_len(), 1);
    harness.get_by_label("Undo").click();
    harness.run();
    assert_eq!(selected(&harness), mirror);
    harness.get_by_label("Redo").click();
    harness.run();
    assert_eq!(selected(&harness).roughness, 1.0);
    snapshots.unwrap();
}

/// The properties panel names the selection's path blocker as the runtime finds it: on the
/// demo's flight of steps, the step in front of it; none for the wall mirror.
#[test]
fn the_panel_names_the_path_blocker() {
    let mut harness = harness();
    open_demo_level(&mut harness);
    let set = harness.state().state.set().cloned().expect("a set");
    let blockers = ppr_runtime::shapes::ShapeTable::from_set(&set).path_blockers;
    let mut named = 0;
    for (r, &b) in set.reflectors.iter().zip(&blockers) {
        if !r.name.starts_with("mirror on step_") && r.name != "mirror on mirror_wall" {
            continue;
        }
        harness.get_by_label(&r.name).click();
        harness.run();
        assert_eq!(selected(&harness).id, r.id);
        match set.reflectors.get(b as usize) {
            Some(blocker) => {
                let line = format!("path blocker: {} (id {}),", blocker.name, blocker.id);
                assert!(
                    harness.query_by_label_contains(&line).is_some(),
                    "{}: `{line}` in the panel",
                    r.name
                );
                named += 1;
            }
            None => assert!(harness.query_by_label("path blocker: none").is_some(), "{}: none", r.name),
        }
    }
    assert!(named >= 3, "the steps in front of other steps block them: {named}");
}
