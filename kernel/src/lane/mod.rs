//! Lanes: the kernel's arithmetic written once over a value type that is one `f32` (SPIR-V,
//! the scalar CPU backend) or several `f32` evaluated in lockstep ([`Lanes`], the CPU's
//! SIMD backend).
//!
//! A formula generic over [`Real`] is compiled once per lane type. Where lanes may take
//! different sides of a condition the formula computes a [`Real::Mask`] and either
//! [`Real::select`]s between two values or runs `branch!`, which evaluates only the side
//! every lane takes and both sides (then selects) only when the lanes disagree. For `f32`
//! the mask is a `bool` and `branch!` is an ordinary `if`, so the scalar code (and the
//! SPIR-V module) does the same work as before it was made generic.
//!
//! ARCHITECTURE.md *Lanes* explains the choice of a small own type over `core::arch`
//! intrinsics or a SIMD crate.

mod complex;
#[cfg(not(target_arch = "spirv"))]
mod lanes;
mod scalar;
mod vec3;

pub use complex::Cx;
#[cfg(not(target_arch = "spirv"))]
pub use lanes::{LaneMask, Lanes};
pub use vec3::V3;

use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A per-lane condition.
pub trait Mask: Copy + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self> {
    /// True when every lane's condition holds.
    fn all(self) -> bool;
    /// True when some lane's condition holds.
    fn any(self) -> bool;
}

/// One or more `f32` lanes: the arithmetic and the few primitives the generic formulas need.
/// Every method acts lane by lane with the semantics of the `f32` seam in [`crate::math`].
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The per-lane condition type.
    type Mask: Mask;
    /// How many `f32` it holds (1 for `f32`).
    const LANES: usize;
    /// `x` in every lane.
    fn splat(x: f32) -> Self;
    /// `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// `self <= o`.
    fn le(self, o: Self) -> Self::Mask;
    /// `self > o`.
    fn gt(self, o: Self) -> Self::Mask;
    /// `self >= o`.
    fn ge(self, o: Self) -> Self::Mask;
    /// `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// Lanes whose sign bit is set (−0 and NaNs with the bit included).
    fn sign_bit(self) -> Self::Mask;
    /// Lanes that hold NaN.
    fn is_nan(self) -> Self::Mask;
    /// Lanes that hold a finite value.
    fn is_finite(self) -> Self::Mask;
    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// |x|.
    fn abs(self) -> Self;
    /// Largest integer not above `x`.
    fn floor(self) -> Self;
    /// `x` rounded toward zero, for `|x| < 2³¹` (the `as i32 as f32` round trip: beyond
    /// that range the result saturates to ±2³¹, and NaN gives 0).
    fn trunc(self) -> Self;
    /// √x (NaN below 0).
    fn sqrt(self) -> Self;
    /// e^x.
    fn exp(self) -> Self;
    /// ln x.
    fn ln(self) -> Self;
    /// `table[i]` per lane for the integer-valued `index`, 0 where it is outside the table.
    fn gather(table: &[f32], index: Self) -> Self;
    /// [`Real::gather`] from a fixed-size array (rust-gpu cannot unsize a constant array to
    /// a slice).
    fn gather_array<const K: usize>(table: &[f32; K], index: Self) -> Self;
}

/// A value that per-lane conditions can choose between: every [`Real`], and the compound
/// lane types built from them ([`Cx`], pairs), so that [`branch!`](crate::lane) works on
/// them alike.
pub trait Blend<M>: Copy {
    /// `a` in the lanes where `m` holds, `b` elsewhere.
    fn blend(m: M, a: Self, b: Self) -> Self;
    /// Zero in every lane (the placeholder for a side no lane takes).
    fn zero() -> Self;
}

impl<R: Real> Blend<R::Mask> for R {
    #[inline(always)]
    fn blend(m: R::Mask, a: R, b: R) -> R {
        R::select(m, a, b)
    }
    #[inline(always)]
    fn zero() -> R {
        R::splat(0.0)
    }
}

impl<R: Real> Blend<R::Mask> for Cx<R> {
    #[inline(always)]
    fn blend(m: R::Mask, a: Self, b: Self) -> Self {
        Cx::new(R::select(m, a.re, b.re), R::select(m, a.im, b.im))
    }
    #[inline(always)]
    fn zero() -> Self {
        Cx::splat(0.0, 0.0)
    }
}

impl<M: Copy, A: Blend<M>, B: Blend<M>> Blend<M> for (A, B) {
    #[inline(always)]
    fn blend(m: M, a: Self, b: Self) -> Self {
        (A::blend(m, a.0, b.0), B::blend(m, a.1, b.1))
    }
    #[inline(always)]
    fn zero() -> Self {
        (A::zero(), B::zero())
    }
}

/// `branch!(m, then, other)`: for any [`Blend`] value, `then` in the lanes where the mask `m` holds and `other`
/// elsewhere, evaluating each expression only if some lane takes it (for `f32`:
/// `if m { then } else { other }`).
///
/// A macro rather than a function of two closures: a closure that LLVM does not inline is
/// compiled for the baseline instruction set, outside the caller's `#[target_feature]`
/// context (measured: the GHS lanes ran at SSE width). Each expression appears once in the
/// expansion, so nested branches do not multiply the code.
macro_rules! branch {
    ($m:expr, $then:expr, $other:expr $(,)?) => {{
        let m = $m;
        let t = if $crate::lane::Mask::any(m) {
            $then
        } else {
            $crate::lane::Blend::zero()
        };
        let o = if $crate::lane::Mask::all(m) {
            $crate::lane::Blend::zero()
        } else {
            $other
        };
        $crate::lane::Blend::blend(m, t, o)
    }};
}
pub(crate) use branch;
