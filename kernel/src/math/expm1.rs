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

/// `e^x − 1`, accurate to a few ulp also for `|x| ≪ 1`.
#[inline]
pub fn expm1(x: f32) -> f32 {
    if super::abs(x) < 1.0e-5 {
        return x + 0.5 * x * x;
    }
    if x > 80.0 {
        return super::exp(x);
    }
    let u = super::exp(x);
    if u == 1.0 {
        return x;
    }
    let um1 = u - 1.0;
    if um1 == -1.0 {
        return -1.0;
    }
    // `u − 1` is exact for u in [1/2, 2]: there `ln u = ln1p(u − 1)` without `Log` near 1.
    let ln_u = if super::abs(um1) < 0.5 {
        ln1p(um1)
    } else {
        super::ln(u)
    };
    um1 * x / ln_u
}

/// `ln(1 + x)` for `x > −1`, accurate to a few ulp also for `|x| ≪ 1`: for `|x| < 1/2`
/// `2 atanh(s)` with `s = x/(2 + x)` (`|s| ≤ 1/3`; the series to `s¹⁵`, truncation
/// ≤ 1.4e-9 relative), else `ln(1 + x)` (away from 1, where `Log` is relatively accurate).
#[inline]
pub fn ln1p(x: f32) -> f32 {
    if super::abs(x) < 0.5 {
        let s = x / (2.0 + x);
        let s2 = s * s;
        // atanh(s)/s − 1 = s²/3 + s⁴/5 + … + s¹⁴/15 (Horner in s²)
        let p = 1.0 / 13.0 + s2 * (1.0 / 15.0);
        let p = 1.0 / 11.0 + s2 * p;
        let p = 1.0 / 9.0 + s2 * p;
        let p = 1.0 / 7.0 + s2 * p;
        let p = 1.0 / 5.0 + s2 * p;
        let p = 1.0 / 3.0 + s2 * p;
        return 2.0 * s + 2.0 * s * (s2 * p);
    }
    if x > 1.0e30 {
        return super::ln(x);
    }
    super::ln(1.0 + x)
}
