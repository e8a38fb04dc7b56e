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

/// `branch!(m, then, other)`: `then` in the lanes where the mask `m` holds and `other`
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
            $crate::lane::Real::splat(0.0)
        };
        let o = if $crate::lane::Mask::all(m) {
            $crate::lane::Real::splat(0.0)
        } else {
            $other
        };
        $crate::lane::Real::select(m, t, o)
    }};
}
pub(crate) use branch;
