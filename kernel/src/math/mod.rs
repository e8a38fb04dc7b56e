//! The one seam for transcendental functions.
//!
//! Every `exp`, `sin`, `sqrt`, … in the kernel goes through this module, so the CPU and the
//! GPU run the same source. On the CPU the calls go to `libm`; rust-gpu recognises the same
//! `libm` calls and lowers them to GLSL.std.450 instructions. Functions rust-gpu lacks
//! (`erf`, `hypot`, complex `sqrt`/`exp`, `Si`) are built here from those primitives.

mod atan;
mod bessel;
mod complex;
mod expm1;
mod faddeeva;
mod gamma;
mod gauss_interval;
mod si;
mod trig_pi;

pub use atan::{acos, angle_between, asin, atan, atan2};
pub use bessel::bessel_i0e;
pub use complex::{C32, cis, cmul_i, cscale, csqrt, csqrt_cx};
pub use expm1::{expm1, ln1p};
pub use faddeeva::{FADDEEVA_FAR, faddeeva, faddeeva_far_lanes, faddeeva_lanes, faddeeva_pair};
pub use gamma::{gamma, gamma_inv, gamma_p, gamma_p_inv, gamma_q, gamma_q_inv, lgamma};
pub use gauss_interval::{
    erf, gauss_fourier_centered, gauss_fourier_centered_lanes, gauss_fourier_interval,
    gauss_fourier_reduced_lanes, gauss_interval, gauss_interval_centered,
};
pub use si::{si, si_split, si_velinov, si_velinov_split};
pub use trig_pi::{
    cis_pi, cis_pi_lanes, one_minus_cis_pi, one_minus_cis_pi_lanes, sin_cos_pi, sin_cos_pi_lanes,
    sinc_pi, sinc_pi_lanes,
};

/// π in `f32`.
pub const PI: f32 = core::f32::consts::PI;
/// 2π in `f32`.
pub const TAU: f32 = core::f32::consts::TAU;
/// √π.
pub const SQRT_PI: f32 = 1.772_453_850_905_516;
/// √2.
pub const SQRT_2: f32 = core::f32::consts::SQRT_2;
/// 1/√π.
pub const FRAC_1_SQRT_PI: f32 = 0.564_189_583_547_756_3;

pub mod portable;
pub mod quadrature;
pub mod twofold;

use crate::lane::Real;

/// e^x.
#[inline]
pub fn exp(x: f32) -> f32 {
    #[cfg(feature = "portable-math")]
    return portable::exp(x);
    #[cfg(not(feature = "portable-math"))]
    libm::expf(x)
}

/// Natural logarithm.
#[inline]
pub fn ln(x: f32) -> f32 {
    #[cfg(feature = "portable-math")]
    return portable::ln_branchless(x);
    #[cfg(not(feature = "portable-math"))]
    libm::logf(x)
}

/// Square root; `sqrt(x)` for `x < 0` is NaN, so callers clamp first (see [`sqrt0`]).
///
/// On x86-64 the `sqrtss` intrinsic rather than libm's `sqrtf`: the same correctly rounded
/// instruction, but libm issues it as inline assembly in the legacy SSE encoding, which
/// inside the SIMD backend's AVX2 code (dirty upper halves of the `ymm` registers) pays the
/// SSE/AVX transition penalty on every call; the intrinsic takes the encoding of its caller.
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn sqrt(x: f32) -> f32 {
    use core::arch::x86_64::{_mm_cvtss_f32, _mm_set_ss, _mm_sqrt_ss};
    // SAFETY: `sqrtss` needs SSE, which every x86-64 CPU has (the target's baseline).
    unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))) }
}

/// Square root; `sqrt(x)` for `x < 0` is NaN, so callers clamp first (see [`sqrt0`]).
#[cfg(not(target_arch = "x86_64"))]
#[inline]
pub fn sqrt(x: f32) -> f32 {
    libm::sqrtf(x)
}

