//! One logged pipeline's WGSL to SPIR-V, as wgpu 30's Vulkan backend converts it: the
//! options of wgpu-hal's `vulkan/adapter.rs` (`naga_options`) changed per pipeline as its
//! `vulkan/device.rs` (`compile_stage`) changes them for our modules' runtime checks and
//! for pipelines without workgroup-memory zeroing.

use naga::back::spv;
use naga::proc::{BoundsCheckPolicies, BoundsCheckPolicy};
use naga::valid::{Capabilities, ValidationFlags, Validator};
use ppr_runtime::pipeline_log::PipelineSource;

use super::PipelineStatsError;
use super::bindings::{DescriptorBinding, binding_map, descriptor_bindings};

/// What of the Vulkan device changes the SPIR-V wgpu writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpirvTarget {
    /// The SPIR-V version: 1.0, 1.3, 1.5 or 1.6 for a Vulkan 1.0, 1.1, 1.2 or 1.3+ device.
    pub lang_version: (u8, u8),
    /// `robustBufferAccess2` is on: the driver checks buffer accesses, naga does not.
    pub robust_buffer_access2: bool,
    /// Image robustness is on (`robustImageAccess2` where `VK_EXT_robustness2` is, else
    /// `robustImageAccess`): the driver checks image loads, naga does not.
    pub robust_image_access: bool,
}

impl SpirvTarget {
    /// A Vulkan 1.3 device with both robustness features, as NVIDIA's drivers report.
    pub const VULKAN_1_3_ROBUST: Self =
        Self { lang_version: (1, 6), robust_buffer_access2: true, robust_image_access: true };

    /// The SPIR-V version wgpu writes for a device of Vulkan `api_version`.
    pub fn lang_version_for(api_version: u32) -> (u8, u8) {
        use ash::vk;
        match (vk::api_version_major(api_version), vk::api_version_minor(api_version)) {
            (1, 0) => (1, 0),
            (1, 1) => (1, 3),
            (1, 2) => (1, 5),
            _ => (1, 6),
        }
    }
}

/// A pipeline ready for Vulkan.
#[derive(Clone, Debug)]
pub struct CompiledPipeline {
    /// The SPIR-V of the entry point alone, overrides applied.
    pub words: Vec<u32>,
    /// Every resource the module declares (the pass's bind-group layout declares them all).
    pub bindings: Vec<DescriptorBinding>,
    /// Invocations per workgroup of the entry point.
    pub workgroup_threads: u32,
    /// Bytes of the workgroup variables the entry point refers to (overrides substituted;
    /// a branch they turn off still counts, though a driver drops it): what the code itself
    /// asks for, so that a driver's shared memory beyond it is its own (spills).
    pub declared_workgroup_bytes: u32,
}

/// naga's SPIR-V options for `target` with `checks` (what [`ppr_runtime::shader::create_module`]
/// asks of wgpu) and no workgroup-memory zeroing (what `compute_pipeline` asks).
pub fn spirv_options(target: &SpirvTarget, checks: &wgpu::ShaderRuntimeChecks) -> spv::Options<'static> {
    // wgpu-hal: index checks always, buffer and image-load checks unless the device's
    // robustness covers them; all unchecked when the module's runtime checks are off.
    let driver_checked = |robust: bool| {
        if robust { BoundsCheckPolicy::Unchecked } else { BoundsCheckPolicy::Restrict }
    };
    let bounds_check_policies = if checks.bounds_checks {
        BoundsCheckPolicies {
            index: BoundsCheckPolicy::Restrict,
            buffer: driver_checked(target.robust_buffer_access2),
            image_load: driver_checked(target.robust_image_access),
            binding_array: BoundsCheckPolicy::Unchecked,
        }
    } else {
        BoundsCheckPolicies {
            index: BoundsCheckPolicy::Unchecked,
            buffer: BoundsCheckPolicy::Unchecked,
            image_load: BoundsCheckPolicy::Unchecked,
            binding_array: BoundsCheckPolicy::Unchecked,
        }
    };
    spv::Options {
        lang_version: target.lang_version,
        // wgpu-hal: LABEL_VARYINGS (but on Qualcomm) and FORCE_POINT_SIZE; DEBUG only with
        // the instance's debug flag (names only: no change to the compiled code).
        flags: spv::WriterFlags::LABEL_VARYINGS | spv::WriterFlags::FORCE_POINT_SIZE,
        fake_missing_bindings: false,
        // Per pipeline (`compile_pipeline`), as wgpu-hal sets it from the pipeline layout.
        binding_map: spv::BindingMap::default(),
        // wgpu-hal lists the device's capabilities to refuse shaders that need others; the
        // written code is the same.
        capabilities: None,
        bounds_check_policies,
        zero_initialize_workgroup_memory: spv::ZeroInitializeWorkgroupMemoryMode::None,
        force_loop_bounding: checks.force_loop_bounding,
        ray_query_initialization_tracking: checks.ray_query_initialization_tracking,
        trace_ray_argument_validation: true,
        use_storage_input_output_16: false,
        debug_info: None,
        task_dispatch_limits: None,
        mesh_shader_primitive_indices_clamp: checks.mesh_shader_primitive_indices_clamp,
        emit_int_div_checks: checks.int_div_checks,
    }
}

