//! Objects as the shading sees them: the shading frame and the scratch-space position of a
//! hit (Werner 2017 §5: scratches placed in a surface parametrisation).
//!
//! * Rectangle: the point `center + a·tangent + b·(normal × tangent)` has scratch-space
//!   position `(a, b)·unit_um` µm and frame `x = tangent`, `y = normal × tangent`,
//!   `z = normal`.
//! * Sphere: `u = φ/2π ∈ [0, 1)`, `v = θ/π` about the pole axis `normal` (φ from `tangent`);
//!   scratch space `(u, 1 − v)·uv_um` µm; frame `x` along `∂P/∂u`, `z` the outward normal,
//!   `y = z × x` (towards the pole).
//! * Mesh: scratch space `UV·uv_um` µm, frame `x` along `∂P/∂u` ([`mesh_point`]).

use crate::math;
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

gpu_enum! {
    /// The shape of a [`Surface`].
    pub enum SurfaceKind {
        /// A rectangle (two triangles in the ray structures).
        Rectangle = 0,
        /// A sphere (a tessellation in the ray structures; shading uses the exact sphere).
        Sphere = 1,
        /// A triangle mesh with texture coordinates ([`mesh_point`]).
        Mesh = 2,
    }
    fallback = Rectangle;
}

/// One object's shading geometry. GPU-visible: 64 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Surface {
    /// A [`SurfaceKind`] as `u32`.
    pub kind: u32,
    /// Index of the object's material.
    pub material: u32,
    /// Explicit padding.
    pub pad: [u32; 2],
    /// Centre.
    pub center: [f32; 3],
    /// µm per scene unit (rectangle) or per unit of `(u, v)` (sphere).
    pub scale_um: f32,
    /// Unit tangent (rectangle: the `a` axis; sphere: the direction of φ = 0).
    pub tangent: [f32; 3],
    /// Sphere radius (scene units).
    pub radius: f32,
    /// Unit normal (rectangle) or pole axis (sphere).
    pub normal: [f32; 3],
    /// Explicit padding.
    pub pad1: f32,
}

const _: () = assert!(core::mem::size_of::<Surface>() == 64);

/// The shading frame and scratch-space position at a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Hit position (scene units).
    pub position: Vec3,
    /// Frame `x` (scratch-space first axis).
    pub x: Vec3,
    /// Frame `y`.
    pub y: Vec3,
    /// Frame `z`, the shading normal.
    pub z: Vec3,
    /// Scratch-space position (µm).
    pub x_um: Vec2,
    /// µm of scratch space per scene unit along `x` and along `y` at this point (the
    /// footprint maps hit-position derivatives with it).
    pub um_per_unit: Vec2,
}

impl SurfacePoint {
    /// A world direction in the shading frame.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// A shading-frame direction in world space.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}

/// The hit position `origin + t·dir`.
#[inline]
pub fn hit_position(origin: [f32; 3], dir: [f32; 3], t: f32) -> Vec3 {
    Vec3::from_array(origin) + Vec3::from_array(dir) * t
}

/// The shading frame and scratch-space position of surface `s` at `p`.
pub fn surface_point(s: &Surface, p: Vec3) -> SurfacePoint {
    let c = Vec3::from_array(s.center);
    let t = Vec3::from_array(s.tangent);
    let n = Vec3::from_array(s.normal);
    let d = p - c;
    if SurfaceKind::from_u32(s.kind) == SurfaceKind::Sphere {
        let z = d.normalize_or_zero();
        let b = n.cross(t);
        // φ about the pole n, from t towards n × t; θ from the pole.
        let (cx, cy, cz) = (z.dot(t), z.dot(b), z.dot(n));
        // φ in [0, 2π), so that u = φ/2π covers [0, 1) like every UV map.
        let phi = math::atan2(cy, cx);
        let phi = if phi < 0.0 { phi + math::TAU } else { phi };
        let theta = math::acos(math::clamp(cz, -1.0, 1.0));
        // ∂P/∂φ ∝ n × z; at the poles fall back to the tangent.
        let mut x = n.cross(z);
        let rho = x.length();
        x = if rho > 1.0e-6 { x / rho } else { t };
        let y = z.cross(x);
        let u = phi / math::TAU;
        let v = theta / math::PI;
        let r = s.radius;
        let rho_s = math::max(rho * r, 1.0e-30);
        SurfacePoint {
            position: p,
            x,
            y,
            z,
            x_um: Vec2::new(u, 1.0 - v) * s.scale_um,
            um_per_unit: Vec2::new(
                s.scale_um / (math::TAU * rho_s),
                s.scale_um / (math::PI * math::max(r, 1.0e-30)),
            ),
        }
    } else {
        let y = n.cross(t);
        SurfacePoint {
            position: p,
            x: t,
            y,
            z: n,
            x_um: Vec2::new(d.dot(t), d.dot(y)) * s.scale_um,
            um_per_unit: Vec2::new(s.scale_um, s.scale_um),
        }
    }
}

/// Texture coordinates of one mesh triangle's vertices. GPU-visible: 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct TriangleUv {
    /// `(u, v)` of `v0`, `v1`, `v2`.
    pub uv: [[f32; 2]; 3],
    /// Explicit padding.
    pub pad: [f32; 2],
}

const _: () = assert!(core::mem::size_of::<TriangleUv>() == 32);

/// The shading frame and scratch-space position on a mesh triangle at barycentrics
/// `(b1, b2)` (weights of `v1`, `v2`): scratch space `UV·uv_um` µm (Werner §5: scratches
/// in the texture parametrisation), `z` the geometric normal (flat shading), `x` along
/// `∂P/∂u` projected into the plane (the first edge when the UVs are degenerate),
/// `y = z × x`.
pub fn mesh_point(
    tri: &crate::ray::Triangle,
    uv: &TriangleUv,
    b1: f32,
    b2: f32,
    p: Vec3,
    uv_um: f32,
) -> SurfacePoint {
    let v0 = Vec3::from_array(tri.v0);
    let e1 = Vec3::from_array(tri.v1) - v0;
    let e2 = Vec3::from_array(tri.v2) - v0;
    let z = e1.cross(e2).normalize_or_zero();
    let t0 = Vec2::from_array(uv.uv[0]);
    let d1 = Vec2::from_array(uv.uv[1]) - t0;
    let d2 = Vec2::from_array(uv.uv[2]) - t0;
    let det = d1.x * d2.y - d2.x * d1.y;
    let (dpdu, dpdv) = if math::abs(det) > 0.0 {
        ((e1 * d2.y - e2 * d1.y) / det, (e2 * d1.x - e1 * d2.x) / det)
    } else {
        (e1, e2)
    };
    let xu = dpdu - z * z.dot(dpdu);
    let x = if xu.length_squared() > 0.0 {
        xu.normalize()
    } else {
        e1.normalize_or_zero()
    };
    let y = z.cross(x);
    let uvp = t0 + d1 * b1 + d2 * b2;
    let lu = math::max(dpdu.length(), 1.0e-30);
    let lv = math::max(dpdv.length(), 1.0e-30);
    SurfacePoint {
        position: p,
        x,
        y,
        z,
        x_um: uvp * uv_um,
        um_per_unit: Vec2::new(uv_um / lu, uv_um / lv),
    }
}
