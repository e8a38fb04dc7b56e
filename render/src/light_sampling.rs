//! Solid-angle sampling of the scene's area lights for the Monte Carlo reference
//! ([`crate::reference`]): one direction per call, with the distance to the light along it
//! and its weight `1/pdf` (sr), returned as a kernel [`AreaNode`] so the kernel's
//! [`area_node_radiance_spectrum`](scratchwave_kernel::render::shading::area_node_radiance_spectrum)
//! (`f·cos θi·L·dω`) turns it into radiance.
//!
//! * Sphere: directions uniform in the cone of half-angle `α = asin(r/d)` about the centre
//!   direction, `cos θ = 1 − u₁(1 − cos α)`, `φ = 2πu₂`, pdf `1/(2π(1 − cos α))`.
//! * Triangle: uniform in the spherical triangle it subtends (Arvo 1995, "Stratified
//!   sampling of spherical triangles", SIGGRAPH '95, Fig. 2), pdf `1/Ω`. When the spherical
//!   triangle is too small or too thin for the construction (its solid angle below
//!   [`MIN_SOLID_ANGLE`] or a non-finite result), the fallback samples a point uniformly
//!   on the triangle's area, `dω = A |cos θ_l| / d²` ([`sample_triangle_area`]).
//!
//! Everything is computed in `f64` (the solid angle of a small light is a difference of
//! nearly equal angles) and rounded once at the end.

use glam::DVec3;
use scratchwave_kernel::render::area::{AreaNode, SceneLight, SceneLightKind};

/// Below this solid angle (sr) a triangle is sampled by area instead of by Arvo's
/// construction.
pub const MIN_SOLID_ANGLE: f64 = 1.0e-12;

/// One sampled direction towards a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Direction, distance and weight `1/pdf` (sr).
    pub node: AreaNode,
    /// The triangle was sampled by area (the fallback), not by solid angle.
    pub area_fallback: bool,
}

fn v3(p: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

fn node(dir: DVec3, dist: f64, weight: f64) -> Option<AreaNode> {
    let d = dir.as_vec3();
    let (dist, weight) = (dist as f32, weight as f32);
    (dist.is_finite() && dist > 0.0 && weight.is_finite() && weight > 0.0 && d.is_finite())
        .then_some(AreaNode {
            dir: d,
            dist,
            weight,
        })
}

/// A direction towards `light` seen from `p` for `u ∈ [0, 1)²`: uniform in solid angle
/// (sphere: uniform cone; triangle: Arvo 1995), `None` for delta lights, a point inside a
/// sphere light or a degenerate triangle.
pub fn sample_light(light: &SceneLight, p: glam::Vec3, u: [f64; 2]) -> Option<LightSample> {
    let p = p.as_dvec3();
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => {
            sample_sphere(v3(light.p0), f64::from(light.p0[3]), p, u).map(|node| LightSample {
                node,
                area_fallback: false,
            })
        }
        SceneLightKind::Triangle => {
            let (a, b, c) = (v3(light.p0), v3(light.p1), v3(light.p2));
            match sample_spherical_triangle(a, b, c, p, u) {
                Some(node) => Some(LightSample {
                    node,
                    area_fallback: false,
                }),
                None => sample_triangle_area(a, b, c, p, u).map(|node| LightSample {
                    node,
                    area_fallback: true,
                }),
            }
        }
        _ => None,
    }
}

/// Uniform direction in the cone a sphere (centre `c`, radius `r`) subtends from `p`;
/// weight `2π(1 − cos α)`, distance to the sphere's near surface.
pub fn sample_sphere(c: DVec3, r: f64, p: DVec3, u: [f64; 2]) -> Option<AreaNode> {
    let to_c = c - p;
    let d2 = to_c.length_squared();
    if !(r > 0.0 && d2 > r * r) {
        return None;
    }
    let d = d2.sqrt();
    let w = to_c / d;
    let sin2 = (r * r) / d2;
    let cos_a = (1.0 - sin2).max(0.0).sqrt();
    // 1 − cos α without cancellation.
    let one_minus_cos = sin2 / (1.0 + cos_a);
    let one_minus_cos_t = u[0] * one_minus_cos;
    let cos_t = 1.0 - one_minus_cos_t;
    let sin_t = (one_minus_cos_t * (2.0 - one_minus_cos_t)).max(0.0).sqrt();
    let phi = std::f64::consts::TAU * u[1];
    let (b1, b2) = w.any_orthonormal_pair();
    let dir = (w * cos_t + b1 * (sin_t * phi.cos()) + b2 * (sin_t * phi.sin())).normalize();
    let proj = dir.dot(to_c);
    let disc = (r * r - (d2 - proj * proj)).max(0.0);
    let dist = proj - disc.sqrt();
    node(dir, dist, std::f64::consts::TAU * one_minus_cos)
}

