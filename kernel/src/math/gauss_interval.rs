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

use super::complex::C32;
use super::faddeeva::{faddeeva, faddeeva_pair};
use super::quadrature::{GL8_W as GL_W, GL8_X as GL_X};
use super::trig_pi::cis_pi_lanes;
use crate::lane::{Blend, Cx, Real, branch};

/// The Faddeeva argument `s(−y + ix)` of the endpoint `z = x + iy`, with `s = sign(x)` so
/// that it lies in the upper half plane. The endpoint's term is then
/// `e^{−x²} e^{−2ixy} w(·)`, with the phase `2xy` formed from the unscaled inputs by the
/// caller (one rounding instead of three).
#[inline(always)]
fn endpoint_arg<R: Real>(x: R, y: R) -> Cx<R> {
    let s = super::sign(x);
    Cx::new(-s * y, s * x)
}

/// A rough lower bound of `|e^{−x²} w(−y + ix)|` (|w| decays like `1/(√π |z|)`), used only
/// to decide which terms are too small to matter.
#[inline(always)]
fn term_scale<R: Real>(g: R, x: R, y: R) -> R {
    g * R::splat(super::FRAC_1_SQRT_PI) / (R::splat(1.0) + x.abs() + y.abs())
}

/// Terms below this fraction of the largest one are skipped (no Faddeeva call): their
/// contribution is under 1e-12 of the result, far below `f32` resolution. This makes the
/// common case of a long scratch whose ends lie outside the window cheap.
const NEGLIGIBLE: f32 = 1.0e-12;

/// `∫_a^b exp(−u²/(2σ²) − 2πiνu) du` for `a ≤ b`, `σ > 0` (returns 0 otherwise): the
/// interval given by its ends; see [`gauss_fourier_centered`], which it calls with
/// `m = (a + b)/2`, `h = (b − a)/2`.
#[inline]
pub fn gauss_fourier_interval(a: f32, b: f32, sigma: f32, nu: f32) -> C32 {
    if !(b > a) {
        return C32::new(0.0, 0.0);
    }
    gauss_fourier_centered(0.5 * (a + b), 0.5 * (b - a), sigma, nu)
}

/// `∫_{m−h}^{m+h} exp(−u²/(2σ²) − 2πiνu) du` for `h > 0`, `σ > 0` (returns 0 otherwise):
/// Werner 2017 App. A, Eqs. 23–24, for a segment whose centre lies `m` from the window's
/// centre along the segment and whose half length is `h`.
///
/// Bounded for every finite input: no overflow for |ν| σ large or for intervals far from
/// the origin. Relative accuracy is limited only by the conditioning of the phase `2πνu`.
///
/// The interval is passed as centre and half length, not as its ends: a short segment far
/// along from the window's centre (`|m| ≫ h`) would lose the digits of its length to the
/// rounding of `m ± h` (a 0.022 µm segment 27 µm along: 1e-4 relative, ten times the
/// conditioning; issue #20), and the short-interval quadrature uses `m` and `h` directly.
pub fn gauss_fourier_centered(mid: f32, half: f32, sigma: f32, nu: f32) -> C32 {
    gauss_fourier_centered_lanes(mid, half, sigma, nu).into()
}

/// [`gauss_fourier_centered`] for any [`Real`] (the one formula).
#[inline(always)]
pub fn gauss_fourier_centered_lanes<R: Real>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    centered::<R, false>(mid, half, sigma, nu)
}

/// [`gauss_fourier_centered`] without the phase of the interval's centre:
/// `∫_{−h}^{h} exp(−(m + t)²/(2σ²) − 2πiνt) dt = e^{2πiνm} I(m − h, m + h)`.
///
/// For a caller that combines that phase with others analytically (the exact across-groove
/// window, [`crate::scratch::window`]): where `|m| ≫ h` the phase `2νm` is large, and
/// rounding it separately from the caller's own large phases would cost their cancellation.
/// The centre's phase is factored out inside anyway (module docs), so this costs nothing
/// more there; across the window's centre (`|m| ≤ h`) it is put back by one `cis`.
#[inline(always)]
pub fn gauss_fourier_reduced_lanes<R: Real>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    centered::<R, true>(mid, half, sigma, nu)
}

