//! An analytic test scene: quads and boxes ray-cast on the CPU (f64), giving the colour and
//! depth buffers the runtime reads and the exact reflection to compare it with.

use glam::{DVec3, Vec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_runtime::Camera;

/// How a quad is coloured (linear RGB as a function of the hit point's quad coordinates).
#[derive(Clone, Copy, Debug)]
pub enum Albedo {
    Solid(Vec3),
    /// Smooth two-axis gradient between two colours.
    Gradient(Vec3, Vec3),
    /// Stripes of two colours along u with the given period (in quad coordinates, 0..1).
    Stripes(Vec3, Vec3, f64),
    /// A smooth sinusoidal pattern with the given period (quad coordinates).
    Waves(f64),
}

impl Albedo {
    fn at(&self, s: f64, t: f64) -> Vec3 {
        match *self {
            Albedo::Solid(c) => c,
            Albedo::Gradient(a, b) => {
                let k = (0.5 * (s + t)).clamp(0.0, 1.0) as f32;
                a.lerp(b, k) * (0.8 + 0.2 * (t as f32).clamp(0.0, 1.0))
            }
            Albedo::Waves(period) => {
                let k = std::f64::consts::TAU / period;
                Vec3::new(
                    (0.5 + 0.35 * (k * s).sin()) as f32,
                    (0.5 + 0.35 * (k * t * 0.7).cos()) as f32,
                    (0.5 + 0.3 * (k * (s + t) * 0.5).sin()) as f32,
                )
            }
            Albedo::Stripes(a, b, period) => {
                if (s / period).floor().rem_euclid(2.0) < 1.0 {
                    a
                } else {
                    b
                }
            }
        }
    }
}

/// A double-sided rectangle.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub center: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub half: [f64; 2],
    pub albedo: Albedo,
    /// Index of the reflector this quad is, if it is one.
    pub mirror: Option<usize>,
    /// Glass: invisible to the colour and depth buffers (drawn after them in a game), seen
    /// only as a layer reflector.
    pub glass: bool,
    /// Normal-map bumps (amplitude, wavelength in metres): the shading normal tilts by up
    /// to `amplitude` radians in a pattern of that wavelength.
    pub bumps: Option<(f64, f64)>,
}

impl Quad {
    fn normal(&self) -> DVec3 {
        self.u.cross(self.v).normalize()
    }

    /// The shading normal at a point of the quad (the plane's, tilted by the bumps).
    fn shading_normal(&self, p: DVec3) -> DVec3 {
        let n = self.normal();
        let Some((amplitude, wavelength)) = self.bumps else { return n };
        let l = p - self.center;
        let k = std::f64::consts::TAU / wavelength;
        let tilt = self.u * (amplitude * (k * l.dot(self.u)).sin())
            + self.v * (amplitude * (k * l.dot(self.v) * 0.7).cos());
        (n + tilt).normalize()
    }

    /// Distance along the ray and quad coordinates in [0, 1]².
    fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, f64, f64)> {
        let n = self.normal();
        let dn = d.dot(n);
        if dn.abs() < 1e-12 {
            return None;
        }
        let t = (self.center - o).dot(n) / dn;
        if t <= 1e-9 {
            return None;
        }
        let l = o + d * t - self.center;
        let (a, b) = (l.dot(self.u), l.dot(self.v));
        (a.abs() <= self.half[0] && b.abs() <= self.half[1])
            .then(|| (t, 0.5 + 0.5 * a / self.half[0], 0.5 + 0.5 * b / self.half[1]))
    }
}

/// A scene of quads; some are mirrors.
#[derive(Clone, Debug, Default)]
pub struct AnalyticScene {
    pub quads: Vec<Quad>,
    /// The reflectors, index = `Quad::mirror`.
    pub set: Vec<Reflector>,
}

pub const SKY: Vec3 = Vec3::new(0.02, 0.02, 0.05);

impl AnalyticScene {
    pub fn quad(&mut self, center: DVec3, u: DVec3, v: DVec3, half: [f64; 2], albedo: Albedo) -> &mut Self {
        self.quads.push(Quad {
            center,
            u: u.normalize(),
            v: v.normalize(),
            half,
            albedo,
            mirror: None,
            glass: false,
            bumps: None,
        });
        self
    }

