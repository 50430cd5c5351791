//! `PassLayout`: which dispatches a frame records and in which compute pass each goes,
//! decided from the plan, the debug options and the slot's state before anything is
//! recorded (`ReflectionRenderer::encode_view` records by it).

use crate::passes::layer_reflection::LayerPlacement;
use crate::plan::FramePlan;
use crate::renderer::DebugOptions;
use crate::timestamps::{
    CLASSIFY, CLEAR, DOWNSAMPLE, FRAME_SPAN, LAYERS, PROJECTION, PROJECTION_REFLECTION, REFLECTION,
    TIMED_PASSES, UPSAMPLE,
};

/// One encode's dispatches and compute passes. The projection's compute pass is always
/// recorded (it holds the lists and the layer writes too); the rest as the fields say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PassLayout {
    /// The plan has visible shapes: the main projection writes and the reflection runs.
    pub has_main: bool,
    /// The tile classification runs (indirect frames with visible shapes).
    pub classify: bool,
    /// ... in the projection's compute pass (else in one of its own before the clear).
    pub classify_with_projection: bool,
    /// The clear pass clears the intermediate buffer (a slot the last encode left dirty).
    pub clear_main: bool,
    /// The clear pass clears the layers' atlas (the same).
    pub clear_atlas: bool,
    /// The layer reflection runs (the plan has layers and the frame gave a layer output).
    pub layers: bool,
    /// ... in the reflection's compute pass (else in its own after it).
    pub layers_with_reflection: bool,
    /// The reflection (and the layers beside it) in the projection's compute pass, else in
    /// one of their own after it.
    pub reflection_with_projection: bool,
    /// A reduced tier: downsample first, upsample last.
    pub reduced: bool,
}

impl PassLayout {
    /// The layout of a non-empty plan's encode: `clean` says whether the slot this encode
    /// takes was cleared by the last one's reflection, `layer_output` whether the frame gave
    /// a layer output, `reduced` whether it runs a reduced tier.
    pub fn new(
        plan: &FramePlan,
        debug: &DebugOptions,
        clean: bool,
        layer_output: bool,
        reduced: bool,
    ) -> Self {
        let has_main = !plan.visible.is_empty();
        let classify = plan.indirect && has_main;
        // A slot is clean where the last encode cleared it for this one (a direct frame's
        // reflection, an indirect frame's classification, each clearing the other slot);
        // else the clear pass clears it whole.
        let clear_main = has_main && !clean;
        let clear_atlas = !plan.layers.is_empty() && !clean;
        // In the projection's compute pass (no barrier between the two dispatches: the
        // classification clears the other slot) unless a clear pass comes between them.
        let classify_with_projection = !(debug.classify_own_pass || clear_main || clear_atlas);
        let layers = !plan.layers.is_empty() && layer_output;
        let placement = debug.layer_placement;
        let layers_with_reflection = has_main && placement != LayerPlacement::OwnPass;
        // A layer dispatch beside the reflection comes first in the projection's pass, and
        // its barrier readies the reflection's buffers too (it binds the intermediate buffer
        // for that); the bench may keep such frames in two passes.
        let layers_beside = layers && layers_with_reflection;
        let reflection_with_projection = has_main
            && !debug.reflection_own_pass
            && !(layers_beside
                && (debug.layered_reflection_own_pass || placement != LayerPlacement::BeforeReflection));
        Self {
            has_main,
            classify,
            classify_with_projection,
            clear_main,
            clear_atlas,
            layers,
            layers_with_reflection,
            reflection_with_projection,
            reduced,
        }
    }

    /// Whether the clear pass is recorded.
    pub fn clears(&self) -> bool {
        self.clear_main || self.clear_atlas
    }

    /// Whether the layer reflection has a compute pass of its own.
    pub fn layers_own_pass(&self) -> bool {
        self.layers && !self.layers_with_reflection
    }