/// [`gauss_fourier_centered_lanes`], or with `REDUCED` its form without the centre's phase.
#[inline(always)]
fn centered<R: Real, const REDUCED: bool>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    let c = R::splat;
    let len = c(2.0) * half;
    branch!(
        half.gt(c(0.0)) & sigma.gt(c(0.0)),
        branch!(
            len.le(c(0.5) * sigma) & (nu.abs() * len).le(c(0.5)),
            gauss_legendre::<R, REDUCED>(mid, half, sigma, nu),
            faddeeva_form::<R, REDUCED>(mid, half, sigma, nu)
        ),
        Cx::splat(0.0, 0.0)
    )
}

/// The closed form through the Faddeeva function at the two ends (the module docs);
/// with `REDUCED`, without the centre's phase `e^{−2πiνm}`.
#[inline(always)]
fn faddeeva_form<R: Real, const REDUCED: bool>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    let c = R::splat;
    let (a, b) = (mid - half, mid + half);
    let k = c(1.0) / (c(super::SQRT_2) * sigma);
    let y = c(super::SQRT_2 * super::PI) * sigma * nu;
    let (xa, xb) = (a * k, b * k);
    let (ga, gb) = ((-xa * xa).exp(), (-xb * xb).exp());
    let (a_pos, b_pos) = (xa.ge(c(0.0)), xb.ge(c(0.0)));
    let same_side = (a_pos & b_pos) | !(a_pos | b_pos);
    let centre = branch!(same_side, c(0.0), c(2.0) * (-y * y).exp());
    let big = super::max(
        centre,
        super::max(term_scale(ga, xa, y), term_scale(gb, xb, y)),
    );
    let (need_a, need_b) = (ga.gt(c(NEGLIGIBLE) * big), gb.gt(c(NEGLIGIBLE) * big));
    let zero = Cx::splat(0.0, 0.0);
    let (wa, wb) = endpoint_faddeeva(endpoint_arg(xa, y), endpoint_arg(xb, y), need_a, need_b);
    // The phases e^{−2πiνa}, e^{−2πiνb} of the end terms. On one side of the window's
    // centre the ends may lie far out (|m| ≫ h) and the two terms nearly cancel (the
    // integrand is almost a pure oscillation there): rounding 2νa and 2νb separately would
    // put independent errors of ε·2|νm| half-turns into them (1.5e-3 relative at m = 189 µm,
    // ν = 2.4/µm; issue #20). So the centre's phase e^{−2πiνm} is factored out and the ends
    // carry e^{±2πiνh}. Across the centre |a|, |b| ≤ 2h and the plain phases are used.
    let ((pa, pb), common) = branch!(
        same_side,
        (
            (
                cis_pi_lanes(c(2.0) * nu * half),
                cis_pi_lanes(c(-2.0) * nu * half),
            ),
            if REDUCED {
                Cx::splat(1.0, 0.0)
            } else {
                cis_pi_lanes(c(-2.0) * nu * mid)
            },
        ),
        (
            (
                cis_pi_lanes(c(-2.0) * nu * a),
                cis_pi_lanes(c(-2.0) * nu * b),
            ),
            Cx::splat(1.0, 0.0),
        )
    );
    let ea = Cx::blend(need_a, (pa * wa).scale(ga), zero);
    let eb = Cx::blend(need_b, (pb * wb).scale(gb), zero);
    let diff = branch!(
        same_side,
        // Same side: the e^{−y²} parts cancel exactly; take them out analytically.
        (common * (ea - eb)).scale(super::sign(xa)),
        if REDUCED {
            // Across the centre `|m| ≤ h`: the phase is small and put back directly.
            cis_pi_lanes(c(2.0) * nu * mid) * (Cx::real(centre) - ea - eb)
        } else {
            Cx::real(centre) - ea - eb
        }
    );
    diff.scale(sigma * c(SQRT_PI_OVER_2))
}

