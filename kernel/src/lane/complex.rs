//! [`Cx`]: a complex number of [`Real`] lanes, for the formulas that the scalar kernel
//! writes with `num_complex::Complex32` and that the SIMD backend also runs in lanes.

use super::Real;
use core::ops::{Add, Mul, Neg, Sub};

/// `re + i·im`, each a [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cx<R> {
    /// Real part.
    pub re: R,
    /// Imaginary part.
    pub im: R,
}

impl<R: Real> Cx<R> {
    /// The number from its parts.
    #[inline(always)]
    pub fn new(re: R, im: R) -> Self {
        Cx { re, im }
    }
    /// The real number `re`.
    #[inline(always)]
    pub fn real(re: R) -> Self {
        Cx::new(re, R::splat(0.0))
    }
    /// `re + i·im` in every lane.
    #[inline(always)]
    pub fn splat(re: f32, im: f32) -> Self {
        Cx::new(R::splat(re), R::splat(im))
    }
    /// |z|².
    #[inline(always)]
    pub fn norm_sqr(self) -> R {
        self.re * self.re + self.im * self.im
    }
    /// `z·s` for a real `s`.
    #[inline(always)]
    pub fn scale(self, s: R) -> Self {
        Cx::new(self.re * s, self.im * s)
    }
}

impl From<crate::math::C32> for Cx<f32> {
    #[inline(always)]
    fn from(z: crate::math::C32) -> Self {
        Cx::new(z.re, z.im)
    }
}

impl From<Cx<f32>> for crate::math::C32 {
    #[inline(always)]
    fn from(z: Cx<f32>) -> Self {
        crate::math::C32::new(z.re, z.im)
    }
}

impl<R: Real> Cx<R> {
    /// `i·z`.
    #[inline(always)]
    pub fn mul_i(self) -> Self {
        Cx::new(-self.im, self.re)
    }

    /// The complex conjugate.
    #[inline(always)]
    pub fn conj(self) -> Self {
        Cx::new(self.re, -self.im)
    }
}

impl<R: Real> Add for Cx<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Cx::new(self.re + o.re, self.im + o.im)
    }
}

impl<R: Real> Neg for Cx<R> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Cx::new(-self.re, -self.im)
    }
}

impl<R: Real> Sub for Cx<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Cx::new(self.re - o.re, self.im - o.im)
    }
}

impl<R: Real> Mul for Cx<R> {
    type Output = Self;
    /// The textbook product (as `num_complex`'s: `re = a·c − b·d`, `im = a·d + b·c`).
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Cx::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}
