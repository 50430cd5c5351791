//! Parallel trees (`ppr_runtime::parallel_trees`): the treads of a stairway and shelves at
//! other heights, walked as one tree per family, write what testing each of them writes,
//! under every culling variant, and the plan merges only what it may.

use ppr_runtime::{Choice, ReflectionRenderer, TestedEntry};

use ppr_tests::harness::{GpuFrame, Output, renderer, run, validated};
use ppr_tests::views::{stairway, stairway_cameras as cameras};

const SIZE: [u32; 2] = [128, 96];

/// A renderer with the given tree choice and culling, full-screen passes.
fn configured(trees: Choice, culling: Choice, super_tiles: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.parallel_trees = trees;
    r.plan_params.tile_culling = culling;
    r.plan_params.super_tiles = super_tiles;
    r.plan_params.indirect = Choice::Off;
    r
}

fn written(out: &Output) -> usize {
    out.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count()
}

#[test]
fn the_write_shortcuts_leave_the_buffer_every_write_leaves() {
    // The projection loads the stored value first and gives up where it wins already (its
    // top field, the major whole part, alone may decide); with debug writes every write
    // goes through the whole path. Squeezed reflections in many treads make most writes
    // lose: the buffers must still be the same, bit for bit.
    let scene = stairway(40);
    let set = validated(&scene.reflector_set());
    let mut decided = 0usize;
    for camera in cameras() {
        let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
        let mut short = configured(Choice::On, Choice::Off, Choice::Off);
        short.set_reflectors(&set);
        let a = run(&mut short, &gpu, &camera);
        let mut full = configured(Choice::On, Choice::Off, Choice::Off);
        full.debug.writes = true;
        full.set_reflectors(&set);
        let b = run(&mut full, &gpu, &camera);
        let n = written(&a);
        assert!(n > 800, "the treads must reflect something: {n}");
        let differing = a.intermediate.iter().zip(&b.intermediate).filter(|(x, y)| x != y).count();
        assert_eq!(differing, 0, "{differing} of {n} written pixels differ");
        decided += n;
    }
    // (Path blockers empty the targets only far treads reached: about 4 600 with them.)
    assert!(decided > 4000, "{decided} written pixels over the cameras");
}

