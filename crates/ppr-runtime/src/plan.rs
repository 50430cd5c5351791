//! The frame plan: which reflectors are visible and which passes run, decided on the CPU.

use std::fmt;

use glam::Vec4;
use ppr_format::ReflectorKind;

use crate::camera::Camera;
use crate::encoding::EncodingLayout;
use crate::parallel_trees::FrameTree;
use crate::path_blockers::NO_BLOCKER;
use crate::shapes::{ShapeSource, ShapeTable};
use crate::source_box::SourceBoxes;

/// A reflector's rectangle on screen, in pixels (inclusive min, exclusive max).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ScreenRect {
    pub min: [u32; 2],
    pub max: [u32; 2],
}

impl ScreenRect {
    /// Pixels covered.
    pub fn area(&self) -> u64 {
        u64::from(self.max[0].saturating_sub(self.min[0]))
            * u64::from(self.max[1].saturating_sub(self.min[1]))
    }
}

/// A decision the plan makes by itself unless told.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Choice {
    /// Let the plan decide from the frame (the thresholds of [`PlanParams`]).
    #[default]
    Auto,
    /// Always on (when anything runs at all).
    On,
    /// Always off.
    Off,
}

impl Choice {
    fn decide(self, auto: bool) -> bool {
        match self {
            Self::Auto => auto,
            Self::On => true,
            Self::Off => false,
        }
    }
}