    /// The timed passes this layout records with their own timestamps (as in
    /// `PassTimings::passes`): with `span`, only the frame's span, where `spans` says the
    /// device writes it.
    pub fn recorded(&self, span: bool, spans: bool) -> [bool; TIMED_PASSES as usize] {
        let mut recorded = [false; TIMED_PASSES as usize];
        if span {
            recorded[FRAME_SPAN as usize] = spans;
            return recorded;
        }
        for (slot, timed) in [
            (CLASSIFY, self.classify && !self.classify_with_projection),
            (CLEAR, self.clears()),
            (PROJECTION, !self.reflection_with_projection),
            (REFLECTION, self.has_main && !self.reflection_with_projection),
            (LAYERS, self.layers_own_pass()),
            (DOWNSAMPLE, self.reduced),
            (UPSAMPLE, self.reduced && (self.has_main || self.layers_own_pass())),
            (PROJECTION_REFLECTION, self.reflection_with_projection),
        ] {
            recorded[slot as usize] = timed;
        }
        recorded
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};

    use super::PassLayout;
    use crate::camera::{Camera, Projection};
    use crate::passes::layer_reflection::LayerPlacement;
    use crate::plan::{FramePlan, LayerAlloc, PlanParams, ScreenRect};
    use crate::renderer::DebugOptions;
    use crate::shapes::ShapeTable;
    use crate::timestamps::{self, FRAME_SPAN, PROJECTION_REFLECTION, TIMED_PASSES};

    const CLASSIFY: usize = timestamps::CLASSIFY as usize;
    const CLEAR: usize = timestamps::CLEAR as usize;
    const PROJECTION: usize = timestamps::PROJECTION as usize;
    const REFLECTION: usize = timestamps::REFLECTION as usize;
    const LAYERS: usize = timestamps::LAYERS as usize;
    const DOWNSAMPLE: usize = timestamps::DOWNSAMPLE as usize;
    const UPSAMPLE: usize = timestamps::UPSAMPLE as usize;

    /// A plan with `visible` shapes (none tested: the layout reads the lists' lengths only),
    /// indirect or not, with or without a layer.
    fn plan(visible: usize, indirect: bool, layer: bool) -> FramePlan {
        let camera = Camera::look_at(DVec3::new(0.0, 1.0, 2.0), DVec3::ZERO, Vec3::Y, Projection::default());
        let mut plan = FramePlan::build(&ShapeTable::default(), &camera, [64, 48], &PlanParams::default());
        plan.visible = (0..visible as u32).collect();
        plan.indirect = indirect;
        if layer {
            let rect = ScreenRect { min: [8, 8], max: [24, 16] };
            plan.layers.push(LayerAlloc {
                shape: 0,
                kind: ppr_format::ReflectorKind::Water,
                rect,
                offset: 0,
            });
            plan.layer_pixels = 16 * 8;
            plan.layer_rect = rect;
        }
        plan
    }

    /// The timed passes recorded with their own timestamps, by index.
    fn timed(layout: &PassLayout) -> Vec<usize> {
        let recorded = layout.recorded(false, true);
        (0..TIMED_PASSES as usize).filter(|&i| recorded[i]).collect()
    }

    #[test]
    fn a_direct_frame_on_a_clean_slot_is_one_compute_pass() {
        let layout = PassLayout::new(&plan(3, false, false), &DebugOptions::default(), true, false, false);
        assert!(layout.reflection_with_projection && !layout.clears() && !layout.classify);
        assert_eq!(timed(&layout), [PROJECTION_REFLECTION as usize]);
        // A slot the last encode left dirty is cleared first, in a pass of its own.
        let dirty = PassLayout::new(&plan(3, false, false), &DebugOptions::default(), false, false, false);
        assert!(dirty.clear_main && !dirty.clear_atlas);
        assert_eq!(timed(&dirty), [CLEAR, PROJECTION_REFLECTION as usize]);
    }

    #[test]
    fn indirect_frames_classify_in_the_projections_pass_unless_a_clear_pass_comes_between() {
        let debug = DebugOptions::default();
        // On a clean slot (the last encode's classification or reflection cleared it) the
        // classification shares the projection's pass.
        let layout = PassLayout::new(&plan(3, true, false), &debug, true, false, false);
        assert!(layout.classify && layout.classify_with_projection && !layout.clears());
        assert_eq!(timed(&layout), [PROJECTION_REFLECTION as usize]);
        // A dirty slot is cleared whole first, its atlas too where the frame has layers.
        let layout = PassLayout::new(&plan(3, true, false), &debug, false, false, false);
        assert!(layout.clear_main && !layout.clear_atlas && !layout.classify_with_projection);
        assert_eq!(timed(&layout), [CLASSIFY, CLEAR, PROJECTION_REFLECTION as usize]);
        let layout = PassLayout::new(&plan(3, true, true), &debug, false, true, false);
        assert!(layout.clear_main && layout.clear_atlas);
        let own = DebugOptions { classify_own_pass: true, ..debug };
        let layout = PassLayout::new(&plan(3, true, false), &own, true, false, false);
        assert_eq!(timed(&layout), [CLASSIFY, PROJECTION_REFLECTION as usize]);
    }