/// `sqrt(max(x, 0))`: the square root of a quantity that is non-negative up to rounding.
#[inline(always)]
pub fn sqrt0<R: Real>(x: R) -> R {
    R::select(x.gt(R::splat(0.0)), x, R::splat(0.0)).sqrt()
}

/// Sine.
#[inline]
pub fn sin(x: f32) -> f32 {
    #[cfg(feature = "portable-math")]
    return portable::sin(x);
    #[cfg(not(feature = "portable-math"))]
    libm::sinf(x)
}

/// Cosine.
#[inline]
pub fn cos(x: f32) -> f32 {
    #[cfg(feature = "portable-math")]
    return portable::cos(x);
    #[cfg(not(feature = "portable-math"))]
    libm::cosf(x)
}

/// `(sin x, cos x)`. On the CPU one `libm::sincosf` call shares the argument reduction
/// (same kernels as `sinf`/`cosf`); on SPIR-V the two GLSL.std.450 intrinsics; under
/// `portable-math` the kernel's own [`sin`] and [`cos`] on both.
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    #[cfg(any(target_arch = "spirv", feature = "portable-math"))]
    {
        (sin(x), cos(x))
    }
    #[cfg(not(any(target_arch = "spirv", feature = "portable-math")))]
    {
        libm::sincosf(x)
    }
}

/// Tangent.
#[inline]
pub fn tan(x: f32) -> f32 {
    libm::tanf(x)
}

/// Hyperbolic tangent.
#[inline]
pub fn tanh(x: f32) -> f32 {
    libm::tanhf(x)
}

/// `x^y`.
#[inline]
pub fn pow(x: f32, y: f32) -> f32 {
    libm::powf(x, y)
}

/// Absolute value.
#[inline]
pub fn abs(x: f32) -> f32 {
    libm::fabsf(x)
}

/// Largest integer not greater than `x`.
#[inline]
pub fn floor(x: f32) -> f32 {
    libm::floorf(x)
}

/// Smallest integer not less than `x`.
#[inline]
pub fn ceil(x: f32) -> f32 {
    libm::ceilf(x)
}

/// `x` clamped to `[lo, hi]`; NaN maps to `lo`.
#[inline(always)]
pub fn clamp<R: Real>(x: R, lo: R, hi: R) -> R {
    R::select(x.gt(hi), hi, R::select(x.ge(lo), x, lo))
}

/// `min(a, b)` that returns the other operand when one is NaN.
#[inline(always)]
pub fn min<R: Real>(a: R, b: R) -> R {
    R::select(a.lt(b) | b.is_nan(), a, b)
}

/// `max(a, b)` that returns the other operand when one is NaN.
#[inline(always)]
pub fn max<R: Real>(a: R, b: R) -> R {
    R::select(a.gt(b) | b.is_nan(), a, b)
}

/// +1 for `x >= 0`, −1 otherwise.
#[inline(always)]
pub fn sign<R: Real>(x: R) -> R {
    R::select(x.ge(R::splat(0.0)), R::splat(1.0), R::splat(-1.0))
}

/// Below this |x| [`sinc`] uses its Taylor series (the error of the three terms is below
/// `x⁶/5040 ≈ 2e-16`).
const SINC_SERIES_BELOW: f32 = 1.0e-2;

/// `sinc(x) = sin(x)/x`, with the removable singularity at 0 evaluated by its Taylor series
/// (no cancellation, exactly 1 at 0).
#[inline]
pub fn sinc(x: f32) -> f32 {
    if abs(x) < SINC_SERIES_BELOW {
        sinc_series(x)
    } else {
        sin(x) / x
    }
}

/// [`sinc`]'s Taylor series, for `|x| <` [`SINC_SERIES_BELOW`].
#[inline(always)]
fn sinc_series<R: Real>(x: R) -> R {
    let c = R::splat;
    let x2 = x * x;
    c(1.0) - x2 * c(1.0 / 6.0) * (c(1.0) - x2 * c(1.0 / 20.0))
}
