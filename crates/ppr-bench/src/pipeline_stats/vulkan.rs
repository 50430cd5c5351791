//! A Vulkan device of our own (ash, the version wgpu-hal links) that compiles SPIR-V compute
//! pipelines with `VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR` and reads what the driver
//! reports of each executable (`VK_KHR_pipeline_executable_properties`). The device enables
//! the robustness features wgpu's Vulkan backend enables, which change the driver's code.

use std::ffi::{CStr, CString};

use ash::{ext, khr, vk};

use super::PipelineStatsError;
use super::spirv::{CompiledPipeline, SpirvTarget};
use super::statistic::{ExecutableStats, StatValue, Statistic};

/// The instance, the device and the extension's functions.
pub struct StatsDevice {
    // Kept loaded for the instance and device (dropped after them).
    _entry: ash::Entry,
    instance: ash::Instance,
    device: ash::Device,
    executables: khr::pipeline_executable_properties::Device,
    /// The device's name, type, Vulkan version and driver.
    pub description: String,
    /// What of the device changes the SPIR-V wgpu would write for it.
    pub target: SpirvTarget,
    /// Stages may run with any subgroup size (what wgpu asks where it has subgroups).
    varying_subgroup_size: bool,
}

/// A physical device that has the extension, and what it supports of wgpu's features.
struct Candidate {
    physical: vk::PhysicalDevice,
    description: String,
    cpu: bool,
    api_version: u32,
    queue_family: u32,
    robust_buffer_access: bool,
    /// `VK_EXT_robustness2`'s features, where it has the extension.
    robustness2: Option<(bool, bool)>,
    /// Vulkan 1.3's `robustImageAccess` and `subgroupSizeControl`, on a 1.3 device.
    vulkan13: Option<(bool, bool)>,
}

impl StatsDevice {
    /// Opens the first device with `VK_KHR_pipeline_executable_properties` and its
    /// `pipelineExecutableInfo` feature, a GPU before a CPU implementation.
    ///
    /// # Errors
    /// No Vulkan loader, no such device, or a failing Vulkan call.
    pub fn open() -> Result<Self, PipelineStatsError> {
        // SAFETY: loading the system's Vulkan loader runs its initialisation, as any Vulkan
        // application does.
        let entry =
            unsafe { ash::Entry::load() }.map_err(|e| PipelineStatsError::NoVulkanLoader(e.to_string()))?;
        // SAFETY: a valid entry; no other Vulkan object yet.
        let loader = unsafe { entry.try_enumerate_instance_version() }
            .map_err(PipelineStatsError::vulkan("vkEnumerateInstanceVersion"))?
            .unwrap_or(vk::API_VERSION_1_0);
        let api_version = loader.min(vk::API_VERSION_1_3);
        if api_version < vk::API_VERSION_1_1 {
            return Err(PipelineStatsError::NoDevice { devices: vec!["the Vulkan loader is 1.0".into()] });
        }
        let app = vk::ApplicationInfo::default()
            .application_name(c"ppr-bench pipeline-stats")
            .api_version(api_version);
        // SAFETY: a valid create info without layers or extensions.
        let instance =
            unsafe { entry.create_instance(&vk::InstanceCreateInfo::default().application_info(&app), None) }
                .map_err(PipelineStatsError::vulkan("vkCreateInstance"))?;
        match open_device(&instance, api_version) {
            Ok((device, description, target, varying_subgroup_size)) => {
                let executables = khr::pipeline_executable_properties::Device::new(&instance, &device);
                Ok(Self {
                    _entry: entry,
                    instance,
                    device,
                    executables,
                    description,
                    target,
                    varying_subgroup_size,
                })
            }
            Err(e) => {
                // SAFETY: nothing was created from the instance that is still alive.
                unsafe { instance.destroy_instance(None) };
                Err(e)
            }
        }
    }

