//! One analytical planar reflector: a rectangle in world space with its metadata.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// How a reflector is shaded, which decides the runtime path it takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ReflectorKind {
    /// A mirror, polished floor, puddle: writes the main intermediate buffer.
    #[default]
    Opaque,
    /// A glass panel or window: gets its own region of the transparent atlas.
    Transparent,
    /// A water plane: gets one of the water reflection layers.
    Water,
}

impl ReflectorKind {
    /// Every kind, in file order.
    pub const ALL: [ReflectorKind; 3] = [Self::Opaque, Self::Transparent, Self::Water];

    /// The name used in the file and on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Opaque => "opaque",
            Self::Transparent => "transparent",
            Self::Water => "water",
        }
    }
}

impl std::fmt::Display for ReflectorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for ReflectorKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.as_str() == s)
            .ok_or_else(|| format!("unknown reflector kind `{s}` (expected opaque, transparent or water)"))
    }
}

/// Where in the source level a reflector came from (glTF names or indices as text).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReflectorSource {
    /// Names (or `#index`) of the nodes whose triangles were fitted.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nodes: Vec<String>,
    /// Names (or `#index`) of the materials of those triangles.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<String>,
}

/// A rectangle that encloses (part of) a reflective planar region.
///
/// Invariants (checked by [`crate::ReflectorSet::validate`]):
/// - `axis_u`, `axis_v` and `normal` are unit length and mutually orthogonal
///   (within [`crate::AXIS_TOLERANCE`]);
/// - `half_extents` are finite and strictly positive;
/// - `center` is finite and within [`crate::MAX_COORDINATE`] of the origin;
/// - `coverage` is in `[0, 1]`;
/// - `roughness` is finite and in `[0, 1]`;
/// - `occluders` are indices of other reflectors of the same set, without repeats;
/// - reflectors of one `parallel_group` face the same way: each normal is within
///   [`crate::PARALLEL_GROUP_MAX_ANGLE_DEG`] of the group's first reflector's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reflector {
    /// Stable identifier, unique within the set; kept across re-extraction and edits.
    pub id: u32,
    /// Human-readable name (for the inspector and error messages).
    pub name: String,
    /// How the reflector is shaded.
    pub kind: ReflectorKind,
    /// Disabled reflectors are kept in the file but never rendered.
    #[serde(default = "default_true")]
    pub enabled: bool,
    /// Centre of the rectangle, world space, metres.
    pub center: DVec3,
    /// First in-plane axis (unit).
    pub axis_u: DVec3,
    /// Second in-plane axis (unit, orthogonal to `axis_u`).
    pub axis_v: DVec3,
    /// Half size along `axis_u` and `axis_v`, metres.
    pub half_extents: DVec2,
    /// Unit normal of the reflecting side (orthogonal to both axes).
    pub normal: DVec3,
    /// Reflective area of the fitted region divided by the rectangle's area, in `[0, 1]`.
    pub coverage: f64,
    /// Perceptual roughness of the surface, as glTF defines it (`roughnessFactor` times the
    /// metallic-roughness texture's green channel): 0 is a perfect mirror, 1 fully rough.
    /// For a reflector fitted to several surfaces, their area-weighted mean. Absent in
    /// version-1 files, which read as 0 (they described perfect mirrors).
    #[serde(default)]
    pub roughness: f64,
    /// Reflectors with the same group share one normal (within the extractor's tolerance,
    /// and at most [`crate::PARALLEL_GROUP_MAX_ANGLE_DEG`] from the group's first normal);
    /// reflectors facing other ways need groups of their own
    /// ([`crate::ReflectorSet::assign_parallel_groups`]).
    pub parallel_group: u32,
    /// Indices (into the set's `reflectors`) of reflectors that may stand between a
    /// camera and this one.
    #[serde(default)]
    pub occluders: Vec<u32>,
    /// What the reflector was fitted to.
    #[serde(default)]
    pub source: ReflectorSource,
    /// The surface has a normal map: the runtime may perturb its reflection when the frame
    /// provides shading normals.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub normal_map: bool,
}

fn default_true() -> bool {
    true
}

impl Reflector {
    /// A rectangle at `center` that reflects on the side `normal` points to, `half_extents`
    /// along `axis_u` and along `axis_v = normal × axis_u`; full coverage, roughness 0 (a
    /// perfect mirror), no occluders.
    ///
    /// The facing is what you pass: a floor seen from above has `normal = +Y` whatever its
    /// in-plane axes. `normal` and `axis_u` must be unit length and orthogonal
    /// ([`crate::ReflectorSet::validate`] checks it).
    pub fn new(
        id: u32,
        name: impl Into<String>,
        kind: ReflectorKind,
        center: DVec3,
        normal: DVec3,
        axis_u: DVec3,
        half_extents: DVec2,
    ) -> Self {
        Self {
            id,
            name: name.into(),
            kind,
            enabled: true,
            center,
            axis_u,
            axis_v: normal.cross(axis_u),
            half_extents,
            normal,
            coverage: 1.0,
            roughness: 0.0,
            parallel_group: 0,
            occluders: Vec::new(),
            source: ReflectorSource::default(),
            normal_map: false,
        }
    }

    /// Area of the rectangle in square metres.
    pub fn area(&self) -> f64 {
        4.0 * self.half_extents.x * self.half_extents.y
    }

    /// The four corners, counter-clockwise seen from the reflecting side.
    pub fn corners(&self) -> [DVec3; 4] {
        let u = self.axis_u * self.half_extents.x;
        let v = self.axis_v * self.half_extents.y;
        let c = self.center;
        if self.axis_u.cross(self.axis_v).dot(self.normal) >= 0.0 {
            [c - u - v, c + u - v, c + u + v, c - u + v]
        } else {
            [c - u + v, c + u + v, c + u - v, c - u - v]
        }
    }

    /// Signed distance of `p` from the reflector's plane (positive on the reflecting side).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        (p - self.center).dot(self.normal)
    }

    /// Coordinates of `p` in the rectangle's frame: (along u, along v, along normal).
    pub fn local(&self, p: DVec3) -> DVec3 {
        let d = p - self.center;
        DVec3::new(d.dot(self.axis_u), d.dot(self.axis_v), d.dot(self.normal))
    }

    /// Whether the projection of `p` on the plane falls inside the rectangle grown by `margin`.
    pub fn contains_projection(&self, p: DVec3, margin: f64) -> bool {
        let l = self.local(p);
        l.x.abs() <= self.half_extents.x + margin && l.y.abs() <= self.half_extents.y + margin
    }
}
