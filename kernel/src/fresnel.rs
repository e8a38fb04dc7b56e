//! Unpolarised Fresnel reflectance for a complex index of refraction `η = n + ik`
//! (Holzschuch & Pacanowski 2017, Eqs. 11–13; valid for dielectrics and conductors).

use crate::lane::{Cx, Real};
use crate::math;

/// Reflectance `F = (F_s + F_p)/2` at incidence cosine `cos_theta` (clamped to [0, 1]) from
/// air onto a medium of relative index `n + ik` (`k ≥ 0` absorbs).
///
/// `F_s = |(cosθ − √(η² − sin²θ)) / (cosθ + √(η² − sin²θ))|²`,
/// `F_p = |(η² cosθ − √(η² − sin²θ)) / (η² cosθ + √(η² − sin²θ))|²`.
/// Any [`Real`] for the cosine (one `f32` or lanes); `n`, `k` are shared.
#[inline(always)]
pub fn fresnel<R: Real>(cos_theta: R, n: f32, k: f32) -> R {
    let c = math::clamp(cos_theta, R::splat(0.0), R::splat(1.0));
    let eta2 = Cx::<R>::splat(n * n - k * k, 2.0 * n * k);
    let root = math::csqrt_cx(Cx::new(
        R::splat((n - 1.0) * (n + 1.0) - k * k) + c * c,
        R::splat(2.0 * n * k),
    ));
    let fs = ratio_norm_sqr(Cx::real(c) - root, Cx::real(c) + root);
    let e2c = eta2.scale(c);
    let fp = ratio_norm_sqr(e2c - root, e2c + root);
    math::clamp(R::splat(0.5) * (fs + fp), R::splat(0.0), R::splat(1.0))
}

/// `|a|²/|b|²`, 1 where `|b| = 0`.
#[inline(always)]
fn ratio_norm_sqr<R: Real>(a: Cx<R>, b: Cx<R>) -> R {
    let den = b.norm_sqr();
    R::select(den.gt(R::splat(0.0)), a.norm_sqr() / den, R::splat(1.0))
}
