//! A process-global log of the compute pipelines this crate creates, with each one's full
//! WGSL, entry point and override constants (feature `pipeline-log`, off by default): what
//! a tool needs to compile the same pipelines again outside wgpu (`ppr-bench
//! pipeline-stats` asks the Vulkan driver for their register counts).
//!
//! Nothing is recorded until [`start`]; while it is off, the only cost is one atomic load
//! per module and pipeline creation. While it is on, [`crate::shader::create_module`]
//! remembers each module's source, keyed by the creating thread and the module itself
//! (wgpu's `ShaderModule` is `Clone + Ord` by its id, which is unique within one
//! `wgpu::Instance` only: two instances, as two tests running side by side have, hand out
//! the same ids; the log keeps a clone, so no other module of the instance can take its id
//! while it is remembered), and `passes::compute_pipeline` records a [`PipelineSource`] for
//! each pipeline whose module the creating thread made. [`stop`] forgets the modules.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::thread::ThreadId;

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
    /// By creating thread and module (`None` until the first is remembered: a `static`
    /// cannot build a `HashMap`).
    modules: Option<HashMap<(ThreadId, wgpu::ShaderModule), String>>,
    pipelines: Vec<PipelineSource>,
    /// Pipelines whose module was created while the log was off (or elsewhere).
    unknown: usize,
}

static LOG: Mutex<Log> = Mutex::new(Log { modules: None, pipelines: Vec::new(), unknown: 0 });

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
    log().modules = None;
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
        log()
            .modules
            .get_or_insert_with(HashMap::new)
            .insert((std::thread::current().id(), module.clone()), source);
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
    let key = (std::thread::current().id(), module.clone());
    let Some(source) = log.modules.as_ref().and_then(|m| m.get(&key)).cloned() else {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_device::device;

    #[test]
    fn two_instances_side_by_side_keep_their_own_sources() {
        // Two threads, each with its own instance (whose module ids start alike), each
        // remember a module before either makes its pipeline: each pipeline is logged with
        // its own thread's source.
        start();
        let both = std::sync::Barrier::new(2);
        std::thread::scope(|scope| {
            for k in 0..2u32 {
                let both = &both;
                scope.spawn(move || {
                    let device = device();
                    let source = format!(
                        "@group(0) @binding(0) var<storage, read_write> out: array<u32>;\n\
                         @compute @workgroup_size(1) fn main() {{ out[0] = {k}u; }}"
                    );
                    let module = crate::shader::create_module(&device, "pipeline log test", source);
                    both.wait();
                    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                        label: None,
                        entries: &[crate::passes::storage_entry(0, false)],
                    });
                    let label = format!("pipeline log test {k}");
                    crate::passes::compute_pipeline(&device, &label, &layout, &module, "main", &[]);
                });
            }
        });
        let logged: Vec<PipelineSource> =
            take().into_iter().filter(|p| p.label.starts_with("pipeline log test")).collect();
        stop();
        assert_eq!(logged.len(), 2, "{logged:?}");
        for p in &logged {
            let k = p.label.rsplit(' ').next().unwrap_or_default();
            assert!(p.source.contains(&format!("out[0] = {k}u;")), "{}: {}", p.label, p.source);
        }
    }
}