/// Parses, validates, applies the override constants and writes the entry point's SPIR-V.
///
/// # Errors
/// [`PipelineStatsError::Shader`] naming the step that failed, or
/// [`PipelineStatsError::Binding`] for a resource with no descriptor type.
pub fn compile_pipeline(
    pipeline: &PipelineSource,
    options: &spv::Options<'_>,
) -> Result<CompiledPipeline, PipelineStatsError> {
    let source = &pipeline.source;
    let fail = |stage: &'static str, reason: String| PipelineStatsError::Shader {
        label: pipeline.label.clone(),
        stage,
        reason,
    };
    let module = naga::front::wgsl::parse_str(source).map_err(|e| fail("WGSL", e.emit_to_string(source)))?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| fail("validation", e.emit_to_string(source)))?;
    let constants: naga::back::PipelineConstants =
        pipeline.constants.iter().map(|(name, value)| (name.clone(), *value)).collect();
    let stage = naga::ShaderStage::Compute;
    let (module_with_constants, info) = naga::back::pipeline_constants::process_overrides(
        &module,
        &info,
        Some((stage, &pipeline.entry_point)),
        &constants,
    )
    .map_err(|e| fail("override constants", e.to_string()))?;
    // wgpu-hal: the pipeline layout's binding map, on a copy of the device's options.
    let bindings = descriptor_bindings(&module, &pipeline.label)?;
    let options = spv::Options { binding_map: binding_map(&bindings), ..options.clone() };
    let pipeline_options =
        spv::PipelineOptions { shader_stage: stage, entry_point: pipeline.entry_point.clone() };
    let words = spv::write_vec(&module_with_constants, &info, &options, Some(&pipeline_options))
        .map_err(|e| fail("SPIR-V", e.to_string()))?;
    let (workgroup_threads, declared_workgroup_bytes) =
        workgroup_use(&module_with_constants, &info, &pipeline.entry_point)
            .ok_or_else(|| fail("entry point", format!("no compute entry point {}", pipeline.entry_point)))?;
    Ok(CompiledPipeline { words, bindings, workgroup_threads, declared_workgroup_bytes })
}

/// The entry point's invocations per workgroup and the bytes of the workgroup variables it
/// uses (`None` without that entry point).
fn workgroup_use(module: &naga::Module, info: &naga::valid::ModuleInfo, entry: &str) -> Option<(u32, u32)> {
    let index = module.entry_points.iter().position(|e| e.name == entry)?;
    let threads = module.entry_points[index].workgroup_size.iter().product();
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).ok()?;
    let used = info.get_entry_point(index);
    let bytes = module
        .global_variables
        .iter()
        .filter(|(h, g)| g.space == naga::AddressSpace::WorkGroup && !used[*h].is_empty())
        .map(|(_, g)| layouter[g.ty].size)
        .sum();
    Some((threads, bytes))
}