    #[test]
    fn layers_go_before_the_reflection_in_the_projections_pass_by_default() {
        let debug = DebugOptions::default();
        let layout = PassLayout::new(&plan(3, false, true), &debug, true, true, false);
        assert!(layout.layers && layout.layers_with_reflection && layout.reflection_with_projection);
        assert_eq!(timed(&layout), [PROJECTION_REFLECTION as usize]);
        // Without a layer output the layers do not run.
        let layout = PassLayout::new(&plan(3, false, true), &debug, true, false, false);
        assert!(!layout.layers && layout.reflection_with_projection);
        // The bench's older layouts: layered frames' reflection in a pass of its own, the
        // layers after the reflection (the same), or in a pass of their own.
        let apart = DebugOptions { layered_reflection_own_pass: true, ..debug };
        let layout = PassLayout::new(&plan(3, false, true), &apart, true, true, false);
        assert_eq!(timed(&layout), [PROJECTION, REFLECTION]);
        let after = DebugOptions { layer_placement: LayerPlacement::AfterReflection, ..debug };
        let layout = PassLayout::new(&plan(3, false, true), &after, true, true, false);
        assert_eq!(timed(&layout), [PROJECTION, REFLECTION]);
        let own = DebugOptions { layer_placement: LayerPlacement::OwnPass, ..debug };
        let layout = PassLayout::new(&plan(3, false, true), &own, true, true, false);
        assert!(layout.layers_own_pass() && layout.reflection_with_projection);
        assert_eq!(timed(&layout), [LAYERS, PROJECTION_REFLECTION as usize]);
        // Layers without visible shapes: the projection's pass, then the layers' own.
        let layout = PassLayout::new(&plan(0, false, true), &debug, true, true, false);
        assert!(!layout.has_main && layout.layers_own_pass());
        assert_eq!(timed(&layout), [PROJECTION, LAYERS]);
    }

    #[test]
    fn a_timed_span_records_only_the_span_and_every_frame_times_its_projection_once() {
        let layout = PassLayout::new(&plan(3, true, true), &DebugOptions::default(), false, true, true);
        let span = layout.recorded(true, true);
        assert_eq!(
            (0..TIMED_PASSES as usize).filter(|&i| span[i]).collect::<Vec<_>>(),
            [FRAME_SPAN as usize]
        );
        assert!(!layout.recorded(true, false).contains(&true));
        // A reduced tier times its downsample, and its upsample where it has something to
        // upsample: not for a plan whose layers have no output and nothing else.
        let reduced = PassLayout::new(&plan(3, false, false), &DebugOptions::default(), true, false, true);
        assert_eq!(timed(&reduced), [DOWNSAMPLE, UPSAMPLE, PROJECTION_REFLECTION as usize]);
        let nothing = PassLayout::new(&plan(0, false, true), &DebugOptions::default(), true, false, true);
        assert_eq!(timed(&nothing), [PROJECTION, DOWNSAMPLE]);
        // Every combination: the projection is timed exactly once, on its own or with the
        // reflection, and the reflection at most once.
        for bits in 0..1u32 << 9 {
            let b = |i: u32| bits & (1 << i) != 0;
            let debug = DebugOptions {
                clear_pass_every_frame: b(0),
                classify_own_pass: b(1),
                reflection_own_pass: b(2),
                layered_reflection_own_pass: b(3),
                ..DebugOptions::default()
            };
            let visible = if b(4) { 2 } else { 0 };
            let layout = PassLayout::new(&plan(visible, b(5), b(6)), &debug, b(7), b(6), b(8));
            let t = layout.recorded(false, true);
            assert!(t[PROJECTION] ^ t[PROJECTION_REFLECTION as usize], "{layout:?}");
            assert!(!(t[REFLECTION] && t[PROJECTION_REFLECTION as usize]), "{layout:?}");
            assert_eq!(t[REFLECTION] || t[PROJECTION_REFLECTION as usize], visible > 0, "{layout:?}");
        }
    }
}
