//! A cheap sine integral for the band integral: `|error| ≤ 6e-5` on the whole real line,
//! against ~5e-2 for Velinov's Eq. 29 ([`crate::math::si_velinov`]) and f32 resolution for
//! the exact [`crate::math::si`].
//!
//! `|x| ≤ 4`: an odd degree-13 polynomial; `|x| > 4`: `π/2 − f(x) cos x − g(x) sin x` with
//! cubic fits of the auxiliary functions in `t = (4/x)²`. Coefficients from
//! `kernel/gen/si_fast_consts.py` (least squares against mpmath). It lives beside the light
//! code because nothing else needs it; it calls only `crate::math` primitives.

use crate::math;

/// Odd polynomial for `|x| ≤ 4`: `Si(x) ≈ x Σ P[k] x^{2k}`.
const P: [f32; 7] = [
    0.9999999924543188,
    -0.05555553689434101,
    0.0016666533196474228,
    -2.834047295406367e-05,
    3.055147784228286e-07,
    -2.2186383572334045e-09,
    9.709989756689907e-12,
];
/// `x f(x) ≈ Σ F[k] t^k` for `|x| > 4`.
const F: [f32; 4] = [
    0.9997490644052712,
    -0.11878208891518849,
    0.05175944625133867,
    -0.016099361086383008,
];
/// `x² g(x) ≈ Σ G[k] t^k` for `|x| > 4`.
const G: [f32; 4] = [
    0.9986042655975264,
    -0.33908077085356414,
    0.20692882972530674,
    -0.07233807945566856,
];

/// Where the two branches meet.
const X0: f32 = 4.0;

/// Fast `Si(x)` (absolute error ≤ 6e-5; exact at 0, odd, tends to ±π/2).
#[inline]
pub fn si_fast(x: f32) -> f32 {
    let (asymptote, rest) = si_fast_split(x);
    asymptote - rest
}

/// [`si_fast`] as `asymptote − rest`, like [`math::si_split`]: `(±π/2, tail)` for
/// |x| > 4, `(0, −Si(x))` otherwise.
pub fn si_fast_split(x: f32) -> (f32, f32) {
    let ax = math::abs(x);
    let s = math::sign(x);
    if ax <= X0 {
        let x2 = ax * ax;
        let mut acc = P[6];
        let mut k = 6;
        while k > 0 {
            k -= 1;
            acc = acc * x2 + P[k];
        }
        (0.0, -s * ax * acc)
    } else {
        let t = X0 * X0 / (ax * ax);
        let f = (F[0] + t * (F[1] + t * (F[2] + t * F[3]))) / ax;
        let g = (G[0] + t * (G[1] + t * (G[2] + t * G[3]))) / (ax * ax);
        (
            s * 0.5 * math::PI,
            s * (f * math::cos(ax) + g * math::sin(ax)),
        )
    }
}
