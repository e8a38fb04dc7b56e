//! The shading frame at a hit: world ↔ local directions. Local `z` is the normal, local `x`
//! the tangent, which is also the first axis of scratch space (positions in µm), so scratch
//! tangents and `ξ` are expressed in the same axes as local directions.

use crate::math;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// Orthonormal shading frame. GPU-visible: 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ShadingFrame {
    /// Unit tangent (local `x`, scratch-space `x`).
    pub t: [f32; 3],
    /// Explicit padding.
    pub pad0: f32,
    /// Unit bitangent `n × t` (local `y`).
    pub b: [f32; 3],
    /// Explicit padding.
    pub pad1: f32,
    /// Unit normal (local `z`).
    pub n: [f32; 3],
    /// Explicit padding.
    pub pad2: f32,
}

const _: () = assert!(core::mem::size_of::<ShadingFrame>() == 48);

impl Default for ShadingFrame {
    fn default() -> Self {
        ShadingFrame::from_normal_tangent(Vec3::Z, Vec3::X)
    }
}

impl ShadingFrame {
    /// The frame of normal `n` and tangent `t` (both normalised here; `t` is made
    /// orthogonal to `n` by Gram–Schmidt). A tangent parallel to the normal (or zero) is
    /// replaced by the branchless basis of Duff et al. 2017, so the frame is always
    /// orthonormal for a finite non-zero normal.
    pub fn from_normal_tangent(n: Vec3, t: Vec3) -> ShadingFrame {
        let n = n.normalize_or_zero();
        let n = if n.length_squared() > 0.0 { n } else { Vec3::Z };
        let tp = t - n * n.dot(t);
        let l2 = tp.length_squared();
        let t = if l2 > 1.0e-12 && l2.is_finite() {
            tp / math::sqrt(l2)
        } else {
            // Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, Listing 3.
            let s = math::sign(n.z);
            let a = -1.0 / (s + n.z);
            let bb = n.x * n.y * a;
            Vec3::new(1.0 + s * n.x * n.x * a, s * bb, -s * n.x)
        };
        let b = n.cross(t);
        ShadingFrame {
            t: t.to_array(),
            pad0: 0.0,
            b: b.to_array(),
            pad1: 0.0,
            n: n.to_array(),
            pad2: 0.0,
        }
    }

    /// World → local: `(v·t, v·b, v·n)`.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(
            v.dot(Vec3::from_array(self.t)),
            v.dot(Vec3::from_array(self.b)),
            v.dot(Vec3::from_array(self.n)),
        )
    }

    /// Local → world: `x t + y b + z n`.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        Vec3::from_array(self.t) * v.x
            + Vec3::from_array(self.b) * v.y
            + Vec3::from_array(self.n) * v.z
    }
}
