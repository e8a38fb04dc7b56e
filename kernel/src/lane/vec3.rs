//! [`V3`]: a 3-vector of [`Real`] lanes (glam's `Vec3` for one lane is `V3<f32>` via `From`).

use super::Real;
use core::ops::{Add, Mul, Sub};

/// `(x, y, z)`, each a [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// x.
    pub x: R,
    /// y.
    pub y: R,
    /// z.
    pub z: R,
}

impl<R: Real> V3<R> {
    /// The vector from its components.
    #[inline(always)]
    pub fn new(x: R, y: R, z: R) -> Self {
        V3 { x, y, z }
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> R {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
}

impl From<glam::Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: glam::Vec3) -> Self {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f32>> for glam::Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}

impl<R: Real> Add for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Mul<R> for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: R) -> Self {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
}
