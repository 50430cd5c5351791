//! A process-global log of the compute pipelines this crate creates, with each one's full
//! WGSL, entry point and override constants (feature `pipeline-log`, off by default): what
//! a tool needs to compile the same pipelines again outside wgpu (`ppr-bench
//! pipeline-stats` asks the Vulkan driver for their register counts).
//!
//! Nothing is recorded until [`start`]; while it is off, the only cost is one atomic load
//! per module and pipeline creation. While it is on, [`crate::shader::create_module`]
//! remembers each module's source, keyed by the module itself (wgpu's `ShaderModule` is
//! `Clone + Ord` by identity; the log keeps a clone, so no other module can take its
//! identity while it is remembered), and `passes::compute_pipeline` records a
//! [`PipelineSource`] for each pipeline whose module it knows. [`stop`] forgets the modules.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};

/// One compute pipeline as this crate created it.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineSource {
    /// The pipeline's label (`ppr projection …`, `ppr reflection …`).
    pub label: String,
    /// The module's whole WGSL, shared modules included.
    pub source: String,
    /// The entry point's name.
    pub entry_point: String,
    /// The override constants, in the order the pass gave them.
    pub constants: Vec<(String, f64)>,
}

static ON: AtomicBool = AtomicBool::new(false);

/// The remembered modules and the pipelines recorded since the last [`take`].
struct Log {
    modules: BTreeMap<wgpu::ShaderModule, String>,
    pipelines: Vec<PipelineSource>,
    /// Pipelines whose module was created while the log was off (or elsewhere).
    unknown: usize,
}

static LOG: Mutex<Log> = Mutex::new(Log { modules: BTreeMap::new(), pipelines: Vec::new(), unknown: 0 });

fn log() -> MutexGuard<'static, Log> {
    // A panic while holding the lock leaves plain data behind: keep using it.
    LOG.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Starts recording modules and pipelines (for the whole process).
pub fn start() {
    log().unknown = 0;
    ON.store(true, Ordering::SeqCst);
}

/// Stops recording and forgets the remembered modules (which the log kept alive); the
/// pipelines not yet taken stay for [`take`].
pub fn stop() {
    ON.store(false, Ordering::SeqCst);
    log().modules.clear();
}

/// Whether the log records.
pub fn is_on() -> bool {
    ON.load(Ordering::Relaxed)
}

/// The pipelines recorded since the last call, in creation order; the log keeps recording.
pub fn take() -> Vec<PipelineSource> {
    std::mem::take(&mut log().pipelines)
}

/// How many pipelines since [`start`] were not recorded because their module was created
/// while the log was off (create the renderer after [`start`]).
pub fn unknown_modules() -> usize {
    log().unknown
}

/// Remembers `source` as `module`'s WGSL (when the log is on).
pub(crate) fn remember_module(module: &wgpu::ShaderModule, source: String) {
    if is_on() {
        log().modules.insert(module.clone(), source);
    }
}

/// Records a pipeline of `module` (when the log is on).
pub(crate) fn record_pipeline(
    label: &str,
    module: &wgpu::ShaderModule,
    entry_point: &str,
    constants: &[(&str, f64)],
) {
    if !is_on() {
        return;
    }
    let mut log = log();
    let Some(source) = log.modules.get(module).cloned() else {
        log.unknown += 1;
        return;
    };
    log.pipelines.push(PipelineSource {
        label: label.to_owned(),
        source,
        entry_point: entry_point.to_owned(),
        constants: constants.iter().map(|&(n, v)| (n.to_owned(), v)).collect(),
    });
}
