//! `e^x − 1` and `ln(1 + x)` without cancellation, built from `exp`/`ln` only (GLSL.std.450
//! has neither `expm1` nor `log1p`, so `libm::expm1f` would not lower on SPIR-V).
//!
//! `ln(1 + x)` for `|x| < 1/2` is the series `2 atanh(s)`, `s = x/(2 + x)`: it must not go
//! through `ln` of a number near 1, because Vulkan only bounds GLSL.std.450 `Log`'s
//! *absolute* error there (2⁻²¹ on [0.5, 2]): lavapipe's `ln(1.001)` is off by ~1e-4
//! relative, which the `1/(c − 1)` of the GHS spread (`ghs::spread`) amplified to 1.4 % of
//! the BRDF (the cross-backend sweep, `conformance/tests/domain_sweep_backends.rs`).
//! `e^x − 1` uses Kahan's correction: the rounding error of `u = e^x` is compensated by
//! dividing through `ln u`, as `ln1p(u − 1)` where `u − 1` is exact (`u` in [1/2, 2]).

use crate::lane::{Real, branch};

/// `e^x − 1`, accurate to a few ulp also for `|x| ≪ 1` (any [`Real`]: one `f32` or lanes).
#[inline(always)]
pub fn expm1<R: Real>(x: R) -> R {
    let one = R::splat(1.0);
    branch!(x.abs().lt(R::splat(1.0e-5)), x + R::splat(0.5) * x * x, {
        let u = x.exp();
        let um1 = u - one;
        // `u − 1` is exact for u in [1/2, 2]: there `ln u = ln1p(u − 1)` without `Log`
        // near 1.
        let ln_u = branch!(um1.abs().lt(R::splat(0.5)), ln1p(um1), u.ln());
        let v = um1 * x / ln_u;
        let v = R::select(u.eq(one), x, v);
        let v = R::select(um1.eq(-one), -one, v);
        R::select(x.gt(R::splat(80.0)), u, v)
    })
}

/// `ln(1 + x)` for `x > −1`, accurate to a few ulp also for `|x| ≪ 1`: for `|x| < 1/2`
/// `2 atanh(s)` with `s = x/(2 + x)` (`|s| ≤ 1/3`; the series to `s¹⁵`, truncation
/// ≤ 1.4e-9 relative, `ln_ratio_series`), else `ln(1 + x)` (away from 1, where `Log` is
/// relatively accurate). Any [`Real`].
#[inline(always)]
pub fn ln1p<R: Real>(x: R) -> R {
    // Beyond 1e30 `1 + x` rounds to `x` anyway; `ln x` avoids its overflow at `f32::MAX`.
    branch!(
        x.abs().lt(R::splat(0.5)),
        ln_ratio_series(x / (R::splat(2.0) + x)),
        R::select(x.gt(R::splat(1.0e30)), x, R::splat(1.0) + x).ln(),
    )
}

/// `ln((1 + s)/(1 − s)) = 2 atanh s = 2(s + s³/3 + … + s¹⁵/15)` for `|s| ≤ 1/3` (the
/// truncation error is at most 1.4e-9 relative). Any [`Real`].
#[inline(always)]
pub(super) fn ln_ratio_series<R: Real>(s: R) -> R {
    let c = R::splat;
    let s2 = s * s;
    // atanh(s)/s − 1 = s²/3 + s⁴/5 + … + s¹⁴/15 (Horner in s²)
    let p = c(1.0 / 13.0) + s2 * c(1.0 / 15.0);
    let p = c(1.0 / 11.0) + s2 * p;
    let p = c(1.0 / 9.0) + s2 * p;
    let p = c(1.0 / 7.0) + s2 * p;
    let p = c(1.0 / 5.0) + s2 * p;
    let p = c(1.0 / 3.0) + s2 * p;
    c(2.0) * s + c(2.0) * s * (s2 * p)
}
