//! Assembles each pass's WGSL with the shared modules (WGSL has no `#include`).
//!
//! Every pass gets `encoding.wgsl` and `common.wgsl`; passes that declare
//! `frame: FrameUniforms` may add [`VIEW`]; the tile-culling passes add [`TILE_TEST`], the
//! reflection passes [`SHADING`].

/// The shared declarations every pass sees: encoding, then frame and shape types.
const SHARED: &str =
    concat!(include_str!("../shaders/encoding.wgsl"), "\n", include_str!("../shaders/common.wgsl"), "\n");

/// Pixel ↔ camera-relative position and depth validity (needs `frame`).
pub const VIEW: &str = include_str!("../shaders/view.wgsl");

/// Tile culling: the box test, the tile box, ordered compaction, the super-tile grid
/// (needs `frame`, `depth_tex` and [`VIEW`]).
pub const TILE_TEST: &str = include_str!("../shaders/tile_test.wgsl");

/// Subgroup culling's subgroup box, lane and ballot, with subgroup operations (only on
/// devices with [`wgpu::Features::SUBGROUP`]; needs [`TILE_TEST`]).
pub const SUBGROUP_CULL: &str = include_str!("../shaders/subgroup_cull.wgsl");

/// The same functions as [`SUBGROUP_CULL`] for a subgroup of one invocation (any device).
pub const SUBGROUP_CULL_FALLBACK: &str = include_str!("../shaders/subgroup_cull_fallback.wgsl");

/// The projection's own block lists (its fused variants: workgroup memory; needs
/// [`TILE_TEST`]).
pub const FUSED_LISTS: &str = include_str!("../shaders/fused_lists.wgsl");

/// The same functions as [`FUSED_LISTS`] for the projection's other variants, which never
/// call them: no workgroup memory.
pub const FUSED_LISTS_STUB: &str = include_str!("../shaders/fused_lists_stub.wgsl");

/// The projection's occupancy pad (bench only: workgroup memory no frame uses; needs
/// `OCCUPANCY_PAD_WORDS`, `frame` and the projection's `intermediate`).
pub const OCCUPANCY_PAD: &str = include_str!("../shaders/occupancy_pad.wgsl");

/// Hole filling, sampling, anti-bleeding (needs `frame`, `color_tex`, `linear_sampler`
/// and [`VIEW`]).
pub const SHADING: &str = include_str!("../shaders/shading.wgsl");

/// Glossy reflections: the reflector lookup and the lobe's taps (needs `frame`,
/// `color_tex`, `linear_sampler`, `depth_tex`, `glossy`, `valid_depth_at`, [`VIEW`] and
/// [`SHADING`]).
pub const GLOSSY: &str = include_str!("../shaders/glossy.wgsl");

/// The source of a pass: the shared modules, then `modules`, then the pass itself.
pub fn source_with(modules: &[&str], pass: &str) -> String {
    let mut s =
        String::with_capacity(SHARED.len() + pass.len() + modules.iter().map(|m| m.len() + 1).sum::<usize>());
    s.push_str(SHARED);
    for m in modules {
        s.push_str(m);
        s.push('\n');
    }
    s.push_str(pass);
    s
}

/// The source of a pass (or a test kernel) with only the shared modules.
pub fn source(pass: &str) -> String {
    source_with(&[], pass)
}

/// Creates the shader module of a pass with extra shared modules.
pub fn module_with(device: &wgpu::Device, label: &str, modules: &[&str], pass: &str) -> wgpu::ShaderModule {
    create_module(device, label, source_with(modules, pass))
}

/// The environment variable that gives every module wgpu's full runtime checks again
/// (`PPR_SHADER_CHECKS=checked`): to compare their cost, or to rule them out.
pub const CHECKS_ENV: &str = "PPR_SHADER_CHECKS";

/// The runtime checks wgpu adds to our shaders. Bounds checks stay (the data comes from
/// reflector files and the frame); two checks that guard against code we do not write are
/// left out, because they cost instructions in the hottest loops (the parallel trees'
/// walk runs 50 iterations a pixel):
/// - loop bounding (a counter in every loop): every loop of these shaders ends by
///   construction (counted loops, and walks of a complete binary tree in heap order,
///   whose node index only moves forward);
/// - integer-division guards: every divisor is a positive constant, a tile count of a
///   non-empty viewport, the upsample's span of reduced samples (at least one), or, in the
///   encoding, positive by its own test (`o.y > 0`, `den >= 65536`), and no signed
///   division divides by -1.
///
/// With [`CHECKS_ENV`] set to `checked`, every check.
pub fn runtime_checks() -> wgpu::ShaderRuntimeChecks {
    runtime_checks_for(std::env::var(CHECKS_ENV).ok().as_deref())
}

