//! `InspectorState`: everything the inspector knows, apart from the UI and the GPU: the
//! level, the edited document, selection, edit history, the extraction job, the preview
//! settings and the messages. Unit-tested without a GPU.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use glam::DVec3;
use ppr_extract::ExtractParams;
use ppr_format::{Reflector, ReflectorSet};

use crate::camera_control::CameraRig;
use crate::commands::EditCommand;
use crate::document::Document;
use crate::edit_history::{EditHistory, HistoryEntry};
use crate::edits_file;
use crate::error::InspectorError;
use crate::extraction_job::{ExtractionJob, JobEvent, JobRequest, LevelSource};
use crate::manual_edits::carry_edits;
use crate::messages::MessageLog;
use crate::preview::PreviewSettings;
use crate::reflector_table::ReflectorSort;

/// The level being inspected.
#[derive(Clone)]
pub struct LoadedLevel {
    /// The glTF file.
    pub path: PathBuf,
    /// The level as the testbed renders it (once loaded).
    pub render: Option<Arc<ppr_testbed::Level>>,
    /// The level as the extractor reads it (once loaded).
    pub extract: Option<Arc<ppr_extract::Level>>,
}

/// What a running job is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JobPurpose {
    /// Opening a level: its extraction becomes the document (unless a set was given).
    Open,
    /// Re-extracting with other parameters: manual edits are carried over.
    Reextract,
}

/// An action that would lose unsaved changes, waiting for the user to confirm.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PendingAction {
    /// Open this level.
    OpenLevel(PathBuf),
    /// Open this set.
    OpenSet(PathBuf),
    /// Close the application.
    Quit,
}

/// Everything the inspector holds.
pub struct InspectorState {
    /// The level, once one is opened.
    pub level: Option<LoadedLevel>,
    /// The edited set, once there is one.
    pub doc: Option<Document>,
    /// Where the set is saved (or was loaded from).
    pub set_path: Option<PathBuf>,
    saved_revision: Option<u64>,
    /// The selected reflector's id.
    pub selection: Option<u32>,
    /// Undo and redo.
    pub history: EditHistory,
    /// The background job, while one runs.
    pub job: Option<ExtractionJob>,
    job_purpose: JobPurpose,
    /// Parameters of the next extraction.
    pub params: ExtractParams,
    /// What the viewport shows.
    pub preview: PreviewSettings,
    /// The viewport camera.
    pub camera: CameraRig,
    /// Order of the reflector list.
    pub sort: ReflectorSort,
    /// What the user was told.
    pub messages: MessageLog,
    /// An action waiting for "discard unsaved changes?".
    pub pending: Option<PendingAction>,
    /// Set when the level changed (the viewport uploads it again).
    pub level_generation: u64,
    /// Set when the application may close (after a confirmed quit).
    pub quit_confirmed: bool,
    notify: Arc<dyn Fn() + Send + Sync>,
    next_gesture: u64,
}

impl Default for InspectorState {
    fn default() -> Self {
        Self::new(Arc::new(|| {}))
    }
}

impl InspectorState {
    /// An empty state; `notify` wakes the UI when the background job reports.
    pub fn new(notify: Arc<dyn Fn() + Send + Sync>) -> Self {
        Self {
            level: None,
            doc: None,
            set_path: None,
            saved_revision: None,
            selection: None,
            history: EditHistory::default(),
            job: None,
            job_purpose: JobPurpose::Open,
            params: ExtractParams::default(),
            preview: PreviewSettings::default(),
            camera: CameraRig::default(),
            sort: ReflectorSort::default(),
            messages: MessageLog::default(),
            pending: None,
            level_generation: 0,
            quit_confirmed: false,
            notify,
            next_gesture: 1,
        }
    }

    /// The current set.
    pub fn set(&self) -> Option<&ReflectorSet> {
        self.doc.as_ref().map(|d| &d.set)
    }

    /// The selected reflector.
    pub fn selected(&self) -> Option<&Reflector> {
        self.set()?.by_id(self.selection?)
    }

    /// Whether the document has changes that are not saved.
    pub fn is_dirty(&self) -> bool {
        self.doc.as_ref().is_some_and(|d| Some(d.revision) != self.saved_revision)
    }

    /// Revision of the document (0 without one): changes whenever the set does.
    pub fn revision(&self) -> u64 {
        self.doc.as_ref().map_or(0, |d| d.revision)
    }

