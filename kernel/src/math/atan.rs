//! Arctangent, `atan2`, `asin` and `acos` from one polynomial, identical source on the CPU
//! and the GPU.
//!
//! GLSL.std.450's inverse trigonometric functions are loose on Vulkan (lavapipe measured
//! against libm: `acos` 1.6e-4 and `asin` 3.9e-4 absolute, `atan2` 3.4e-6; see
//! `backend-spirv/tests/math_probe.rs`), enough to move a light's crossing points and cost
//! 1 % in a light integral. So the kernel does not call them: the argument is reduced to
//! `|u| ≤ tan(π/8)` and `atan(u) = u + u z P(z)`, `z = u²`, with a degree-3 `P` fitted by
//! `reference/math/atan_fit.py` (0.66 ULP relative on the reduced range, evaluated in f32).
//! `asin` and `acos` go through `atan2` with `√((1 − x)(1 + x))`, exact near ±1. Measured
//! against f64 libm (tests below): `atan2` ≤ 2.4 ULP, `asin`/`acos` ≤ 3.0 ULP (libm's f32
//! functions: ≤ 1 ULP; the price is the argument reduction's roundings).

use super::{clamp, sqrt0};
use crate::lane::{Real, branch};

/// `tan(π/8)`.
const TAN_PI_8: f32 = 0.414_213_57;
/// `n·π/4` for `n = 0…4` split as `HI + LO` (`HI` the nearest f32), so that adding a
/// multiple of π/4 costs one rounding.
const QUARTER_PI_HI: [f32; 5] = [
    0.0,
    core::f32::consts::FRAC_PI_4,
    core::f32::consts::FRAC_PI_2,
    2.356_194_5,
    core::f32::consts::PI,
];
/// See [`QUARTER_PI_HI`].
const QUARTER_PI_LO: [f32; 5] = [
    0.0,
    -2.185_569_4e-8,
    -4.371_138_8e-8,
    -5.962_440_3e-9,
    -8.742_277_7e-8,
];
/// `P(z)` coefficients, `z⁰ … z³` (`reference/math/atan_fit.py`).
const P: [f32; 4] = [-0.333_329_38, 0.199_773_61, -0.138_744_49, 0.080_444_66];

/// `atan(t) = k·π/4 + v` for `t ∈ [0, 1]`: returns `(k, v)`, `k ∈ {0, 1}` (as a [`Real`]).
#[inline(always)]
fn atan_unit<R: Real>(t: R) -> (R, R) {
    let c = R::splat;
    let big = t.gt(c(TAN_PI_8));
    let u = branch!(big, (t - c(1.0)) / (t + c(1.0)), t);
    let z = u * u;
    let p = ((c(P[3]) * z + c(P[2])) * z + c(P[1])) * z + c(P[0]);
    (R::select(big, c(1.0), c(0.0)), u + u * z * p)
}

/// The angle (radians, in `[0, π]`) between the non-zero vectors `a` and `b`:
/// `atan2(|a × b|, a · b)`, accurate near 0 and π where `acos` of the dot product is not.
#[inline]
pub fn angle_between(a: glam::Vec3, b: glam::Vec3) -> f32 {
    atan2(a.cross(b).length(), a.dot(b))
}

/// The angle of `(x, y)` in `[−π, π]`, NaN if either is NaN (any [`Real`]).
#[inline(always)]
pub fn atan2<R: Real>(y: R, x: R) -> R {
    let c = R::splat;
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay.gt(ax);
    let lo = R::select(steep, ax, ay);
    let hi = R::select(steep, ay, ax);
    let t = R::select(
        hi.eq(c(0.0)),
        c(0.0),
        R::select(lo.eq(c(f32::INFINITY)), c(1.0), lo / hi),
    );
    let (k, v) = atan_unit(t);
    // The angle is n·π/4 ± v: mirrored about π/4 when steep, about π/2 when x < 0, so
    // n = k, 2 − k, 2 + k, 4 − k and v flips sign where exactly one mirror applies.
    let neg = x.sign_bit();
    let flip = (steep & !neg) | (!steep & neg);
    let n = R::select(steep, c(2.0), R::select(neg, c(4.0), c(0.0))) + R::select(flip, -k, k);
    let v = R::select(flip, -v, v);
    let r = R::gather_array(&QUARTER_PI_HI, n) + (R::gather_array(&QUARTER_PI_LO, n) + v);
    let r = R::select(y.sign_bit(), -r, r);
    R::select(x.is_nan() | y.is_nan(), c(f32::NAN), r)
}

/// Arctangent.
#[inline]
pub fn atan(x: f32) -> f32 {
    atan2(x, 1.0)
}

/// Arcsine of `x` clamped to [-1, 1] (no NaN for arguments just outside by rounding).
#[inline]
pub fn asin(x: f32) -> f32 {
    let x = clamp(x, -1.0, 1.0);
    atan2(x, sqrt0((1.0 - x) * (1.0 + x)))
}

/// Arccosine of `x` clamped to [-1, 1].
#[inline(always)]
pub fn acos<R: Real>(x: R) -> R {
    let one = R::splat(1.0);
    let x = clamp(x, -one, one);
    atan2(sqrt0((one - x) * (one + x)), x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ULP distance to the correctly rounded value of the f64 reference.
    fn ulp_err(got: f32, want: f64) -> f64 {
        let ulp =
            f64::from(f32::from_bits((want as f32).abs().to_bits() + 1) - (want as f32).abs());
        (f64::from(got) - want).abs() / ulp
    }

    #[test]
    fn atan2_is_within_three_ulp_of_f64_libm_on_every_quadrant() {
        let mut worst: f64 = 0.0;
        for i in 0..200_000 {
            let a = (i as f64 + 0.5) / 200_000.0 * core::f64::consts::TAU - core::f64::consts::PI;
            let r = 10f64.powf((i % 13) as f64 - 6.0);
            let (y, x) = ((r * a.sin()) as f32, (r * a.cos()) as f32);
            let want = libm::atan2(f64::from(y), f64::from(x));
            worst = worst.max(ulp_err(atan2(y, x), want));
        }
        assert!(worst <= 3.0, "atan2: {worst} ulp");
    }

    #[test]
    fn asin_acos_are_accurate_up_to_the_endpoints() {
        let mut worst: f64 = 0.0;
        for i in 0..=200_000 {
            let x = (i as f64 / 100_000.0 - 1.0) as f32;
            let (s, c) = (asin(x), acos(x));
            worst = worst.max(ulp_err(s, libm::asin(f64::from(x))));
            worst = worst.max(ulp_err(c, libm::acos(f64::from(x))));
        }
        assert!(worst <= 4.0, "asin/acos: {worst} ulp");
        assert_eq!(asin(1.5), asin(1.0));
        assert_eq!(acos(-2.0), acos(-1.0));
    }

    #[test]
    fn special_values_follow_libm() {
        for (y, x) in [
            (0.0f32, 0.0f32),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (f32::INFINITY, f32::INFINITY),
            (-f32::INFINITY, f32::INFINITY),
            (f32::INFINITY, -f32::INFINITY),
            (1.0, f32::INFINITY),
            (1.0, -f32::INFINITY),
            (f32::INFINITY, 1.0),
        ] {
            let (got, want) = (atan2(y, x), libm::atan2f(y, x));
            assert!(
                (got - want).abs() <= 2.0 * f32::EPSILON * want.abs(),
                "atan2({y}, {x}) = {got}, libm {want}"
            );
            assert_eq!(
                got.is_sign_negative(),
                want.is_sign_negative(),
                "sign of atan2({y}, {x})"
            );
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
    }
}
