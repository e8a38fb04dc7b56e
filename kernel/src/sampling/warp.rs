//! Elementary warps from `[0, 1)²`.

use crate::math;
use glam::{Vec2, Vec3};

/// Cosine-weighted hemisphere (Malley: uniform disk lifted), pdf `cosθ/π`.
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let r = math::sqrt0(u.x);
    let phi = math::TAU * u.y;
    let (x, y) = (r * math::cos(phi), r * math::sin(phi));
    Vec3::new(x, y, math::sqrt0(1.0 - u.x))
}

/// pdf of [`cosine_hemisphere`].
#[inline]
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z > 0.0 {
        w.z * (1.0 / math::PI)
    } else {
        0.0
    }
}

/// Inverse of [`cosine_hemisphere`].
#[inline]
pub fn cosine_hemisphere_inverse(w: Vec3) -> Vec2 {
    let r2 = w.x * w.x + w.y * w.y;
    let mut phi = math::atan2(w.y, w.x) * (1.0 / math::TAU);
    if phi < 0.0 {
        phi += 1.0;
    }
    Vec2::new(r2, phi)
}

/// Orthonormal azimuth helper: `(cos φ, sin φ)` of the projection of `w`, `(1, 0)` at the pole.
#[inline]
pub fn azimuth(w: Vec3) -> (f32, f32) {
    let r = math::sqrt(w.x * w.x + w.y * w.y);
    if r > 1.0e-12 {
        (w.x / r, w.y / r)
    } else {
        (1.0, 0.0)
    }
}
