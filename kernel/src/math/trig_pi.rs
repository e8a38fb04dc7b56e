//! Trigonometry of arguments given in half-turns: `sin(πx)`, `cos(πx)`, `e^{iπx}`,
//! `1 − e^{iπx}` and `sin(πx)/(πx)`, with exact argument reduction.
//!
//! Every phase of the scratch model is π times a product of inputs: the depth phase
//! `κ = 2πγD/λ`, `β = πWξ₂`, the across-scratch phase `2π s_b ξ₂`, the Fourier phase
//! `2πνu` (Werner 2017 Eqs. 14, 17, 23, 26–31). Written as `sin(TAU * q)` the product with
//! π is rounded first and a large argument is then reduced by π/2 in f32, so the result
//! carries an absolute error of ~`2⁻²⁴·|2πq|`. Near a zero of the result — a groove whose
//! depth phase is close to a whole number of waves, where `|1 − e^{iκ}|` is small — that
//! becomes a large relative error of the scratch term, and the cancellation in `|B − S|²`
//! amplifies it (the worst `random_werner_1e4` query: 1.4e-5 relative in one `M − P`).
//!
//! Here `x` is reduced to quarter turns by `2|x| − 4⌊|x|/2⌋` and `m − round(m)`, both exact
//! in f32, π multiplies only the remainder `|r| ≤ 1/2`, and the polynomials are the kernel's
//! own ([`super::portable`]). So the result has a relative error of a few ULP everywhere,
//! zeros included, and CPU and GPU evaluate the same `+ − ×` (no `GLSL.std.450` `Sin`/`Cos`,
//! whose Vulkan bound is 2⁻¹¹ absolute). Contraction into `fma` by a SPIR-V optimiser or
//! driver changes only the polynomial's last bit, not the reduction, which has no
//! multiply-add to fuse.

use super::C32;
use super::portable::{cos_poly, sin_poly};
use crate::lane::{Cx, Real, branch};

/// π/2.
const FRAC_PI_2: f32 = core::f32::consts::FRAC_PI_2;
/// From 2²² on every f32 is a multiple of ½ (so 2x is an integer, no remainder).
const HALF_INTEGERS: f32 = 4_194_304.0;
/// From 2²⁴ on every f32 is an even integer: `sin(πx) = 0`, `cos(πx) = 1`.
const ALL_EVEN: f32 = 16_777_216.0;

/// `(sin πx, cos πx)` within 2 ULP (measured 1.75) for every finite `x`; NaN for ±∞ and NaN.
#[inline]
pub fn sin_cos_pi(x: f32) -> (f32, f32) {
    sin_cos_pi_lanes(x)
}

/// [`sin_cos_pi`] for any [`Real`] (the one formula).
#[inline(always)]
pub fn sin_cos_pi_lanes<R: Real>(x: R) -> (R, R) {
    let c = R::splat;
    let ax = x.abs();
    // π|x| = j·π/2 + θ with j the nearest quarter turn, |θ| ≤ π/4. For |x| < 2²² both
    // `2|x| + ½` and `2|x| − j` are exact in f32 (truncation is a floor, since the value is
    // positive); up to 2²⁴, 2|x| is itself an integer; beyond, a multiple of 4 (j = 0).
    let y = c(2.0) * ax;
    let small = ax.lt(c(HALF_INTEGERS));
    let j = R::select(
        small,
        (y + c(0.5)).trunc(),
        R::select(ax.lt(c(ALL_EVEN)), y, c(0.0)),
    );
    let theta = R::select(small, (y - j) * c(FRAC_PI_2), c(0.0));
    let (s, co) = (sin_poly(theta), cos_poly(theta));
    // Quarter turn q = j mod 4 (exact: j < 2²⁵): odd q swaps sin and cos; sin flips in
    // turns 2, 3 and cos in turns 1, 2.
    let q = j - c(4.0) * (j * c(0.25)).trunc();
    let (one, two) = (q.eq(c(1.0)), q.eq(c(2.0)));
    let odd = one | q.eq(c(3.0));
    let (s, co) = (R::select(odd, co, s), R::select(odd, s, co));
    let sin_ax = R::select(q.ge(c(2.0)), -s, s);
    let cos = R::select(one | two, -co, co);
    let sin = R::select(x.lt(c(0.0)), -sin_ax, sin_ax);
    let finite = ax.le(c(f32::MAX));
    (
        R::select(finite, sin, c(f32::NAN)),
        R::select(finite, cos, c(f32::NAN)),
    )
}