    /// Compiles `pipeline`'s `entry_point` and returns every executable's statistics.
    ///
    /// # Errors
    /// A failing Vulkan call (creating the layouts, module or pipeline; the queries).
    pub fn statistics(
        &self,
        pipeline: &CompiledPipeline,
        entry_point: &str,
    ) -> Result<Vec<ExecutableStats>, PipelineStatsError> {
        let mut created = Created::new(&self.device);
        let groups = pipeline.bindings.iter().map(|b| b.group + 1).max().unwrap_or(0);
        for group in 0..groups {
            let bindings: Vec<vk::DescriptorSetLayoutBinding<'_>> = pipeline
                .bindings
                .iter()
                .filter(|b| b.group == group)
                .map(|b| {
                    vk::DescriptorSetLayoutBinding::default()
                        .binding(b.vk_binding)
                        .descriptor_type(b.kind.vk())
                        .descriptor_count(b.count)
                        .stage_flags(vk::ShaderStageFlags::COMPUTE)
                })
                .collect();
            let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
            // SAFETY: a valid device and create info.
            let layout = unsafe { self.device.create_descriptor_set_layout(&info, None) }
                .map_err(PipelineStatsError::vulkan("vkCreateDescriptorSetLayout"))?;
            created.set_layouts.push(layout);
        }
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&created.set_layouts);
        // SAFETY: the set layouts are alive.
        created.layout = unsafe { self.device.create_pipeline_layout(&info, None) }
            .map_err(PipelineStatsError::vulkan("vkCreatePipelineLayout"))?;
        let info = vk::ShaderModuleCreateInfo::default().code(&pipeline.words);
        // SAFETY: the words are SPIR-V that naga wrote for this device's version.
        created.module = unsafe { self.device.create_shader_module(&info, None) }
            .map_err(PipelineStatsError::vulkan("vkCreateShaderModule"))?;
        let name = CString::new(entry_point).map_err(|_| PipelineStatsError::Shader {
            label: entry_point.to_owned(),
            stage: "entry point",
            reason: "a NUL in the name".into(),
        })?;
        let stage_flags = if self.varying_subgroup_size {
            vk::PipelineShaderStageCreateFlags::ALLOW_VARYING_SUBGROUP_SIZE
        } else {
            vk::PipelineShaderStageCreateFlags::empty()
        };
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .flags(stage_flags)
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(created.module)
            .name(&name);
        let info = vk::ComputePipelineCreateInfo::default()
            .flags(vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR)
            .stage(stage)
            .layout(created.layout);
        // SAFETY: the module and layout are alive; one create info, one pipeline.
        let pipelines =
            unsafe { self.device.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) }
                .map_err(|(_, result)| PipelineStatsError::Vulkan {
                    call: "vkCreateComputePipelines",
                    result,
                })?;
        created.pipeline = pipelines[0];
        self.read_statistics(created.pipeline)
    }

    fn read_statistics(&self, pipeline: vk::Pipeline) -> Result<Vec<ExecutableStats>, PipelineStatsError> {
        let info = vk::PipelineInfoKHR::default().pipeline(pipeline);
        // SAFETY: the pipeline was created with CAPTURE_STATISTICS on this device.
        let executables = unsafe { self.executables.get_pipeline_executable_properties(&info) }
            .map_err(PipelineStatsError::vulkan("vkGetPipelineExecutablePropertiesKHR"))?;
        let mut out = Vec::new();
        for (index, executable) in (0u32..).zip(&executables) {
            let info = vk::PipelineExecutableInfoKHR::default().pipeline(pipeline).executable_index(index);
            // SAFETY: the index is one of the executables just listed.
            let raw = unsafe { self.executables.get_pipeline_executable_statistics(&info) }
                .map_err(PipelineStatsError::vulkan("vkGetPipelineExecutableStatisticsKHR"))?;
            let statistics = raw
                .iter()
                .filter_map(|s| {
                    // SAFETY: the union is read as the member `format` names.
                    let value = unsafe {
                        match s.format {
                            vk::PipelineExecutableStatisticFormatKHR::BOOL32 => {
                                StatValue::Bool(s.value.b32 != 0)
                            }
                            vk::PipelineExecutableStatisticFormatKHR::INT64 => StatValue::Int(s.value.i64),
                            vk::PipelineExecutableStatisticFormatKHR::UINT64 => StatValue::Uint(s.value.u64),
                            vk::PipelineExecutableStatisticFormatKHR::FLOAT64 => {
                                StatValue::Float(s.value.f64)
                            }
                            _ => return None,
                        }
                    };
                    Some(Statistic {
                        name: text(s.name_as_c_str()),
                        description: text(s.description_as_c_str()),
                        value,
                    })
                })
                .collect();
            out.push(ExecutableStats {
                name: text(executable.name_as_c_str()),
                description: text(executable.description_as_c_str()),
                subgroup_size: executable.subgroup_size,
                statistics,
            });
        }
        Ok(out)
    }
}