    fn reflector(&mut self, name: &str, kind: ReflectorKind, quad: Quad) -> &mut Reflector {
        let index = self.set.len();
        self.quads.push(Quad { mirror: Some(index), ..quad });
        let r = Reflector::new(
            index as u32,
            name,
            kind,
            quad.center,
            quad.u.cross(quad.v),
            quad.u,
            glam::DVec2::new(quad.half[0], quad.half[1]),
        );
        self.set.push(r);
        self.set.last_mut().expect("just pushed")
    }

    fn reflector_quad(center: DVec3, u: DVec3, v: DVec3, half: [f64; 2]) -> Quad {
        Quad {
            center,
            u: u.normalize(),
            v: v.normalize(),
            half,
            albedo: Albedo::Solid(Vec3::splat(0.1)),
            mirror: None,
            glass: false,
            bumps: None,
        }
    }

    /// A glass panel (a transparent reflector not in the colour and depth buffers); its
    /// reflecting side is `u × v`.
    pub fn glass(&mut self, name: &str, center: DVec3, u: DVec3, v: DVec3, half: [f64; 2]) -> &mut Self {
        let quad = Quad { glass: true, ..Self::reflector_quad(center, u, v, half) };
        self.reflector(name, ReflectorKind::Transparent, quad);
        self
    }

    /// A water plane (in the colour and depth buffers, kind `water`).
    pub fn water(&mut self, name: &str, center: DVec3, u: DVec3, v: DVec3, half: [f64; 2]) -> &mut Self {
        let quad = Self::reflector_quad(center, u, v, half);
        self.reflector(name, ReflectorKind::Water, quad);
        self
    }

    /// A mirror with a normal map of bumps (amplitude in radians, wavelength in metres).
    pub fn bumpy_mirror(
        &mut self,
        name: &str,
        center: DVec3,
        u: DVec3,
        v: DVec3,
        half: [f64; 2],
        bumps: (f64, f64),
    ) -> &mut Self {
        let quad = Quad { bumps: Some(bumps), ..Self::reflector_quad(center, u, v, half) };
        self.reflector(name, ReflectorKind::Opaque, quad).normal_map = true;
        self
    }

    /// A mirror quad; its reflecting side is `u × v`.
    pub fn mirror(&mut self, name: &str, center: DVec3, u: DVec3, v: DVec3, half: [f64; 2]) -> &mut Self {
        let quad = Self::reflector_quad(center, u, v, half);
        self.reflector(name, ReflectorKind::Opaque, quad);
        self
    }

    /// An axis-aligned box of six quads with slightly different shades per face.
    pub fn cuboid(&mut self, min: DVec3, max: DVec3, colour: Vec3) -> &mut Self {
        let c = (min + max) * 0.5;
        let h = (max - min) * 0.5;
        let faces = [
            (DVec3::X, DVec3::Y, DVec3::Z, [h.z, h.y], 0.8),
            (DVec3::NEG_X, DVec3::Y, DVec3::NEG_Z, [h.z, h.y], 0.7),
            (DVec3::Y, DVec3::Z, DVec3::X, [h.x, h.z], 1.0),
            (DVec3::NEG_Y, DVec3::X, DVec3::Z, [h.x, h.z], 0.5),
            (DVec3::Z, DVec3::X, DVec3::Y, [h.x, h.y], 0.9),
            (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y, [h.x, h.y], 0.75),
        ];
        for (n, u, v, half, shade) in faces {
            let offset = n * h.dot(n.abs());
            self.quad(c + offset, u, v, half, Albedo::Solid(colour * shade));
        }
        self
    }

    /// Gives the reflector `name` a roughness (its reflection becomes glossy).
    pub fn roughen(&mut self, name: &str, roughness: f64) -> &mut Self {
        let r = self.set.iter_mut().find(|r| r.name == name).unwrap_or_else(|| panic!("no reflector {name}"));
        r.roughness = roughness;
        self
    }

    /// The scene's reflectors as a valid set (parallel groups by normal).
    pub fn reflector_set(&self) -> ReflectorSet {
        let mut set = ReflectorSet::new("analytic scene");
        set.reflectors = self.set.clone();
        set.assign_parallel_groups();
        set.validate().expect("the test scene's reflectors are valid");
        set
    }

    /// Nearest hit along a ray: (distance, colour, quad index).
    fn cast(&self, o: DVec3, d: DVec3) -> Option<(f64, Vec3, usize)> {
        let mut best: Option<(f64, Vec3, usize)> = None;
        for (i, q) in self.quads.iter().enumerate().filter(|(_, q)| !q.glass) {
            if let Some((t, s, u)) = q.intersect(o, d)
                && best.is_none_or(|b| t < b.0)
            {
                best = Some((t, q.albedo.at(s, u), i));
            }
        }
        best
    }