/// `e^{iπx}`.
#[inline]
pub fn cis_pi(x: f32) -> C32 {
    cis_pi_lanes(x).into()
}

/// [`cis_pi`] for any [`Real`].
#[inline(always)]
pub fn cis_pi_lanes<R: Real>(x: R) -> Cx<R> {
    let (s, c) = sin_cos_pi_lanes(x);
    Cx::new(c, s)
}

/// `1 − e^{iπx} = −2i sin(πx/2) e^{iπx/2}`: full relative accuracy near every zero
/// (`x` near an even integer), where the plain difference cancels.
#[inline]
pub fn one_minus_cis_pi(x: f32) -> C32 {
    one_minus_cis_pi_lanes(x).into()
}

/// [`one_minus_cis_pi`] for any [`Real`].
#[inline(always)]
pub fn one_minus_cis_pi_lanes<R: Real>(x: R) -> Cx<R> {
    let (s, c) = sin_cos_pi_lanes(R::splat(0.5) * x);
    // −2i s (c + i s) = 2s² − 2i s c
    Cx::new(R::splat(2.0) * s * s, R::splat(-2.0) * s * c)
}

/// `sin(πx)/(πx)` (the normalised sinc), exactly 1 at 0 and accurate near its zeros.
#[inline]
pub fn sinc_pi(x: f32) -> f32 {
    sinc_pi_lanes(x)
}

