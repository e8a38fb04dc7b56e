//! The coherent scratch sum `S = Σ_k S_k` (Werner 2017 Eq. 17), accumulated exactly on a
//! fixed grid so that `B − S` (Eq. 15) keeps its relative accuracy.
//!
//! Near the mirror direction a densely scratched window has `|B − S|` far below `|B|` and
//! `|S_k|`: in `random_werner_1e4` down to 1/240 of them. An ordinary f32 running sum then
//! rounds every partial sum at the size of `S` (~10³ µm²) and the result at the size of
//! `B − S`, so the rounding of the sum alone moves `|B − S|²` by up to 4e-5, and it differs
//! between targets that add in another order or fuse `acc + a·b` into `fma`.
//!
//! Here each term is split into `hi`, a multiple of a power-of-two grid `g`, and `lo = x − hi`
//! (`|lo| < g`); both steps are exact in f32. Sums of multiples of `g` below `2²⁴g` are
//! exact in any order, so `B_hi − Σ hi` is exact, and the `lo` parts are too small to matter
//! (`g = 2⁻¹⁶` of the base response's peak `B(0) = 2πσ²`). `B − S` is then rounded once, at
//! its own size. The exactness comes from representability, not from an evaluation order,
//! so a SPIR-V optimiser or driver that contracts or reorders the arithmetic cannot undo it
//! (unlike a compensated sum). The sum stays exact while `|Σ hi| < 128 B(0)`, far beyond any
//! physical coverage; past that it degrades to an ordinary f32 sum.

use crate::lane::{Cx, Real};
use crate::math::{self, C32};

/// `g / B(0)` (up to the power of two below `B(0)`): 2⁻¹⁶.
const GRID_SCALE: f32 = 1.0 / 65_536.0;
/// Bounds on the grid, so that `1/g` and `g` stay finite and normal for any σ.
const GRID_MIN: f32 = 7.888_609e-31; // 2⁻¹⁰⁰
const GRID_MAX: f32 = 1.267_650_6e30; // 2¹⁰⁰

/// `S = Σ S_k` as an exact grid part and a small remainder, in one or more lanes (each
/// lane its own sum; the grid is shared).
#[derive(Clone, Copy, Debug)]
pub struct CoherentSum<R = f32> {
    hi: Cx<R>,
    lo: Cx<R>,
    grid: R,
    inv_grid: R,
}

impl<R: Real> CoherentSum<R> {
    /// An empty sum whose terms are of the order of `scale` (the base response's peak).
    #[inline]
    pub fn new(scale: f32) -> Self {
        // The largest power of two ≤ |scale| (exponent bits only), then 2⁻¹⁶ of it.
        let pow2 = f32::from_bits(math::abs(scale).to_bits() & 0x7f80_0000);
        let grid = math::clamp(pow2 * GRID_SCALE, GRID_MIN, GRID_MAX);
        CoherentSum {
            hi: Cx::splat(0.0, 0.0),
            lo: Cx::splat(0.0, 0.0),
            grid: R::splat(grid),
            inv_grid: R::splat(1.0 / grid),
        }
    }

    /// Adds one term.
    #[inline(always)]
    pub fn add(&mut self, z: impl Into<Cx<R>>) {
        let z = z.into();
        let (re_hi, re_lo) = self.split(z.re);
        let (im_hi, im_lo) = self.split(z.im);
        self.hi = self.hi + Cx::new(re_hi, im_hi);
        self.lo = self.lo + Cx::new(re_lo, im_lo);
    }

    /// `S`, rounded once.
    #[inline(always)]
    pub fn total_lanes(&self) -> Cx<R> {
        self.hi + self.lo
    }

    /// `b − S` for a real `b` (the base response), rounded once at the size of the result.
    #[inline(always)]
    pub fn subtracted_from_lanes(&self, b: R) -> Cx<R> {
        let (b_hi, b_lo) = self.split(b);
        Cx::new(
            (b_hi - self.hi.re) + (b_lo - self.lo.re),
            -(self.hi.im + self.lo.im),
        )
    }

    /// `x = hi + lo` exactly, `hi` a multiple of the grid, `|lo| < grid`. Every step is
    /// exact (scaling by powers of two, truncation of a value below 2²⁴ in magnitude, and
    /// the difference of `x` and its own truncation), so contraction changes nothing. The
    /// clamp keeps the conversion defined for absurd terms (and maps NaN to a finite `hi`,
    /// leaving the NaN in `lo`).
    #[inline(always)]
    fn split(&self, x: R) -> (R, R) {
        let t = R::splat(TRUNC_LIMIT);
        let v = math::clamp(x * self.inv_grid, -t, t);
        let hi = v.trunc() * self.grid;
        (hi, x - hi)
    }
}

