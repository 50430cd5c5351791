//! Which views the exact reference renders beyond the first bounce: for every view, each
//! other reflector plane it may show, seen through it (breadth first, so that a capped
//! budget drops the deepest bounces first).

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;

use crate::mirror_camera::MirrorClipping;
use crate::mirror_chain::{ChainedView, may_show_in, mirrored_view_through};
use crate::reflector_planes::ReflectorPlane;

/// Where a later-bounce view is seen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BounceParent {
    /// In the first-bounce (mirrored) view of plane group `k`.
    Plane(usize),
    /// In the later-bounce view `i` of [`BouncePlan::views`].
    View(usize),
}

/// A view at bounce 2 or more.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BounceView {
    /// The view it is seen in.
    pub parent: BounceParent,
    /// Its bounce: 2 for a mirror seen in a first-bounce view.
    pub depth: u32,
    /// The plane group seen through.
    pub plane: usize,
    /// Its matrices.
    pub chain: ChainedView,
}

/// A first-bounce view (the plane group and its mirrored view), where the recursion starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BounceRoot {
    pub plane: usize,
    pub chain: ChainedView,
}

/// The later-bounce views of a frame, at most a budget of them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BouncePlan {
    /// Breadth first: every view of bounce `d` before those of `d + 1`.
    pub views: Vec<BounceView>,
    /// Views that would have been rendered but were over the budget (their plane then
    /// shows its own colour at that bounce, as in a one-bounce reference).
    pub skipped: usize,
}

impl BouncePlan {
    /// The views seen in `parent`, with their indices.
    pub fn children(&self, parent: BounceParent) -> impl Iterator<Item = (usize, &BounceView)> {
        self.views.iter().enumerate().filter(move |(_, v)| v.parent == parent)
    }
}

/// What [`plan_bounces`] needs besides the roots.
pub struct BounceScene<'a> {
    pub set: &'a ReflectorSet,
    pub planes: &'a [ReflectorPlane],
    pub camera: &'a Camera,
    /// Width over height.
    pub aspect: f64,
    pub clipping: MirrorClipping,
}

/// The views of bounces 2 to `bounces` below `roots`, at most `max_views` of them.
///
/// A plane is never looked for in its own view (it is clipped there); a view is made only
/// when the plane may show in its parent and the camera is on the reflecting side of its
/// image.
pub fn plan_bounces(
    scene: &BounceScene<'_>,
    roots: &[BounceRoot],
    bounces: u32,
    max_views: usize,
) -> BouncePlan {
    let mut plan = BouncePlan::default();
    let mut frontier: Vec<(BounceParent, usize, ChainedView)> =
        roots.iter().map(|r| (BounceParent::Plane(r.plane), r.plane, r.chain)).collect();
    for depth in 2..=bounces {
        let mut next = Vec::new();
        for (parent, last, chain) in &frontier {
            for (q, group) in scene.planes.iter().enumerate() {
                if q == *last || !may_show_in(scene.set, group, scene.camera, &chain.view.clip_from_rel) {
                    continue;
                }
                let Some(view) = mirrored_view_through(
                    scene.camera,
                    scene.aspect,
                    &chain.reflection,
                    &group.plane,
                    scene.clipping,
                ) else {
                    continue;
                };
                if plan.views.len() >= max_views {
                    plan.skipped += 1;
                    continue;
                }
                plan.views.push(BounceView { parent: *parent, depth, plane: q, chain: view });
                next.push((BounceParent::View(plan.views.len() - 1), q, view));
            }
        }
        frontier = next;
    }
    plan
}
