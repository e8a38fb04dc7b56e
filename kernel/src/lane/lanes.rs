//! [`Lanes`]: `N` `f32` evaluated in lockstep, for the CPU's SIMD backend.
//!
//! Every operation is a loop over `N` independent lanes with no branch inside, which LLVM
//! turns into vector instructions of the width the calling function is compiled for (8 f32
//! with AVX2 under `#[target_feature(enable = "avx2,fma")]`, 4 with SSE2 otherwise). The
//! transcendentals are the kernel's branch-free portable forms
//! ([`crate::math::portable::exp_branchless`], [`crate::math::portable::ln_branchless`]);
//! libm's would be one call per lane. Not compiled for SPIR-V, where a lane is one `f32`.

use super::{Mask, Real};
use crate::math::portable;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// `N` f32 lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Lanes<const N: usize>(pub [f32; N]);

/// `N` per-lane conditions, each all ones (true) or all zeros (false): the form a vector
/// compare produces, so masks stay in vector registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaneMask<const N: usize>(pub [u32; N]);

impl<const N: usize> Lanes<N> {
    /// `f` applied to each lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f32) -> f32) -> Self {
        let mut o = [0.0; N];
        let mut i = 0;
        while i < N {
            o[i] = f(self.0[i]);
            i += 1;
        }
        Lanes(o)
    }

    #[inline(always)]
    fn zip(self, b: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        let mut o = [0.0; N];
        let mut i = 0;
        while i < N {
            o[i] = f(self.0[i], b.0[i]);
            i += 1;
        }
        Lanes(o)
    }

    #[inline(always)]
    fn test(self, b: Self, f: impl Fn(f32, f32) -> bool) -> LaneMask<N> {
        let mut o = [0; N];
        let mut i = 0;
        while i < N {
            o[i] = if f(self.0[i], b.0[i]) { u32::MAX } else { 0 };
            i += 1;
        }
        LaneMask(o)
    }
}

impl<const N: usize> super::V3<Lanes<N>> {
    /// The `N` vectors as one vector of lanes (lane `i` holds `v[i]`).
    #[inline(always)]
    pub fn from_vecs(v: [glam::Vec3; N]) -> Self {
        super::V3::new(
            Lanes(v.map(|v| v.x)),
            Lanes(v.map(|v| v.y)),
            Lanes(v.map(|v| v.z)),
        )
    }
}

impl<const N: usize> Mask for LaneMask<N> {
    #[inline(always)]
    fn all(self) -> bool {
        let mut a = u32::MAX;
        let mut i = 0;
        while i < N {
            a &= self.0[i];
            i += 1;
        }
        a != 0
    }
    #[inline(always)]
    fn any(self) -> bool {
        let mut a = 0;
        let mut i = 0;
        while i < N {
            a |= self.0[i];
            i += 1;
        }
        a != 0
    }
}

macro_rules! mask_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const N: usize> $tr for LaneMask<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, b: Self) -> Self {
                let mut o = [0; N];
                let mut i = 0;
                while i < N {
                    o[i] = self.0[i] $op b.0[i];
                    i += 1;
                }
                LaneMask(o)
            }
        }
    };
}
mask_op!(BitAnd, bitand, &);
mask_op!(BitOr, bitor, |);

impl<const N: usize> Not for LaneMask<N> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let mut o = self.0;
        let mut i = 0;
        while i < N {
            o[i] = !o[i];
            i += 1;
        }
        LaneMask(o)
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const N: usize> $tr for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, b: Self) -> Self {
                self.zip(b, |x, y| x $op y)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const N: usize> Neg for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|x| -x)
    }
}

/// Four correctly rounded square roots: `sqrtps` on x86-64 (SSE is part of its baseline),
/// else one `sqrt` per lane.
#[inline(always)]
fn sqrt4(x: [f32; 4]) -> [f32; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `sqrtps` needs SSE, which every x86-64 CPU has (the target's baseline).
        bytemuck::cast(unsafe { core::arch::x86_64::_mm_sqrt_ps(bytemuck::cast(x)) })
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        x.map(crate::math::sqrt)
    }
}

impl<const N: usize> Real for Lanes<N> {
    type Mask = LaneMask<N>;
    const LANES: usize = N;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Lanes([x; N])
    }
    #[inline(always)]
    fn lt(self, o: Self) -> LaneMask<N> {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> LaneMask<N> {
        self.test(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> LaneMask<N> {
        self.test(o, |a, b| a > b)
    }
    #[inline(always)]
    fn ge(self, o: Self) -> LaneMask<N> {
        self.test(o, |a, b| a >= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> LaneMask<N> {
        self.test(o, |a, b| a == b)
    }
    #[inline(always)]
    fn sign_bit(self) -> LaneMask<N> {
        self.test(self, |a, _| a.to_bits() >> 31 != 0)
    }
    #[inline(always)]
    fn is_nan(self) -> LaneMask<N> {
        self.test(self, |a, b| a != b)
    }
    #[inline(always)]
    fn is_finite(self) -> LaneMask<N> {
        // Finite ⇔ x − x == 0 (∞ − ∞ and NaN − NaN are NaN).
        self.test(self, |a, b| a - b == 0.0)
    }
    #[inline(always)]
    fn select(m: LaneMask<N>, a: Self, b: Self) -> Self {
        let mut o = [0.0; N];
        let mut i = 0;
        while i < N {
            let m = m.0[i];
            o[i] = f32::from_bits((a.0[i].to_bits() & m) | (b.0[i].to_bits() & !m));
            i += 1;
        }
        Lanes(o)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(|x| f32::from_bits(x.to_bits() & 0x7fff_ffff))
    }
    #[inline(always)]
    fn floor(self) -> Self {
        self.map(portable::floor_branchless)
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        // `(x as i32) as f32` per lane would scalarise the loop (a saturating conversion).
        self.map(portable::trunc_branchless)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // libm's `sqrtf` is the scalar `sqrtss` instruction, which LLVM does not vectorise;
        // `sqrtps` is the same correctly rounded square root, four lanes at a time.
        let mut o = self.0;
        let mut i = 0;
        while i + 4 <= N {
            let q = sqrt4([o[i], o[i + 1], o[i + 2], o[i + 3]]);
            o[i..i + 4].copy_from_slice(&q);
            i += 4;
        }
        while i < N {
            o[i] = crate::math::sqrt(o[i]);
            i += 1;
        }
        Lanes(o)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        self.map(portable::exp_branchless)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        self.map(portable::ln_branchless)
    }
    /// Written so that LLVM can vectorise it (`vpgatherdd` with AVX2): the index is
    /// clamped into the table and converted by the 2²³ rounding trick (exact for the
    /// integer-valued indices of a table below 2²³ entries) instead of a saturating
    /// float→int conversion, and the load cannot go out of bounds.
    #[inline(always)]
    fn gather(table: &[f32], index: Self) -> Self {
        let Some(last) = table.len().checked_sub(1) else {
            return Self::splat(0.0);
        };
        let mut o = [0.0; N];
        let mut i = 0;
        while i < N {
            let x = index.0[i];
            let inside = x >= 0.0 && x <= last as f32;
            let c = if inside { x } else { 0.0 };
            let k = ((c + 8_388_608.0).to_bits() - 0x4b00_0000) as usize;
            let v = table[if k < last { k } else { last }];
            o[i] = if inside { v } else { 0.0 };
            i += 1;
        }
        Lanes(o)
    }
    #[inline(always)]
    fn gather_array<const K: usize>(table: &[f32; K], index: Self) -> Self {
        Self::gather(table, index)
    }
}