impl Drop for StatsDevice {
    fn drop(&mut self) {
        // SAFETY: every object made from the device was destroyed by its `Created`.
        unsafe {
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

/// What one pipeline's compilation created, destroyed when it goes out of scope.
struct Created<'a> {
    device: &'a ash::Device,
    set_layouts: Vec<vk::DescriptorSetLayout>,
    layout: vk::PipelineLayout,
    module: vk::ShaderModule,
    pipeline: vk::Pipeline,
}

impl<'a> Created<'a> {
    fn new(device: &'a ash::Device) -> Self {
        Self {
            device,
            set_layouts: Vec::new(),
            layout: vk::PipelineLayout::null(),
            module: vk::ShaderModule::null(),
            pipeline: vk::Pipeline::null(),
        }
    }
}

impl Drop for Created<'_> {
    fn drop(&mut self) {
        let device = self.device;
        // SAFETY: each handle is null or made from `device`, and no command uses them.
        unsafe {
            device.destroy_pipeline(self.pipeline, None);
            device.destroy_shader_module(self.module, None);
            device.destroy_pipeline_layout(self.layout, None);
            for &l in &self.set_layouts {
                device.destroy_descriptor_set_layout(l, None);
            }
        }
    }
}

/// A driver string (lossy; empty when it has no NUL).
fn text(c: Result<&CStr, std::ffi::FromBytesUntilNulError>) -> String {
    c.map(|c| c.to_string_lossy().into_owned()).unwrap_or_default()
}

/// Picks a device and creates it with the extension, its feature and wgpu's robustness.
fn open_device(
    instance: &ash::Instance,
    api_version: u32,
) -> Result<(ash::Device, String, SpirvTarget, bool), PipelineStatsError> {
    // SAFETY: a valid instance.
    let physicals = unsafe { instance.enumerate_physical_devices() }
        .map_err(PipelineStatsError::vulkan("vkEnumeratePhysicalDevices"))?;
    let mut passed_over = Vec::new();
    let mut candidates = Vec::new();
    for physical in physicals {
        match candidate(instance, physical, api_version)? {
            Ok(c) => candidates.push(c),
            Err(why) => passed_over.push(why),
        }
    }
    // A GPU before a CPU implementation (lavapipe beside the GPU's driver).
    let Some(c) = candidates.iter().find(|c| !c.cpu).or(candidates.first()) else {
        return Err(PipelineStatsError::NoDevice { devices: passed_over });
    };
    let mut extensions = vec![khr::pipeline_executable_properties::NAME.as_ptr()];
    if c.robustness2.is_some() {
        extensions.push(ext::robustness2::NAME.as_ptr());
    }
    let core = vk::PhysicalDeviceFeatures::default().robust_buffer_access(c.robust_buffer_access);
    let mut executable_info =
        vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default().pipeline_executable_info(true);
    let mut robustness2 = c.robustness2.map(|(buffer, image)| {
        vk::PhysicalDeviceRobustness2FeaturesEXT::default()
            .robust_buffer_access2(buffer)
            .robust_image_access2(image)
    });
    let mut vulkan13 = c.vulkan13.map(|(image, subgroup_size)| {
        vk::PhysicalDeviceVulkan13Features::default()
            .robust_image_access(image)
            .subgroup_size_control(subgroup_size)
    });
    let mut features = vk::PhysicalDeviceFeatures2::default().features(core).push_next(&mut executable_info);
    if let Some(r) = robustness2.as_mut() {
        features = features.push_next(r);
    }
    if let Some(v) = vulkan13.as_mut() {
        features = features.push_next(v);
    }
    let priorities = [1.0];
    let queues = [vk::DeviceQueueCreateInfo::default()
        .queue_family_index(c.queue_family)
        .queue_priorities(&priorities)];
    let info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queues)
        .enabled_extension_names(&extensions)
        .push_next(&mut features);
    // SAFETY: the extensions and features were read from this physical device.
    let device = unsafe { instance.create_device(c.physical, &info, None) }
        .map_err(PipelineStatsError::vulkan("vkCreateDevice"))?;
    let target = SpirvTarget {
        lang_version: SpirvTarget::lang_version_for(c.api_version),
        robust_buffer_access2: c.robustness2.is_some_and(|(buffer, _)| buffer),
        // wgpu-hal: robustImageAccess2 where VK_EXT_robustness2 is, else robustImageAccess.
        robust_image_access: match (c.robustness2, c.vulkan13) {
            (Some((_, image2)), _) => image2,
            (None, Some((image, _))) => image,
            (None, None) => false,
        },
    };
    let varying_subgroup_size = c.vulkan13.is_some_and(|(_, s)| s);
    Ok((device, c.description.clone(), target, varying_subgroup_size))
}