/// How the frame plan chooses passes and shader variants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanParams {
    /// Per-tile shape lists in the projection pass (seed's "multiple parallel shapes").
    pub tile_culling: Choice,
    /// With `Auto`, tile culling runs from this many visible shapes on. Measured on the
    /// H200 at 3840×2160 (docs/perf/scaling.md): the block-list pass costs a fixed
    /// 0.08–0.1 ms there, repaid from 8 shapes on a stairway and a floor of puddles and
    /// from 16 on a window facade.
    pub tile_culling_min_shapes: usize,
    /// With tile culling, a first pass lists per 64 × 64-pixel super-tile the shapes that
    /// may reflect into it, and each 16 × 16 tile tests only its super-tile's list (the
    /// per-tile test is otherwise O(tiles × shapes)).
    pub super_tiles: Choice,
    /// With `Auto`, super-tile lists are built from this many tested entries on. Measured on
    /// an H100 at 3840×2160 (docs/perf/scaling.md, thirtieth session): every shape tested
    /// alone, they are slower than flat tile lists at 512 and 640 in all four generated
    /// families (the stairway 0.496 against 0.448 ms at 512, 0.555 against 0.514 at 640)
    /// and faster on the stairway from 768 on (0.635 against 0.689; the facade from 1 024).
    pub super_tiles_min_shapes: usize,
    /// With tile culling, the projection builds each block's list itself, in workgroup
    /// memory from the positions it loads anyway, instead of a block-list pass before it
    /// (the same lists; saves that pass's launch, depth reads and unprojections, costs the
    /// projection barriers). `Auto`: on, but the renderer turns it off on CPU adapters
    /// (Mesa's llvmpipe turns barriers into coroutines, and compiles such shaders slowly).
    pub fused_lists: Choice,
    /// With fused lists ([`Self::fused_lists`] not `Off`), `Auto` tile culling runs from
    /// this many tested entries on, instead of [`Self::tile_culling_min_shapes`] or
    /// [`Self::subgroup_tile_culling_min_shapes`]. Measured on the H200 at 3840×2160
    /// (docs/perf/runtime.md, sixteenth session): with the list built in the projection,
    /// culling is 0.011–0.027 ms faster on the demo's cameras (8–9 shapes), 0.004 faster
    /// than subgroup culling on the kitchen's overview (23) and 0.03 on a collision-world
    /// view; it is 0.02 faster on the 6-wall mirror room but 0.015 slower on a 6-shape
    /// kitchen view (and within 0.005 either way on a 5-shape one).
    pub fused_tile_culling_min_shapes: usize,
    /// Among parallel shapes, only the nearest plane reflects a pixel (the seed's bonus
    /// slides). An approximation, never chosen by `Auto` (off): shapes of one plane never
    /// both reflect a pixel, so among them the rule changes nothing, and among parallel
    /// planes at different heights (a table top over a floor, stair treads) it drops real
    /// reflections — the floor's of what stands on the table. `On` trades those for fewer
    /// writes on many stacked parallel shapes.
    pub parallel_rule: Choice,
    /// Classify tiles and run the clear and reflection passes only over tiles that show
    /// a visible reflector (indirect dispatch).
    pub indirect: Choice,
    /// With `Auto`, indirect dispatch runs when the visible shapes' screen rectangles cover
    /// at most this share of a screen of 3840×2160 pixels or more; smaller screens take a
    /// smaller share, none up to 1920×1080 ([`Self::indirect_coverage_limit`]). Measured on
    /// the H200 at 3840×2160 (docs/perf/scaling.md, seventeenth session): the classification
    /// and the per-tile reflection are faster up to 0.3 (0.127 against 0.129 ms) and slower
    /// from 0.4 (0.140 against 0.129).
    pub indirect_max_coverage: f32,
    /// Glass panels and water planes get their own atlas regions (a second output, the
    /// layer output). `Off`: glass is not reflected, water goes into the main buffer.
    /// `Auto`: on, unless the renderer's last frame with layers had no layer output
    /// ([`crate::FrameInputs::layer_output`]) and no later frame gave one: then off.
    pub layers: Choice,
    /// The water planes most present on screen that get a layer each; the others go into
    /// the main buffer.
    pub max_water_layers: usize,
    /// Perturb reflections by the frame's shading normals on reflectors with a normal map
    /// (when the frame provides normals).
    pub normal_maps: Choice,
    /// Reflectors rougher than this are not rendered: their blur would need more taps
    /// than the glossy reflection takes, so the renderer's fallback (a probe) shows there
    /// ([`FramePlan::too_rough`] counts them). Up to it, a reflector with roughness is
    /// blurred by its lobe when [`crate::ReflectionSettings::glossy`] is on.
    pub max_roughness: f32,
    /// Do not write a reflection where the surface the depth buffer shows at its target
    /// lies in front of the reflector's plane (whatever stands in between). `Auto`: on.
    pub depth_occlusion: Choice,
    /// With depth occlusion, a write tests it at its target before its encoding rather
    /// than after (the same buffer either way). `Auto`: first, unless the frame walks
    /// parallel trees. Measured on the H200 at 3840×2160 (docs/perf/runtime.md, twelfth
    /// session): the rooms' projection with 494 walls visible 0.330 → 0.298 ms (the test
    /// keeps 38 % of their pixels from a value), the 10 000-tread stairway's 2.08 → 2.23
    /// ms (there it seldom decides: most writes lose to a nearer tread's value, and pay
    /// the test before they find out), the demo and the kitchen within 0.002 ms.
    pub occlusion_first: Choice,
    /// The seed's occluder test: the ray to each reflection point against the reflector's
    /// list of occluding reflectors from the extractor. `Auto`: off (the depth test catches
    /// every occluder, listed or not, at one read per write).
    pub occluder_lists: Choice,
    /// Before a write into a member of a parallel family, test whether the reflection's
    /// path crosses the member in front of it ([`crate::path_blockers`]): writes that
    /// could only lose (a flight of mirror treads reflects every pixel in four or five
    /// treads, all but the nearest behind the tread above) or show what a reflector
    /// hides are spared their projection, encoding and atomic. `Auto`: on wherever a
    /// visible shape has a blocker. Measured on an H100 at 3840×2160 (docs/perf/runtime.md,
    /// thirty-fourth session), whole frames: the 1 000-tread stairway 0.692 → 0.526 ms,
    /// the 10 000-tread one 1.774 → 1.457; collision-world 0.04–0.05 ms slower for 0.1 and
    /// 1.1 dB more on-screen PSNR on its two cameras (reflections through its floors and
    /// walls gone); the demo and the kitchen, whose steps and counters have blockers,
    /// 0.000–0.009 ms slower with the same images to 0.02 dB.
    pub path_blockers: Choice,
    /// Give the projection pass, per visible shape, the screen box of the pixels that may
    /// reflect into it ([`FramePlan::source_rects`]), so that blocks outside it skip the
    /// shape. `Auto`: on (on the H200 at 3840×2160 it takes 0.03–0.08 ms off the demo
    /// room's projection, docs/perf/runtime.md).
    pub source_boxes: Choice,
    /// Test coplanar visible shapes (a floor of puddles, a facade of windows) as one: the
    /// projection tests their group's plane once per pixel and looks the reflection point
    /// up in a grid of its members ([`crate::plane_groups`]). Never with the occluder
    /// lists (which are per shape) or [`crate::DebugOptions::writes`] (whose masks are).
    pub plane_groups: Choice,
    /// With `Auto`, a plane group is merged when at least this many of its members are
    /// visible.
    pub plane_group_min_shapes: usize,
    /// Test the visible shapes of one parallel family (one normal, many plane offsets:
    /// stair treads, shelves, storeys) as one: each pixel walks a tree of their offsets
    /// and boxes and tests only the members whose box its reflection point can reach
    /// ([`crate::parallel_trees`]); the writes are the plain loop's. Never with the
    /// parallel rule, the occluder lists or [`crate::DebugOptions::writes`].
    pub parallel_trees: Choice,
    /// With `Auto`, a family's visible shapes (those not merged into a plane group) become
    /// a tree from this many on. Measured on an H100 at 3840×2160 (docs/perf/scaling.md,
    /// thirtieth session): on the stairway the tree is slower than the plan without it at
    /// 512 and 640 treads (0.547 against 0.493 ms, 0.584 against 0.554), even at 768
    /// (0.639 against 0.640) and faster from 896 (0.665 against 0.705; at 10 000, 1.68
    /// against 12.1); on collision-world, whose families are walls of separate rooms,
    /// trees of 16 and more members doubled the projection.
    pub parallel_tree_min_shapes: usize,
    /// Give each parallel tree an offset index where its members' offsets spread (a flight
    /// of stairs): a pixel then solves the root's test for the offsets it passes and tests
    /// the members there, walking the tree only where they are many
    /// ([`crate::parallel_trees`], "The offset index"). The same writes. `Auto`: on.
    pub tree_index: Choice,
    /// Give the projection pass the shape tests in a uniform buffer (at most
    /// [`UNIFORM_TESTS_CAPACITY`] visible shapes and layers) instead of a storage buffer:
    /// the per-shape loads of every pixel go through the constant cache. `Auto`: on
    /// whenever they fit.
    pub uniform_tests: Choice,
    /// Each subgroup of the projection tests its candidates' boxes against the box of its
    /// pixels' positions, one candidate per invocation, and visits only those that pass
    /// (the block lists' test at the scale of a subgroup, without their pass). `Auto`: on
    /// when the device has [`wgpu::Features::SUBGROUP`] (the renderer turns `Auto` off
    /// without it; `On` there runs the same bookkeeping per invocation: the same image,
    /// slower), from [`Self::subgroup_cull_min_shapes`] tested entries and without tile
    /// culling.
    pub subgroup_cull: Choice,
    /// With `Auto`, subgroup culling runs from this many tested entries on. Measured on
    /// the H200 at 3840×2160 (docs/perf/scaling.md, sixth session): it costs 0.01–0.025 ms
    /// at 1 to 6 entries, is even at 8–9 (the demo room) and 0.01–0.05 ms faster than tile
    /// lists from 16 on.
    pub subgroup_cull_min_shapes: usize,
    /// With subgroups, `Auto` tile culling runs from this many tested entries on (instead
    /// of [`Self::tile_culling_min_shapes`]): below, subgroup culling is faster than the
    /// block-list pass (rooms at 128: 0.34 against 0.40 ms; the stairway at 128 is the
    /// first count where lists win, 0.43 against 0.47). Subgroup culling sorts at most 128
    /// candidates.
    pub subgroup_tile_culling_min_shapes: usize,
}

/// Default [`PlanParams::max_roughness`]: the extractor's own limit for metals (0.5), so
/// every reflector it writes is rendered.
pub const DEFAULT_MAX_ROUGHNESS: f32 = 0.5;

/// Most shape tests (visible shapes plus layers) the projection's uniform copy holds: 128 ×
/// 80 B = 10 KiB, under the 16 KiB uniform binding every wgpu adapter offers.
pub const UNIFORM_TESTS_CAPACITY: usize = 128;