#[test]
fn a_walked_tree_writes_what_its_shapes_write() {
    let scene = stairway(40);
    let set = validated(&scene.reflector_set());
    let (mut checked, mut occlusion_decided) = (0usize, 0usize);
    for camera in cameras() {
        let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
        let mut plain = configured(Choice::Off, Choice::Off, Choice::Off);
        plain.set_reflectors(&set);
        let a = run(&mut plain, &gpu, &camera);
        let mut walked = configured(Choice::On, Choice::Off, Choice::Off);
        walked.set_reflectors(&set);
        let b = run(&mut walked, &gpu, &camera);
        eprintln!("{}", b.plan);
        assert_eq!(b.plan.trees.len(), 1, "treads and shelves share one normal: {}", b.plan);
        assert_eq!(b.plan.tested, vec![TestedEntry::ParallelTree(0)], "{}", b.plan);
        assert_eq!(b.plan.trees[0].members.len(), b.plan.visible.len());
        assert_eq!(a.plan.tested.len(), a.plan.visible.len(), "Off merges nothing");
        let n = written(&a);
        let differing = a.intermediate.iter().zip(&b.intermediate).filter(|(x, y)| x != y).count();
        eprintln!("{} visible, {n} pixels written, {differing} differ", a.plan.visible.len());
        assert!(n > 800, "the treads must reflect something: {n}");
        // Each reached member runs the plain loop's own test: the same writes.
        assert_eq!(differing, 0, "{differing} of {n} written pixels differ");
        checked += n;

        // The treads' offsets spread: the tree has an offset index (`Auto`), and the pixels
        // that take their members from it write what walking writes.
        assert!(b.plan.tree_index && b.plan.to_string().contains("with offset indexes"), "{}", b.plan);
        let words = ppr_runtime::shape_tests::frame_tests(walked.shapes(), &b.plan, camera.position);
        let header = (words.tests[0].shape & !ppr_runtime::parallel_trees::TREE_TEST_FLAG) as usize;
        assert_ne!(words.group_words[header + 13], 0, "the flight's tree has an index");
        let mut unindexed = configured(Choice::On, Choice::Off, Choice::Off);
        unindexed.plan_params.tree_index = Choice::Off;
        unindexed.set_reflectors(&set);
        let u = run(&mut unindexed, &gpu, &camera);
        assert!(!u.plan.tree_index, "{}", u.plan);
        let words = ppr_runtime::shape_tests::frame_tests(unindexed.shapes(), &u.plan, camera.position);
        assert_eq!(words.group_words[header + 13], 0, "no index unasked");
        assert_eq!(u.intermediate, b.intermediate, "walked only and through the index");

        // Block lists and super-tile lists treat the tree's test like any other.
        for (culling, super_tiles) in [(Choice::On, Choice::Off), (Choice::On, Choice::On)] {
            let mut tiled = configured(Choice::On, culling, super_tiles);
            tiled.set_reflectors(&set);
            let c = run(&mut tiled, &gpu, &camera);
            assert!(c.plan.tile_culling, "{}", c.plan);
            assert_eq!(c.intermediate, b.intermediate, "culling {culling:?}, super-tiles {super_tiles:?}");
        }
        // The depth occlusion tested before the encoding or after it (`Auto`: after with
        // trees, before without): the same buffer, walked or not.
        assert!(b.plan.depth_occlusion && !b.plan.occlusion_first && a.plan.occlusion_first, "{}", b.plan);
        for (trees, order, reference) in [(Choice::On, Choice::On, &b), (Choice::Off, Choice::Off, &a)] {
            let mut other = configured(trees, Choice::Off, Choice::Off);
            other.plan_params.occlusion_first = order;
            other.set_reflectors(&set);
            let d = run(&mut other, &gpu, &camera);
            assert_eq!(d.plan.occlusion_first, order == Choice::On, "{}", d.plan);
            assert_eq!(d.intermediate, reference.intermediate, "occlusion first {order:?}, trees {trees:?}");
        }
        // ... where the test decides something: without it the buffer differs.
        let mut unoccluded = configured(Choice::Off, Choice::Off, Choice::Off);
        unoccluded.plan_params.depth_occlusion = Choice::Off;
        unoccluded.set_reflectors(&set);
        let e = run(&mut unoccluded, &gpu, &camera);
        occlusion_decided += a.intermediate.iter().zip(&e.intermediate).filter(|(x, y)| x != y).count();
    }
    assert!(checked > 4000, "{checked} written pixels over the cameras");
    assert!(occlusion_decided > 100, "the depth test decides {occlusion_decided} pixels over the cameras");
}

#[test]
fn the_plan_walks_only_what_it_may() {
    let scene = stairway(24);
    let camera = cameras().remove(0);
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    let mut r = renderer();
    // A threshold this small scene reaches (the default is read from GPU runs of longer
    // flights).
    r.plan_params.parallel_tree_min_shapes = 16;
    r.set_reflectors(&validated(&scene.reflector_set()));
    let out = run(&mut r, &gpu, &camera);
    let visible = out.plan.visible.len();
    assert!(visible >= r.plan_params.parallel_tree_min_shapes, "{}", out.plan);
    assert_eq!(out.plan.tested.len(), 1, "Auto walks the family as a tree: {}", out.plan);
    assert!(out.plan.to_string().contains("parallel trees:"), "{}", out.plan);

    // Below the threshold, with debug write masks (per shape) or the parallel rule (which
    // keeps one member per pixel): every visible shape tested alone.
    r.plan_params.parallel_tree_min_shapes = visible + 1;
    assert_eq!(run(&mut r, &gpu, &camera).plan.tested.len(), visible);
    r.plan_params.parallel_tree_min_shapes = 2;
    r.debug.writes = true;
    assert_eq!(run(&mut r, &gpu, &camera).plan.tested.len(), visible);
    r.debug.writes = false;
    r.plan_params.parallel_rule = Choice::On;
    let ruled = run(&mut r, &gpu, &camera);
    assert!(ruled.plan.trees.is_empty(), "{}", ruled.plan);
    assert_eq!(ruled.plan.tested.len(), visible);
}
