//! `pipeline-stats` without Vulkan (CI has none): the runtime's pipeline log over one 64×36
//! frame of the demo level (llvmpipe through GL where there is no GPU), every logged
//! pipeline's WGSL turned into SPIR-V that naga's own SPIR-V front end reads back, and the
//! projection's descriptor layout as the tool derives it.

use std::path::PathBuf;

use ppr_bench::config::{BenchConfig, Resolution};
use ppr_bench::pipeline_stats::bindings::DescriptorKind;
use ppr_bench::pipeline_stats::spirv::{SpirvTarget, compile_pipeline, spirv_options};
use ppr_bench::suites::pipeline_stats::{PipelineStatsConfig, log_pipelines};
use ppr_runtime::pipeline_log::PipelineSource;
use ppr_testbed::GpuContext;

fn constant(p: &PipelineSource, name: &str) -> Option<f64> {
    p.constants.iter().find(|(n, _)| n == name).map(|&(_, v)| v)
}

#[test]
fn logged_runtime_pipelines_convert_to_spirv_with_their_layouts() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = tempfile::tempdir().expect("temp dir");
    let cfg = BenchConfig::full(out.path().into(), root.clone(), root.join("../shared/scenes"));
    let pc = PipelineStatsConfig {
        scenes: vec!["demo".into()],
        resolution: Resolution { width: 64, height: 36 },
        max_cameras: 1,
        projection_variants: true,
    };
    let logged = log_pipelines(&gpu, &cfg, &pc).expect("one frame of the demo level");
    assert_eq!(logged.frames, 1, "{:?}", logged.notes);
    let labels: Vec<&str> = logged.pipelines.iter().map(|p| p.label.as_str()).collect();
    eprintln!("{} distinct pipelines: {labels:?}", labels.len());

    // The two hot passes are logged with their whole WGSL and their constants.
    let with_prefix = |prefix: &str| -> Vec<&PipelineSource> {
        logged.pipelines.iter().filter(|p| p.label.starts_with(prefix)).collect()
    };
    let projection = with_prefix("ppr projection");
    // The frame's own variant, and every one of `projection_variants` besides.
    let variants = ppr_bench::suites::pipeline_stats::projection_variants();
    assert!(projection.len() > variants.len(), "{} projection pipelines", projection.len());
    for v in &variants {
        let label = format!("ppr projection {v:?}");
        assert!(projection.iter().any(|p| p.label == label), "{label} not logged");
    }
    let no_layers = with_prefix("ppr tile classify (no layers)");
    assert_eq!(no_layers.len(), 1, "{labels:?}");
    assert_eq!(constant(no_layers[0], "LAYERS"), Some(0.0));
    // Every upsample variant: the per-pixel ones the renderer builds, the shared ones built
    // on request.
    let upsample = with_prefix("ppr upsample");
    assert_eq!(upsample.len(), 8, "{labels:?}");
    for shared in [0.0, 1.0] {
        let n = upsample.iter().filter(|p| constant(p, "SHARED") == Some(shared)).count();
        assert_eq!(n, 4, "SHARED={shared}: {labels:?}");
    }
    let reflection = with_prefix("ppr reflection");
    assert!(!projection.is_empty() && !reflection.is_empty(), "{labels:?}");
    for p in projection.iter().chain(&reflection) {
        assert!(p.source.contains("struct FrameUniforms"), "{}: the shared modules are in", p.label);
        assert!(p.source.contains(&format!("fn {}(", p.entry_point)), "{}: {}", p.label, p.entry_point);
    }
    for p in &projection {
        assert_eq!(p.entry_point, "main");
        assert!(constant(p, "TILE_CULLING").is_some() && constant(p, "ABLATION").is_some(), "{}", p.label);
    }
    assert!(projection.iter().any(|p| constant(p, "ABLATION") == Some(0.0)), "the frame's own variant");
    for p in &reflection {
        assert!(["main", "main_quads"].contains(&p.entry_point.as_str()), "{}", p.entry_point);
        assert!(constant(p, "GLOSSY").is_some() && constant(p, "INDIRECT").is_some(), "{:?}", p.constants);
    }

    // Every pipeline becomes SPIR-V that naga's SPIR-V front end reads back, with its entry
    // point alone. (Not validated again: that front end turns valid SPIR-V, such as a
    // logical and of bool vectors, into IR that naga's validator refuses.)
    let options = spirv_options(&SpirvTarget::VULKAN_1_3_ROBUST, &ppr_runtime::shader::runtime_checks());
    for p in &logged.pipelines {
        let compiled = compile_pipeline(p, &options).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(compiled.words[..2], [0x0723_0203, 0x0001_0600], "{}: SPIR-V 1.6 header", p.label);
        let bytes: Vec<u8> = compiled.words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let module = naga::front::spv::parse_u8_slice(&bytes, &naga::front::spv::Options::default())
            .unwrap_or_else(|e| panic!("{}: naga cannot read the SPIR-V back: {e}", p.label));

        let entries: Vec<&str> = module.entry_points.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(entries, [p.entry_point.as_str()], "{}: the entry point alone", p.label);
        // The upsample's span arrays (18 × 18 colours and distances) only where SHARED reads
        // them: the per-pixel pipelines, every renderer's, declare one element of each.
        if p.label.starts_with("ppr upsample") {
            let bytes = compiled.declared_workgroup_bytes;
            let shared = constant(p, "SHARED") == Some(1.0);
            assert_eq!(bytes, if shared { 18 * 18 * 20 } else { 20 }, "{}", p.label);
        }
    }

    // The workgroup memory the code declares: the fused list (256 words) and the box slots
    // in the projection with fused lists, none in the reflection pass; 256 invocations each.
    for p in projection.iter().chain(&reflection) {
        let compiled = compile_pipeline(p, &options).expect("converts");
        assert_eq!(compiled.workgroup_threads, 256, "{}", p.label);
        let fused = constant(p, "FUSED_LISTS") == Some(1.0) && constant(p, "TILE_CULLING") == Some(1.0);
        if p.label.starts_with("ppr reflection") {
            assert_eq!(compiled.declared_workgroup_bytes, 0, "{}", p.label);
        } else if fused {
            assert!(
                compiled.declared_workgroup_bytes > 1024,
                "{}: {}",
                p.label,
                compiled.declared_workgroup_bytes
            );
        }
    }

    // The projection's resources, as `ProjectionPass::new` lays them out.
    use DescriptorKind::{SampledImage, StorageBuffer, UniformBuffer};
    let compiled = compile_pipeline(projection[0], &options).expect("converts");
    let kinds: Vec<(u32, u32, u32, DescriptorKind)> =
        compiled.bindings.iter().map(|b| (b.group, b.binding, b.vk_binding, b.kind)).collect();
    let mut expected = vec![(0, 0, 0, UniformBuffer), (0, 1, 1, SampledImage)];
    expected.extend((2..=11).map(|b| (0, b, b, StorageBuffer)));
    expected.extend([(0, 12, 12, UniformBuffer), (0, 13, 13, StorageBuffer), (0, 14, 14, StorageBuffer)]);
    assert_eq!(kinds, expected);
}