/// Up to this many pixels (1920×1080) `Auto` never takes indirect dispatch; from
/// [`INDIRECT_FULL_PIXELS`] (3840×2160) on, up to [`PlanParams::indirect_max_coverage`];
/// linear in the pixel count between (at 2560×1440: up to 7.8 %). On an H100
/// (docs/perf/scaling.md, thirtieth session) forced indirect dispatch at 1080p gained at
/// most 0.001 ms on the demo's and the kitchen's overviews (0.1080 against 0.1085 ms,
/// 0.0733 against 0.0741) and 0.006 on one floor mirror at 5 % coverage (0.036 against
/// 0.042), was even at 20 % and lost from 30 %: not worth a threshold there. At 1440p it
/// took 0.004 off the kitchen's overview (4 % coverage: 0.0841 against 0.0874) and the
/// demo's (24 %, over the limit: 0.1558 against 0.1597) and lost 0.005–0.021 on the four
/// fuller views; at 4K it pays up to 30 %. (In the seventeenth session, before the
/// classification moved into the projection's compute pass, it lost at 1440p on the
/// kitchen's overview, 0.105 against 0.099.)
const INDIRECT_MIN_PIXELS: f64 = 1920.0 * 1080.0;
const INDIRECT_FULL_PIXELS: f64 = 3840.0 * 2160.0;

impl PlanParams {
    /// The largest screen coverage at which `Auto` takes indirect dispatch on a viewport of
    /// `pixels`: none up to 1920×1080, [`Self::indirect_max_coverage`] from 3840×2160 on,
    /// linear in the pixel count between.
    pub fn indirect_coverage_limit(&self, pixels: u64) -> f32 {
        let share = ((pixels as f64 - INDIRECT_MIN_PIXELS) / (INDIRECT_FULL_PIXELS - INDIRECT_MIN_PIXELS))
            .clamp(0.0, 1.0);
        (f64::from(self.indirect_max_coverage) * share) as f32
    }
}

impl Default for PlanParams {
    fn default() -> Self {
        Self {
            tile_culling: Choice::Auto,
            tile_culling_min_shapes: 16,
            super_tiles: Choice::Auto,
            super_tiles_min_shapes: 768,
            fused_lists: Choice::Auto,
            fused_tile_culling_min_shapes: 8,
            parallel_rule: Choice::Auto,
            indirect: Choice::Auto,
            indirect_max_coverage: 0.3,
            layers: Choice::Auto,
            max_water_layers: 4,
            normal_maps: Choice::Auto,
            max_roughness: DEFAULT_MAX_ROUGHNESS,
            source_boxes: Choice::Auto,
            depth_occlusion: Choice::Auto,
            occlusion_first: Choice::Auto,
            occluder_lists: Choice::Auto,
            path_blockers: Choice::Auto,
            uniform_tests: Choice::Auto,
            plane_groups: Choice::Auto,
            plane_group_min_shapes: 4,
            parallel_trees: Choice::Auto,
            parallel_tree_min_shapes: 768,
            tree_index: Choice::Auto,
            subgroup_cull: Choice::Auto,
            subgroup_cull_min_shapes: 16,
            subgroup_tile_culling_min_shapes: 128,
        }
    }
}

/// Most layer reflectors (glass panels and water planes) one frame gives atlas regions.
pub const MAX_LAYERS: usize = 64;

/// A glass panel or water plane given its own region of the atlas this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerAlloc {
    /// Index of the reflector in the set.
    pub shape: u32,
    /// Its kind (transparent or water).
    pub kind: ReflectorKind,
    /// Its screen rectangle: the region's size.
    pub rect: ScreenRect,
    /// Where the region starts in the atlas (u32 entries).
    pub offset: u32,
}

/// What one projection test covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TestedEntry {
    /// A visible shape (index into the set).
    Shape(u32),
    /// A merged group of coplanar visible shapes (index into
    /// [`crate::plane_groups::PlaneGroups::groups`]).
    PlaneGroup(u32),
    /// The visible shapes of a parallel family, walked as a tree (index into
    /// [`FramePlan::trees`]).
    ParallelTree(u32),
}

/// What one frame will do, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// Viewport size in pixels.
    pub viewport: [u32; 2],
    /// The aspect ratio (width / height) of the camera's projection: the viewport's, or
    /// in the reduced tiers the full-size output's ([`Self::build_for_output`]).
    pub aspect: f32,
    /// Indices (into the set) of the shapes the main buffer renders this frame.
    pub visible: Vec<u32>,
    /// Screen rectangle of each visible shape (same order as `visible`).
    pub screen_rects: Vec<ScreenRect>,
    /// What the projection pass tests, in order: the visible shapes, those of a merged
    /// plane group replaced by one entry for the group (where its first member stood).
    pub tested: Vec<TestedEntry>,
    /// Visible shapes the merged plane groups of `tested` cover.
    pub grouped_shapes: usize,
    /// The parallel trees of `tested`.
    pub trees: Vec<FrameTree>,
    /// The trees get offset indexes ([`PlanParams::tree_index`]).
    pub tree_index: bool,
    /// With source boxes: the screen box of the pixels that may reflect into each entry of
    /// `tested`, then into each layer (`crate::source_box`). Empty without.
    pub source_rects: Vec<ScreenRect>,
    /// Shapes disabled in the set.
    pub disabled: usize,
    /// Shapes whose reflecting side faces away from the camera (or the camera is on the plane).
    pub culled_back_side: usize,
    /// Shapes outside the view frustum.
    pub culled_frustum: usize,
    /// Visible glass panels, which the main buffer does not render (they need the
    /// transparent atlas).
    pub transparent_skipped: usize,
    /// Whether the projection pass tests the occluder lists (asked for, and some visible
    /// shape has one).
    pub occluder_tests: bool,
    /// Whether the projection pass tests the members' path blockers
    /// ([`PlanParams::path_blockers`]; the tests carry them).
    pub path_blockers: bool,
    /// Whether the projection pass tests occlusion against the depth buffer.
    pub depth_occlusion: bool,
    /// Whether a write tests the depth occlusion before its encoding
    /// ([`PlanParams::occlusion_first`]).
    pub occlusion_first: bool,
    /// Whether the projection pass builds per-tile shape lists.
    pub tile_culling: bool,
    /// Whether the tile lists are built from per-super-tile lists (a pass before the
    /// projection, timed with it).
    pub super_tiles: bool,
    /// With `tile_culling`: whether the projection builds its blocks' lists itself
    /// ([`PlanParams::fused_lists`]) rather than the block-list pass.
    pub fused_lists: bool,
    /// Whether only the nearest of parallel shapes reflects a pixel.
    pub parallel_rule: bool,
    /// Whether the projection reads the shape tests from the uniform copy
    /// ([`PlanParams::uniform_tests`]).
    pub uniform_tests: bool,
    /// The projection's subgroups cull their candidates ([`PlanParams::subgroup_cull`]).
    pub subgroup_cull: bool,
    /// Whether tiles are classified and the clear and reflection passes run indirectly.
    pub indirect: bool,
    /// Share of the screen the visible shapes' screen rectangles cover (summed, at most 1).
    pub coverage: f32,
    /// Glass panels and water planes with an atlas region (the layer pass runs when any).
    pub layers: Vec<LayerAlloc>,
    /// Atlas entries the layers use.
    pub layer_pixels: u32,
    /// The union of the layers' screen rectangles: the layer pass writes the 16 × 16 tiles,
    /// from its corner, that meet a layer's rectangle ([`Self::layer_tiles`], one workgroup
    /// each), and nothing else of it.
    pub layer_rect: ScreenRect,
    /// Visible glass panels or water planes that got no layer (over [`MAX_LAYERS`] or the
    /// atlas capacity of two screens).
    pub layers_dropped: usize,
    /// Whether a visible reflector has a normal map (the reflection pass perturbs it when
    /// the frame provides normals).
    pub normal_maps: bool,
    /// Visible shapes of the main buffer with roughness above 0 whose reflection the
    /// reflection pass blurs (largest on screen first, at most
    /// [`crate::gpu_types::GLOSSY_CAPACITY`]).
    pub glossy: Vec<u32>,
    /// Visible glossy shapes over that capacity: reflected as mirrors.
    pub glossy_dropped: usize,
    /// Shapes rougher than [`PlanParams::max_roughness`]: not rendered, left to the
    /// renderer's fallback.
    pub too_rough: usize,
    /// The encoding layout for this viewport.
    pub encoding: EncodingLayout,
}

