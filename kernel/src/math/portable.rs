//! The kernel's own `f32` `exp`, `sin` and `cos`: Cody–Waite range reduction and short
//! polynomials (Cephes `expf`/`sinf`/`cosf` coefficients) written with `+`, `-`, `*`,
//! `floor` and bit casts only — no libm call, no GLSL.std.450 instruction.
//!
//! Why: with the default seam the CPU runs libm and the GPU runs the driver's
//! `GLSL.std.450` `Exp`/`Sin`/`Cos` (Vulkan allows them 3 ULP / absolute 2⁻¹¹ error), so CPU
//! and GPU results differ in the last bits. Feature `portable-math` routes
//! [`super::exp`], [`super::sin`] and [`super::cos`] here on every target, which makes the
//! two results identical wherever the driver rounds `+`/`*` exactly and does not fuse them
//! into `fma` (measured in the SPIR-V backend's math-seam test; see ARCHITECTURE.md).
//!
//! | function | domain of full accuracy | max error (vs. correctly rounded) |
//! |---|---|---|
//! | [`exp`] | all `f32`; overflow to `+∞` above 88.72, `0` below −103.97 | ≤ 2 ULP (measured, CPU and lavapipe) |
//! | [`sin`], [`cos`] | \|x\| ≤ 8192 (3-part π/4 reduction) | ≈ 1 ULP; absolute error grows with \|x\| beyond |
//!
//! NaN in, NaN out. These are always compiled, so both variants can be compared in one
//! build; the feature only changes which one the seam calls. The `|r| ≤ π/4` polynomials
//! also serve [`super::sin_cos_pi`] on every build (no feature), where the reduction is
//! exact and so survives the driver's rewriting.

use crate::lane::Real;

/// 1/ln2_hi (rounding is harmless: it only picks k).
const FRAC_1_LN2_HI: f32 = 1.442_253_5;
/// ln 2 split so that `k * LN2_HI` is exact for |k| < 2⁹: `LN2_HI + LN2_LO ≈ ln 2`.
const LN2_HI: f32 = 0.693_359_375;
const LN2_LO: f32 = -2.121_944_400_546_905_8e-4;
/// Above this `e^x` overflows `f32`.
const EXP_OVERFLOW: f32 = 88.722_839;
/// Below this `e^x` rounds to zero (half the smallest subnormal).
const EXP_UNDERFLOW: f32 = -103.972_08;

/// 4/π.
const FRAC_4_PI: f32 = 1.273_239_544_735_162_7;
/// π/4 split into three parts whose products with a quadrant count below 2¹³ are exact.
const PIO4_1: f32 = 0.785_156_25;
const PIO4_2: f32 = 2.418_756_484_985_351_6e-4;
const PIO4_3: f32 = 3.774_894_977_445_941e-8;

/// `2^k` for `k` in `-126..=127`, by assembling the exponent field.
#[inline]
fn exp2i(k: i32) -> f32 {
    f32::from_bits(((k + 127) as u32) << 23)
}

/// e^x within 2 ULP (1 ULP from the polynomial, at most 1 from the `e^{−k·ln2_lo}` factor).
#[inline]
pub fn exp(x: f32) -> f32 {
    if x > EXP_OVERFLOW {
        return f32::INFINITY;
    }
    if x < EXP_UNDERFLOW {
        return 0.0;
    }
    // x = k ln2_hi + r, |r| ≤ ln2_hi/2, exactly: k ln2_hi is exact (9 + 8 significant
    // bits) and so is the difference (Sterbenz). The rest of k ln 2, u = −k ln2_lo
    // (|u| < 0.032), goes through its own short series instead of being subtracted from r:
    // a driver that re-associates `x − k·hi − k·lo` into `x − k·(hi + lo)` rounds the
    // product and loses up to 18 ULP (measured on lavapipe); two separate factors leave it
    // nothing to merge.
    let kf = libm_free_floor(x * FRAC_1_LN2_HI + 0.5);
    let er = exp_reduced(x, kf);
    // 2^k in two factors so that k = 128 (x near the overflow edge) and k < -126
    // (subnormal results) stay representable; NaN makes `k` meaningless but keeps `er` NaN.
    let k = kf as i32;
    let k1 = k / 2;
    er * exp2i(k1) * exp2i(k - k1)
}

