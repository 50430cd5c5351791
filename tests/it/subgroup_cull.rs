//! Subgroup culling (`PlanParams::subgroup_cull`): each subgroup of the projection visits
//! only the candidates whose box test passes against the box of its pixels' positions, and
//! tests only the plane of those whose pyramid holds that whole box. It writes what every
//! candidate writes (bit for bit, with and without block lists and the parallel rule) and
//! visits fewer candidates. Runs in `it` on the default adapter
//! (llvmpipe through GL in CI: no subgroup operations, so each invocation culls alone with
//! `subgroup_cull_fallback.wgsl`) and in `subgroups` on lavapipe through Vulkan, whose
//! subgroups run `subgroup_cull.wgsl`.

use ppr_runtime::{BoxReduction, Choice, ReflectionRenderer};

use ppr_tests::gpu::{gpu, read_buffer};
use ppr_tests::harness::{GpuFrame, renderer, run, validated};
use ppr_tests::random_scenes::{Rng, grouped_set, puddle_floor, random_camera, random_scene};

const SIZE: [u32; 2] = [128, 96];

/// Opens this binary's device (first thing in every test: the first `gpu()` picks it).
fn open_device() {
    crate::select_backends();
    if crate::REQUIRE_SUBGROUPS {
        assert!(
            gpu().device.features().contains(wgpu::Features::SUBGROUP),
            "this test binary needs an adapter with subgroups (lavapipe through Vulkan: \
             Debian's mesa-vulkan-drivers); got {:?}",
            gpu().info
        );
    }
}

fn configured(subgroups: Choice, culling: Choice, parallel_rule: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.subgroup_cull = subgroups;
    r.plan_params.tile_culling = culling;
    r.plan_params.parallel_rule = parallel_rule;
    r.plan_params.indirect = Choice::Off;
    r
}

fn debug_words(r: &ReflectionRenderer) -> Vec<u32> {
    bytemuck::pod_collect_to_vec(&read_buffer(r.debug_writes_buffer().expect("debug writes on")))
}

#[test]
fn subgroup_culling_writes_what_every_candidate_writes() {
    open_device();
    let mut rng = Rng(0x5eed_0101);
    let mut written = 0usize;
    for case in 0..6 {
        let parallel = case % 2 == 0;
        let scene = if case == 5 { puddle_floor(&mut rng) } else { random_scene(&mut rng, parallel) };
        let camera = random_camera(&mut rng);
        let frame = GpuFrame::upload(&scene.render(&camera, SIZE));
        let set = validated(&grouped_set(&scene));
        let rule = if case == 2 { Choice::On } else { Choice::Off };
        let mut plain = configured(Choice::Off, Choice::Off, rule);
        plain.set_reflectors(&set);
        let a = run(&mut plain, &frame, &camera);
        assert!(!a.plan.subgroup_cull);
        for culling in [Choice::Off, Choice::On] {
            let mut culled = configured(Choice::On, culling, rule);
            culled.set_reflectors(&set);
            let b = run(&mut culled, &frame, &camera);
            assert!(b.plan.subgroup_cull, "{}", b.plan);
            assert_eq!(b.plan.tile_culling, culling == Choice::On);
            assert_eq!(
                a.intermediate, b.intermediate,
                "intermediate buffers differ: case {case}, culling {culling:?}"
            );
            let bits =
                |o: &[glam::Vec4]| o.iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
            assert!(bits(&a.pixels) == bits(&b.pixels), "images differ: case {case}, culling {culling:?}");
        }
        written += a.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    }
    assert!(written > 3_000, "the random scenes must produce writes: {written}");
}

