//! Quality metrics computed on worker threads (FLIP at 4K takes seconds of CPU time), once a
//! scene's timing is done: metric threads running beside the frame loop slowed the GPU
//! timestamps of the runs next to them on the H100.

use std::collections::VecDeque;
use std::sync::Arc;
use std::thread::JoinHandle;

use image::Rgba32FImage;
use ppr_testbed::image_io::ToneMap;

use crate::quality::{Quality, ReferenceFrame};

type Job = (usize, JoinHandle<Result<Quality, String>>);

/// A bounded set of metric threads.
pub struct QualityPool {
    limit: usize,
    running: VecDeque<Job>,
    done: Vec<(usize, Result<Quality, String>)>,
}

impl QualityPool {
    /// A pool of at most `limit` threads at once (at least one).
    pub fn new(limit: usize) -> Self {
        Self { limit: limit.max(1), running: VecDeque::new(), done: Vec::new() }
    }

    /// Threads to use on this machine: all cores but one (the GPU driver's).
    pub fn default_limit() -> usize {
        std::thread::available_parallelism().map_or(1, |n| n.get().saturating_sub(1).max(1))
    }

    /// Measures `image` against `reference` on a thread (waiting for a free one); `id` names
    /// the result.
    pub fn submit(
        &mut self,
        id: usize,
        reference: Arc<ReferenceFrame>,
        image: Rgba32FImage,
        tone_map: ToneMap,
    ) {
        while self.running.len() >= self.limit {
            self.join_oldest();
        }
        let handle = std::thread::spawn(move || {
            Quality::measure(&reference, &image, tone_map).map_err(|e| e.to_string())
        });
        self.running.push_back((id, handle));
    }

    fn join_oldest(&mut self) {
        if let Some((id, handle)) = self.running.pop_front() {
            let result = handle.join().unwrap_or_else(|_| Err("metric thread panicked".into()));
            self.done.push((id, result));
        }
    }

    /// Waits for every job; results by id.
    pub fn finish(mut self) -> Vec<(usize, Result<Quality, String>)> {
        while !self.running.is_empty() {
            self.join_oldest();
        }
        self.done
    }
}