/// Width / height of a viewport (of at least one pixel's height).
pub fn aspect_of([w, h]: [u32; 2]) -> f32 {
    w as f32 / h.max(1) as f32
}

impl FramePlan {
    /// Culls the table's shapes for `camera` and decides the passes.
    pub fn build(table: &ShapeTable, camera: &Camera, viewport: [u32; 2], params: &PlanParams) -> Self {
        Self::build_for_output(table, camera, viewport, viewport, params)
    }

    /// [`Self::build`] for passes that run at `viewport` but serve an output (and a depth
    /// buffer) of `output` pixels, as the reduced tiers' do: the camera's projection is
    /// the output's, of its aspect ratio, whatever the rounding of the reduced size.
    pub fn build_for_output(
        table: &ShapeTable,
        camera: &Camera,
        viewport: [u32; 2],
        output: [u32; 2],
        params: &PlanParams,
    ) -> Self {
        let [w, h] = viewport;
        let aspect = aspect_of(output);
        let clip_from_rel = camera.clip_from_relative(aspect);
        let mut plan = FramePlan {
            viewport,
            aspect,
            visible: Vec::new(),
            screen_rects: Vec::new(),
            tested: Vec::new(),
            grouped_shapes: 0,
            trees: Vec::new(),
            tree_index: false,
            source_rects: Vec::new(),
            disabled: 0,
            culled_back_side: 0,
            culled_frustum: 0,
            transparent_skipped: 0,
            occluder_tests: false,
            path_blockers: false,
            depth_occlusion: params.depth_occlusion.decide(true),
            occlusion_first: false,
            tile_culling: false,
            super_tiles: false,
            fused_lists: false,
            parallel_rule: false,
            uniform_tests: false,
            subgroup_cull: false,
            indirect: false,
            coverage: 0.0,
            layers: Vec::new(),
            layer_pixels: 0,
            layer_rect: ScreenRect { min: [0, 0], max: [0, 0] },
            layers_dropped: 0,
            normal_maps: false,
            glossy: Vec::new(),
            glossy_dropped: 0,
            too_rough: 0,
            encoding: EncodingLayout::for_resolution(w.max(1), h.max(1)),
        };
        let layers_on = params.layers.decide(true);
        // (shape, kind, rect) of visible glass and water, before allocation.
        let mut layer_candidates: Vec<(u32, ReflectorKind, ScreenRect)> = Vec::new();
        for (i, s) in table.shapes.iter().enumerate() {
            if !s.enabled {
                plan.disabled += 1;
                continue;
            }
            // In front means a negative plane distance; NaN (a broken camera) culls too.
            if s.roughness > params.max_roughness {
                plan.too_rough += 1;
                continue;
            }
            let in_front = s.plane_dist_from(camera.position) < 0.0;
            if !in_front {
                plan.culled_back_side += 1;
                continue;
            }
            let clip = s.corners().map(|c| clip_from_rel * (c - camera.position).as_vec3().extend(1.0));
            if outside_frustum(&clip) {
                plan.culled_frustum += 1;
                continue;
            }
            // One shape with a blocking occluder turns the tests on: the rest need no look.
            plan.occluder_tests = plan.occluder_tests || table.has_blocking_occluders(i);
            plan.normal_maps |= s.normal_map;
            let rect = screen_rect(&clip, viewport);
            match s.kind {
                ReflectorKind::Transparent if !layers_on => plan.transparent_skipped += 1,
                ReflectorKind::Transparent | ReflectorKind::Water if layers_on => {
                    layer_candidates.push((i as u32, s.kind, rect));
                }
                _ => {
                    plan.visible.push(i as u32);
                    plan.screen_rects.push(rect);
                }
            }
        }
        plan.allocate_layers(layer_candidates, params);
        plan.pick_glossy(table);
        plan.normal_maps &= params.normal_maps.decide(true);
        plan.occluder_tests &= params.occluder_lists.decide(false);
        // Sorted by parallel group (then set order): the projection pass's parallel rule
        // walks each group as one run.
        // The keys are unique (a shape is visible once): an unstable sort gives that order.
        let mut order: Vec<(u32, u32, u32)> = (plan.visible.iter().enumerate())
            .map(|(k, &i)| (table.shapes[i as usize].parallel_group, i, k as u32))
            .collect();
        order.sort_unstable();
        plan.visible = order.iter().map(|&(_, i, _)| i).collect();
        plan.screen_rects = order.iter().map(|&(_, _, k)| plan.screen_rects[k as usize]).collect();

        let screen = (w as f64 * h as f64).max(1.0);
        let covered: f64 = plan.screen_rects.iter().map(|r| r.area() as f64).sum();
        plan.coverage = (covered / screen).min(1.0) as f32;
        plan.parallel_rule = params.parallel_rule.decide(false);
        plan.merge_plane_groups(table, params);
        plan.merge_parallel_trees(table, params);
        plan.occlusion_first = plan.depth_occlusion && params.occlusion_first.decide(plan.trees.is_empty());
        let blocked = |i: &u32| table.path_blockers.get(*i as usize).is_some_and(|&b| b != NO_BLOCKER);
        plan.path_blockers = params.path_blockers.decide(true) && plan.visible.iter().any(blocked);
        let tested = plan.tested.len();
        // The renderer turns `Auto` subgroup culling off on devices without subgroups.
        let subgroups = params.subgroup_cull != Choice::Off;
        // The renderer turns `Auto` fused lists off on CPU adapters.
        let culling_from = if params.fused_lists != Choice::Off {
            params.fused_tile_culling_min_shapes
        } else if subgroups {
            params.subgroup_tile_culling_min_shapes
        } else {
            params.tile_culling_min_shapes
        };
        plan.tile_culling = params.tile_culling.decide(tested >= culling_from);
        plan.subgroup_cull =
            params.subgroup_cull.decide(!plan.tile_culling && tested >= params.subgroup_cull_min_shapes);
        plan.super_tiles =
            plan.tile_culling && params.super_tiles.decide(tested >= params.super_tiles_min_shapes);
        plan.fused_lists = plan.tile_culling && params.fused_lists.decide(true);
        plan.uniform_tests =
            params.uniform_tests.decide(true) && tested + plan.layers.len() <= UNIFORM_TESTS_CAPACITY;
        let pixels = u64::from(viewport[0]) * u64::from(viewport[1]);
        plan.indirect = params.indirect.decide(plan.coverage <= params.indirect_coverage_limit(pixels));
        if params.source_boxes.decide(true) {
            let boxes = SourceBoxes::new(camera.position, &clip_from_rel, viewport);
            let rect = |s: &ShapeSource| boxes.rect(s);
            let layers = plan.layers.iter().map(|l| rect(&table.shapes[l.shape as usize]));
            let entries = plan.tested.iter().map(|e| match *e {
                TestedEntry::Shape(i) => rect(&table.shapes[i as usize]),
                TestedEntry::PlaneGroup(g) => rect(&table.plane_groups.groups[g as usize].bounding_shape()),
                TestedEntry::ParallelTree(t) => {
                    let members = &plan.trees[t as usize].members;
                    boxes.union(members.len(), |k| &table.shapes[members[k] as usize]).0
                }
            });
            plan.source_rects = entries.chain(layers).collect();
        }
        plan
    }

