//! Unpolarised Fresnel reflectance for a complex index of refraction `η = n + ik`
//! (Holzschuch & Pacanowski 2017, Eqs. 11–13; valid for dielectrics and conductors).

use crate::lane::{Cx, Real};
use crate::math;

/// Reflectance `F = (F_s + F_p)/2` at incidence cosine `cos_theta` (clamped to [0, 1]) from
/// air onto a medium of relative index `n + ik` (`k ≥ 0` absorbs).
///
/// `F_s = |(cosθ − √(η² − sin²θ)) / (cosθ + √(η² − sin²θ))|²`,
/// `F_p = |(η² cosθ − √(η² − sin²θ)) / (η² cosθ + √(η² − sin²θ))|²`.
/// Any [`Real`]: one `f32` or lanes, the IOR per lane as well (a spectral IOR,
/// [`crate::conductor::ior`], differs between wavelengths).
#[inline(always)]
pub fn fresnel<R: Real>(cos_theta: R, n: R, k: R) -> R {
    let c = math::clamp(cos_theta, R::splat(0.0), R::splat(1.0));
    let eta2m1 = eta2_minus_1(n, k);
    let eta2 = Cx::new(n * n - k * k, eta2m1.im);
    let root = math::csqrt_cx(Cx::new(eta2m1.re + c * c, eta2m1.im));
    let fs = ratio_norm_sqr(Cx::real(c) - root, Cx::real(c) + root);
    let e2c = eta2.scale(c);
    let fp = ratio_norm_sqr(e2c - root, e2c + root);
    math::clamp(R::splat(0.5) * (fs + fp), R::splat(0.0), R::splat(1.0))
}

/// `η² − 1` for `η = n + ik`: `(n − 1)(n + 1) − k²` (exact for `n` near 1, where `n² − 1`
/// would cancel) and `2nk`.
#[inline(always)]
pub(crate) fn eta2_minus_1<R: Real>(n: R, k: R) -> Cx<R> {
    let one = R::splat(1.0);
    Cx::new((n - one) * (n + one) - k * k, R::splat(2.0) * n * k)
}

/// `|a|²/|b|²`, 1 where `|b| = 0`.
#[inline(always)]
fn ratio_norm_sqr<R: Real>(a: Cx<R>, b: Cx<R>) -> R {
    let den = b.norm_sqr();
    R::select(den.gt(R::splat(0.0)), a.norm_sqr() / den, R::splat(1.0))
}
