//! `e^x − 1` and `ln(1 + x)` without cancellation, built from `exp`/`ln` only (GLSL.std.450
//! has neither `expm1` nor `log1p`, so `libm::expm1f` would not lower on SPIR-V).
//!
//! Both use Kahan's correction trick: the rounding error of `u = e^x` (or `u = 1 + x`) is
//! compensated by dividing through the exactly representable `ln u` (or `u − 1`).

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
    um1 * x / super::ln(u)
}

/// `ln(1 + x)` for `x > −1`, accurate to a few ulp also for `|x| ≪ 1`.
#[inline]
pub fn ln1p(x: f32) -> f32 {
    if x > 1.0e30 {
        return super::ln(x);
    }
    let u = 1.0 + x;
    if u == 1.0 {
        return x;
    }
    super::ln(u) * x / (u - 1.0)
}