/// The device as a candidate, or why it is not one.
fn candidate(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    instance_version: u32,
) -> Result<Result<Candidate, String>, PipelineStatsError> {
    // SAFETY: `physical` came from this instance.
    let props = unsafe { instance.get_physical_device_properties(physical) };
    let name = text(props.device_name_as_c_str());
    let api_version = props.api_version.min(instance_version);
    let v = |v: u32| format!("{}.{}", vk::api_version_major(v), vk::api_version_minor(v));
    let driver = if api_version >= vk::API_VERSION_1_2 {
        let mut d = vk::PhysicalDeviceDriverProperties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut d);
        // SAFETY: a Vulkan 1.2 device has the driver properties.
        unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
        format!("{} {}", text(d.driver_name_as_c_str()), text(d.driver_info_as_c_str()))
    } else {
        format!("{:#x}", props.driver_version)
    };
    let description = format!(
        "{name} ({:?}, Vulkan {}, driver {})",
        props.device_type,
        v(props.api_version),
        driver.trim()
    );
    if api_version < vk::API_VERSION_1_1 {
        return Ok(Err(format!("{name}: Vulkan 1.0")));
    }
    // SAFETY: as above.
    let extensions = unsafe { instance.enumerate_device_extension_properties(physical) }
        .map_err(PipelineStatsError::vulkan("vkEnumerateDeviceExtensionProperties"))?;
    let has = |wanted: &CStr| extensions.iter().any(|e| e.extension_name_as_c_str() == Ok(wanted));
    if !has(khr::pipeline_executable_properties::NAME) {
        return Ok(Err(format!("{name}: no VK_KHR_pipeline_executable_properties")));
    }
    let has_robustness2 = has(ext::robustness2::NAME);
    let is_1_3 = api_version >= vk::API_VERSION_1_3;
    let mut executable_info = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default();
    let mut robustness2 = vk::PhysicalDeviceRobustness2FeaturesEXT::default();
    let mut vulkan13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut executable_info);
    if has_robustness2 {
        features = features.push_next(&mut robustness2);
    }
    if is_1_3 {
        features = features.push_next(&mut vulkan13);
    }
    // SAFETY: the chain holds only structures of extensions and versions the device has.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    let robust_buffer_access = features.features.robust_buffer_access != 0;
    if executable_info.pipeline_executable_info == 0 {
        return Ok(Err(format!("{name}: pipelineExecutableInfo not supported")));
    }
    // SAFETY: as above.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    let Some(queue_family) = (0u32..)
        .zip(&families)
        .find_map(|(i, f)| f.queue_flags.contains(vk::QueueFlags::COMPUTE).then_some(i))
    else {
        return Ok(Err(format!("{name}: no compute queue")));
    };
    Ok(Ok(Candidate {
        physical,
        description,
        cpu: props.device_type == vk::PhysicalDeviceType::CPU,
        api_version,
        queue_family,
        robust_buffer_access,
        robustness2: has_robustness2
            .then_some((robustness2.robust_buffer_access2 != 0, robustness2.robust_image_access2 != 0)),
        vulkan13: is_1_3.then_some((vulkan13.robust_image_access != 0, vulkan13.subgroup_size_control != 0)),
    }))
}