#[test]
fn subgroups_visit_fewer_candidates_and_keep_every_write() {
    open_device();
    let mut rng = Rng(0x5eed_0102);
    let (mut visited, mut candidates) = (0u64, 0u64);
    for case in 0..3 {
        let scene = random_scene(&mut rng, case == 1);
        let camera = random_camera(&mut rng);
        let frame = GpuFrame::upload(&scene.render(&camera, SIZE));
        let set = validated(&grouped_set(&scene));
        let mut masks = Vec::new();
        let mut lists = Vec::new();
        for subgroups in [Choice::Off, Choice::On] {
            for tile_lists in [false, true] {
                let mut r = configured(subgroups, Choice::Off, Choice::Off);
                r.debug.writes = true;
                r.debug.tile_lists = tile_lists;
                r.set_reflectors(&set);
                let out = run(&mut r, &frame, &camera);
                let words = debug_words(&r);
                if tile_lists {
                    lists.push((out.plan.visible.len() as u32, words));
                } else {
                    masks.push(words);
                }
            }
        }
        assert_eq!(
            masks[0], masks[1],
            "subgroup culling changed which shapes a pixel writes for: case {case}"
        );
        // Without culling a pixel visits no list (0xffffffff); with it, the candidates its
        // subgroup kept: never more than the visible shapes, never fewer than it writes for.
        let (shapes, unculled) = &lists[0];
        assert!(unculled.iter().all(|&n| n == u32::MAX));
        let (_, kept) = &lists[1];
        for (i, (&n, &m)) in kept.iter().zip(&masks[1]).enumerate() {
            assert!(n <= *shapes, "pixel {i} visits {n} of {shapes} candidates");
            assert!(m.count_ones() <= n, "pixel {i} writes for {} shapes but visits {n}", m.count_ones());
        }
        visited += kept.iter().map(|&n| u64::from(n)).sum::<u64>();
        candidates += u64::from(*shapes) * kept.len() as u64;
    }
    eprintln!("subgroup culling: {visited} of {candidates} pixel candidates visited");
    assert!(visited * 10 < candidates * 7, "culling must drop candidates: {visited} of {candidates} visited");
}

/// The fused lists' box of the block's positions reduced per subgroup first
/// (`DebugOptions::box_reduction`), then either with one invocation a subgroup in the
/// workgroup's atomics or through a slot per subgroup and one barrier, builds the lists of
/// the workgroup's atomics alone: every pixel's list length and every write equal. On
/// lavapipe (8-wide subgroups) the slots run as themselves; on llvmpipe through GL both
/// subgroup reductions fall back to subgroups of one.
#[test]
fn a_subgroup_reduced_box_builds_the_same_block_lists() {
    open_device();
    if crate::REQUIRE_SUBGROUPS {
        let info = &gpu().info;
        assert!(
            info.subgroup_min_size >= 8,
            "the slots' reduction needs subgroups at least 8 wide (else it falls back and goes \
             untested here); got {info:?}"
        );
    }
    let mut rng = Rng(0x5eed_0103);
    let mut listed = 0u64;
    for case in 0..4 {
        let scene = random_scene(&mut rng, case % 2 == 1);
        let camera = random_camera(&mut rng);
        let frame = GpuFrame::upload(&scene.render(&camera, SIZE));
        let set = validated(&grouped_set(&scene));
        let mut lists = Vec::new();
        let mut intermediates = Vec::new();
        for box_reduction in
            [BoxReduction::Atomics, BoxReduction::SubgroupAtomics, BoxReduction::SubgroupSlots]
        {
            for tile_lists in [false, true] {
                let mut r = configured(Choice::Off, Choice::On, Choice::Off);
                r.plan_params.fused_lists = Choice::On;
                r.debug.box_reduction = box_reduction;
                r.debug.writes = tile_lists;
                r.debug.tile_lists = tile_lists;
                r.set_reflectors(&set);
                let out = run(&mut r, &frame, &camera);
                assert!(out.plan.tile_culling && out.plan.fused_lists, "{}", out.plan);
                if tile_lists {
                    lists.push(debug_words(&r));
                } else {
                    intermediates.push(out.intermediate);
                }
            }
        }
        for (k, name) in [(1, "subgroup atomics"), (2, "subgroup slots")] {
            assert_eq!(lists[0], lists[k], "the {name}' box changed a block's list: case {case}");
            assert_eq!(intermediates[0], intermediates[k], "the {name}' box changed a write: case {case}");
        }
        listed += lists[0].iter().filter(|&&n| n != u32::MAX).map(|&n| u64::from(n)).sum::<u64>();
    }
    assert!(listed > 0, "the blocks must list candidates");
}
