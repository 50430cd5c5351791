//! What the Vulkan driver compiles each runtime pipeline to (`pipeline-stats`): the logged
//! WGSL converted to SPIR-V as wgpu's Vulkan backend converts it ([`spirv`]), its
//! descriptor layouts read from the shader ([`bindings`]), and a Vulkan device of our own
//! that compiles it and reports each executable's statistics through
//! `VK_KHR_pipeline_executable_properties` ([`vulkan`], [`statistic`]).

pub mod bindings;
pub mod spirv;
pub mod statistic;
pub mod vulkan;

/// Why a pipeline's statistics could not be had.
#[derive(Debug, thiserror::Error)]
pub enum PipelineStatsError {
    /// The Vulkan loader library could not be loaded.
    #[error(
        "cannot load the Vulkan loader (libvulkan.so.1 / vulkan-1.dll): {0}; `pipeline-stats` \
         compiles the pipelines with the Vulkan driver itself: install the loader and a driver \
         (apt install libvulkan1 and the GPU's driver) or run it on the GPU machine"
    )]
    NoVulkanLoader(String),
    /// A Vulkan call failed.
    #[error("Vulkan: {call} failed: {result}")]
    Vulkan { call: &'static str, result: ash::vk::Result },
    /// No physical device reports the extension and its feature.
    #[error(
        "no Vulkan device supports VK_KHR_pipeline_executable_properties with \
         pipelineExecutableInfo (devices: {})",
        if devices.is_empty() { "none".to_owned() } else { devices.join("; ") }
    )]
    NoDevice {
        /// Each device's name and why it was passed over.
        devices: Vec<String>,
    },
    /// The WGSL could not be turned into SPIR-V (parse, validation, constants, writer).
    #[error("pipeline `{label}`: {stage}: {reason}")]
    Shader { label: String, stage: &'static str, reason: String },
    /// A resource the shader declares has no Vulkan descriptor type here.
    #[error("pipeline `{label}`: binding @group({group}) @binding({binding}): {reason}")]
    Binding { label: String, group: u32, binding: u32, reason: String },
}

impl PipelineStatsError {
    /// A failed Vulkan `call`.
    pub fn vulkan(call: &'static str) -> impl FnOnce(ash::vk::Result) -> Self {
        move |result| Self::Vulkan { call, result }
    }
}
