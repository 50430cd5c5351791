//! Hot reload of the reflector set: when the `*.ppr.json` changes on disk (an artist saves
//! in the inspector), the running game takes the new set within a second, without a stall.
//!
//! **How:** a thread polls the file's modification time and length every
//! [`POLL_INTERVAL`] (250 ms) and, when they change, reads, parses and validates the file
//! *on that thread*; the render loop only takes finished results from a channel
//! ([`ReflectorSetWatcher::poll`]) and hands a new set to
//! `ReflectionRenderer::set_reflectors`, which is cheap (no pipeline is rebuilt).
//!
//! **Why polling rather than a file-system notification crate:** the inspector and
//! `ppr-extract` save atomically (write a temporary file, then rename it over the set), and
//! editors do the same; a watch on the file itself loses track after the first rename and a
//! watch on the folder reports several events per save that must be debounced anyway. One
//! `stat` every 250 ms costs nothing, behaves the same on every platform and network file
//! system, needs no dependency, and meets the one-second budget with room to spare. (A file
//! rewritten twice within one tick of a coarse modification clock, at the same length, is
//! missed; the file systems games ship on have nanosecond times.)
//!
//! **Errors:** a file that does not parse or validate is reported ([`SetStatus::Refused`],
//! with the message naming the field) and the last good set stays in use. A missing file is
//! waited for, so the walkthrough can start before `ppr-extract` has run (in a window; a
//! headless run refuses to start without a set). A set extracted from other bytes than the
//! level's is refused the same way ([`LevelMatch`]), unless the mismatch is accepted.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, SystemTime};

use ppr_format::ValidatedSet;

use crate::level_match::{LevelMatch, MatchOutcome};

/// How often the watcher looks at the file.
pub const POLL_INTERVAL: Duration = Duration::from_millis(250);

/// What the watcher found after a change of the file.
#[derive(Debug)]
pub enum ReloadEvent {
    /// The file parsed and validated.
    Loaded(Box<ValidatedSet>),
    /// The file is there but is not a valid set (the message names the field).
    Refused(String),
    /// The file cannot be read (missing, or no permission).
    Unreadable(String),
}

/// The state of the set as the game shows it.
#[derive(Clone, Debug, PartialEq)]
pub enum SetStatus {
    /// No valid set has been read yet.
    Waiting(String),
    /// The set in use was loaded `reloads` times (1 at start-up) and is current.
    Current { reflectors: usize, reloads: u32, at: SystemTime },
    /// The file on disk was refused; the last good set (if any) stays in use.
    Refused { message: String, keeping: Option<usize> },
}

/// Watches one reflector-set file from a background thread.
pub struct ReflectorSetWatcher {
    path: PathBuf,
    events: Receiver<ReloadEvent>,
    stop: Option<Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

/// The file's identity as far as polling can see: modification time and length.
type Stamp = Option<(SystemTime, u64)>;

fn stamp(path: &Path) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
}

fn read(path: &Path) -> ReloadEvent {
    match std::fs::read_to_string(path) {
        Err(e) => ReloadEvent::Unreadable(format!("{}: cannot read: {e}", path.display())),
        Ok(text) => match ValidatedSet::from_json_str(&text) {
            Ok(set) => ReloadEvent::Loaded(Box::new(set)),
            Err(e) => ReloadEvent::Refused(format!("{}: {e}", path.display())),
        },
    }
}

impl ReflectorSetWatcher {
    /// Starts watching `path` with the default [`POLL_INTERVAL`]. The first event (the
    /// file as it is now) is sent at once.
    pub fn start(path: impl Into<PathBuf>) -> Self {
        Self::with_interval(path, POLL_INTERVAL)
    }

