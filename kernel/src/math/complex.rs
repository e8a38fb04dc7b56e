//! Complex helpers built on the scalar seam (rust-gpu has no `hypot`, so `num_complex`'s
//! `norm`, `sqrt`, `exp`, … are not used in the kernel).

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
    let (a, b) = (z.re, z.im);
    let m = super::max(super::abs(a), super::abs(b));
    if m == 0.0 {
        return C32::new(0.0, b);
    }
    // |z| computed with scaling to avoid overflow in a² + b².
    let (sa, sb) = (a / m, b / m);
    let r = m * super::sqrt(sa * sa + sb * sb);
    if a >= 0.0 {
        let t = super::sqrt(0.5 * (r + a));
        C32::new(t, b / (2.0 * t))
    } else {
        let t = super::sqrt(0.5 * (r - a));
        C32::new(super::abs(b) / (2.0 * t), if b < 0.0 { -t } else { t })
    }
}
