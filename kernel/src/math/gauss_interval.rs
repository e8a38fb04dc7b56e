//! Gaussian-windowed Fourier integrals over an interval, evaluated without overflow.
//!
//! `I(a, b) = ∫_a^b exp(−u²/(2σ²) − 2πiνu) du` is the core of Werner's finite-segment spatial
//! phase (Werner 2017 App. A, Eqs. 23–24). The closed form
//! `σ√(π/2) e^{−2π²σ²ν²} [erf(z_b) − erf(z_a)]`, `z = (u + 2πiσ²ν)/(σ√2)`, overflows when
//! evaluated as printed (`erf` of a large imaginary part grows like `e^{y²}` while the
//! prefactor underflows like `e^{−y²}`). With `z = x + iy` we combine the exponents before
//! calling `exp`: for `x ≥ 0`,
//! `e^{−y²} erf(z) = e^{−y²} − e^{−x² − 2ixy} w(−y + ix)`
//! with the Faddeeva function `w` evaluated in the upper half plane (|w| ≤ 1), and
//! `erf(−z) = −erf(z)` covers `x < 0`. Every term is then bounded by 1.
//!
//! Short intervals (where the difference of two nearly equal `erf` values would cancel) are
//! integrated directly by 8-point Gauss–Legendre instead.

use super::complex::{C32, cscale};
use super::faddeeva::{faddeeva, faddeeva_lanes};
use super::quadrature::{GL8_W as GL_W, GL8_X as GL_X};
use super::trig_pi::cis_pi;

/// The Faddeeva argument `s(−y + ix)` of the endpoint `z = x + iy`, with `s = sign(x)` so
/// that it lies in the upper half plane. The endpoint's term is then
/// `e^{−x²} e^{−2ixy} w(·)`, with the phase `2xy` formed from the unscaled inputs by the
/// caller (one rounding instead of three).
#[inline]
fn endpoint_arg(x: f32, y: f32) -> C32 {
    let s = super::sign(x);
    C32::new(-s * y, s * x)
}

/// A rough lower bound of `|e^{−x²} w(−y + ix)|` (|w| decays like `1/(√π |z|)`), used only
/// to decide which terms are too small to matter.
#[inline]
fn term_scale(g: f32, x: f32, y: f32) -> f32 {
    g * super::FRAC_1_SQRT_PI / (1.0 + super::abs(x) + super::abs(y))
}

/// Terms below this fraction of the largest one are skipped (no Faddeeva call): their
/// contribution is under 1e-12 of the result, far below `f32` resolution. This makes the
/// common case of a long scratch whose ends lie outside the window cheap.
const NEGLIGIBLE: f32 = 1.0e-12;

/// `∫_a^b exp(−u²/(2σ²) − 2πiνu) du` for `a ≤ b`, `σ > 0` (returns 0 otherwise).
///
/// Bounded for every finite input: no overflow for |ν| σ large or for intervals far from
/// the origin. Relative accuracy is limited only by the conditioning of the phase `2πνu`.
pub fn gauss_fourier_interval(a: f32, b: f32, sigma: f32, nu: f32) -> C32 {
    if !(b > a) || !(sigma > 0.0) {
        return C32::new(0.0, 0.0);
    }
    let len = b - a;
    if len <= 0.5 * sigma && super::abs(nu) * len <= 0.5 {
        return gauss_legendre(a, b, sigma, nu);
    }
    let k = 1.0 / (super::SQRT_2 * sigma);
    let y = super::SQRT_2 * super::PI * sigma * nu;
    let (xa, xb) = (a * k, b * k);
    let (ga, gb) = (super::exp(-xa * xa), super::exp(-xb * xb));
    let same_side = (xa >= 0.0) == (xb >= 0.0);
    let centre = if same_side {
        0.0
    } else {
        2.0 * super::exp(-y * y)
    };
    let big = super::max(
        centre,
        super::max(term_scale(ga, xa, y), term_scale(gb, xb, y)),
    );
    let (need_a, need_b) = (ga > NEGLIGIBLE * big, gb > NEGLIGIBLE * big);
    let zero = C32::new(0.0, 0.0);
    // Both Faddeeva evaluations in one two-lane call when both ends matter.
    let (wa, wb) = if need_a && need_b {
        let w = faddeeva_lanes([endpoint_arg(xa, y), endpoint_arg(xb, y)]);
        (w[0], w[1])
    } else if need_a {
        (faddeeva(endpoint_arg(xa, y)), zero)
    } else if need_b {
        (zero, faddeeva(endpoint_arg(xb, y)))
    } else {
        (zero, zero)
    };
    let ea = if need_a {
        cscale(cis_pi(-2.0 * nu * a) * wa, ga)
    } else {
        zero
    };
    let eb = if need_b {
        cscale(cis_pi(-2.0 * nu * b) * wb, gb)
    } else {
        zero
    };
    let diff = if same_side {
        // Same side: the e^{−y²} parts cancel exactly; take them out analytically.
        cscale(ea - eb, super::sign(xa))
    } else {
        C32::new(centre, 0.0) - ea - eb
    };
    cscale(diff, sigma * SQRT_PI_OVER_2)
}

/// √(π/2).
const SQRT_PI_OVER_2: f32 = 1.253_314_137_315_500_3;

/// Direct 8-point Gauss–Legendre quadrature of the integrand (short intervals only).
fn gauss_legendre(a: f32, b: f32, sigma: f32, nu: f32) -> C32 {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let inv2s2 = 0.5 / (sigma * sigma);
    let mut acc = C32::new(0.0, 0.0);
    let mut i = 0;
    while i < 4 {
        let d = half * GL_X[i];
        let mut j = 0;
        while j < 2 {
            let u = if j == 0 { mid - d } else { mid + d };
            let g = super::exp(-u * u * inv2s2) * GL_W[i];
            acc += cscale(cis_pi(-2.0 * nu * u), g);
            j += 1;
        }
        i += 1;
    }
    cscale(acc, half)
}

/// `∫_a^b exp(−u²/(2σ²)) du` (real), e.g. a segment's Gaussian-weighted length.
#[inline]
pub fn gauss_interval(a: f32, b: f32, sigma: f32) -> f32 {
    gauss_fourier_interval(a, b, sigma, 0.0).re
}

/// The real error function, via the same Faddeeva machinery (`erf x = 1 − e^{−x²} w(ix)`).
pub fn erf(x: f32) -> f32 {
    let ax = super::abs(x);
    if ax < 0.5 {
        // Taylor series: avoids cancellation in 1 − erfc near 0.
        let x2 = x * x;
        let p = 1.0
            - x2 * (1.0 / 3.0
                - x2 * (1.0 / 10.0 - x2 * (1.0 / 42.0 - x2 * (1.0 / 216.0 - x2 / 1320.0))));
        return 2.0 * super::FRAC_1_SQRT_PI * x * p;
    }
    let erfc = super::exp(-ax * ax) * faddeeva(C32::new(0.0, ax)).re;
    super::sign(x) * (1.0 - erfc)
}