fn runtime_checks_for(env: Option<&str>) -> wgpu::ShaderRuntimeChecks {
    if env == Some("checked") {
        return wgpu::ShaderRuntimeChecks::checked();
    }
    // Every check off (wgpu 30's integer-division guards among them; wgpu 29 has none),
    // then those that stay back on (the fields both versions have).
    let mut checks = wgpu::ShaderRuntimeChecks::unchecked();
    checks.bounds_checks = true;
    checks.ray_query_initialization_tracking = true;
    checks.task_shader_dispatch_tracking = true;
    checks.mesh_shader_primitive_indices_clamp = true;
    checks
}

/// Creates a module of our own WGSL `source` with [`runtime_checks`] (what every pass of
/// this crate and the baselines use).
pub fn create_module(device: &wgpu::Device, label: &str, source: String) -> wgpu::ShaderModule {
    #[cfg(feature = "pipeline-log")]
    let logged = crate::pipeline_log::is_on().then(|| source.clone());
    let desc =
        wgpu::ShaderModuleDescriptor { label: Some(label), source: wgpu::ShaderSource::Wgsl(source.into()) };
    // SAFETY: the checks left out are the two `runtime_checks` names; the shaders are this
    // crate's and the baselines', whose loops all end and whose integer divisors are all
    // positive (see `runtime_checks`).
    let module = unsafe { device.create_shader_module_trusted(desc, runtime_checks()) };
    #[cfg(feature = "pipeline-log")]
    if let Some(source) = logged {
        crate::pipeline_log::remember_module(&module, source);
    }
    module
}

/// Creates the shader module of a pass (or a test kernel) with only the shared modules.
pub fn module(device: &wgpu::Device, label: &str, pass: &str) -> wgpu::ShaderModule {
    module_with(device, label, &[], pass)
}

/// Every pass's WGSL with the modules it is built with (for validation).
pub fn all_passes() -> Vec<(&'static str, String)> {
    use crate::passes::*;
    let no_pad = projection::occupancy_pad_source(0);
    let pad = projection::occupancy_pad_source(256);
    vec![
        ("clear", source(clear::WGSL)),
        ("tile classify", source_with(&[VIEW], tile_classify::WGSL)),
        ("super-tile lists", source_with(&[VIEW, TILE_TEST], super_tile_lists::WGSL)),
        ("block lists", source_with(&[VIEW, TILE_TEST], block_lists::WGSL)),
        (
            "projection",
            source_with(
                &[VIEW, TILE_TEST, SUBGROUP_CULL_FALLBACK, FUSED_LISTS_STUB, &no_pad],
                projection::WGSL,
            ),
        ),
        (
            "projection (subgroups)",
            source_with(&[VIEW, TILE_TEST, SUBGROUP_CULL, FUSED_LISTS_STUB, &no_pad], projection::WGSL),
        ),
        (
            "projection (fused lists)",
            source_with(&[VIEW, TILE_TEST, SUBGROUP_CULL_FALLBACK, FUSED_LISTS, &no_pad], projection::WGSL),
        ),
        (
            "projection (fused lists, occupancy pad)",
            source_with(&[VIEW, TILE_TEST, SUBGROUP_CULL_FALLBACK, FUSED_LISTS, &pad], projection::WGSL),
        ),
        (
            "projection (subgroups, fused lists)",
            source_with(&[VIEW, TILE_TEST, SUBGROUP_CULL, FUSED_LISTS, &no_pad], projection::WGSL),
        ),
        ("reflection", source_with(&[VIEW, SHADING, GLOSSY], reflection::WGSL)),
        ("layer reflection", source_with(&[VIEW, SHADING], layer_reflection::WGSL)),
        ("downsample", source_with(&[VIEW], downsample::WGSL)),
        ("upsample", source_with(&[VIEW, upsample::SPAN_STUB], upsample::WGSL)),
        ("upsample (shared)", source_with(&[VIEW, upsample::SPAN], upsample::WGSL)),
    ]
}

#[cfg(test)]
mod tests {
    /// Loop bounding and integer-division guards are left out unless the environment asks
    /// for every check; bounds checks always stay.
    #[test]
    fn runtime_checks_leave_out_two_checks_unless_asked() {
        let all = format!("{:?}", wgpu::ShaderRuntimeChecks::checked());
        for env in [None, Some(""), Some("trusted")] {
            let c = super::runtime_checks_for(env);
            assert!(
                c.bounds_checks && c.ray_query_initialization_tracking && !c.force_loop_bounding,
                "{env:?}"
            );
            // wgpu 30's integer-division guards are off too (wgpu 29 has none).
            assert!(!format!("{c:?}").contains("int_div_checks: true"), "{env:?}: {c:?}");
            assert_ne!(format!("{c:?}"), all);
        }
        assert_eq!(format!("{:?}", super::runtime_checks_for(Some("checked"))), all);
    }

