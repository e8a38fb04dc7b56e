//! Unpolarised Fresnel reflectance for a complex index of refraction `η = n + ik`
//! (Holzschuch & Pacanowski 2017, Eqs. 11–13; valid for dielectrics and conductors).

use crate::math::{self, C32};

/// Reflectance `F = (F_s + F_p)/2` at incidence cosine `cos_theta` (clamped to [0, 1]) from
/// air onto a medium of relative index `n + ik` (`k ≥ 0` absorbs).
///
/// `F_s = |(cosθ − √(η² − sin²θ)) / (cosθ + √(η² − sin²θ))|²`,
/// `F_p = |(η² cosθ − √(η² − sin²θ)) / (η² cosθ + √(η² − sin²θ))|²`.
pub fn fresnel(cos_theta: f32, n: f32, k: f32) -> f32 {
    let c = math::clamp(cos_theta, 0.0, 1.0);
    let eta2 = C32::new(n * n - k * k, 2.0 * n * k);
    // η² − sin²θ = (η² − 1) + cos²θ, with η² − 1 = (n − k)(n + k) − 1 + 2ink: no
    // cancellation at grazing incidence (`η² − (1 − cos²θ)` loses cos²θ once it is below
    // f32 resolution of 1) nor for n ≈ 1.
    let root = math::csqrt(C32::new((n - 1.0) * (n + 1.0) - k * k + c * c, 2.0 * n * k));
    let fs = ratio_norm_sqr(C32::new(c, 0.0) - root, C32::new(c, 0.0) + root);
    let e2c = math::cscale(eta2, c);
    let fp = ratio_norm_sqr(e2c - root, e2c + root);
    math::clamp(0.5 * (fs + fp), 0.0, 1.0)
}

/// `|a/b|²`, 1 when both vanish (grazing incidence on a matched medium).
#[inline]
fn ratio_norm_sqr(a: C32, b: C32) -> f32 {
    let den = b.norm_sqr();
    if den > 0.0 { a.norm_sqr() / den } else { 1.0 }
}
