//! Upsample pass of the reduced-resolution tiers: the reduced reflection (and layer
//! reflection) to the full-resolution outputs, edge-aware (`crates/ppr-runtime/shaders/upsample.wgsl`).

use super::bind_group_cache::BindGroupCache;
use super::reflection::OUTPUT_FORMAT;
use super::{
    BufferPart, TILE, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry,
    write_texture_entry,
};

pub const WGSL: &str = include_str!("../../shaders/upsample.wgsl");

/// The workgroup arrays of the shared variants (`SPAN_EDGE`² samples).
pub const SPAN: &str = include_str!("../../shaders/upsample_span.wgsl");

/// The same arrays for the per-pixel variants, which never touch them: one element each,
/// so that their pipelines declare no workgroup memory to speak of.
pub const SPAN_STUB: &str = include_str!("../../shaders/upsample_span_stub.wgsl");

/// What the upsample pass reads and writes.
pub struct UpsampleBindings<'a> {
    /// The reduced plan's uniforms.
    pub uniforms: BufferPart<'a>,
    pub full_depth: &'a wgpu::TextureView,
    pub reduced_depth: &'a wgpu::TextureView,
    pub reduced_output: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
    /// The reduced plan's tile flags (read with indirect dispatch).
    pub tile_flags: &'a wgpu::Buffer,
}

/// Which of the upsample's pipelines records a dispatch (the shader's override constants).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UpsampleVariant {
    /// Reduced tiles not cleared this frame read as empty (`INDIRECT`: indirect dispatch).
    pub indirect: bool,
    /// The layer output: plain bilinear over the layer rectangle (`LAYERS`).
    pub layers: bool,
    /// Each workgroup reads the reduced samples its pixels need into workgroup memory
    /// first, instead of each pixel reading its own four (`SHARED`; bench only, the same
    /// image: `DebugOptions::shared_upsample`).
    pub shared: bool,
}

impl UpsampleVariant {
    /// The pass builds one pipeline per variant.
    const COUNT: usize = 8;

    /// The variant's pipeline: bit 0 `indirect`, 1 `layers`, 2 `shared`.
    fn index(self) -> usize {
        usize::from(self.indirect) | usize::from(self.layers) << 1 | usize::from(self.shared) << 2
    }

    /// The variant of pipeline `index` ([`Self::index`]'s inverse).
    fn from_index(index: usize) -> Self {
        Self { indirect: index & 1 != 0, layers: index & 2 != 0, shared: index & 4 != 0 }
    }

    /// The shader's override constants for this variant.
    pub(crate) fn constants(self) -> [(&'static str, f64); 3] {
        [("INDIRECT", flag(self.indirect)), ("LAYERS", flag(self.layers)), ("SHARED", flag(self.shared))]
    }
}

/// What a probe of the upsample's time records instead of the upsample (the shader's
/// `PROBE`; bench only, `DebugOptions::upsample_probe`): not the image, the parts of the
/// pass's time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UpsampleProbe {
    /// The upsample itself.
    #[default]
    None,
    /// Only the store of an empty reflection, every pixel.
    StoreOnly,
    /// The pixel's depth read, and the store.
    DepthOnly,
    /// The upsample with the pixel's camera distance from its four samples', not from its
    /// depth: no full-resolution read (a different image at silhouettes).
    NoOwnDepth,
}

impl UpsampleProbe {
    /// The shader's `PROBE`.
    fn code(self) -> u32 {
        match self {
            Self::None => 0,
            Self::StoreOnly => 1,
            Self::DepthOnly => 2,
            Self::NoOwnDepth => 3,
        }
    }
}