/// [`sinc_pi`] for any [`Real`].
#[inline(always)]
pub fn sinc_pi_lanes<R: Real>(x: R) -> R {
    let t = R::splat(super::PI) * x;
    branch!(
        t.abs().lt(R::splat(super::SINC_SERIES_BELOW)),
        super::sinc_series(t),
        sin_cos_pi_lanes(x).0 / t
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error of `ours` against the f64 value `exact`, in units of f32 epsilon at
    /// `exact` (so a correctly rounded result scores ≤ 0.5).
    fn ulp_err(ours: f32, exact: f64) -> f64 {
        if exact == 0.0 {
            return if ours == 0.0 { 0.0 } else { f64::INFINITY };
        }
        let ulp = f64::from(f32::EPSILON) * 2f64.powi(libm::floor(libm::log2(exact.abs())) as i32);
        (f64::from(ours) - exact).abs() / ulp
    }

    /// `sin(πx)`, `cos(πx)` in f64: reduce `x` mod 2 exactly (f64 holds every f32 and the
    /// reduction of an f32 by an even integer is exact), then one f64 product with π. The
    /// zeros (integers for sin, odd halves for cos) are set exactly, since f64's π is not π.
    fn exact_sin_cos_pi(x: f32) -> (f64, f64) {
        let x = f64::from(x);
        let r = x - 2.0 * libm::round(0.5 * x);
        let t = core::f64::consts::PI * r;
        let s = if r == libm::round(r) {
            0.0
        } else {
            libm::sin(t)
        };
        let c = if 2.0 * r == libm::round(2.0 * r) && r != libm::round(r) {
            0.0
        } else {
            libm::cos(t)
        };
        (s, c)
    }

    fn args() -> impl Iterator<Item = f32> {
        // Dense near zero, near the quadrant boundaries and zeros up to 8, sparse beyond;
        // both signs, plus the exact half-integers.
        let dense = (-80_000..=80_000).map(|i| i as f32 * 1.0e-4 + 1.3e-7);
        let wide = (0..20_000).map(|i| libm::powf(1.0017, i as f32) * 1.0e-9);
        let halves = (-64..=64).map(|i| i as f32 * 0.5);
        let near = (-16..=16).flat_map(|i| {
            let v = i as f32 * 0.5;
            [
                f32::from_bits(v.to_bits() + 1),
                f32::from_bits(v.to_bits().wrapping_sub(1)),
            ]
        });
        dense
            .chain(wide.clone())
            .chain(wide.map(|x| -x))
            .chain(halves)
            .chain(near)
    }

    #[test]
    fn sin_cos_pi_within_2_ulp_including_zeros() {
        let (mut worst_s, mut worst_c) = (0.0_f64, 0.0_f64);
        for x in args().filter(|x| x.is_finite()) {
            let (s, c) = sin_cos_pi(x);
            let (es, ec) = exact_sin_cos_pi(x);
            // Values below 1e-30 of the amplitude are 0 in any f32 phase computation.
            if es.abs() > 1e-30 {
                worst_s = worst_s.max(ulp_err(s, es));
            } else {
                assert!(s.abs() < 1e-29, "sin(π·{x}) = {s}");
            }
            if ec.abs() > 1e-30 {
                worst_c = worst_c.max(ulp_err(c, ec));
            } else {
                assert!(c.abs() < 1e-29, "cos(π·{x}) = {c}");
            }
        }
        assert!(
            worst_s <= 2.0 && worst_c <= 2.0,
            "sin {worst_s} ULP, cos {worst_c} ULP"
        );
    }

    #[test]
    fn exact_values_and_symmetry() {
        for k in -40_i32..=40 {
            let x = k as f32;
            let (s, c) = sin_cos_pi(x);
            assert_eq!(s.abs(), 0.0, "sin(π·{k})");
            assert_eq!(c, if k % 2 == 0 { 1.0 } else { -1.0 }, "cos(π·{k})");
            let (s, c) = sin_cos_pi(x + 0.5);
            assert_eq!(c.abs(), 0.0, "cos(π·({k} + ½))");
            assert_eq!(s, if k.rem_euclid(2) == 0 { 1.0 } else { -1.0 });
        }
        for x in [0.1_f32, 0.37, 1.9, 123.456] {
            let (s, c) = sin_cos_pi(x);
            let (sn, cn) = sin_cos_pi(-x);
            assert_eq!((sn, cn), (-s, c));
        }
        assert_eq!(sin_cos_pi(3.0e7), (0.0, 1.0));
        assert_eq!(sin_cos_pi(-f32::MAX), (-0.0, 1.0));
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let (s, c) = sin_cos_pi(bad);
            assert!(s.is_nan() && c.is_nan(), "{bad}");
        }
    }

    #[test]
    fn one_minus_cis_pi_keeps_relative_accuracy_near_whole_waves() {
        // x = 2 + δ: |1 − e^{iπx}| = 2|sin(πδ/2)| ≈ π|δ|, which sin(TAU·…)-style
        // evaluation gets only to ~2⁻²⁴·2π absolute.
        for k in [0.0_f32, 2.0, 4.0, 8.0, -6.0] {
            for d in [1.0e-6_f32, -3.0e-5, 0.01, 0.041] {
                let x = k + d;
                let z = one_minus_cis_pi(x);
                let xd = f64::from(x);
                let (s, c) = (
                    libm::sin(core::f64::consts::PI * (xd - k as f64)),
                    libm::cos(core::f64::consts::PI * (xd - k as f64)),
                );
                let (re, im) = (1.0 - c, -s);
                let err = ((f64::from(z.re) - re).powi(2) + (f64::from(z.im) - im).powi(2)).sqrt();
                let rel = err / (re * re + im * im).sqrt();
                assert!(rel < 4.0 * f64::from(f32::EPSILON), "x = {x}: {rel:e}");
            }
        }
    }

    #[test]
    fn sinc_pi_matches_f64() {
        for x in args().filter(|x| x.abs() < 1.0e4) {
            let got = sinc_pi(x);
            let exact = if x == 0.0 {
                1.0
            } else {
                exact_sin_cos_pi(x).0 / (core::f64::consts::PI * f64::from(x))
            };
            if exact.abs() > 1e-30 {
                assert!(
                    ulp_err(got, exact) <= 4.0,
                    "sinc_pi({x}) = {got} vs {exact}"
                );
            }
        }
    }
}
