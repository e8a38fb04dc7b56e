//! [`Real`] for one `f32`: the kernel's scalar seam ([`crate::math`]), so generic formulas
//! instantiated at `f32` compute exactly what the scalar kernel computes.

use super::{Mask, Real};
use crate::math;

impl Mask for bool {
    #[inline(always)]
    fn all(self) -> bool {
        self
    }
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
}

impl Real for f32 {
    type Mask = bool;
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn lt(self, o: f32) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: f32) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: f32) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: f32) -> bool {
        self >= o
    }
    #[inline(always)]
    fn eq(self, o: f32) -> bool {
        self == o
    }
    #[inline(always)]
    fn sign_bit(self) -> bool {
        self.is_sign_negative()
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        self.is_nan()
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn select(m: bool, a: f32, b: f32) -> f32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn abs(self) -> f32 {
        math::abs(self)
    }
    #[inline(always)]
    fn floor(self) -> f32 {
        math::floor(self)
    }
    #[inline(always)]
    fn trunc(self) -> f32 {
        (self as i32) as f32
    }
    #[inline(always)]
    fn sqrt(self) -> f32 {
        math::sqrt(self)
    }
    #[inline(always)]
    fn exp(self) -> f32 {
        math::exp(self)
    }
    #[inline(always)]
    fn ln(self) -> f32 {
        math::ln(self)
    }
    #[inline(always)]
    fn gather_array<const K: usize>(table: &[f32; K], index: f32) -> f32 {
        match table_index(index, K) {
            Some(i) => table[i],
            None => 0.0,
        }
    }
    #[inline(always)]
    fn gather(table: &[f32], index: f32) -> f32 {
        match table_index(index, table.len()) {
            Some(i) => table[i],
            None => 0.0,
        }
    }
}

/// `index` as a position in a table of `len` entries, `None` outside it (and for NaN).
#[inline(always)]
fn table_index(index: f32, len: usize) -> Option<usize> {
    if index >= 0.0 && index < len as f32 {
        Some(index as usize)
    } else {
        None
    }
}