/// Workgroups of `threads` invocations that fit on an NVIDIA multiprocessor of compute
/// capability 9.0 (H100, H200) by registers and threads alone: 64 Ki registers allocated
/// per warp in steps of 8 per invocation, at most 2 048 invocations and 32 workgroups
/// (shared memory not counted).
pub fn nvidia_sm90_workgroups_by_registers(registers: u32, threads: u32) -> u32 {
    let warps = threads.div_ceil(32).max(1);
    let per_warp = registers.max(1).next_multiple_of(8) * 32;
    let by_registers = 65_536 / (per_warp * warps);
    by_registers.min(2_048 / (warps * 32)).min(32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workgroups_per_multiprocessor_by_registers() {
        // 256 invocations: 48 registers leave 5, 40 (and 37, allocated as 40) 6, 32 8,
        // 61 (as 64) 4; 16 registers are bound by the 2 048 invocations.
        let cases = [(48, 5), (40, 6), (37, 6), (32, 8), (61, 4), (16, 8)];
        for (registers, workgroups) in cases {
            assert_eq!(nvidia_sm90_workgroups_by_registers(registers, 256), workgroups, "{registers}");
        }
        assert_eq!(nvidia_sm90_workgroups_by_registers(32, 64), 32, "the workgroup limit");
    }

    #[test]
    fn declared_workgroup_memory_counts_the_entry_point_s_variables_after_overrides() {
        let source = "
            override BIG: bool = true;
            var<workgroup> list: array<u32, 256>;
            var<workgroup> unused: array<u32, 1000>;
            var<workgroup> count: atomic<u32>;
            @group(0) @binding(0) var<storage, read_write> out: array<u32>;
            @compute @workgroup_size(16, 16)
            fn main(@builtin(local_invocation_index) i: u32) {
                if (BIG) { list[i] = i; }
                atomicAdd(&count, 1u);
                out[i] = atomicLoad(&count);
            }
            @compute @workgroup_size(64)
            fn other(@builtin(local_invocation_index) i: u32) { unused[i] = i; }";
        let pipeline = |entry: &str| PipelineSource {
            label: "test".into(),
            source: source.into(),
            entry_point: entry.into(),
            constants: vec![],
        };
        let options = spirv_options(&SpirvTarget::VULKAN_1_3_ROBUST, &ppr_runtime::shader::runtime_checks());
        let main = compile_pipeline(&pipeline("main"), &options).expect("compiles");
        assert_eq!((main.workgroup_threads, main.declared_workgroup_bytes), (256, 256 * 4 + 4));
        let other = compile_pipeline(&pipeline("other"), &options).expect("compiles");
        assert_eq!((other.workgroup_threads, other.declared_workgroup_bytes), (64, 4000));
    }

    /// Every pass of the runtime, with its WGSL's default constants, turns into SPIR-V.
    #[test]
    fn every_runtime_pass_converts_to_spirv() {
        let options = spirv_options(&SpirvTarget::VULKAN_1_3_ROBUST, &ppr_runtime::shader::runtime_checks());
        for (name, source) in ppr_runtime::shader::all_passes() {
            let module = naga::front::wgsl::parse_str(&source).expect("parses");
            for entry in &module.entry_points {
                let p = PipelineSource {
                    label: name.into(),
                    source: source.clone(),
                    entry_point: entry.name.clone(),
                    constants: Vec::new(),
                };
                let compiled = compile_pipeline(&p, &options).unwrap_or_else(|e| panic!("{e}"));
                assert_eq!(compiled.words.first(), Some(&0x0723_0203), "{name} {}", entry.name);
                assert!(!compiled.bindings.is_empty(), "{name}");
            }
        }
    }

    /// The runtime's checks as wgpu-hal applies them: index checks stay, buffer and image
    /// checks are the driver's where it is robust; loop bounding and division guards off.
    #[test]
    fn options_follow_the_runtime_checks_and_the_device() {
        let checks = ppr_runtime::shader::runtime_checks();
        let o = spirv_options(&SpirvTarget::VULKAN_1_3_ROBUST, &checks);
        assert_eq!(o.lang_version, (1, 6));
        assert_eq!(o.bounds_check_policies.index, BoundsCheckPolicy::Restrict);
        assert_eq!(o.bounds_check_policies.buffer, BoundsCheckPolicy::Unchecked);
        assert!(!o.force_loop_bounding && !o.emit_int_div_checks);
        assert_eq!(o.zero_initialize_workgroup_memory, spv::ZeroInitializeWorkgroupMemoryMode::None);
        let plain =
            SpirvTarget { lang_version: (1, 5), robust_buffer_access2: false, robust_image_access: false };
        let o = spirv_options(&plain, &checks);
        assert_eq!(o.bounds_check_policies.buffer, BoundsCheckPolicy::Restrict);
        assert_eq!(o.bounds_check_policies.image_load, BoundsCheckPolicy::Restrict);
        assert_eq!(SpirvTarget::lang_version_for(ash::vk::API_VERSION_1_2), (1, 5));
        assert_eq!(SpirvTarget::lang_version_for(ash::vk::make_api_version(0, 1, 4, 0)), (1, 6));
    }
}