/// The solid angle (sr) of the triangle `a, b, c` seen from the origin of its unit
/// directions (Van Oosterom & Strackee 1983).
pub fn solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let num = a.dot(b.cross(c)).abs();
    let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
    2.0 * num.atan2(den)
}

/// The component of `v` orthogonal to the unit vector `n`, normalised.
fn ortho(v: DVec3, n: DVec3) -> DVec3 {
    (v - n * v.dot(n)).normalize_or_zero()
}

/// Angle at vertex `a` of the spherical triangle `a, b, c` (unit vectors).
fn vertex_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (tb, tc) = (ortho(b, a), ortho(c, a));
    tb.dot(tc).clamp(-1.0, 1.0).acos()
}

/// Uniform direction in the spherical triangle that the triangle `v0, v1, v2` subtends from
/// `p` (Arvo 1995); weight Ω, distance to the triangle's plane. `None` below
/// [`MIN_SOLID_ANGLE`] or when the construction is not finite.
pub fn sample_spherical_triangle(
    v0: DVec3,
    v1: DVec3,
    v2: DVec3,
    p: DVec3,
    u: [f64; 2],
) -> Option<AreaNode> {
    let (a, b, c) = (
        (v0 - p).normalize_or_zero(),
        (v1 - p).normalize_or_zero(),
        (v2 - p).normalize_or_zero(),
    );
    let omega = solid_angle(a, b, c);
    if !(omega > MIN_SOLID_ANGLE) {
        return None;
    }
    // Arvo 1995, Fig. 2: α is the angle at A, c the arc length of the edge AB.
    let alpha = vertex_angle(a, b, c);
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let cos_c = a.dot(b);
    let area = u[0] * omega;
    let (s, t) = (area - alpha).sin_cos();
    let uu = t - cos_alpha;
    let vv = s + sin_alpha * cos_c;
    let q = ((vv * t - uu * s) * cos_alpha - vv) / ((vv * s + uu * t) * sin_alpha);
    let q = q.clamp(-1.0, 1.0);
    let c_hat = a * q + ortho(c, a) * (1.0 - q * q).max(0.0).sqrt();
    let z = 1.0 - u[1] * (1.0 - c_hat.dot(b));
    let dir = (b * z + ortho(c_hat, b) * (1.0 - z * z).max(0.0).sqrt()).normalize_or_zero();
    let n = (v1 - v0).cross(v2 - v0);
    let dist = n.dot(v0 - p) / n.dot(dir);
    if !q.is_finite() {
        return None;
    }
    node(dir, dist, omega)
}

/// The fallback: a point uniform on the triangle's area, weight `A |cos θ_l| / d²`
/// (the solid angle per unit pdf of area sampling).
pub fn sample_triangle_area(
    v0: DVec3,
    v1: DVec3,
    v2: DVec3,
    p: DVec3,
    u: [f64; 2],
) -> Option<AreaNode> {
    let (mut x, mut y) = (u[0], u[1]);
    if x + y > 1.0 {
        (x, y) = (1.0 - x, 1.0 - y);
    }
    let q = v0 + (v1 - v0) * x + (v2 - v0) * y;
    let cross = (v1 - v0).cross(v2 - v0);
    let area = 0.5 * cross.length();
    let to_q = q - p;
    let d2 = to_q.length_squared();
    if !(area > 0.0 && d2 > 0.0) {
        return None;
    }
    let dist = d2.sqrt();
    let dir = to_q / dist;
    let cos_l = cross.normalize().dot(dir).abs();
    node(dir, dist, area * cos_l / d2)
}
