//! Every shared scene (`../shared/scenes/`) opens in the inspector, for the extractor and
//! for the viewport, as it does in `ppr-extract`: all read it through `ppr-level`. (The
//! meshopt-compressed `fps_mine_sketch_compressed.glb` could once be extracted but not
//! reviewed.)

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use ppr_extract::ExtractParams;
use ppr_inspector::extraction_job::{ExtractionJob, JobEvent, JobRequest, LevelSource};

#[test]
fn every_shared_scene_opens_for_review() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    let files = ppr_level::level_files(&dir);
    assert!(files.len() >= 5, "the shared scenes are missing from {}: {files:?}", dir.display());
    for path in files {
        let request = JobRequest {
            source: LevelSource::File(path.clone()),
            params: ExtractParams::default(),
            load_render_level: true,
            extract: false,
        };
        let mut job = ExtractionJob::start(request, path.display().to_string(), Arc::new(|| {}));
        let events = job.wait(Duration::from_secs(120));
        let loaded = events.iter().find_map(|e| match e {
            JobEvent::LevelLoaded { extract_level, render_level } => Some((extract_level, render_level)),
            _ => None,
        });
        let failed: Vec<&String> =
            events.iter().filter_map(|e| if let JobEvent::Failed(m) = e { Some(m) } else { None }).collect();
        let Some((extract_level, Some(render_level))) = loaded else {
            panic!("{}: not opened: {failed:?}", path.display());
        };
        assert!(failed.is_empty(), "{}: {failed:?}", path.display());
        assert!(!extract_level.triangles.is_empty(), "{}", path.display());
        assert_eq!(render_level.triangle_count(), extract_level.triangles.len(), "{}", path.display());
    }
}