/// `e^x / 2^k` for `k = kf` (an integer with `|x − k·ln2_hi| ≤ ln2_hi/2`): `e^r · e^u` with
/// `r = x − k·ln2_hi` (exact) and `u = −k·ln2_lo`, shared by [`exp`] and [`exp_branchless`].
#[inline(always)]
fn exp_reduced(x: f32, kf: f32) -> f32 {
    let r = x - kf * LN2_HI;
    let u = -kf * LN2_LO;
    let lo = 1.0 + u * (1.0 + u * (0.5 + u * (1.0 / 6.0 + u * (1.0 / 24.0))));
    let r2 = r * r;
    let mut p = 1.987_569_150_0e-4_f32;
    p = p * r + 1.398_199_950_7e-3;
    p = p * r + 8.333_451_907_3e-3;
    p = p * r + 4.166_579_589_4e-2;
    p = p * r + 1.666_666_545_9e-1;
    p = p * r + 5.000_000_120_1e-1;
    (p * r2 + r + 1.0) * lo
}

/// 2²³: adding and subtracting it rounds an `x ∈ [0, 2²³)` to the nearest integer.
const ROUND_MAGIC: f32 = 8_388_608.0;

/// `floor(x)` without a branch or a float→int conversion (either keeps LLVM from
/// vectorising a loop of it): exact for every `f32` (|x| ≥ 2²³ is already integral), and
/// `floor(−0) = −0` as libm's.
#[inline(always)]
pub fn floor_branchless(x: f32) -> f32 {
    let ax = f32::from_bits(x.to_bits() & 0x7fff_ffff);
    let n = (ax + ROUND_MAGIC) - ROUND_MAGIC;
    // x's sign on the rounded |x| (a sign test would turn −0 into +0).
    let n = f32::from_bits(n.to_bits() | (x.to_bits() & 0x8000_0000));
    let f = if n > x { n - 1.0 } else { n };
    if ax < ROUND_MAGIC { f } else { x }
}

/// `(x as i32) as f32` (truncation toward zero, saturating at ±2³¹, NaN to +0, and +0 for
/// every `x` in (−1, 1)), bit for bit, written without branches or float→int conversions,
/// for [`crate::lane::Lanes`]: a saturating `as i32` scalarises a loop over lanes.
#[inline(always)]
pub fn trunc_branchless(x: f32) -> f32 {
    // The rounding step of `floor_branchless`, on |x|: written out again rather than taken
    // as `floor_branchless(|x|)`, because that composition stopped LLVM vectorising the
    // lane loops (its instructions inside the AVX2 table batch went from 3.0 M to 13.3 M in a
    // callgrind count, and the SIMD table fell from 1.9 M to 1.3 M evaluations/s).
    let ax = f32::from_bits(x.to_bits() & 0x7fff_ffff);
    // Below 2²³ the magic sum rounds |x| to an integer; one less where it rounded up.
    let n = (ax + ROUND_MAGIC) - ROUND_MAGIC;
    let t = if n > ax { n - 1.0 } else { n };
    // From 2²³ on every f32 is an integer; from 2³¹ on the conversion saturates.
    let t = if ax < ROUND_MAGIC {
        t
    } else if ax < I32_LIMIT {
        ax
    } else {
        I32_LIMIT
    };
    // `0 − t`, not `−t`: a negative x above −1 truncates to +0, as the conversion does.
    let t = if x < 0.0 { 0.0 - t } else { t };
    if x.is_nan() { 0.0 } else { t }
}

/// 2³¹, where `as i32` saturates (`i32::MAX as f32` rounds to it).
const I32_LIMIT: f32 = 2_147_483_648.0;