/// `w` at both endpoint arguments, where needed (an unneeded one is multiplied by zero).
///
/// On the CPU only the ends some lane needs are evaluated, both in one two-chain call when
/// both matter: a long segment whose ends lie outside the window then costs no Faddeeva
/// call.
#[cfg(not(target_arch = "spirv"))]
#[inline(always)]
fn endpoint_faddeeva<R: Real>(
    za: Cx<R>,
    zb: Cx<R>,
    need_a: R::Mask,
    need_b: R::Mask,
) -> (Cx<R>, Cx<R>) {
    use super::faddeeva::faddeeva_lanes;
    use crate::lane::Mask;
    let zero = Cx::splat(0.0, 0.0);
    match (need_a.any(), need_b.any()) {
        (true, true) => faddeeva_pair(za, zb),
        (true, false) => (faddeeva_lanes(za), zero),
        (false, true) => (zero, faddeeva_lanes(zb)),
        (false, false) => (zero, zero),
    }
}

/// `w` at both endpoint arguments, always both in one two-chain call.
///
/// On SPIR-V the Faddeeva loop must not sit in a branch that neighbouring invocations take
/// differently: with the CPU's choice of calls above, lavapipe (Mesa 22.3) returned values
/// for a footprint average that depended on the other footprints of its SIMD group (2.4e-3
/// off in `backend-spirv/tests/table.rs`, right when evaluated alone). Evaluating both ends
/// unconditionally keeps the control flow uniform; the callers discard an unneeded end.
/// Not needed on Mesa 25's lavapipe (ARCHITECTURE.md *Divergence*).
#[cfg(target_arch = "spirv")]
#[inline(always)]
fn endpoint_faddeeva<R: Real>(
    za: Cx<R>,
    zb: Cx<R>,
    _need_a: R::Mask,
    _need_b: R::Mask,
) -> (Cx<R>, Cx<R>) {
    faddeeva_pair(za, zb)
}

/// √(π/2).
const SQRT_PI_OVER_2: f32 = 1.253_314_137_315_500_3;

/// `acc` plus the nodes `m ∓ d` of weight `w` in [`gauss_legendre`]: the window there
/// times the offsets' phases `e^{±2πiνd}`.
#[inline(always)]
fn gl_node_pair<R: Real>(mut acc: Cx<R>, mid: R, d: R, inv2s2: R, nu: R, w: R) -> Cx<R> {
    let c = R::splat;
    let mut j = 0;
    while j < 2 {
        let (u, off) = if j == 0 { (mid - d, -d) } else { (mid + d, d) };
        let g = (-u * u * inv2s2).exp() * w;
        acc = acc + cis_pi_lanes(c(-2.0) * nu * off).scale(g);
        j += 1;
    }
    acc
}

/// Direct 8-point Gauss–Legendre quadrature of the integrand over `[m − h, m + h]` (short
/// intervals only). The phase at the centre, `e^{−2πiνm}`, is factored out, so the nodes
/// carry only the small phases `2πν·(±d)` of their offsets (with `REDUCED`, left out).
#[inline(always)]
fn gauss_legendre<R: Real, const REDUCED: bool>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    let c = R::splat;
    let inv2s2 = c(0.5) / (sigma * sigma);
    // The node pairs ±x_i by constant index (no panic path; see `faddeeva::horner`).
    let mut acc = Cx::splat(0.0, 0.0);
    acc = gl_node_pair(acc, mid, half * c(GL_X[0]), inv2s2, nu, c(GL_W[0]));
    acc = gl_node_pair(acc, mid, half * c(GL_X[1]), inv2s2, nu, c(GL_W[1]));
    acc = gl_node_pair(acc, mid, half * c(GL_X[2]), inv2s2, nu, c(GL_W[2]));
    acc = gl_node_pair(acc, mid, half * c(GL_X[3]), inv2s2, nu, c(GL_W[3]));
    if REDUCED {
        acc.scale(half)
    } else {
        (cis_pi_lanes(c(-2.0) * nu * mid) * acc).scale(half)
    }
}

/// `∫_a^b exp(−u²/(2σ²)) du` (real), e.g. a segment's Gaussian-weighted length.
#[inline]
pub fn gauss_interval(a: f32, b: f32, sigma: f32) -> f32 {
    gauss_fourier_interval(a, b, sigma, 0.0).re
}

