//! Scene lights and deterministic quadrature over the solid angle of the area lights.
//!
//! The coherent models (Werner) and GHS have no closed form over an area light, so their
//! light integral `∫ f cos θi L dω` is a fixed quadrature (also what the shadow rays of
//! every model sample):
//! * sphere: the cone of half-angle `α = asin(r/d)` about the centre direction, 4-point
//!   Gauss–Legendre in `cos θ ∈ [cos α, 1]` × 8 equal sectors in φ (32 nodes, exact solid
//!   angle `2π(1 − cos α)`);
//! * triangle: split into `6 × 6` similar sub-triangles, one node at each centroid with
//!   `dω = A_sub cos θ_l / d²` (36 nodes).
//!
//! The error is that of resolving the BRDF's angular structure: smooth lobes (GHS, the
//! incoherent sum) converge like the midpoint rule; Werner's speckle and narrow specular
//! lobe (angular width ~λ/(2πσ) ≈ 0.01 rad at σ = 10 µm) are not resolved by nodes spaced
//! wider than that, so images of coherent models under large area lights are an estimate
//! whose error is not bounded by this rule (see `docs/render.md`).

use crate::math;
use crate::math::quadrature::{GL4_W, GL4_X};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

gpu_enum! {
    /// The kind of a [`SceneLight`].
    pub enum SceneLightKind {
        /// Point light: `p0` position, `emission` intensity (W/sr).
        Point = 0,
        /// Directional light: `p0` unit direction towards the light, `emission` irradiance
        /// on a surface facing it.
        Directional = 1,
        /// Sphere light: `p0` centre, `p0[3]` radius, `emission` radiance.
        Sphere = 2,
        /// Triangle of a polygon light: `p0`, `p1`, `p2` vertices, `emission` radiance.
        Triangle = 3,
    }
    fallback = Point;
}

/// One light of a scene (polygon lights arrive as triangles). GPU-visible: 80 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SceneLight {
    /// A [`SceneLightKind`] as `u32`.
    pub kind: u32,
    /// Index of the scene light this record belongs to (triangles of one polygon share it).
    pub source: u32,
    /// Explicit padding.
    pub pad: [u32; 2],
    /// Position, direction or sphere centre (+ radius); first vertex.
    pub p0: [f32; 4],
    /// Second vertex (triangles).
    pub p1: [f32; 4],
    /// Third vertex (triangles).
    pub p2: [f32; 4],
    /// Intensity, irradiance or radiance (the same at every wavelength).
    pub emission: f32,
    /// Explicit padding.
    pub pad1: [f32; 3],
}

const _: () = assert!(core::mem::size_of::<SceneLight>() == 80);

/// Gauss–Legendre points in `cos θ` across a sphere light's cone.
pub const SPHERE_RINGS: u32 = 4;
/// Sectors in φ around a sphere light's centre direction.
pub const SPHERE_SECTORS: u32 = 8;
/// `(sin φ, cos φ)` of the sector centres `φ = 2π(s + ½)/8` (to f32 rounding).
const SECTOR_SIN_COS: [(f32, f32); SPHERE_SECTORS as usize] = [
    (0.382_683_43, 0.923_879_5),
    (0.923_879_5, 0.382_683_43),
    (0.923_879_5, -0.382_683_43),
    (0.382_683_43, -0.923_879_5),
    (-0.382_683_43, -0.923_879_5),
    (-0.923_879_5, -0.382_683_43),
    (-0.923_879_5, 0.382_683_43),
    (-0.382_683_43, 0.923_879_5),
];

/// A triangle light is split into `TRIANGLE_SPLITS²` sub-triangles.
pub const TRIANGLE_SPLITS: u32 = 6;
/// The most quadrature nodes of one light record.
pub const MAX_NODES: u32 = 36;

/// Probe nodes of a sphere light: 4 nodes of the outermost ring, a quarter turn apart.
pub const SPHERE_PROBES: u32 = 4;
/// Probe nodes of a triangle light: its 3 corner sub-triangles.
pub const TRIANGLE_PROBES: u32 = 3;