/// 1.5·2²³: `n + K_MAGIC` holds the integer `|n| < 2²²` in its low mantissa bits.
const K_MAGIC: f32 = 12_582_912.0;

/// [`exp`] with the same reduction, polynomial and result (bit for bit), written without
/// branches or float→int conversions, for [`crate::lane::Lanes`] (a loop of it vectorises).
#[inline(always)]
pub fn exp_branchless(x: f32) -> f32 {
    let xc = if x > EXP_OVERFLOW { EXP_OVERFLOW } else { x };
    let xc = if xc < EXP_UNDERFLOW {
        EXP_UNDERFLOW
    } else {
        xc
    };
    let kf = floor_branchless(xc * FRAC_1_LN2_HI + 0.5);
    let er = exp_reduced(xc, kf);
    // k from the mantissa of `kf + 1.5·2²³` (kf is an integer in [-150, 128]).
    let k = ((kf + K_MAGIC).to_bits() as i32) - (K_MAGIC.to_bits() as i32);
    let k1 = k >> 1;
    let v = er * exp2i(k1) * exp2i(k - k1);
    let v = if x > EXP_OVERFLOW { f32::INFINITY } else { v };
    let v = if x < EXP_UNDERFLOW { 0.0 } else { v };
    if x.is_nan() { x } else { v }
}

/// ln 2 split for [`ln_branchless`]: `e·LN2_HI` is exact for |e| < 2⁹.
const LOG_LN2_HI: f32 = 0.693_359_375;
const LOG_LN2_LO: f32 = -2.121_944_400_546_905_8e-4;

/// `ln x` within 2 ULP, without branches or float→int conversions (for
/// [`crate::lane::Lanes`]): `x = 2^e·m` with `m ∈ [√½, √2)` from the bits, and
/// `ln m = 2 atanh((m − 1)/(m + 1))` by the same series as [`super::ln1p`]
/// (`expm1::ln_ratio_series`). Subnormals are scaled by 2²³ first; `ln 0 = −∞`,
/// `ln x = NaN` below 0, `ln ∞ = ∞`.
#[inline(always)]
pub fn ln_branchless(x: f32) -> f32 {
    let sub = x < f32::MIN_POSITIVE;
    let xs = if sub { x * 8_388_608.0 } else { x };
    let bits = xs.to_bits();
    // x = 2^e·m with m ∈ [√½, √2): adding 1.0's bits minus √½'s carries into the
    // exponent exactly when the mantissa is at least √½'s.
    let b = bits.wrapping_add(0x3f80_0000 - 0x3f35_04f3);
    let e = ((b >> 23) as i32) - 127 - if sub { 23 } else { 0 };
    let m = f32::from_bits((b & 0x007f_ffff).wrapping_add(0x3f35_04f3));
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let ef = e as f32;
    let v = ef * LOG_LN2_HI + (super::expm1::ln_ratio_series(s) + ef * LOG_LN2_LO);
    let v = if x == 0.0 { f32::NEG_INFINITY } else { v };
    let v = if x == f32::INFINITY { x } else { v };
    if x < 0.0 || x.is_nan() { f32::NAN } else { v }
}

/// Sine, about 1 ULP for |x| ≤ 8192.
#[inline]
pub fn sin(x: f32) -> f32 {
    let (j, r) = reduce_pio4(x);
    // sin(-x) = -sin(x); quadrants 2, 3 (mod 4) flip the sign once more.
    let negate = (x < 0.0) != (j & 4 != 0);
    let s = if j & 2 != 0 { cos_poly(r) } else { sin_poly(r) };
    if negate { -s } else { s }
}

/// Cosine, about 1 ULP for |x| ≤ 8192.
#[inline]
pub fn cos(x: f32) -> f32 {
    let (j, r) = reduce_pio4(x);
    let negate = ((j + 2) & 4) != 0;
    let c = if j & 2 != 0 { sin_poly(r) } else { cos_poly(r) };
    if negate { -c } else { c }
}