    /// Fills `tested`: each visible shape, but one entry for the visible members of a plane
    /// group with enough of them (none of them too rough, no occluder lists).
    fn merge_plane_groups(&mut self, table: &ShapeTable, params: &PlanParams) {
        let groups = &table.plane_groups;
        let mut visible_members = vec![0usize; groups.groups.len()];
        for &i in &self.visible {
            if let Some(g) = groups.group_of[i as usize] {
                visible_members[g as usize] += 1;
            }
        }
        let merged: Vec<bool> = groups
            .groups
            .iter()
            .zip(&visible_members)
            .map(|(group, &n)| {
                !self.occluder_tests
                    && n >= 2
                    && group.max_roughness <= params.max_roughness
                    && params.plane_groups.decide(n >= params.plane_group_min_shapes)
            })
            .collect();
        let mut emitted = vec![false; groups.groups.len()];
        self.tested.clear();
        self.grouped_shapes = 0;
        for &i in &self.visible {
            match groups.group_of[i as usize] {
                Some(g) if merged[g as usize] => {
                    self.grouped_shapes += 1;
                    if !std::mem::replace(&mut emitted[g as usize], true) {
                        self.tested.push(TestedEntry::PlaneGroup(g));
                    }
                }
                _ => self.tested.push(TestedEntry::Shape(i)),
            }
        }
    }

    /// Replaces, in `tested`, the single shapes of each parallel family with enough of them
    /// by one tree entry (where its first member stood).
    fn merge_parallel_trees(&mut self, table: &ShapeTable, params: &PlanParams) {
        self.trees.clear();
        self.tree_index = params.tree_index.decide(true);
        if self.occluder_tests || self.parallel_rule {
            return;
        }
        let families = &table.parallel_families;
        let mut singles = vec![0usize; families.families.len()];
        for e in &self.tested {
            if let TestedEntry::Shape(i) = *e
                && let Some((f, _)) = families.family_of[i as usize]
            {
                singles[f as usize] += 1;
            }
        }
        let merged: Vec<bool> = singles
            .iter()
            .map(|&n| n >= 2 && params.parallel_trees.decide(n >= params.parallel_tree_min_shapes))
            .collect();
        if !merged.contains(&true) {
            return;
        }
        let mut tree_of: Vec<Option<u32>> = vec![None; families.families.len()];
        let mut tested = Vec::with_capacity(self.tested.len());
        for e in std::mem::take(&mut self.tested) {
            let TestedEntry::Shape(i) = e else {
                tested.push(e);
                continue;
            };
            match families.family_of[i as usize] {
                Some((f, _)) if merged[f as usize] => {
                    let t = *tree_of[f as usize].get_or_insert_with(|| {
                        tested.push(TestedEntry::ParallelTree(self.trees.len() as u32));
                        self.trees.push(FrameTree { family: f, members: Vec::new() });
                        self.trees.len() as u32 - 1
                    });
                    self.trees[t as usize].members.push(i);
                }
                _ => tested.push(e),
            }
        }
        self.tested = tested;
        for t in &mut self.trees {
            t.members.sort_by_key(|&m| families.family_of[m as usize].map(|(_, rank)| rank));
        }
    }

