//! The descriptor set layouts of a pipeline, read from its shader: every global resource's
//! group, binding and kind, as wgpu's bind-group layouts give them to Vulkan.

use naga::{AddressSpace, ImageClass, TypeInner};

use super::PipelineStatsError;

/// The Vulkan descriptor type a resource binds as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DescriptorKind {
    /// `var<uniform>`.
    UniformBuffer,
    /// `var<storage, …>`.
    StorageBuffer,
    /// A sampled (or depth) texture: `texture_2d<f32>`, `texture_depth_2d`, …
    SampledImage,
    /// A storage texture: `texture_storage_2d<…>`.
    StorageImage,
    /// `sampler` or `sampler_comparison`.
    Sampler,
}

impl DescriptorKind {
    /// The Vulkan descriptor type (wgpu binds textures and samplers separately).
    pub fn vk(self) -> ash::vk::DescriptorType {
        use ash::vk::DescriptorType as D;
        match self {
            Self::UniformBuffer => D::UNIFORM_BUFFER,
            Self::StorageBuffer => D::STORAGE_BUFFER,
            Self::SampledImage => D::SAMPLED_IMAGE,
            Self::StorageImage => D::STORAGE_IMAGE,
            Self::Sampler => D::SAMPLER,
        }
    }
}

/// One resource of the shader.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct DescriptorBinding {
    pub group: u32,
    /// The WGSL `@binding`.
    pub binding: u32,
    /// The Vulkan binding: wgpu numbers a group's entries 0, 1, 2, … in binding order.
    pub vk_binding: u32,
    pub kind: DescriptorKind,
    /// Descriptors at this binding (the size of a binding array; 1 otherwise).
    pub count: u32,
    /// The WGSL name, for messages.
    pub name: String,
}

/// Every resource `module` declares, sorted by group and binding, numbered in each group
/// as wgpu-hal's Vulkan backend numbers them.
///
/// # Errors
/// [`PipelineStatsError::Binding`] for a resource with no descriptor type here (external
/// textures, acceleration structures, unsized binding arrays).
pub fn descriptor_bindings(
    module: &naga::Module,
    label: &str,
) -> Result<Vec<DescriptorBinding>, PipelineStatsError> {
    let mut out = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = var.binding else { continue };
        let fail = |reason: String| PipelineStatsError::Binding {
            label: label.to_owned(),
            group: rb.group,
            binding: rb.binding,
            reason,
        };
        let (inner, count) = match module.types[var.ty].inner {
            TypeInner::BindingArray { base, size } => {
                let n = match size {
                    naga::ArraySize::Constant(n) => n.get(),
                    _ => return Err(fail("a binding array without a constant size".into())),
                };
                (&module.types[base].inner, n)
            }
            ref inner => (inner, 1),
        };
        let kind = match var.space {
            AddressSpace::Uniform => DescriptorKind::UniformBuffer,
            AddressSpace::Storage { .. } => DescriptorKind::StorageBuffer,
            AddressSpace::Handle => match *inner {
                TypeInner::Sampler { .. } => DescriptorKind::Sampler,
                TypeInner::Image { class: ImageClass::Sampled { .. } | ImageClass::Depth { .. }, .. } => {
                    DescriptorKind::SampledImage
                }
                TypeInner::Image { class: ImageClass::Storage { .. }, .. } => DescriptorKind::StorageImage,
                ref other => return Err(fail(format!("no descriptor type for {other:?}"))),
            },
            other => return Err(fail(format!("a resource in address space {other:?}"))),
        };
        let name = var.name.clone().unwrap_or_default();
        out.push(DescriptorBinding {
            group: rb.group,
            binding: rb.binding,
            vk_binding: 0,
            kind,
            count,
            name,
        });
    }
    out.sort();
    for i in 0..out.len() {
        let first_of_group = i == 0 || out[i - 1].group != out[i].group;
        out[i].vk_binding = if first_of_group { 0 } else { out[i - 1].vk_binding + 1 };
    }
    Ok(out)
}

/// The binding map wgpu-hal gives naga: each resource's descriptor set and Vulkan binding.
pub fn binding_map(bindings: &[DescriptorBinding]) -> naga::back::spv::BindingMap {
    bindings
        .iter()
        .map(|b| {
            let info = naga::back::spv::BindingInfo {
                descriptor_set: b.group,
                binding: b.vk_binding,
                binding_array_size: (b.count > 1).then_some(b.count),
            };
            (naga::ResourceBinding { group: b.group, binding: b.binding }, info)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(wgsl: &str) -> Vec<(u32, u32, u32, DescriptorKind)> {
        let module = naga::front::wgsl::parse_str(wgsl).expect("WGSL parses");
        let bindings = descriptor_bindings(&module, "test").expect("bindings");
        bindings.iter().map(|b| (b.group, b.binding, b.vk_binding, b.kind)).collect()
    }

    #[test]
    fn each_resource_kind_maps_to_its_descriptor_type() {
        let wgsl = "
            @group(1) @binding(0) var<uniform> u: vec4<f32>;
            @group(0) @binding(3) var<storage, read_write> s: array<u32>;
            @group(0) @binding(1) var t: texture_2d<f32>;
            @group(0) @binding(2) var d: texture_depth_2d;
            @group(0) @binding(0) var samp: sampler;
            @group(0) @binding(7) var o: texture_storage_2d<rgba16float, write>;
            @compute @workgroup_size(1) fn main() {}
        ";
        use DescriptorKind::*;
        assert_eq!(
            kinds(wgsl),
            [
                (0, 0, 0, Sampler),
                (0, 1, 1, SampledImage),
                (0, 2, 2, SampledImage),
                (0, 3, 3, StorageBuffer),
                (0, 7, 4, StorageImage),
                (1, 0, 0, UniformBuffer)
            ]
        );
    }
}