/// |x| = j·π/4 + r with j even (octant pair) and |r| ≤ π/4; returns (j, r).
#[inline]
fn reduce_pio4(x: f32) -> (u32, f32) {
    let ax = if x < 0.0 { -x } else { x };
    // Beyond 2²⁴ octants the result is meaningless anyway; the clamp only keeps the
    // float-to-int conversion below defined on SPIR-V. NaN and ∞ give NaN in `r`.
    let q = libm_free_floor(ax * FRAC_4_PI);
    let q = if q < 16_777_216.0 { q } else { 0.0 };
    let mut j = q as u32;
    let mut y = q;
    // Map odd octants onto the next even one: r then lies in [-π/4, π/4].
    if j & 1 != 0 {
        j += 1;
        y += 1.0;
    }
    let r = ((ax - y * PIO4_1) - y * PIO4_2) - y * PIO4_3;
    (j & 7, r)
}

/// `(sin θ, cos θ)` for |θ| ≤ π/2, any [`Real`], about 1 ULP: the polynomials below
/// directly up to π/4 and on the complement `π/2 − |θ|` beyond (the difference with the
/// leading part of π/2 is exact there, Sterbenz, and its trailing part is added once), so
/// `cos θ` keeps its relative accuracy up to the ends of the range.
#[inline(always)]
pub fn sin_cos_within_half_pi<R: Real>(theta: R) -> (R, R) {
    let c = R::splat;
    let a = theta.abs();
    let direct = a.le(c(core::f32::consts::FRAC_PI_4));
    let r = R::select(direct, a, (c(PIO2_HI) - a) + c(PIO2_LO));
    let (s, co) = (sin_poly(r), cos_poly(r));
    let sin_a = R::select(direct, s, co);
    let cos_a = R::select(direct, co, s);
    (R::select(theta.lt(c(0.0)), -sin_a, sin_a), cos_a)
}

/// π/2 rounded to `f32`.
const PIO2_HI: f32 = core::f32::consts::FRAC_PI_2;
/// The remainder `π/2 − PIO2_HI` (to `f32`).
const PIO2_LO: f32 = -4.371_139e-8;

/// sin(r) for |r| ≤ π/4.
#[inline(always)]
pub(super) fn sin_poly<R: Real>(r: R) -> R {
    let c = R::splat;
    let z = r * r;
    ((c(-1.951_529_589_1e-4) * z + c(8.332_160_873_6e-3)) * z - c(1.666_665_461_1e-1)) * z * r + r
}

/// cos(r) for |r| ≤ π/4.
#[inline(always)]
pub(super) fn cos_poly<R: Real>(r: R) -> R {
    let c = R::splat;
    let z = r * r;
    ((c(2.443_315_711_809_948e-5) * z - c(1.388_731_625_493_765e-3)) * z
        + c(4.166_664_568_298_827e-2))
        * z
        * z
        - c(0.5) * z
        + c(1.0)
}