    /// Where "Save" writes: the set's file, else `<level stem>.ppr.json` beside the level.
    pub fn default_set_path(&self) -> Option<PathBuf> {
        self.set_path.clone().or_else(|| {
            let level = &self.level.as_ref()?.path;
            let stem = level.file_stem()?.to_string_lossy().into_owned();
            Some(level.with_file_name(format!("{stem}.ppr.json")))
        })
    }

    /// A new gesture number (edits with one number form one undo step).
    pub fn new_gesture(&mut self) -> u64 {
        self.next_gesture += 1;
        self.next_gesture
    }

    // ---- opening ------------------------------------------------------------------

    /// Runs `action` now, or keeps it for confirmation when there are unsaved changes.
    pub fn request(&mut self, action: PendingAction) {
        if self.is_dirty() {
            self.pending = Some(action);
        } else {
            self.run(action);
        }
    }

    /// Runs the pending action, discarding unsaved changes.
    pub fn confirm_pending(&mut self) {
        if let Some(action) = self.pending.take() {
            self.run(action);
        }
    }

    /// Forgets the pending action.
    pub fn cancel_pending(&mut self) {
        self.pending = None;
    }

    fn run(&mut self, action: PendingAction) {
        match action {
            PendingAction::OpenLevel(path) => self.open_level(&path, None),
            PendingAction::OpenSet(path) => self.open_set(&path),
            PendingAction::Quit => self.quit_confirmed = true,
        }
    }

