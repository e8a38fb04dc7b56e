//! Energy split between the micro-facet and diffraction lobes (H&P Eqs. 16/37, 35, 50, 57).
//!
//! `A = exp(−(2π σs/λ (cosθi + cosθo))²)` (Eq. 37) is the specular fraction of
//! Generalized Harvey–Shack on the macro surface; on a micro-facet of normal `h` in its own
//! mirror configuration `cosθi + cosθo = 2 cosθd`, which gives the reflection lobe's
//! attenuation `exp(−(4π σs cosθd / λ)²)` (Eq. 35 prints it without the `/λ`: erratum, the
//! exponent must be dimensionless; with σs in µm it would also make the result depend on the
//! length unit).

use crate::lane::Real;
use crate::math;

/// `(2π σs/λ · x)²` for `sigma_over_lambda = σs/λ`.
#[inline(always)]
fn phase_variance<R: Real>(sigma_over_lambda: R, x: R) -> R {
    let t = R::splat(math::TAU) * sigma_over_lambda * x;
    t * t
}

/// `A` of Eq. 37.
#[inline(always)]
pub fn specular_fraction<R: Real>(sigma_over_lambda: R, cos_i: R, cos_o: R) -> R {
    (-phase_variance(sigma_over_lambda, cos_i + cos_o)).exp()
}

/// `1 − A` without cancellation for smooth surfaces (σs/λ → 0).
#[inline(always)]
pub fn diffracted_fraction<R: Real>(sigma_over_lambda: R, cos_i: R, cos_o: R) -> R {
    -math::expm1(-phase_variance(sigma_over_lambda, cos_i + cos_o))
}

/// Reflection-lobe attenuation `exp(−(4π σs cosθd/λ)²)` (Eq. 35, corrected).
#[inline(always)]
pub fn reflection_attenuation<R: Real>(sigma_over_lambda: R, cos_d: R) -> R {
    (-phase_variance(sigma_over_lambda, R::splat(2.0) * cos_d)).exp()
}

/// `A_imp = exp(−(2π σs/λ cosθi)²)` (Eq. 57): the probability of sampling the micro-facet
/// lobe rather than the diffraction lobe (a heuristic; the pdf accounts for it exactly).
#[inline]
pub fn sampling_split(sigma_over_lambda: f32, cos_i: f32) -> f32 {
    math::exp(-phase_variance(sigma_over_lambda, cos_i))
}

/// Normal-incidence reflectance `F0 = ((n−1)² + k²)/((n+1)² + k²)` (Eq. 50): the estimated
/// energy `E_C` of the glossy lobes for lobe selection.
#[inline]
pub fn normal_reflectance(n: f32, k: f32) -> f32 {
    let k2 = k * k;
    ((n - 1.0) * (n - 1.0) + k2) / ((n + 1.0) * (n + 1.0) + k2)
}