/// Number of visibility probes of `light` (0 for point and directional lights).
///
/// Adaptive visibility: a renderer traces the probes' shadow rays first; when all agree
/// (the light wholly visible or wholly hidden, as almost everywhere outside penumbrae) it
/// takes that answer for every node, and traces the remaining nodes only when they
/// disagree. An occluder that hides part of the light but none of its probes is missed.
#[inline]
pub fn probe_count(light: &SceneLight) -> u32 {
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => SPHERE_PROBES,
        SceneLightKind::Triangle => TRIANGLE_PROBES,
        _ => 0,
    }
}

/// The node index of probe `k` of `light` ([`probe_count`]): sphere, ring 0 (the
/// Gauss–Legendre node nearest the rim) at sectors 0, 2, 4, 6; triangle, the sub-triangles
/// at `v0`, `v1` and `v2`.
#[inline]
pub fn probe_node(light: &SceneLight, k: u32) -> u32 {
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => (k % SPHERE_PROBES) * (SPHERE_SECTORS / SPHERE_PROBES),
        SceneLightKind::Triangle => {
            let n = TRIANGLE_SPLITS;
            match k {
                0 => 0,
                1 => (n - 1) * (n - 1),
                _ => n * n - 1,
            }
        }
        _ => 0,
    }
}

/// One quadrature node: the unit direction from the shading point towards it, the distance
/// to the light surface along it, and its solid-angle weight (sr).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaNode {
    /// Unit direction (world).
    pub dir: Vec3,
    /// Distance to the light along `dir` (the shadow ray's extent).
    pub dist: f32,
    /// Solid-angle weight (sr).
    pub weight: f32,
}

/// Number of quadrature nodes of `light` (0 for point and directional lights).
#[inline]
pub fn node_count(light: &SceneLight) -> u32 {
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => SPHERE_RINGS * SPHERE_SECTORS,
        SceneLightKind::Triangle => TRIANGLE_SPLITS * TRIANGLE_SPLITS,
        _ => 0,
    }
}

/// An orthonormal pair perpendicular to the unit vector `n` (Duff et al. 2017).
#[inline]
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Node `i` of `light` seen from `p`; `None` when the node does not exist (a point inside
/// the sphere, a degenerate triangle, a node seen edge-on or from behind).
pub fn area_node(light: &SceneLight, p: Vec3, i: u32) -> Option<AreaNode> {
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => sphere_node(light, p, i),
        SceneLightKind::Triangle => triangle_node(light, p, i),
        _ => None,
    }
}

/// The per-point part of a sphere light's quadrature, shared by its nodes.
#[derive(Clone, Copy, Debug)]
struct SphereView {
    to_c: Vec3,
    d: f32,
    r: f32,
    w: Vec3,
    b1: Vec3,
    b2: Vec3,
    mid: f32,
    span: f32,
}

fn sphere_view(light: &SceneLight, p: Vec3) -> Option<SphereView> {
    let c = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
    let r = light.p0[3];
    let to_c = c - p;
    let d = to_c.length();
    if !(d > r && r > 0.0) {
        return None;
    }
    let w = to_c / d;
    let sin_a = r / d;
    let cos_a = math::sqrt0((1.0 - sin_a) * (1.0 + sin_a));
    let (b1, b2) = orthonormal_basis(w);
    Some(SphereView {
        to_c,
        d,
        r,
        w,
        b1,
        b2,
        mid: 0.5 * (1.0 + cos_a),
        span: 0.5 * (1.0 - cos_a),
    })
}

fn sphere_view_node(v: &SphereView, i: u32) -> AreaNode {
    let ring = (i / SPHERE_SECTORS) % SPHERE_RINGS;
    let sector = i % SPHERE_SECTORS;
    // 4-point Gauss–Legendre on [cos α, 1] from the symmetric half tables.
    let half = (ring % 2) as usize;
    let (xk, wk) = if ring < 2 {
        (-GL4_X[1 - half], GL4_W[1 - half])
    } else {
        (GL4_X[half], GL4_W[half])
    };
    let cos_t = v.mid + v.span * xk;
    let sin_t = math::sqrt0((1.0 - cos_t) * (1.0 + cos_t));
    let (sp, cp) = SECTOR_SIN_COS[(sector % SPHERE_SECTORS) as usize];
    let dir = (v.w * cos_t + v.b1 * (sin_t * cp) + v.b2 * (sin_t * sp)).normalize_or_zero();
    // Distance to the sphere's near surface along dir.
    let proj = dir.dot(v.to_c);
    let disc = math::max(v.r * v.r - (v.d * v.d - proj * proj), 0.0);
    let dist = proj - math::sqrt0(disc);
    let weight = v.span * wk * math::TAU / SPHERE_SECTORS as f32;
    AreaNode { dir, dist, weight }
}

