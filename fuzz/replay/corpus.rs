//! Replaying the committed fuzz inputs in ordinary (stable) tests: the files of a target's
//! `fuzz/corpus/<target>` and `fuzz/regressions/<target>`, and the bytes one replay
//! allocates. Included with `#[path]` by the `fuzz_corpus` test of each crate the fuzzers
//! reach (`ppr-level`, `ppr-format`, `ppr-extract`), so the three read the corpus alike.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

/// The system allocator, counting the bytes each thread asks for.
pub struct CountingAllocator;

thread_local! {
    static ALLOCATED: Cell<u64> = const { Cell::new(0) };
}

fn count(bytes: usize) {
    let _ = ALLOCATED.try_with(|a| a.set(a.get().saturating_add(bytes as u64)));
}

// SAFETY: every call is forwarded to `System` unchanged; counting touches only a
// thread-local cell initialised without allocating.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: the caller's contract is `System`'s.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size);
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: CountingAllocator = CountingAllocator;

/// The committed inputs of fuzz target `target`, sorted by path: its minimised corpus
/// (which must exist and hold files, or the replay would pass by testing nothing) and its
/// crash reproducers.
pub fn inputs(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let corpus = files(&fuzz.join("corpus").join(target));
    assert!(
        !corpus.is_empty(),
        "fuzz/corpus/{target} is missing or empty: the replay would test nothing (see fuzz/README.md)"
    );
    let mut all = corpus;
    all.extend(files(&fuzz.join("regressions").join(target)));
    all.sort();
    all.into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (p, bytes)
        })
        .collect()
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    entries
        .map(|e| e.expect("a readable corpus folder").path())
        .filter(|p| p.is_file() && p.file_name().is_some_and(|n| !n.to_string_lossy().starts_with('.')))
        .collect()
}

/// What a replay saw.
#[derive(Clone, Copy, Debug)]
pub struct Replayed {
    /// Inputs `entry` accepted.
    pub accepted: usize,
    /// Inputs replayed.
    pub total: usize,
    /// The most bytes one input's replay allocated (zero would mean nothing was measured).
    pub most_allocated: u64,
}

/// Runs `entry` on every committed input of `target`; fails naming each input whose replay
/// panics or allocates more than `max_bytes(input length)` bytes in all.
pub fn replay(target: &str, max_bytes: impl Fn(usize) -> u64, entry: impl Fn(&[u8]) -> bool) -> Replayed {
    let inputs = inputs(target);
    let mut failures = Vec::new();
    let mut seen = Replayed { accepted: 0, total: inputs.len(), most_allocated: 0 };
    for (path, bytes) in &inputs {
        let before = ALLOCATED.with(Cell::get);
        let outcome = catch_unwind(AssertUnwindSafe(|| entry(bytes)));
        let allocated = ALLOCATED.with(Cell::get) - before;
        seen.most_allocated = seen.most_allocated.max(allocated);
        match outcome {
            Err(_) => failures.push(format!("{}: panicked", path.display())),
            Ok(ok) => seen.accepted += usize::from(ok),
        }
        if allocated > max_bytes(bytes.len()) {
            failures.push(format!(
                "{}: allocated {allocated} bytes for {} input bytes",
                path.display(),
                bytes.len()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} inputs failed:\n{}",
        failures.len(),
        inputs.len(),
        failures.join("\n")
    );
    seen
}