/// The upsample pass.
pub struct UpsamplePass {
    /// Pipelines by [`UpsampleVariant::index`]: the per-pixel ones built with the pass, the
    /// shared ones (bench only) on request ([`Self::prepare_shared`]).
    pipelines: [Option<wgpu::ComputePipeline>; UpsampleVariant::COUNT],
    /// The probes' pipelines (per-pixel, not layers), by probe and `indirect`, on request
    /// ([`Self::prepare_probe`]).
    probes: Vec<(UpsampleProbe, bool, wgpu::ComputePipeline)>,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl UpsamplePass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr upsample"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                loaded_texture_entry(2),
                loaded_texture_entry(3),
                write_texture_entry(4, OUTPUT_FORMAT),
                storage_entry(5, true),
            ],
        });
        let mut pass = Self {
            pipelines: std::array::from_fn(|_| None),
            probes: Vec::new(),
            layout,
            bind_groups: BindGroupCache::default(),
        };
        pass.build(device, false);
        pass
    }

    /// Builds the shared variants' pipelines (`DebugOptions::shared_upsample`), once.
    pub fn prepare_shared(&mut self, device: &wgpu::Device) {
        if self.pipelines.iter().any(Option::is_none) {
            self.build(device, true);
        }
    }

    /// Builds the pipelines of `probe` (`DebugOptions::upsample_probe`), once.
    pub fn prepare_probe(&mut self, device: &wgpu::Device, probe: UpsampleProbe) {
        if probe == UpsampleProbe::None || self.probes.iter().any(|p| p.0 == probe) {
            return;
        }
        let module = crate::shader::module_with(
            device,
            "ppr upsample (probe)",
            &[crate::shader::VIEW, SPAN_STUB],
            WGSL,
        );
        for indirect in [false, true] {
            let variant = UpsampleVariant { indirect, ..UpsampleVariant::default() };
            let mut constants = variant.constants().to_vec();
            constants.push(("PROBE", f64::from(probe.code())));
            let label = format!("ppr upsample probe {probe:?} indirect={indirect}");
            self.probes.push((
                probe,
                indirect,
                compute_pipeline(device, &label, &self.layout, &module, "main", &constants),
            ));
        }
    }

    /// Builds the pipelines of the variants with this `shared`, from their own module (the
    /// per-pixel ones without the span's workgroup arrays).
    fn build(&mut self, device: &wgpu::Device, shared: bool) {
        let (label, span) =
            if shared { ("ppr upsample (shared)", SPAN) } else { ("ppr upsample", SPAN_STUB) };
        let module = crate::shader::module_with(device, label, &[crate::shader::VIEW, span], WGSL);
        for (index, slot) in self.pipelines.iter_mut().enumerate() {
            let variant = UpsampleVariant::from_index(index);
            if variant.shared != shared {
                continue;
            }
            let UpsampleVariant { indirect, layers, shared } = variant;
            let label = format!("ppr upsample indirect={indirect} layers={layers} shared={shared}");
            *slot =
                Some(compute_pipeline(device, &label, &self.layout, &module, "main", &variant.constants()));
        }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &UpsampleBindings<'_>) -> wgpu::BindGroup {
        let view =
            |binding, v| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) };
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr upsample"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    view(1, b.full_depth),
                    view(2, b.reduced_depth),
                    view(3, b.reduced_output),
                    view(4, b.output),
                    wgpu::BindGroupEntry { binding: 5, resource: b.tile_flags.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the pass over `pixels` output pixels (the whole output, or with
    /// `variant.layers` the layer rectangle's pixels at full resolution plus a margin).
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        pixels: [u32; 2],
        variant: UpsampleVariant,
        probe: UpsampleProbe,
    ) {
        let pipeline = if probe == UpsampleProbe::None || variant.layers || variant.shared {
            self.pipelines[variant.index()].as_ref()
        } else {
            self.probes.iter().find(|p| p.0 == probe && p.1 == variant.indirect).map(|p| &p.2)
        };
        pass.set_pipeline(
            pipeline.expect("prepare_shared() / prepare_probe() before encoding their variants"),
        );
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(pixels[0].div_ceil(TILE), pixels[1].div_ceil(TILE), 1);
    }
}

#[cfg(test)]
mod tests {
    use super::UpsampleVariant;

    /// Each variant has a pipeline of its own.
    #[test]
    fn every_variant_has_its_own_pipeline() {
        for index in 0..UpsampleVariant::COUNT {
            assert_eq!(UpsampleVariant::from_index(index).index(), index);
        }
        let all = UpsampleVariant { indirect: true, layers: true, shared: true };
        assert_eq!(all.index(), UpsampleVariant::COUNT - 1);
    }

    /// The constants each pipeline sets are the shader's bool overrides, and its workgroup
    /// is the tile the pass dispatches by: 16 × 16 ([`crate::passes::TILE`]) pixels, whose
    /// reduced samples (SHARED) fit the workgroup arrays: at most TILE + 1 per axis (a
    /// scale of at most 1), and one of margin.
    #[test]
    fn shader_matches_rust() {
        use crate::passes::TILE;
        let source = crate::shader::source_with(&[crate::shader::VIEW, super::SPAN], super::WGSL);
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        for (name, _) in UpsampleVariant::from_index(0).constants() {
            let o = module.overrides.iter().find(|(_, o)| o.name.as_deref() == Some(name));
            let o = o.unwrap_or_else(|| panic!("no override {name}")).1;
            assert_eq!(module.types[o.ty].inner, naga::TypeInner::Scalar(naga::Scalar::BOOL), "{name}");
        }
        // PROBE, the one more, is set by the probes' pipelines alone.
        let probe =
            module.overrides.iter().find(|(_, o)| o.name.as_deref() == Some("PROBE")).expect("PROBE").1;
        assert_eq!(module.types[probe.ty].inner, naga::TypeInner::Scalar(naga::Scalar::U32));
        assert_eq!(module.overrides.len(), 4, "every override is set");
        let entry = module.entry_points.iter().find(|e| e.name == "main").expect("upsample main");
        assert_eq!(entry.workgroup_size, [TILE, TILE, 1]);
        let constant = |name: &str| {
            let c = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name));
            let c = c.unwrap_or_else(|| panic!("no constant {name}")).1;
            match module.global_expressions[c.init] {
                naga::Expression::Literal(naga::Literal::I32(n)) => n,
                ref e => panic!("{name} is not an i32 literal: {e:?}"),
            }
        };
        let tile = TILE as i32;
        assert_eq!((constant("GROUP_EDGE"), constant("SPAN_EDGE")), (tile, tile + 2));
        for name in ["span_colour", "span_distance"] {
            let g = module.global_variables.iter().find(|(_, g)| g.name.as_deref() == Some(name));
            let g = g.unwrap_or_else(|| panic!("no {name}")).1;
            let naga::TypeInner::Array { size: naga::ArraySize::Constant(n), .. } = module.types[g.ty].inner
            else {
                panic!("{name} is not a sized array");
            };
            assert_eq!(n.get(), (TILE + 2) * (TILE + 2), "{name}");
        }
    }
}
