//! Complex helpers built on the scalar seam (rust-gpu has no `hypot`, so `num_complex`'s
//! `norm`, `sqrt`, `exp`, … are not used in the kernel).

use crate::lane::{Cx, Real};
use num_complex::Complex32;

/// The kernel's complex type.
pub type C32 = Complex32;

/// `e^{iθ}`.
#[inline]
pub fn cis(theta: f32) -> C32 {
    let (s, c) = super::sin_cos(theta);
    C32::new(c, s)
}

/// `i z`.
#[inline]
pub fn cmul_i(z: C32) -> C32 {
    C32::new(-z.im, z.re)
}

/// `s z` for real `s`.
#[inline]
pub fn cscale(z: C32, s: f32) -> C32 {
    C32::new(z.re * s, z.im * s)
}

/// Principal square root, branch cut on the negative real axis, without overflow for
/// |z| up to `f32::MAX / 2`.
#[inline]
pub fn csqrt(z: C32) -> C32 {
    let r = csqrt_cx(Cx::new(z.re, z.im));
    C32::new(r.re, r.im)
}

/// [`csqrt`] for any [`Real`] (the one formula; `0.5(r + |a|)` is `0.5(r + a)` for `a ≥ 0`
/// and `0.5(r − a)` for `a < 0`).
#[inline(always)]
pub fn csqrt_cx<R: Real>(z: Cx<R>) -> Cx<R> {
    let c = R::splat;
    let (a, b) = (z.re, z.im);
    let m = super::max(a.abs(), b.abs());
    let (sa, sb) = (a / m, b / m);
    let r = m * (sa * sa + sb * sb).sqrt();
    let t = (c(0.5) * (r + a.abs())).sqrt();
    let two_t = c(2.0) * t;
    let pos = a.ge(c(0.0));
    let re = R::select(pos, t, b.abs() / two_t);
    let im = R::select(pos, b / two_t, R::select(b.lt(c(0.0)), -t, t));
    let zero = m.eq(c(0.0));
    Cx::new(R::select(zero, c(0.0), re), R::select(zero, b, im))
}
