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

use crate::demo::demo_level_path;

/// Window size of the snapshots, points.
const SIZE: egui::Vec2 = egui::Vec2::new(1000.0, 620.0);

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

fn wait_for_extraction(harness: &mut Harness<'_, InspectorApp>) {
    assert!(harness.state_mut().state.wait_for_job(Duration::from_secs(120)), "extraction finished in time");
    harness.run();
}

fn selected(harness: &Harness<'_, InspectorApp>) -> ppr_format::Reflector {
    harness.state().state.selected().cloned().expect("a reflector is selected")
}

#[test]
fn open_select_edit_undo_redo_save_reload() {
    let mut snapshots = SnapshotResults::new();
    let mut harness = harness();
    assert!(harness.state().viewport.adapter().is_some(), "the app renders on the harness's wgpu device");

    // Open the demo level by typing its path.
    harness.get_by_label("Path").set_text_value_accesskit(&demo_level_path().display().to_string());
    harness.run();
    harness.get_by_label("Open level").click();
    harness.run_ok();
    wait_for_extraction(&mut harness);
    assert_eq!(harness.state().state.set().map(|s| s.reflectors.len()), Some(14));
    assert!(harness.state().viewport.has_frame(), "a preview was rendered");
    snapshots.add(harness.try_snapshot("inspector/opened"));

    // Select the mirror in the list.
    harness.get_by_label("mirror on mirror_wall").click();
    harness.run();
    let mirror = selected(&harness);
    assert_eq!(mirror.name, "mirror on mirror_wall");
    snapshots.add(harness.try_snapshot("inspector/selected"));

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
    snapshots.add(harness.try_snapshot("inspector/edited"));

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
    harness.run();
    assert_eq!(selected(&harness).id, mirror.id);
    snapshots.add(harness.try_snapshot("inspector/reloaded"));
    snapshots.unwrap();
}

#[test]
fn unsaved_changes_guard_asks_before_opening() {
    let mut harness = harness();
    harness.get_by_label("Path").set_text_value_accesskit(&demo_level_path().display().to_string());
    harness.run();
    harness.get_by_label("Open level").click();
    harness.run_ok();
    wait_for_extraction(&mut harness);
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
    assert_eq!(harness.state().state.set().map(|s| s.reflectors.len()), Some(14));
}