    /// Every pass parses and validates (clear messages without a GPU).
    #[test]
    fn every_pass_validates() {
        for (name, source) in super::all_passes() {
            let module = naga::front::wgsl::parse_str(&source)
                .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::all(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
        }
    }

    /// The size of the WGSL struct `name` in `module`.
    fn struct_size(module: &naga::Module, name: &str) -> usize {
        module
            .types
            .iter()
            .find_map(|(_, t)| match &t.inner {
                naga::TypeInner::Struct { span, .. } if t.name.as_deref() == Some(name) => {
                    Some(*span as usize)
                }
                _ => None,
            })
            .unwrap_or_else(|| panic!("no struct {name} in the WGSL"))
    }

    /// The WGSL structs the Rust side uploads have the sizes of their `#[repr(C)]` mirrors
    /// (a field added on one side only would shift every field after it).
    #[test]
    fn shared_structs_match_their_rust_mirrors() {
        use crate::gpu_types::{FrameUniforms, GpuLayer, GpuShape};
        let source = super::source("");
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        let size = |name: &str| struct_size(&module, name);
        assert_eq!(size("FrameUniforms"), std::mem::size_of::<FrameUniforms>());
        assert_eq!(size("Shape"), std::mem::size_of::<GpuShape>());
        assert_eq!(size("Layer"), std::mem::size_of::<GpuLayer>());
        assert_eq!(size("EncodingParams"), std::mem::size_of::<crate::encoding::EncodingParams>());
    }

    /// The constants both sides use have the same values (flags, kinds, tile and block
    /// sizes, list capacities, the encoding's bit counts), and the shape tests and the
    /// uniform copy of them have their Rust sizes.
    #[test]
    fn wgsl_constants_match_rust() {
        use crate::encoding::{CLEAR_VALUE, FRACTION_SCALE_NUMERATOR, OFFSET_SUBPIXEL_BITS, TANGENT_BITS};
        use crate::gpu_types::*;
        use crate::passes::block_lists::BLOCK_LIST_CAPACITY;
        use crate::passes::projection::BLOCK;
        use crate::passes::super_tile_lists::{SUPER_LIST_CAPACITY, SUPER_TILE};
        use naga::Literal::{I32, U32};
        use ppr_format::ReflectorKind;

        let source = super::source_with(
            &[
                super::VIEW,
                super::TILE_TEST,
                super::SUBGROUP_CULL_FALLBACK,
                super::FUSED_LISTS_STUB,
                &crate::passes::projection::occupancy_pad_source(0),
            ],
            crate::passes::projection::WGSL,
        );
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        let constant = |name: &str| {
            let c = module
                .constants
                .iter()
                .find(|(_, c)| c.name.as_deref() == Some(name))
                .unwrap_or_else(|| panic!("no constant {name}"))
                .1;
            match module.global_expressions[c.init] {
                naga::Expression::Literal(l) => l,
                ref e => panic!("{name} is not a literal: {e:?}"),
            }
        };
        let expected = [
            ("PPR_FLAG_HOLES", U32(FLAG_HOLES)),
            ("PPR_FLAG_FILTERING", U32(FLAG_FILTERING)),
            ("PPR_FLAG_ANTI_BLEEDING", U32(FLAG_ANTI_BLEEDING)),
            ("PPR_FLAG_OCCLUDER_TESTS", U32(FLAG_OCCLUDER_TESTS)),
            ("PPR_FLAG_WRITE_LAST", U32(FLAG_WRITE_LAST)),
            ("PPR_FLAG_WRITE_MAX", U32(FLAG_WRITE_MAX)),
            ("PPR_FLAG_WATER_STRETCH", U32(FLAG_WATER_STRETCH)),
            ("PPR_FLAG_REPLACE_FAR", U32(FLAG_REPLACE_FAR)),
            ("PPR_SHAPE_OCCLUDES", U32(SHAPE_OCCLUDES)),
            ("PPR_KIND_OPAQUE", U32(kind_code(ReflectorKind::Opaque))),
            ("PPR_KIND_TRANSPARENT", U32(kind_code(ReflectorKind::Transparent))),
            ("PPR_KIND_WATER", U32(kind_code(ReflectorKind::Water))),
            ("PPR_CLEAR_VALUE", U32(CLEAR_VALUE)),
            ("PPR_OFFSET_SUBPIXEL_BITS", U32(OFFSET_SUBPIXEL_BITS)),
            ("PPR_TANGENT_BITS", U32(TANGENT_BITS)),
            ("PPR_FRACTION_SCALE_NUMERATOR", I32(FRACTION_SCALE_NUMERATOR)),
            ("BLOCK_SIZE", U32(BLOCK)),
            ("QUARTER", U32(BLOCK / 2)),
            ("BLOCK_LIST_CAPACITY", U32(BLOCK_LIST_CAPACITY)),
            ("SUPER_TILE_SIZE", U32(SUPER_TILE)),
            ("SUPER_LIST_CAPACITY", U32(SUPER_LIST_CAPACITY)),
            ("GROUP_TEST_FLAG", U32(crate::plane_groups::GROUP_TEST_FLAG)),
            ("GROUP_RECT_WORDS", U32(crate::plane_groups::RECT_WORDS as u32)),
        ];
        for (name, value) in expected {
            assert_eq!(constant(name), value, "{name}");
        }
        // The projection's workgroup is 16 x 16 threads of four pixels: one block.
        let entry = module.entry_points.iter().find(|e| e.name == "main").expect("projection main");
        assert_eq!(entry.workgroup_size, [crate::passes::TILE, crate::passes::TILE, 1]);
        assert_eq!(crate::passes::TILE * 2, BLOCK);
        // The uniform copy of the shape tests: `array<ShapeTest, N>` with N the plan's capacity.
        let uniform_tests = module
            .global_variables
            .iter()
            .find(|(_, g)| g.name.as_deref() == Some("uniform_tests"))
            .expect("uniform_tests")
            .1;
        let size = module.types[uniform_tests.ty].inner.size(module.to_ctx()) as usize;
        assert_eq!(size, crate::plan::UNIFORM_TESTS_CAPACITY * std::mem::size_of::<GpuShapeTest>());
        let test_size = struct_size(&module, "ShapeTest");
        assert_eq!(test_size, std::mem::size_of::<GpuShapeTest>());
    }

    /// The classification's tile and block edges are the ones the Rust side dispatches and
    /// reads by: its tiles are the reflection's and clear's 16 × 16 ([`crate::passes::TILE`]),
    /// its workgroup one 32 × 32 block of 2 × 2 tiles ([`crate::passes::projection::BLOCK`],
    /// the grid `TileClassifyPass::encode` dispatches), 16 × 16 threads.
    #[test]
    fn classification_constants_match_rust() {
        use naga::Literal::U32;
        let source = super::source_with(&[super::VIEW], crate::passes::tile_classify::WGSL);
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        let constant = |name: &str| {
            let c = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name));
            let c = c.unwrap_or_else(|| panic!("no constant {name}")).1;
            module.global_expressions[c.init].clone()
        };
        let tile = crate::passes::TILE;
        let block = crate::passes::projection::BLOCK;
        assert!(matches!(constant("TILE_SIZE"), naga::Expression::Literal(U32(n)) if n == tile));
        assert!(matches!(constant("BLOCK_SIZE"), naga::Expression::Literal(U32(n)) if n == block));
        assert_eq!(block, 2 * tile, "a block is 2 x 2 tiles");
        let entry = module.entry_points.iter().find(|e| e.name == "classify").expect("classify");
        assert_eq!(entry.workgroup_size, [tile, tile, 1]);
    }

    /// The glossy uniform of the reflection pass has its Rust size and capacity.
    #[test]
    fn glossy_uniform_matches_rust() {
        use crate::gpu_types::{GLOSSY_CAPACITY, GpuGlossyShape, GpuGlossyShapes};
        let source = super::source_with(
            &[super::VIEW, super::SHADING, super::GLOSSY],
            crate::passes::reflection::WGSL,
        );
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        let size = |name: &str| struct_size(&module, name);
        assert_eq!(size("GlossyShape"), std::mem::size_of::<GpuGlossyShape>());
        assert_eq!(size("GlossyShapes"), std::mem::size_of::<GpuGlossyShapes>());
        let capacity = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some("GLOSSY_CAPACITY"))
            .map(|(_, c)| module.global_expressions[c.init].clone())
            .expect("GLOSSY_CAPACITY");
        assert!(
            matches!(capacity, naga::Expression::Literal(naga::Literal::U32(n)) if n as usize == GLOSSY_CAPACITY),
            "{capacity:?}"
        );
    }
}