    /// Opens a level: loads it in the background and extracts it, or, with `set`, loads
    /// that set instead of extracting. Unsaved changes are dropped (see [`Self::request`]).
    pub fn open_level(&mut self, path: &Path, set: Option<&Path>) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
        self.level = Some(LoadedLevel { path: path.to_owned(), render: None, extract: None });
        self.level_generation += 1;
        self.doc = None;
        self.set_path = None;
        self.saved_revision = None;
        self.selection = None;
        self.history.clear();
        if let Some(set) = set {
            self.open_set(set);
        }
        let request = JobRequest {
            source: LevelSource::File(path.to_owned()),
            params: self.params.clone(),
            load_render_level: true,
            extract: set.is_none(),
        };
        let what = if set.is_none() { "loading and extracting" } else { "loading" };
        self.start_job(request, JobPurpose::Open, format!("{what} {}", path.display()));
    }

    /// Loads a reflector set from a file; errors name the file and the field.
    pub fn open_set(&mut self, path: &Path) {
        match ReflectorSet::load(path) {
            Ok(set) => {
                let mut doc = Document::from_set(set);
                let mut loaded =
                    format!("loaded {} reflectors from {}", doc.set.reflectors.len(), path.display());
                match edits_file::load(path, &doc.set) {
                    Ok(Some(edits)) => {
                        let n = edits.edited.len() + edits.replacements.len();
                        loaded.push_str(&format!(
                            " and {n} manual edit(s) from {}",
                            edits_file::edits_path(path).display()
                        ));
                        doc.edits = edits;
                    }
                    Ok(None) => {}
                    Err(e) => self
                        .messages
                        .warning(format!("{e}; re-extraction will not keep earlier manual edits")),
                }
                self.messages.info(loaded);
                self.saved_revision = Some(doc.revision);
                self.doc = Some(doc);
                self.set_path = Some(path.to_owned());
                self.selection = None;
                self.history.clear();
                self.warn_if_other_level();
            }
            Err(e) => {
                let field = e.field_path().map(|f| format!(" (field `{f}`)")).unwrap_or_default();
                self.messages.error(format!("cannot open the set: {e}{field}"));
            }
        }
    }

    /// Warns when the opened set was extracted from other bytes than the loaded level's
    /// (`source.hash`); the artist may go on editing. Checked once both are there.
    fn warn_if_other_level(&mut self) {
        let (Some(doc), Some(set_path), Some(level)) = (&self.doc, &self.set_path, &self.level) else {
            return;
        };
        let Some(extract) = &level.extract else { return };
        if let Err(mismatch) = doc.set.check_source(set_path, &level.path, &extract.hash) {
            self.messages.warning(format!(
                "{mismatch}. You may go on editing; re-extracting keeps your manual edits that still apply"
            ));
        }
    }

    // ---- extraction ---------------------------------------------------------------

    fn start_job(&mut self, request: JobRequest, purpose: JobPurpose, description: String) {
        self.job_purpose = purpose;
        self.job = Some(ExtractionJob::start(request, description, self.notify.clone()));
    }

    /// Extracts the level again with [`Self::params`]; manual edits are carried over by id.
    ///
    /// # Errors
    /// When no level is loaded yet, a job is running, or the parameters are out of range.
    pub fn reextract(&mut self) -> Result<(), InspectorError> {
        self.params.validate().map_err(InspectorError::Params)?;
        if self.job.is_some() {
            return Err(InspectorError::Missing("an extraction is already running".into()));
        }
        let level =
            self.level.as_ref().ok_or_else(|| InspectorError::Missing("open a level first".into()))?;
        let extract = level
            .extract
            .clone()
            .ok_or_else(|| InspectorError::Missing("the level is still loading".into()))?;
        let request = JobRequest {
            source: LevelSource::Loaded(extract),
            params: self.params.clone(),
            load_render_level: false,
            extract: true,
        };
        let description = format!("re-extracting {}", level.path.display());
        self.start_job(request, JobPurpose::Reextract, description);
        Ok(())
    }

    /// Stops waiting for the running job (its results are dropped).
    pub fn cancel_job(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
            self.messages.warning(format!("cancelled: {}", job.description));
        }
    }

    /// Handles what the job reported since the last call (never blocks).
    pub fn poll_job(&mut self) {
        let Some(job) = self.job.as_mut() else { return };
        let events = job.poll();
        self.handle_job_events(events);
    }

    /// Blocks until the job ends or `timeout` passes, handling its events (tests, screenshots).
    /// Returns whether no job is left running.
    pub fn wait_for_job(&mut self, timeout: Duration) -> bool {
        if let Some(job) = self.job.as_mut() {
            let events = job.wait(timeout);
            self.handle_job_events(events);
        }
        self.job.is_none()
    }

    fn handle_job_events(&mut self, events: Vec<JobEvent>) {
        for event in events {
            match event {
                JobEvent::Progress(_) => {}
                JobEvent::LevelLoaded { extract_level, render_level } => {
                    self.level_loaded(extract_level, render_level)
                }
                JobEvent::Extracted(x) => self.extracted(&x),
                JobEvent::Failed(message) => self.messages.error(message),
                JobEvent::Finished => self.job = None,
            }
        }
        if self.job.as_ref().is_some_and(ExtractionJob::is_finished) {
            self.job = None;
        }
    }

    fn level_loaded(&mut self, extract: Arc<ppr_extract::Level>, render: Option<Arc<ppr_testbed::Level>>) {
        let Some(level) = self.level.as_mut() else { return };
        level.extract = Some(extract);
        if let Some(render) = render {
            level.render = Some(render.clone());
            let path = level.path.display().to_string();
            for w in &render.warnings {
                self.messages.warning(format!("{path}: {w}"));
            }
            if let Some((lo, hi)) = render.bounds() {
                self.camera.scene_size = (hi - lo).length().max(1e-3);
                self.camera.frame_box(lo, hi);
            }
            if let Some(first) = render.cameras.first() {
                self.view_from(first);
            }
            self.level_generation += 1;
        }
        if self.job_purpose == JobPurpose::Open {
            self.warn_if_other_level();
        }
    }

    fn extracted(&mut self, x: &ppr_extract::Extraction) {
        let fresh = Document::from_extraction(x);
        for w in &x.warnings {
            self.messages.info(format!("extraction: {w}"));
        }
        match (self.job_purpose, self.doc.as_ref()) {
            (JobPurpose::Reextract, Some(current)) => match carry_edits(current, fresh) {
                Ok((doc, report)) => {
                    for k in &report.kept {
                        self.messages.info(format!("kept manual edit: {k}"));
                    }
                    for n in &report.not_applicable {
                        self.messages.warning(n.clone());
                    }
                    self.messages.info(format!(
                        "re-extracted: {} reflectors, {} manual edits kept, {} no longer apply",
                        doc.set.reflectors.len(),
                        report.kept.len(),
                        report.not_applicable.len()
                    ));
                    self.commit("re-extract".into(), doc, None, None);
                }
                Err(e) => self.messages.error(format!("re-extraction result refused: {e}")),
            },
            _ => {
                self.messages.info(format!("extracted {} reflectors", fresh.set.reflectors.len()));
                self.doc = Some(fresh);
                self.saved_revision = None;
                self.selection = None;
                self.history.clear();
            }
        }
    }

    // ---- editing ------------------------------------------------------------------

    /// Applies an edit (validated first); a refused edit is reported and changes nothing.
    /// Returns whether it was applied.
    pub fn apply(&mut self, command: EditCommand) -> bool {
        self.apply_in_gesture(command, None)
    }

    /// Like [`Self::apply`], merging the undo step with others of the same `gesture`.
    pub fn apply_in_gesture(&mut self, command: EditCommand, gesture: Option<u64>) -> bool {
        let Some(doc) = self.doc.as_ref() else {
            self.messages.error("nothing to edit: open a level or a set first");
            return false;
        };
        let label = command.describe(&doc.set);
        match command.apply(doc) {
            Ok(outcome) => {
                self.commit(label, outcome.doc, outcome.select, gesture);
                true
            }
            Err(e) => {
                self.messages.error(e.to_string());
                false
            }
        }
    }

    fn commit(&mut self, label: String, after: Document, select: Option<u32>, gesture: Option<u64>) {
        let Some(before) = self.doc.replace(after.clone()) else { return };
        self.history.record(HistoryEntry { label, before, after, gesture });
        if let Some(id) = select {
            self.selection = Some(id);
        }
        self.fix_selection();
    }

    /// Undoes the last step.
    pub fn undo(&mut self) {
        match self.history.undo() {
            Some((label, doc)) => {
                self.doc = Some(doc);
                self.messages.info(format!("undid {label}"));
                self.fix_selection();
            }
            None => self.messages.info("nothing to undo"),
        }
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) {
        match self.history.redo() {
            Some((label, doc)) => {
                self.doc = Some(doc);
                self.messages.info(format!("redid {label}"));
                self.fix_selection();
            }
            None => self.messages.info("nothing to redo"),
        }
    }

    fn fix_selection(&mut self) {
        if self.selection.is_some() && self.selected().is_none() {
            self.selection = None;
        }
    }

    /// Selects a reflector (or none).
    pub fn select(&mut self, id: Option<u32>) {
        self.selection = id.filter(|&id| self.set().is_some_and(|s| s.by_id(id).is_some()));
    }

    // ---- camera -------------------------------------------------------------------

    /// Points the camera at the selected reflector.
    pub fn frame_selected(&mut self) {
        let Some(r) = self.selected() else { return };
        let corners = r.corners();
        let (lo, hi) = corners
            .iter()
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        self.camera.frame_box(lo, hi);
    }

    /// Puts the viewport camera where a camera of the level file is.
    pub fn view_from(&mut self, camera: &ppr_testbed::LevelCamera) {
        let c = camera.to_camera(ppr_runtime::Projection::default());
        self.camera.fov_y = camera.yfov;
        self.camera.look_from(c.position, c.forward().as_dvec3(), self.camera.scene_size * 0.35);
    }

    /// Points the camera at the whole level.
    pub fn frame_level(&mut self) {
        if let Some((lo, hi)) = self.level.as_ref().and_then(|l| l.render.as_ref()).and_then(|l| l.bounds()) {
            self.camera.frame_box(lo, hi);
        }
    }

    // ---- saving -------------------------------------------------------------------

    /// Saves to [`Self::default_set_path`] (atomically).
    ///
    /// # Errors
    /// Nothing to save, no path, or the format's save error (file and field named).
    pub fn save(&mut self) -> Result<PathBuf, InspectorError> {
        let path = self
            .default_set_path()
            .ok_or_else(|| InspectorError::Missing("no file to save to: use Save as".into()))?;
        self.save_as(&path)?;
        Ok(path)
    }

    /// Saves to `path` atomically; it becomes the set's file.
    ///
    /// # Errors
    /// Nothing to save, or the format's save error.
    pub fn save_as(&mut self, path: &Path) -> Result<(), InspectorError> {
        let doc = self.doc.as_ref().ok_or_else(|| InspectorError::Missing("nothing to save".into()))?;
        doc.set.save(path)?;
        // The set is saved; its edits go beside it (a failure is reported, the set stays).
        let edits = edits_file::save(path, &doc.edits);
        self.saved_revision = Some(doc.revision);
        self.set_path = Some(path.to_owned());
        self.messages.info(format!("saved {} reflectors to {}", doc.set.reflectors.len(), path.display()));
        edits
    }

    /// Runs `result`, logging its error.
    pub fn report<T>(&mut self, result: Result<T, InspectorError>) -> Option<T> {
        match result {
            Ok(v) => Some(v),
            Err(e) => {
                self.messages.error(e.to_string());
                None
            }
        }
    }
}