/// `∫_{m−h}^{m+h} exp(−u²/(2σ²)) du` (real), the interval as centre and half length (see
/// [`gauss_fourier_centered`]).
#[inline]
pub fn gauss_interval_centered(mid: f32, half: f32, sigma: f32) -> f32 {
    gauss_fourier_centered(mid, half, sigma, 0.0).re
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The integral in f64 by composite 8-point Gauss–Legendre on `[m − h, m + h]` (the
    /// ends formed in f64, where they are exact for these inputs).
    fn quadrature(mid: f32, half: f32, sigma: f32, nu: f32) -> (f64, f64) {
        let (m, h, s, n) = (
            f64::from(mid),
            f64::from(half),
            f64::from(sigma),
            f64::from(nu),
        );
        let panels = 64;
        let (mut re, mut im) = (0.0, 0.0);
        for p in 0..panels {
            let lo = m - h + 2.0 * h * p as f64 / panels as f64;
            let hw = h / panels as f64;
            for (x, w) in GL_X.iter().zip(GL_W.iter()) {
                for u in [
                    lo + hw * (1.0 - f64::from(*x)),
                    lo + hw * (1.0 + f64::from(*x)),
                ] {
                    let g = f64::from(*w) * hw * libm::exp(-u * u / (2.0 * s * s));
                    let ph = -2.0 * core::f64::consts::PI * n * u;
                    re += g * libm::cos(ph);
                    im += g * libm::sin(ph);
                }
            }
        }
        (re, im)
    }

    #[test]
    fn interval_far_out_keeps_the_phase_difference_of_its_ends() {
        // Ends 186 and 193 µm along a σ = 87 µm window, ν = 2.43/µm: the end terms nearly
        // cancel, so their phases must not be rounded separately at 2ν·190 ≈ 900 half-turns
        // (which cost 1.4e-3 relative); the common phase may be (|I| does not see it).
        for (mid, half, sigma, nu) in [
            (189.330_9_f32, 3.299_293_5_f32, 87.356_72_f32, 2.428_543_f32),
            (104.488_976, 3.807_491, 94.026_344, 0.518_732_6),
            (-310.2, 20.0, 70.0, -1.93),
        ] {
            let got = f64::from(gauss_fourier_centered(mid, half, sigma, nu).norm());
            let (re, im) = quadrature(mid, half, sigma, nu);
            let mag = (re * re + im * im).sqrt();
            assert!(
                (got / mag - 1.0).abs() < 5.0e-5,
                "m {mid} h {half} ν {nu}: |I| {got} vs {mag}"
            );
        }
    }

    #[test]
    fn short_interval_far_along_keeps_its_length() {
        // A 0.022 µm segment 27 µm along the window (σ = 8 µm): forming its ends m ± h in
        // f32 loses 1e-4 of the length; the centred form keeps it.
        for (mid, half, sigma, nu) in [
            (
                27.398_483_f32,
                0.011_166_851_f32,
                8.081_127_f32,
                -2.189_449_5_f32,
            ),
            (-140.7, 0.003, 60.0, 0.7),
            (3.2, 0.25, 1.5, 0.9),
            (0.0, 0.1, 1.0, 0.0),
        ] {
            let got = gauss_fourier_centered(mid, half, sigma, nu);
            let (re, im) = quadrature(mid, half, sigma, nu);
            let mag = (re * re + im * im).sqrt();
            let err = ((f64::from(got.re) - re).powi(2) + (f64::from(got.im) - im).powi(2)).sqrt();
            // the phase 2πνm is rounded once (|2νm| ≤ 200 half-turns: 2.4e-5 rad) and
            // the magnitude to a few ulp
            let phase_ulp = 4.0 * f64::from(f32::EPSILON) * (2.0 * f64::from(nu * mid)).abs();
            assert!(
                err <= mag * (1.0e-6 + phase_ulp * core::f64::consts::PI),
                "m {mid} h {half}: {got:?} vs ({re}, {im})"
            );
            let got_mag = f64::from(got.norm());
            assert!(
                (got_mag / mag - 1.0).abs() < 1.0e-6,
                "m {mid} h {half}: |I| {got_mag} vs {mag}"
            );
        }
    }
}