fn sphere_node(light: &SceneLight, p: Vec3, i: u32) -> Option<AreaNode> {
    if i >= SPHERE_RINGS * SPHERE_SECTORS {
        return None;
    }
    sphere_view(light, p).map(|v| sphere_view_node(&v, i))
}

/// Most probes of one light record.
pub const MAX_PROBES: usize = 4;

/// The probe nodes of `light` seen from `p` (entry `k` is
/// `area_node(light, p, probe_node(light, k))`, bitwise), sharing the per-point set-up.
pub fn probe_nodes(light: &SceneLight, p: Vec3) -> [Option<AreaNode>; MAX_PROBES] {
    let mut out = [None; MAX_PROBES];
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => {
            if let Some(v) = sphere_view(light, p) {
                let mut k = 0;
                while k < SPHERE_PROBES as usize && k < MAX_PROBES {
                    out[k] = Some(sphere_view_node(&v, probe_node(light, k as u32)));
                    k += 1;
                }
            }
        }
        SceneLightKind::Triangle => {
            let mut k = 0;
            while k < TRIANGLE_PROBES as usize && k < MAX_PROBES {
                out[k] = triangle_node(light, p, probe_node(light, k as u32));
                k += 1;
            }
        }
        _ => {}
    }
    out
}

/// Whether every point of `light` lies below the plane through `p` with normal `n` (no
/// node can then be above the horizon): a sphere whose centre is more than its radius
/// below, a triangle with no vertex above.
pub fn below_horizon(light: &SceneLight, p: Vec3, n: Vec3) -> bool {
    let h = |v: [f32; 4]| (Vec3::new(v[0], v[1], v[2]) - p).dot(n);
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => h(light.p0) < -light.p0[3],
        SceneLightKind::Triangle => h(light.p0) <= 0.0 && h(light.p1) <= 0.0 && h(light.p2) <= 0.0,
        _ => false,
    }
}

fn triangle_node(light: &SceneLight, p: Vec3, i: u32) -> Option<AreaNode> {
    let n = TRIANGLE_SPLITS;
    if i >= n * n {
        return None;
    }
    let v0 = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
    let v1 = Vec3::new(light.p1[0], light.p1[1], light.p1[2]);
    let v2 = Vec3::new(light.p2[0], light.p2[1], light.p2[2]);
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    let cross = e1.cross(e2);
    let area2 = cross.length();
    if !(area2 > 0.0) {
        return None;
    }
    let normal = cross / area2;
    // Sub-triangle i: row `a` (0..n), index `b` in the row (0..2a+1); even b points up.
    let mut a = 0;
    while (a + 1) * (a + 1) <= i {
        a += 1;
    }
    let b = i - a * a;
    let nf = n as f32;
    let (ca, cb) = if b & 1 == 0 {
        let k = (b / 2) as f32;
        // Corners (a, k), (a+1, k), (a+1, k+1) in (row, column) lattice units.
        ((3.0 * a as f32 + 2.0) / 3.0, (3.0 * k + 1.0) / 3.0)
    } else {
        let k = (b / 2) as f32;
        // Corners (a, k), (a, k+1), (a+1, k+1).
        ((3.0 * a as f32 + 1.0) / 3.0, (3.0 * k + 2.0) / 3.0)
    };
    // Lattice point (row ρ, column κ) ↦ v0 + (ρ − κ)/n e1 + κ/n e2 (row ρ spans ρ+1 points).
    let q = v0 + e1 * ((ca - cb) / nf) + e2 * (cb / nf);
    let to_q = q - p;
    let dist = to_q.length();
    if !(dist > 0.0) {
        return None;
    }
    let dir = to_q / dist;
    let cos_l = math::abs(normal.dot(dir));
    let sub_area = 0.5 * area2 / (nf * nf);
    let weight = sub_area * cos_l / (dist * dist);
    if !(weight > 0.0) {
        return None;
    }
    Some(AreaNode { dir, dist, weight })
}