    /// Starts watching `path`, looking every `interval`.
    pub fn with_interval(path: impl Into<PathBuf>, interval: Duration) -> Self {
        let path = path.into();
        let (tx, events) = mpsc::channel();
        let (stop, stopped) = mpsc::channel::<()>();
        let watched = path.clone();
        let thread = std::thread::Builder::new()
            .name("ppr set watcher".into())
            .spawn(move || {
                let mut last: Stamp = None;
                let mut first = true;
                loop {
                    let now = stamp(&watched);
                    if first || now != last {
                        first = false;
                        last = now;
                        if tx.send(read(&watched)).is_err() {
                            return;
                        }
                    }
                    match stopped.recv_timeout(interval) {
                        Err(RecvTimeoutError::Timeout) => {}
                        Ok(()) | Err(RecvTimeoutError::Disconnected) => return,
                    }
                }
            })
            .ok();
        Self { path, events, stop: Some(stop), thread }
    }

    /// The watched file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Every event that arrived since the last call, oldest first; never blocks.
    pub fn poll(&self) -> Vec<ReloadEvent> {
        self.events.try_iter().collect()
    }

    /// Waits up to `timeout` for the next event (tests and the headless start-up).
    pub fn wait(&self, timeout: Duration) -> Option<ReloadEvent> {
        self.events.recv_timeout(timeout).ok()
    }
}

impl Drop for ReflectorSetWatcher {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The set the game renders with and what it says about it: applies [`ReloadEvent`]s,
/// keeping the last good set when a new file is refused.
#[derive(Debug)]
pub struct ReflectorSetState {
    set: Option<ValidatedSet>,
    status: SetStatus,
    reloads: u32,
    level: Option<LevelMatch>,
    warning: Option<String>,
}

impl ReflectorSetState {
    /// No set yet: `waiting_for` says what for.
    pub fn new(waiting_for: impl Into<String>) -> Self {
        Self {
            set: None,
            status: SetStatus::Waiting(waiting_for.into()),
            reloads: 0,
            level: None,
            warning: None,
        }
    }

    /// Checks every loaded set against this level's hash: a mismatch is refused like an
    /// invalid file, or, when accepted, taken with a warning ([`Self::take_warning`]).
    pub fn with_level_match(mut self, level: LevelMatch) -> Self {
        self.level = Some(level);
        self
    }

    /// Applies one event; returns the new set when the renderer must take it.
    pub fn apply(&mut self, event: ReloadEvent) -> Option<&ValidatedSet> {
        let keeping = self.set.as_ref().map(|s| s.reflectors.len());
        match event {
            ReloadEvent::Loaded(set) => {
                match self.level.as_ref().map_or(MatchOutcome::Matches, |level| level.check(&set)) {
                    MatchOutcome::Matches => {}
                    MatchOutcome::Accepted(warning) => self.warning = Some(warning),
                    MatchOutcome::Refused(message) => {
                        self.status = SetStatus::Refused { message, keeping };
                        return None;
                    }
                }
                self.reloads += 1;
                self.status = SetStatus::Current {
                    reflectors: set.reflectors.len(),
                    reloads: self.reloads,
                    at: SystemTime::now(),
                };
                self.set = Some(*set);
                return self.set.as_ref();
            }
            ReloadEvent::Refused(message) => self.status = SetStatus::Refused { message, keeping },
            ReloadEvent::Unreadable(message) => {
                self.status = match keeping {
                    None => SetStatus::Waiting(message),
                    Some(_) => SetStatus::Refused { message, keeping },
                }
            }
        }
        None
    }

    /// The last good set.
    pub fn set(&self) -> Option<&ValidatedSet> {
        self.set.as_ref()
    }

    pub fn status(&self) -> &SetStatus {
        &self.status
    }

    /// The warning of the last accepted level mismatch, once.
    pub fn take_warning(&mut self) -> Option<String> {
        self.warning.take()
    }
}

/// Waits up to `timeout` for the watcher's first event and applies it (used at start-up
/// so the first frame already has the set).
pub fn apply_first_event(watcher: &ReflectorSetWatcher, state: &mut ReflectorSetState, timeout: Duration) {
    if let Some(event) = watcher.wait(timeout) {
        state.apply(event);
    }
}