    /// Renders the colour, depth and normal buffers and the exact reflections.
    pub fn render(&self, camera: &Camera, [w, h]: [u32; 2]) -> Frame {
        let aspect = w as f64 / h as f64;
        let clip_from_rel = camera.clip_from_relative(aspect as f32).as_dmat4();
        let rel_from_clip = clip_from_rel.inverse();
        let eye = camera.position;
        let n = (w * h) as usize;
        let mut f = Frame {
            size: [w, h],
            color: vec![SKY; n],
            depth: vec![camera.projection.far_depth(); n],
            normals: vec![Vec3::ZERO; n],
            mirror: vec![None; n],
            reference: vec![Vec3::ZERO; n],
            on_screen: vec![false; n],
            source_px: vec![glam::Vec2::ZERO; n],
            glass: vec![None; n],
            glass_reference: vec![Vec3::ZERO; n],
            glass_on_screen: vec![false; n],
            glass_depth: vec![None; n],
            glossy_reference: vec![Vec3::ZERO; n],
            far_depth: camera.projection.far_depth(),
        };
        let project = |p_rel: DVec3| {
            let c = clip_from_rel * p_rel.extend(1.0);
            (c.x / c.w, c.y / c.w, c.z / c.w, c.w)
        };
        // The colour seen along a reflected ray from `hit`, whether that point is on
        // screen, and where.
        let reflect = |hit: DVec3, r: DVec3, n: DVec3| -> (Vec3, bool, glam::Vec2) {
            match self.cast(hit + n * 1e-9, r) {
                None => (SKY, false, glam::Vec2::ZERO),
                Some((tr, c, _)) => {
                    // On screen: inside the viewport and the nearest surface there.
                    let q_rel = hit + r * tr - eye;
                    let (nx, ny, _, cw) = project(q_rel);
                    let inside = cw > 0.0 && nx.abs() < 1.0 && ny.abs() < 1.0;
                    let visible = self.cast(eye, q_rel.normalize()).is_some_and(|(tq, _, _)| {
                        (tq - q_rel.length()).abs() <= 1e-6 * q_rel.length().max(1.0)
                    });
                    let px = glam::Vec2::new(
                        ((nx * 0.5 + 0.5) * w as f64) as f32,
                        ((0.5 - 0.5 * ny) * h as f64) as f32,
                    );
                    (c, inside && visible, px)
                }
            }
        };
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let ndc = glam::DVec4::new(
                    (x as f64 + 0.5) / w as f64 * 2.0 - 1.0,
                    1.0 - (y as f64 + 0.5) / h as f64 * 2.0,
                    0.5,
                    1.0,
                );
                let p = rel_from_clip * ndc;
                let dir = (p.truncate() / p.w).normalize();
                let opaque = self.cast(eye, dir);
                // The nearest glass panel in front of the opaque surface, seen from its
                // reflecting side.
                let mut glass: Option<(f64, usize)> = None;
                for (qi, q) in self.quads.iter().enumerate().filter(|(_, q)| q.glass) {
                    if let Some((t, _, _)) = q.intersect(eye, dir)
                        && dir.dot(q.normal()) < 0.0
                        && opaque.is_none_or(|o| t < o.0)
                        && glass.is_none_or(|g| t < g.0)
                    {
                        glass = Some((t, qi));
                    }
                }
                if let Some((t, qi)) = glass {
                    let q = &self.quads[qi];
                    let hit = eye + dir * t;
                    let n = q.normal();
                    let (c, on_screen, _) = reflect(hit, dir - 2.0 * dir.dot(n) * n, n);
                    f.glass[i] = q.mirror;
                    f.glass_reference[i] = c;
                    f.glass_on_screen[i] = on_screen;
                    f.glass_depth[i] = Some(project(dir * t).2 as f32);
                }
                let Some((t, colour, qi)) = opaque else { continue };
                f.color[i] = colour;
                f.depth[i] = project(dir * t).2 as f32;
                let quad = &self.quads[qi];
                let hit = eye + dir * t;
                let shading = quad.shading_normal(hit);
                f.normals[i] = shading.as_vec3();
                let Some(m) = quad.mirror else { continue };
                // Seen from the reflecting side only.
                if dir.dot(quad.normal()) >= 0.0 {
                    continue;
                }
                f.mirror[i] = Some(m);
                let (c, on_screen, px) = reflect(hit, dir - 2.0 * dir.dot(shading) * shading, quad.normal());
                let roughness = self.set[m].roughness;
                f.glossy_reference[i] = if roughness > 0.0 {
                    glossy(roughness, quad.normal(), dir, |r| reflect(hit, r, quad.normal()).0)
                } else {
                    c
                };
                f.reference[i] = c;
                f.on_screen[i] = on_screen;
                f.source_px[i] = px;
            }
        }
        f
    }
}

