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
/// A triangle light is split into `TRIANGLE_SPLITS²` sub-triangles.
pub const TRIANGLE_SPLITS: u32 = 6;
/// The most quadrature nodes of one light record.
pub const MAX_NODES: u32 = 36;

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

fn sphere_node(light: &SceneLight, p: Vec3, i: u32) -> Option<AreaNode> {
    let c = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
    let r = light.p0[3];
    let to_c = c - p;
    let d = to_c.length();
    if !(d > r && r > 0.0) || i >= SPHERE_RINGS * SPHERE_SECTORS {
        return None;
    }
    let w = to_c / d;
    let sin_a = r / d;
    let cos_a = math::sqrt0((1.0 - sin_a) * (1.0 + sin_a));
    let ring = i / SPHERE_SECTORS;
    let sector = i % SPHERE_SECTORS;
    // 4-point Gauss–Legendre on [cos α, 1] from the symmetric half tables.
    let half = (ring % 2) as usize;
    let (xk, wk) = if ring < 2 {
        (-GL4_X[1 - half], GL4_W[1 - half])
    } else {
        (GL4_X[half], GL4_W[half])
    };
    let mid = 0.5 * (1.0 + cos_a);
    let span = 0.5 * (1.0 - cos_a);
    let cos_t = mid + span * xk;
    let sin_t = math::sqrt0((1.0 - cos_t) * (1.0 + cos_t));
    let phi = math::TAU * (sector as f32 + 0.5) / SPHERE_SECTORS as f32;
    let (sp, cp) = math::sin_cos(phi);
    let (b1, b2) = orthonormal_basis(w);
    let dir = (w * cos_t + b1 * (sin_t * cp) + b2 * (sin_t * sp)).normalize_or_zero();
    // Distance to the sphere's near surface along dir.
    let proj = dir.dot(to_c);
    let disc = math::max(r * r - (d * d - proj * proj), 0.0);
    let dist = proj - math::sqrt0(disc);
    let weight = span * wk * math::TAU / SPHERE_SECTORS as f32;
    Some(AreaNode { dir, dist, weight })
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