    /// Gives glass panels (largest first) and the `max_water_layers` largest water planes
    /// atlas regions; water planes left over go into the main buffer.
    fn allocate_layers(
        &mut self,
        mut candidates: Vec<(u32, ReflectorKind, ScreenRect)>,
        params: &PlanParams,
    ) {
        candidates.sort_by_key(|&(i, kind, rect)| {
            (kind == ReflectorKind::Water, std::cmp::Reverse(rect.area()), i)
        });
        let capacity = 2 * u64::from(self.viewport[0]) * u64::from(self.viewport[1]);
        let mut water = 0;
        let mut used = 0u64;
        for (shape, kind, rect) in candidates {
            let is_water = kind == ReflectorKind::Water;
            let fits = self.layers.len() < MAX_LAYERS && used + rect.area() <= capacity && rect.area() > 0;
            if fits && (!is_water || water < params.max_water_layers) {
                water += usize::from(is_water);
                self.layers.push(LayerAlloc { shape, kind, rect, offset: used as u32 });
                used += rect.area();
            } else if is_water {
                self.visible.push(shape);
                self.screen_rects.push(rect);
            } else {
                self.layers_dropped += 1;
            }
        }
        self.layer_pixels = used as u32;
        if let Some(first) = self.layers.first() {
            let mut r = first.rect;
            for l in &self.layers[1..] {
                r.min = [r.min[0].min(l.rect.min[0]), r.min[1].min(l.rect.min[1])];
                r.max = [r.max[0].max(l.rect.max[0]), r.max[1].max(l.rect.max[1])];
            }
            self.layer_rect = r;
        }
    }

    /// The visible shapes with roughness, largest on screen first, up to the capacity.
    fn pick_glossy(&mut self, table: &ShapeTable) {
        let mut rough: Vec<(u32, u64)> = self
            .visible
            .iter()
            .zip(&self.screen_rects)
            .filter(|&(&i, _)| table.shapes[i as usize].roughness > 0.0)
            .map(|(&i, r)| (i, r.area()))
            .collect();
        rough.sort_by_key(|&(i, area)| (std::cmp::Reverse(area), i));
        self.glossy_dropped = rough.len().saturating_sub(crate::gpu_types::GLOSSY_CAPACITY);
        self.glossy = rough.iter().take(crate::gpu_types::GLOSSY_CAPACITY).map(|&(i, _)| i).collect();
    }

    /// True when no pass runs this frame (nothing is dispatched; no output is written).
    pub fn is_empty(&self) -> bool {
        self.visible.is_empty() && self.layers.is_empty()
    }

    /// Names of the passes this frame records, in order.
    pub fn passes(&self) -> Vec<&'static str> {
        if self.is_empty() {
            return vec![];
        }
        let has_main = !self.visible.is_empty();
        let mut passes = Vec::new();
        // The clears: the classification's in indirect frames (the active tiles and the
        // atlas); a clear pass in direct frames only where the frame before's reflection
        // pass did not clear this frame's buffers (`FrameBuffers::take_slot`).
        passes.push(match (has_main, self.indirect) {
            (false, _) => "clear (atlas)",
            (true, true) => "classify + clear",
            (true, false) => "clear (unless done ahead)",
        });
        if self.tile_culling && !self.fused_lists {
            // The block lists' own pass (with fused lists the projection builds them).
            passes.push("block lists");
        }
        passes.push(match (self.tile_culling, self.super_tiles, self.subgroup_cull) {
            (true, true, false) => "projection (super-tiles, tiled)",
            (true, false, false) => "projection (tiled)",
            (false, _, false) => "projection",
            (true, true, true) => "projection (super-tiles, tiled, subgroup culling)",
            (true, false, true) => "projection (tiled, subgroup culling)",
            (false, _, true) => "projection (subgroup culling)",
        });
        if has_main {
            passes.push(match (self.indirect, self.normal_maps, !self.glossy.is_empty()) {
                (true, true, true) => "reflection (tiles, normal maps, glossy)",
                (true, true, false) => "reflection (tiles, normal maps)",
                (true, false, true) => "reflection (tiles, glossy)",
                (true, false, false) => "reflection (tiles)",
                (false, true, true) => "reflection (normal maps, glossy)",
                (false, true, false) => "reflection (normal maps)",
                (false, false, true) => "reflection (glossy)",
                (false, false, false) => "reflection",
            });
        }
        if !self.layers.is_empty() {
            passes.push("layers");
        }
        passes
    }

    /// Number of 16 × 16 tiles of the viewport.
    pub fn tile_count(&self) -> u32 {
        self.viewport[0].div_ceil(16) * self.viewport[1].div_ceil(16)
    }

    /// The layer pass's workgroups: the 16 × 16 tiles, from [`Self::layer_rect`]'s corner,
    /// that each layer's rectangle meets, layer after layer (a tile two rectangles meet
    /// counts twice). `layer_reflection.wgsl`'s `listed_tile` walks them in this order.
    pub fn layer_tiles(&self) -> u32 {
        let origin = self.layer_rect.min;
        self.layers
            .iter()
            .map(|l| {
                let span =
                    |a: usize| (l.rect.max[a] - origin[a]).div_ceil(16) - (l.rect.min[a] - origin[a]) / 16;
                span(0) * span(1)
            })
            .sum()
    }
}

/// Whether all corners lie outside one of the clip volume's planes (conservative).
fn outside_frustum(clip: &[Vec4; 4]) -> bool {
    let planes: [fn(&Vec4) -> f32; 5] = [
        |c| c.w + c.x,
        |c| c.w - c.x,
        |c| c.w + c.y,
        |c| c.w - c.y,
        // Near plane: z ≥ 0 for standard Z, z ≤ w for reversed Z; w > 0 covers both
        // conservatively (everything in front of the camera).
        |c| c.w,
    ];
    planes.iter().any(|inside| clip.iter().all(|c| inside(c) < 0.0))
}

/// Bounding rectangle of the corners on screen; the whole viewport if any corner is
/// behind the camera (the projection is unbounded then).
fn screen_rect(clip: &[Vec4; 4], [w, h]: [u32; 2]) -> ScreenRect {
    if clip.iter().any(|c| c.w <= 1e-6) {
        return ScreenRect { min: [0, 0], max: [w, h] };
    }
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::MAX), glam::Vec2::splat(f32::MIN));
    for c in clip {
        let ndc = c.truncate().truncate() / c.w;
        let px = (ndc * glam::Vec2::new(0.5, -0.5) + 0.5) * glam::Vec2::new(w as f32, h as f32);
        lo = lo.min(px);
        hi = hi.max(px);
    }
    let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
    ScreenRect {
        min: [clamp(lo.x.floor(), w), clamp(lo.y.floor(), h)],
        max: [clamp(hi.x.ceil(), w), clamp(hi.y.ceil(), h)],
    }
}

