//! Loading a level and extracting its reflectors on a background thread, with progress
//! over a channel. The UI polls; it never waits. Cancelling abandons the thread: whatever
//! it still produces is dropped (the extractor has no stop point inside a stage).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError, channel};
use std::time::{Duration, Instant};

use ppr_extract::{ExtractParams, Extraction, Stage};

/// Where the level to extract comes from.
#[derive(Clone)]
pub enum LevelSource {
    /// Load it from this file.
    File(PathBuf),
    /// Already loaded (re-extraction with other parameters).
    Loaded(Arc<ppr_extract::Level>),
}

/// What a job is asked to do.
#[derive(Clone)]
pub struct JobRequest {
    /// The level.
    pub source: LevelSource,
    /// Extraction parameters (validated by the caller).
    pub params: ExtractParams,
    /// Also load the level for rendering (testbed meshes); only with [`LevelSource::File`].
    pub load_render_level: bool,
    /// Run the extractor (false: only load the level).
    pub extract: bool,
}

/// Progress through the stages.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JobProgress {
    /// The stage running.
    pub stage: Stage,
    /// How far through it, in `[0, 1]`.
    pub fraction: f32,
}

impl JobProgress {
    /// Overall fraction done, stages weighted equally.
    pub fn overall(&self) -> f32 {
        let index = Stage::ALL.iter().position(|s| *s == self.stage).unwrap_or(0) as f32;
        let stages = (Stage::ALL.len() - 1) as f32; // `Write` is not run here
        ((index + self.fraction.clamp(0.0, 1.0)) / stages).clamp(0.0, 1.0)
    }
}

/// What a job reports.
pub enum JobEvent {
    /// A stage started, progressed or ended.
    Progress(JobProgress),
    /// The level was loaded.
    LevelLoaded {
        /// The level for the extractor.
        extract_level: Arc<ppr_extract::Level>,
        /// The level for rendering, when asked for.
        render_level: Option<Arc<ppr_testbed::Level>>,
    },
    /// Extraction finished.
    Extracted(Box<Extraction>),
    /// Loading failed (the message names the file).
    Failed(String),
    /// The job ended (after its last event).
    Finished,
}

/// A running job.
pub struct ExtractionJob {
    receiver: Receiver<JobEvent>,
    cancel: Arc<AtomicBool>,
    /// Latest progress.
    pub progress: JobProgress,
    /// What the job does, for the UI (`extracting demo_room.glb`).
    pub description: String,
    /// When it started.
    pub started: Instant,
    finished: bool,
}

impl ExtractionJob {
    /// Starts `request` on a new thread; `notify` is called after each event (to wake the UI).
    pub fn start(request: JobRequest, description: String, notify: Arc<dyn Fn() + Send + Sync>) -> Self {
        let (sender, receiver) = channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = cancel.clone();
        std::thread::Builder::new()
            .name("ppr-inspector extraction".into())
            .spawn(move || run(request, &sender, &flag, notify.as_ref()))
            .map_or_else(
                |e| {
                    // The thread could not start: report it through a fresh channel.
                    let (s, r) = channel();
                    let _ = s.send(JobEvent::Failed(format!("cannot start the extraction thread: {e}")));
                    let _ = s.send(JobEvent::Finished);
                    Self::with(r, cancel.clone(), description.clone())
                },
                |_| Self::with(receiver, cancel.clone(), description.clone()),
            )
    }

    fn with(receiver: Receiver<JobEvent>, cancel: Arc<AtomicBool>, description: String) -> Self {
        Self {
            receiver,
            cancel,
            progress: JobProgress { stage: Stage::Load, fraction: 0.0 },
            description,
            started: Instant::now(),
            finished: false,
        }
    }

    /// Events received since the last call (never blocks).
    pub fn poll(&mut self) -> Vec<JobEvent> {
        let mut events = Vec::new();
        loop {
            match self.receiver.try_recv() {
                Ok(e) => events.push(self.note(e)),
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    events.push(self.disconnected());
                    break;
                }
            }
            if self.finished {
                break;
            }
        }
        events
    }

    /// Waits up to `timeout` for the job to finish and returns its events (tests, headless use).
    pub fn wait(&mut self, timeout: Duration) -> Vec<JobEvent> {
        let deadline = Instant::now() + timeout;
        let mut events = Vec::new();
        while !self.finished {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.receiver.recv_timeout(left) {
                Ok(e) => events.push(self.note(e)),
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => events.push(self.disconnected()),
            }
        }
        events
    }

    fn note(&mut self, e: JobEvent) -> JobEvent {
        match &e {
            JobEvent::Progress(p) => self.progress = *p,
            JobEvent::Finished => self.finished = true,
            _ => {}
        }
        e
    }

    fn disconnected(&mut self) -> JobEvent {
        if self.finished {
            return JobEvent::Finished;
        }
        self.finished = true;
        JobEvent::Failed("the extraction thread stopped without a result".into())
    }

    /// Whether the job has ended (its last event was polled).
    pub fn is_finished(&self) -> bool {
        self.finished
    }

    /// Asks the thread to stop; it sends nothing more.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

/// The level read once by `ppr-level`: flattened for the extractor and, when asked,
/// converted for the testbed's renderer (textures decoded only then).
fn load_levels(
    path: &std::path::Path,
    render: bool,
) -> Result<(Arc<ppr_extract::Level>, Option<Arc<ppr_testbed::Level>>), String> {
    let params = if render { ppr_level::LoadParams::render() } else { ppr_level::LoadParams::geometry() };
    let scene = ppr_level::load_scene(path, &params).map_err(|e| e.to_string())?;
    let extract_level = ppr_level::Level::from_scene(&scene).map_err(|e| e.to_string())?;
    let render_level = if render {
        Some(Arc::new(ppr_testbed::Level::from_scene(&scene).map_err(|e| e.to_string())?))
    } else {
        None
    };
    Ok((Arc::new(extract_level), render_level))
}

fn run(
    request: JobRequest,
    sender: &Sender<JobEvent>,
    cancel: &AtomicBool,
    notify: &(dyn Fn() + Send + Sync),
) {
    let send = |e: JobEvent| {
        if !cancel.load(Ordering::Relaxed) {
            let _ = sender.send(e);
            notify();
        }
    };
    let fail = |message: String| {
        send(JobEvent::Failed(message));
        send(JobEvent::Finished);
    };
    send(JobEvent::Progress(JobProgress { stage: Stage::Load, fraction: 0.0 }));
    let (extract_level, render_level) = match &request.source {
        LevelSource::File(path) => match load_levels(path, request.load_render_level) {
            Ok((extract_level, render_level)) => (extract_level, render_level),
            Err(message) => return fail(message),
        },
        LevelSource::Loaded(level) => (level.clone(), None),
    };
    send(JobEvent::Progress(JobProgress { stage: Stage::Load, fraction: 1.0 }));
    send(JobEvent::LevelLoaded { extract_level: extract_level.clone(), render_level });
    if request.extract && !cancel.load(Ordering::Relaxed) {
        let progress =
            |stage: Stage, fraction: f32| send(JobEvent::Progress(JobProgress { stage, fraction }));
        let extraction = ppr_extract::extract(&extract_level, &request.params, &progress);
        send(JobEvent::Extracted(Box::new(extraction)));
    }
    send(JobEvent::Finished);
}
