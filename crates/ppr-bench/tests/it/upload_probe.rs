//! The upload probe times every variant where the adapter writes timestamps between passes,
//! and none where it cannot.

use ppr_bench::upload_probe::{Upload, run_upload_probe};
use ppr_testbed::GpuContext;

#[test]
fn the_upload_probe_times_every_variant_where_the_adapter_can() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let rows = run_upload_probe(&gpu.device, &gpu.queue, 3);
    let needed = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
    if !gpu.device.features().contains(needed) {
        assert!(rows.is_empty(), "no encoder timestamps, no rows: {rows:?}");
        return;
    }
    // Timers that report an end before the begin (llvmpipe's GL ones, now and then) leave a
    // variant out; the others are all there, in order, with their copy counts.
    assert!(!rows.is_empty(), "every run's timestamps unusable");
    let labels: Vec<String> = Upload::ALL.iter().map(|u| u.label()).collect();
    let mut at = 0;
    for r in &rows {
        let i = labels[at..].iter().position(|l| *l == r.variant).expect("a variant, in order") + at;
        assert_eq!(r.copies, Upload::ALL[i].copies(), "{}", r.variant);
        assert!(r.median_ms.is_finite() && r.median_ms >= 0.0, "{r:?}");
        at = i + 1;
    }
}