impl fmt::Display for FramePlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [w, h] = self.viewport;
        writeln!(
            f,
            "frame {w}x{h}: {} visible reflector(s); culled {} back-side, {} off-screen; {} disabled{}",
            self.visible.len(),
            self.culled_back_side,
            self.culled_frustum,
            self.disabled,
            if self.transparent_skipped > 0 {
                format!("; {} glass panel(s) skipped (layers off)", self.transparent_skipped)
            } else {
                String::new()
            }
        )?;
        if !self.layers.is_empty() || self.layers_dropped > 0 {
            let glass = self.layers.iter().filter(|l| l.kind == ReflectorKind::Transparent).count();
            writeln!(
                f,
                "layers: {glass} glass, {} water, {} atlas px{}",
                self.layers.len() - glass,
                self.layer_pixels,
                if self.layers_dropped > 0 {
                    format!(", {} dropped", self.layers_dropped)
                } else {
                    String::new()
                }
            )?;
        }
        if self.grouped_shapes > 0 {
            let groups = self.tested.iter().filter(|e| matches!(e, TestedEntry::PlaneGroup(_))).count();
            writeln!(
                f,
                "plane groups: {} coplanar reflector(s) tested as {groups} plane(s); {} projection test(s)",
                self.grouped_shapes,
                self.tested.len()
            )?;
        }
        if !self.trees.is_empty() {
            writeln!(
                f,
                "parallel trees: {} reflector(s) at many plane offsets walked as {} tree(s){}; {} projection test(s)",
                self.trees.iter().map(|t| t.members.len()).sum::<usize>(),
                self.trees.len(),
                if self.tree_index { " with offset indexes" } else { "" },
                self.tested.len()
            )?;
        }
        if !self.glossy.is_empty() || self.glossy_dropped > 0 || self.too_rough > 0 {
            writeln!(
                f,
                "glossy: {} blurred, {} over capacity (as mirrors), {} too rough (left to the fallback)",
                self.glossy.len(),
                self.glossy_dropped,
                self.too_rough
            )?;
        }
        if self.is_empty() {
            return write!(f, "passes: none (nothing dispatched)");
        }
        let l = &self.encoding;
        write!(
            f,
            "passes: {}; occlusion {}; parallel rule {}; screen coverage {:.0}%; encoding {}.{}/{}.{} bits (major/minor whole.fraction)",
            self.passes().join(" -> "),
            match (self.depth_occlusion, self.occluder_tests) {
                (true, true) => "depth + lists",
                (true, false) if self.occlusion_first => "depth, before encoding",
                (true, false) => "depth",
                (false, true) => "lists",
                (false, false) => "off",
            }
            .to_owned()
                + if self.path_blockers { " + path blockers" } else { "" },
            if self.parallel_rule { "on" } else { "off" },
            self.coverage * 100.0,
            l.major_int_bits,
            l.major_frac_bits,
            l.minor_int_bits,
            l.minor_frac_bits,
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec3};
    use ppr_format::{Reflector, ReflectorKind, ReflectorSet};

    use super::{Choice, FramePlan, LayerAlloc, PlanParams, ScreenRect};
    use crate::camera::{Camera, Projection};
    use crate::shapes::ShapeTable;

    /// `n` small floor mirrors in a grid in front of the camera, each tested alone.
    fn plan(n: usize, params: &PlanParams) -> FramePlan {
        let mut set = ReflectorSet::new("grid");
        for k in 0..n {
            let center = DVec3::new((k % 16) as f64 * 0.5 - 4.0, 0.0, -2.0 - (k / 16) as f64 * 0.5);
            set.reflectors.push(Reflector::new(
                k as u32,
                format!("tile {k}"),
                ReflectorKind::Opaque,
                center,
                DVec3::Y,
                DVec3::X,
                DVec2::splat(0.2),
            ));
        }
        let camera = Camera::look_at(
            DVec3::new(0.0, 4.0, 2.0),
            DVec3::new(0.0, 0.0, -4.0),
            Vec3::Y,
            Projection::default(),
        );
        let params = PlanParams { plane_groups: Choice::Off, ..*params };
        FramePlan::build(&ShapeTable::from_set(&set), &camera, [320, 180], &params)
    }

    #[test]
    fn indirect_dispatch_runs_up_to_the_coverage_threshold() {
        let d = PlanParams::default();
        let camera =
            Camera::look_at(DVec3::new(0.0, 4.0, 0.01), DVec3::ZERO, Vec3::NEG_Z, Projection::default());
        let (mut direct, mut indirect, mut qhd_direct, mut qhd_indirect) = (0, 0, 0, 0);
        // One floor mirror seen from above, growing until it fills the screen.
        for half in [0.2, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0] {
            let mut set = ReflectorSet::new("floor");
            set.reflectors.push(Reflector::new(
                0,
                "floor",
                ReflectorKind::Opaque,
                DVec3::ZERO,
                DVec3::Y,
                DVec3::X,
                DVec2::splat(half),
            ));
            let table = ShapeTable::from_set(&set);
            let p = FramePlan::build(&table, &camera, [3840, 2160], &d);
            assert_eq!(p.indirect, p.coverage <= d.indirect_max_coverage, "half extent {half}: {p}");
            // At 1080p and below the classification never pays; at 1440p up to a smaller share.
            for size in [[1920, 1080], [320, 180]] {
                let small = FramePlan::build(&table, &camera, size, &d);
                assert!(!small.indirect, "half extent {half}, {size:?}: {small}");
            }
            let qhd = FramePlan::build(&table, &camera, [2560, 1440], &d);
            assert_eq!(qhd.indirect, qhd.coverage <= d.indirect_coverage_limit(2560 * 1440), "{qhd}");
            qhd_indirect += usize::from(qhd.indirect);
            qhd_direct += usize::from(!qhd.indirect);
            if p.indirect {
                indirect += 1;
            } else {
                direct += 1;
            }
            let forced =
                FramePlan::build(&table, &camera, [320, 180], &PlanParams { indirect: Choice::On, ..d });
            assert!(forced.indirect, "{forced}");
        }
        assert!(
            direct > 0 && indirect > 0,
            "the sizes span the threshold: {direct} direct, {indirect} indirect"
        );
        assert!(qhd_direct > 0 && qhd_indirect > 0, "1440p: {qhd_direct} direct, {qhd_indirect} indirect");
    }

    #[test]
    fn the_indirect_coverage_limit_grows_with_the_pixel_count() {
        let d = PlanParams::default();
        let limit = |w: u64, h: u64| d.indirect_coverage_limit(w * h);
        assert_eq!(limit(320, 180), 0.0);
        assert_eq!(limit(1920, 1080), 0.0);
        assert!(limit(2560, 1440) > 0.05 && limit(2560, 1440) < 0.1, "{}", limit(2560, 1440));
        assert_eq!(limit(3840, 2160), d.indirect_max_coverage);
        assert_eq!(limit(7680, 4320), d.indirect_max_coverage);
        let sizes = [(1920, 1080), (2560, 1440), (2880, 1620), (3200, 1800), (3840, 2160), (5120, 2880)];
        for pair in sizes.windows(2) {
            let ((w0, h0), (w1, h1)) = (pair[0], pair[1]);
            assert!(limit(w0, h0) <= limit(w1, h1), "{pair:?}");
        }
        assert!(limit(2880, 1620) > 0.0 && limit(3200, 1800) > limit(2880, 1620));
        assert!(limit(3200, 1800) < d.indirect_max_coverage);
    }

    #[test]
    fn fused_tile_culling_runs_from_its_own_threshold() {
        let d = PlanParams::default();
        for (n, tiles) in
            [(d.fused_tile_culling_min_shapes - 1, false), (d.fused_tile_culling_min_shapes, true)]
        {
            let p = plan(n, &d);
            assert_eq!(p.tested.len(), n, "every mirror visible: {p}");
            assert_eq!((p.tile_culling, p.fused_lists), (tiles, tiles), "{n} shapes: {p}");
            assert!(!p.subgroup_cull, "{n} shapes: {p}");
        }
        assert!(!plan(d.fused_tile_culling_min_shapes, &d).to_string().contains("block lists"));
        let separate = PlanParams { fused_lists: Choice::Off, ..d };
        let p = plan(d.tile_culling_min_shapes, &PlanParams { subgroup_cull: Choice::Off, ..separate });
        assert!(p.tile_culling && !p.fused_lists, "{p}");
        assert!(p.to_string().contains("block lists -> projection (tiled)"), "{p}");
    }

    #[test]
    fn subgroup_culling_takes_the_counts_between_its_thresholds() {
        // With the block-list pass (fused lists off, as on CPU adapters).
        let d = PlanParams { fused_lists: Choice::Off, ..PlanParams::default() };
        for (n, subgroup, tiles) in [
            (d.subgroup_cull_min_shapes - 1, false, false),
            (d.subgroup_cull_min_shapes, true, false),
            (d.subgroup_tile_culling_min_shapes - 1, true, false),
            (d.subgroup_tile_culling_min_shapes, false, true),
        ] {
            let p = plan(n, &d);
            assert_eq!(p.tested.len(), n, "every mirror visible: {p}");
            assert_eq!((p.subgroup_cull, p.tile_culling), (subgroup, tiles), "{n} shapes: {p}");
        }
        // Without subgroups (the renderer turns Auto off) tile culling keeps its own
        // threshold; `On` culls by subgroup beside tile lists too.
        let off = PlanParams { subgroup_cull: Choice::Off, ..d };
        let p = plan(d.tile_culling_min_shapes, &off);
        assert!(!p.subgroup_cull && p.tile_culling, "{p}");
        let on = PlanParams { subgroup_cull: Choice::On, ..d };
        let p = plan(d.subgroup_tile_culling_min_shapes, &on);
        assert!(p.subgroup_cull && p.tile_culling, "{p}");
    }

    #[test]
    fn occlusion_comes_before_the_encoding_without_trees() {
        let d = PlanParams::default();
        let p = plan(20, &d);
        assert!(p.trees.is_empty() && p.depth_occlusion && p.occlusion_first, "{p}");
        assert!(p.to_string().contains("occlusion depth, before encoding"), "{p}");
        let p = plan(20, &PlanParams { occlusion_first: Choice::Off, ..d });
        assert!(!p.occlusion_first && p.to_string().contains("occlusion depth;"), "{p}");
        let p = plan(20, &PlanParams { depth_occlusion: Choice::Off, occlusion_first: Choice::On, ..d });
        assert!(!p.occlusion_first, "nothing to test first without depth occlusion: {p}");
        // The grid's mirrors share one plane; taken as a parallel tree, after the encoding.
        let p = plan(20, &PlanParams { parallel_trees: Choice::On, plane_groups: Choice::Off, ..d });
        assert!(!p.trees.is_empty() && !p.occlusion_first, "{p}");
    }

    #[test]
    fn layer_tiles_count_each_layers_tiles_from_the_common_corner() {
        let camera = Camera::look_at(DVec3::new(0.0, 1.0, 2.0), DVec3::ZERO, Vec3::Y, Projection::default());
        let mut p = FramePlan::build(&ShapeTable::default(), &camera, [256, 128], &PlanParams::default());
        assert_eq!(p.layer_tiles(), 0);
        let layer = |min: [u32; 2], max: [u32; 2]| LayerAlloc {
            shape: 0,
            kind: ReflectorKind::Water,
            rect: ScreenRect { min, max },
            offset: 0,
        };
        // From the common corner (10, 5): the first spans x 0..40 (3 tiles) and y 0..20 (2),
        // the second x 90..91 (1 tile, the sixth) and y 15..16 (the first); the tile
        // columns of the grid over the common rectangle, not the screen's.
        p.layers = vec![layer([10, 5], [50, 25]), layer([100, 20], [101, 21])];
        p.layer_rect = ScreenRect { min: [10, 5], max: [101, 25] };
        assert_eq!(p.layer_tiles(), 3 * 2 + 1);
        // A layer inside the first's tiles counts again (both workgroups shade it alike).
        p.layers.push(layer([20, 6], [25, 9]));
        assert_eq!(p.layer_tiles(), 3 * 2 + 1 + 1);
    }
}