/// Samples of the GGX lobe per pixel of the glossy reference.
pub const GLOSSY_SAMPLES: u32 = 256;

/// The glossy reflection seen along `dir` off a surface of normal `n`: the mean of the
/// colour `along` the reflected rays over the GGX distribution of microfacet normals
/// (alpha = roughness²; tan θ = alpha √(ξ/(1−ξ)), Hammersley points), rays that leave
/// below the surface left out. It is what the runtime's glossy blur approximates.
fn glossy(roughness: f64, n: DVec3, dir: DVec3, along: impl Fn(DVec3) -> Vec3) -> Vec3 {
    let alpha = roughness * roughness;
    let (t, b) = n.any_orthonormal_pair();
    let (mut sum, mut count) = (Vec3::ZERO, 0u32);
    for k in 0..GLOSSY_SAMPLES {
        let xi = (f64::from(k) + 0.5) / f64::from(GLOSSY_SAMPLES);
        let phi = std::f64::consts::TAU * f64::from(k.reverse_bits()) / 2f64.powi(32);
        let tan = alpha * (xi / (1.0 - xi)).sqrt();
        let h = (n + tan * (phi.cos() * t + phi.sin() * b)).normalize();
        let r = dir - 2.0 * dir.dot(h) * h;
        if r.dot(n) > 0.0 {
            sum += along(r);
            count += 1;
        }
    }
    if count == 0 { Vec3::ZERO } else { sum / count as f32 }
}

/// CPU images of one frame (row-major, top row first).
pub struct Frame {
    pub size: [u32; 2],
    pub color: Vec<Vec3>,
    pub depth: Vec<f32>,
    /// Reflector index seen at each pixel (reflecting side only).
    pub mirror: Vec<Option<usize>>,
    /// The exact reflected colour at mirror pixels.
    pub reference: Vec<Vec3>,
    /// Mirror pixels whose reflected point is visible on screen.
    pub on_screen: Vec<bool>,
    /// Where the reflected point of each on-screen mirror pixel is on screen (pixels).
    pub source_px: Vec<glam::Vec2>,
    /// The depth of pixels where nothing was hit (the projection's far depth).
    pub far_depth: f32,
    /// Shading normal of the opaque surface at each pixel (zero where nothing was hit).
    pub normals: Vec<Vec3>,
    /// The glass panel (reflector index) in front of the opaque surface at each pixel.
    pub glass: Vec<Option<usize>>,
    /// The exact reflection off that glass panel.
    pub glass_reference: Vec<Vec3>,
    /// Glass pixels whose reflected point is visible on screen.
    pub glass_on_screen: Vec<bool>,
    /// The depth of the glass panel at glass pixels (what a renderer whose depth pass
    /// writes glass would have in its depth buffer).
    pub glass_depth: Vec<Option<f32>>,
    /// The glossy reflection at mirror pixels (reflectors with roughness; the exact
    /// reflection on mirrors): see [`GLOSSY_SAMPLES`].
    pub glossy_reference: Vec<Vec3>,
}

impl Frame {
    /// A copy of every image (for comparisons against another reference).
    pub fn clone_images(&self) -> Frame {
        Frame {
            size: self.size,
            color: self.color.clone(),
            depth: self.depth.clone(),
            mirror: self.mirror.clone(),
            reference: self.reference.clone(),
            on_screen: self.on_screen.clone(),
            source_px: self.source_px.clone(),
            far_depth: self.far_depth,
            normals: self.normals.clone(),
            glass: self.glass.clone(),
            glass_reference: self.glass_reference.clone(),
            glass_on_screen: self.glass_on_screen.clone(),
            glass_depth: self.glass_depth.clone(),
            glossy_reference: self.glossy_reference.clone(),
        }
    }

    pub fn on_screen_count(&self) -> usize {
        self.on_screen.iter().filter(|&&b| b).count()
    }
}
