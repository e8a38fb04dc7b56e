//! Unevaluated sums `hi + lo` of two `f32` (about 48 significant bits) from error-free
//! transformations: Knuth's two-sum and Dekker's two-product by splitting (Dekker 1971),
//! in plain `f32` arithmetic, so the same source runs on the CPU and on SPIR-V. Every
//! product in [`two_prod`]'s correction is exact (12 × 12 significant bits), so a compiler
//! that fuses a multiply and an add there changes nothing.
//!
//! For the few quantities whose `f32` rounding a query's inputs resolve more finely than
//! `ε` of an O(1) value: the angle between a small sphere light's axis and a band
//! ([`crate::lights::sphere::SphereCap`]) and a small polygon's height over a band
//! ([`crate::lights::polygon::SphericalPolygon`]).

use super::sqrt;

/// `hi + lo`, `|lo| ≤ ulp(hi)/2` after [`Twofold::normalized`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Twofold {
    /// The leading part.
    pub hi: f32,
    /// The trailing part.
    pub lo: f32,
}

/// `a + b` exactly, as `(fl(a + b), error)` (Knuth; no ordering of `a`, `b` needed).
#[inline]
pub fn two_sum(a: f32, b: f32) -> Twofold {
    let s = a + b;
    let bb = s - a;
    Twofold {
        hi: s,
        lo: (a - (s - bb)) + (b - bb),
    }
}

/// `a` as `hi + lo`, each with at most 12 significant bits (Veltkamp's split; `|a|` below
/// ~8e34, where `4097 a` overflows).
#[inline]
fn split(a: f32) -> (f32, f32) {
    let c = 4097.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a · b` exactly, as `(fl(a b), error)` (Dekker), barring underflow.
#[inline]
pub fn two_prod(a: f32, b: f32) -> Twofold {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    Twofold {
        hi: p,
        lo: ((ah * bh - p) + ah * bl + al * bh) + al * bl,
    }
}

impl Twofold {
    /// `x` exactly.
    #[inline]
    pub fn from(x: f32) -> Twofold {
        Twofold { hi: x, lo: 0.0 }
    }

    /// The same sum with `|lo| ≤ ulp(hi)/2`.
    #[inline]
    pub fn normalized(self) -> Twofold {
        two_sum(self.hi, self.lo)
    }

    /// The nearest `f32`.
    #[inline]
    pub fn value(self) -> f32 {
        self.hi + self.lo
    }

    /// `√self` (`self ≥ 0`): the `f32` root corrected by one Newton step on the residual
    /// `self − hi²`, formed exactly.
    #[inline]
    pub fn sqrt(self) -> Twofold {
        let hi = sqrt(self.hi);
        if !(hi > 0.0) {
            return Twofold::from(hi);
        }
        let sq = two_prod(hi, hi);
        let residual = ((self.hi - sq.hi) - sq.lo) + self.lo;
        Twofold {
            hi,
            lo: residual / (2.0 * hi),
        }
        .normalized()
    }
}

impl core::ops::Add for Twofold {
    type Output = Twofold;

    /// `self + other`.
    #[inline]
    fn add(self, other: Twofold) -> Twofold {
        let s = two_sum(self.hi, other.hi);
        Twofold {
            hi: s.hi,
            lo: s.lo + (self.lo + other.lo),
        }
        .normalized()
    }
}

impl core::ops::Mul for Twofold {
    type Output = Twofold;

    /// `self · other`.
    #[inline]
    fn mul(self, other: Twofold) -> Twofold {
        let p = two_prod(self.hi, other.hi);
        Twofold {
            hi: p.hi,
            lo: p.lo + (self.hi * other.lo + self.lo * other.hi),
        }
        .normalized()
    }
}

impl core::ops::Div for Twofold {
    type Output = Twofold;

    /// `self / other` (`other ≠ 0`): the `f32` quotient `q` corrected once by the residual
    /// `self − q·other`, whose leading part is formed exactly.
    #[inline]
    fn div(self, other: Twofold) -> Twofold {
        let q = self.hi / other.hi;
        let p = two_prod(q, other.hi);
        let residual = (((self.hi - p.hi) - p.lo) + self.lo) - q * other.lo;
        Twofold {
            hi: q,
            lo: residual / other.hi,
        }
        .normalized()
    }
}

/// `a₀ b₀ + a₁ b₁`, each product exact and their sum compensated.
#[inline]
pub fn dot2(a0: f32, b0: f32, a1: f32, b1: f32) -> Twofold {
    two_prod(a0, b0) + two_prod(a1, b1)
}

/// `|v|`, its square formed from exact products.
#[inline]
pub fn length(x: f32, y: f32, z: f32) -> Twofold {
    (two_prod(x, x) + two_prod(y, y) + two_prod(z, z)).sqrt()
}