/// `floor` from a float→int round trip: exact for |x| < 2²³ (the only range used above),
/// identical on every target (no libm, no `GLSL.std.450 Floor`).
#[inline]
fn libm_free_floor(x: f32) -> f32 {
    // |x| ≥ 2²³ is already integral (and NaN stays NaN).
    let ax = if x < 0.0 { -x } else { x };
    if !(ax < 8_388_608.0) {
        return x;
    }
    let t = (x as i32) as f32;
    if t > x { t - 1.0 } else { t }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite floats of the same sign.
    fn ulps(a: f32, b: f32) -> u32 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs() as u32
    }

    #[test]
    fn exp_matches_libm_within_2_ulp() {
        let mut worst = 0;
        let mut x = -87.0_f32;
        while x < 88.5 {
            worst = worst.max(ulps(exp(x), libm::expf(x)));
            x += 0.013_7;
        }
        assert!(worst <= 2, "worst {worst} ULP");
    }

    #[test]
    fn exp_branchless_is_exp_bit_for_bit() {
        let mut x = -110.0_f32;
        while x < 90.0 {
            assert_eq!(exp_branchless(x).to_bits(), exp(x).to_bits(), "x = {x}");
            x += 0.003_1;
        }
        for x in [
            0.0,
            -0.0,
            88.72,
            88.73,
            -103.9,
            -104.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ] {
            assert_eq!(exp_branchless(x).to_bits(), exp(x).to_bits(), "x = {x}");
        }
        assert!(exp_branchless(f32::NAN).is_nan());
    }

    #[test]
    fn floor_branchless_is_floor() {
        let mut x = -3.0e7_f32;
        while x < 3.0e7 {
            for y in [x, x * 1.0e-6, x * 1.0e-3 + 0.5] {
                assert_eq!(floor_branchless(y), libm::floorf(y), "y = {y}");
            }
            x += 12_345.678;
        }
        for y in [
            0.0,
            -0.5,
            0.5,
            -1.0,
            4_194_303.5,
            -4_194_303.5,
            1.0e30,
            -1.0e30,
        ] {
            assert_eq!(floor_branchless(y), libm::floorf(y), "y = {y}");
        }
    }

    #[test]
    fn ln_branchless_is_within_2_ulp_of_f64_ln_from_subnormals_to_max() {
        let mut worst = 0.0_f64;
        // Every 97th f32 bit pattern of the positive finite range, subnormals included.
        let mut bits = 1_u32;
        while bits < 0x7f80_0000 {
            let x = f32::from_bits(bits);
            let want = libm::log(f64::from(x));
            let got = f64::from(ln_branchless(x));
            let w = want as f32;
            let ulp = f64::from(f32::from_bits(w.abs().to_bits() + 1) - w.abs());
            worst = worst.max((got - want).abs() / ulp);
            bits += 97;
        }
        assert!(worst <= 2.0, "worst {worst} ULP");
        assert_eq!(ln_branchless(1.0), 0.0);
        assert_eq!(ln_branchless(0.0), f32::NEG_INFINITY);
        assert_eq!(ln_branchless(-0.0), f32::NEG_INFINITY);
        assert_eq!(ln_branchless(f32::INFINITY), f32::INFINITY);
        assert!(ln_branchless(-1.0).is_nan() && ln_branchless(f32::NAN).is_nan());
    }

    #[test]
    fn exp_edge_cases() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(f32::INFINITY), f32::INFINITY);
        assert_eq!(exp(f32::NEG_INFINITY), 0.0);
        assert!(exp(f32::NAN).is_nan());
        assert_eq!(exp(89.0), f32::INFINITY);
        assert_eq!(exp(-104.0), 0.0);
        // k = 128 at the overflow edge, subnormal results below -87.3.
        assert!(ulps(exp(88.7), libm::expf(88.7)) <= 2);
        let sub = exp(-100.0);
        assert!(sub > 0.0 && sub < f32::MIN_POSITIVE);
        assert!((sub / libm::expf(-100.0) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn sin_cos_match_libm_within_2_ulp_or_tiny_absolute() {
        let mut x = -8192.0_f32;
        while x < 8192.0 {
            for (ours, reference) in [(sin(x), libm::sinf(x)), (cos(x), libm::cosf(x))] {
                // Near zeros of sin/cos the relative error of any f32 reduction is large;
                // judge those by absolute error (the reduced argument carries ~2⁻²⁴·|x|).
                let ok = ulps(ours, reference) <= 2
                    || (ours - reference).abs() < 1e-7 * x.abs().max(1.0);
                assert!(ok, "x = {x}: {ours} vs {reference}");
            }
            x += 0.377;
        }
    }

    #[test]
    fn sin_cos_edge_cases() {
        assert_eq!(sin(0.0), 0.0);
        assert_eq!(cos(0.0), 1.0);
        assert!(sin(f32::NAN).is_nan() && cos(f32::NAN).is_nan());
        assert!(sin(f32::INFINITY).is_nan() && cos(f32::INFINITY).is_nan());
        assert_eq!(sin(-1.0), -sin(1.0));
        assert_eq!(cos(-1.0), cos(1.0));
    }
}
