//! Deterministic parallel maps: contiguous chunks of the input on scoped standard threads,
//! results concatenated in input order, so the output never depends on the thread count.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The worker threads to use for `requested` (0: every available core).
pub fn thread_count(requested: usize) -> usize {
    if requested > 0 {
        requested
    } else {
        std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
    }
}

/// `f` over `0..len` in contiguous ranges, on up to `threads` threads; the ranges' outputs
/// concatenated in order. `f` gets each range once; ranges are about `len / (8 threads)` long.
pub fn map_ranges<R: Send>(
    len: usize,
    threads: usize,
    f: impl Fn(std::ops::Range<usize>) -> Vec<R> + Sync,
) -> Vec<R> {
    let threads = threads.max(1).min(len.max(1));
    if threads == 1 {
        return f(0..len);
    }
    let chunk = len.div_ceil(threads * 8).max(1);
    let chunks = len.div_ceil(chunk);
    let next = AtomicUsize::new(0);
    let mut parts: Vec<(usize, Vec<R>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let k = next.fetch_add(1, Ordering::Relaxed);
                        if k >= chunks {
                            break;
                        }
                        done.push((k, f(k * chunk..((k + 1) * chunk).min(len))));
                    }
                    done
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    });
    parts.sort_unstable_by_key(|(k, _)| *k);
    parts.into_iter().flat_map(|(_, v)| v).collect()
}

/// `f` over every item of `items` (mutably), on up to `threads` threads; the outputs in
/// item order.
pub fn map_slice_mut<T: Send, R: Send>(
    items: &mut [T],
    threads: usize,
    f: impl Fn(&mut T) -> R + Sync,
) -> Vec<R> {
    let threads = threads.max(1).min(items.len().max(1));
    if threads == 1 {
        return items.iter_mut().map(f).collect();
    }
    let chunk = items.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let workers: Vec<_> = items
            .chunks_mut(chunk)
            .map(|part| scope.spawn(|| part.iter_mut().map(&f).collect::<Vec<R>>()))
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_output_for_every_thread_count() {
        let one = map_ranges(1000, 1, |r| r.map(|i| i * i).collect());
        for threads in [2, 3, 8, 2000] {
            assert_eq!(map_ranges(1000, threads, |r| r.map(|i| i * i).collect()), one, "{threads} threads");
        }
        assert!(map_ranges(0, 4, |r| r.collect::<Vec<_>>()).is_empty());
        let mut items: Vec<usize> = (0..1000).collect();
        let squares = map_slice_mut(&mut items, 3, |i| {
            *i += 1;
            *i * *i
        });
        assert_eq!(squares, (1..=1000).map(|i| i * i).collect::<Vec<_>>());
    }
}