impl CoherentSum {
    /// `S`, rounded once.
    #[inline]
    pub fn total(&self) -> C32 {
        self.total_lanes().into()
    }

    /// `b − S` for a real `b` (the base response), rounded once at the size of the result.
    #[inline]
    pub fn subtracted_from(&self, b: f32) -> C32 {
        self.subtracted_from_lanes(b).into()
    }
}

/// 2²⁴: below it an f32 → i32 → f32 round trip is exact.
const TRUNC_LIMIT: f32 = 16_777_216.0;

#[cfg(test)]
mod tests {
    use super::*;

    /// Terms per test sum, like the scratches of `random_werner_1e4`.
    const N: usize = 24;

    /// A small deterministic generator (the kernel has no RNG dependency).
    fn lcg(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((*state >> 40) as f32) / (1u64 << 24) as f32
    }

    /// Terms of size ~B/4 whose sum cancels `b` to about 1e-4 of it, like a densely
    /// scratched window near the mirror direction.
    fn cancelling_terms(seed: u64, b: f32) -> [C32; N] {
        let mut s = seed;
        let mut terms: [C32; N] = core::array::from_fn(|_| {
            C32::new(
                0.5 * b * lcg(&mut s) / N as f32 * 4.0,
                0.3 * b * (lcg(&mut s) - 0.5),
            )
        });
        // Make Σ re ≈ b and Σ im ≈ 0 (up to f32 rounding of the adjustment itself).
        let (sr, si) = terms.iter().fold((0.0_f64, 0.0_f64), |(a, c), z| {
            (a + f64::from(z.re), c + f64::from(z.im))
        });
        terms[N - 1].re += (f64::from(b) - sr + 1.0e-4 * f64::from(b)) as f32;
        terms[N - 1].im -= (si - 3.0e-5 * f64::from(b)) as f32;
        terms
    }

    /// `b − Σ terms` in f64 (exact for a few dozen f32 terms of similar size).
    fn exact(b: f32, terms: &[C32]) -> (f64, f64) {
        terms.iter().fold((f64::from(b), 0.0), |(r, i), z| {
            (r - f64::from(z.re), i - f64::from(z.im))
        })
    }

    #[test]
    fn b_minus_s_within_one_ulp_and_order_free() {
        for (seed, sigma) in [(1_u64, 10.0_f32), (2, 0.7), (3, 55.0), (4, 3.0)] {
            let b = math::TAU * sigma * sigma;
            let terms = cancelling_terms(seed, b);
            let (er, ei) = exact(b, &terms);
            let mut sum = CoherentSum::new(b);
            terms.iter().for_each(|&z| sum.add(z));
            let d = sum.subtracted_from(b);
            // One rounding of the result: at most one ULP from the f64 value (a plain
            // running sum is off by thousands of ULP of `b − S` here).
            let ulps = |a: f32, e: f64| (a.to_bits() as i64 - (e as f32).to_bits() as i64).abs();
            assert!(ulps(d.re, er) <= 1, "seed {seed}: {} vs {er}", d.re);
            assert!(ulps(d.im, ei) <= 1, "seed {seed}: {} vs {ei}", d.im);
            // Any other order gives the same bits.
            let mut rev = CoherentSum::new(b);
            terms.iter().rev().for_each(|&z| rev.add(z));
            assert_eq!(rev.subtracted_from(b), d);
        }
    }

    #[test]
    fn total_and_degenerate_scales() {
        let terms = [
            C32::new(1.5, -2.0),
            C32::new(-0.25, 0.125),
            C32::new(1.0e-9, 3.0),
        ];
        let mut sum = CoherentSum::new(6.0);
        terms.iter().for_each(|&z| sum.add(z));
        assert_eq!(sum.total(), C32::new(1.25 + 1.0e-9, 1.125));
        // Zero, subnormal and huge scales keep a finite grid; results stay finite.
        for scale in [0.0, 1.0e-40, f32::MAX, f32::INFINITY] {
            let mut s = CoherentSum::new(scale);
            terms.iter().for_each(|&z| s.add(z));
            let t = s.total();
            assert!(t.re.is_finite() && t.im.is_finite(), "scale {scale}: {t:?}");
            assert!((t.re - 1.25).abs() < 1e-6 && (t.im - 1.125).abs() < 1e-6);
        }
    }
}
