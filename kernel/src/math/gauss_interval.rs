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
//! integrated directly instead: by a power series within 12σ of the window's centre, by
//! 8-point Gauss–Legendre beyond. Narrow intervals (at most σ/2 long, e.g. across a groove)
//! that are not short oscillate fast enough that both ends' Faddeeva arguments lie far out,
//! `|z|² > 19.7`, where `w` takes its asymptotic series.

use super::complex::C32;
use super::faddeeva::{faddeeva, faddeeva_far_lanes, faddeeva_pair};
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
/// Out of line on SPIR-V: one copy of its four forms per `REDUCED` in the shader, where
/// every interval integral of every walk would otherwise inline them (ARCHITECTURE.md
/// *Shader size*); the CPU keeps it inline in each lane type.
#[cfg_attr(not(target_arch = "spirv"), inline(always))]
#[cfg_attr(target_arch = "spirv", inline(never))]
fn centered<R: Real, const REDUCED: bool>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    let c = R::splat;
    let len = c(2.0) * half;
    let narrow = len.le(c(0.5) * sigma);
    let short = narrow & (nu.abs() * len).le(c(0.5));
    // A short interval whose window slope across it is moderate, |m| h ≤ 3σ², takes the
    // power series (every interval within 12σ of the window's centre).
    let series = short & (mid.abs() * half).le(c(SERIES_SLOPE) * sigma * sigma);
    // A narrow interval that is not short has `|ν| σ > 1`, so both its ends' Faddeeva
    // arguments have `|z|² ≥ y² = 2π²σ²ν² > 19.74`: Faddeeva's asymptotic series holds
    // there. Where lanes differ, the short lanes' values from that form (outside its
    // domain, possibly not finite) are discarded lane by lane by `branch!`.
    branch!(
        half.gt(c(0.0)) & sigma.gt(c(0.0)),
        branch!(
            series,
            power_series::<R, REDUCED>(mid, half, sigma, nu),
            branch!(
                short,
                gauss_legendre::<R, REDUCED>(mid, half, sigma, nu),
                branch!(
                    narrow,
                    faddeeva_form::<R, REDUCED, true>(mid, half, sigma, nu),
                    faddeeva_form::<R, REDUCED, false>(mid, half, sigma, nu)
                )
            )
        ),
        Cx::splat(0.0, 0.0)
    )
}

/// The bound on `|m| h / σ²` (the real part of [`power_series`]' `z`) below which a short
/// interval takes the power series.
const SERIES_SLOPE: f32 = 3.0;

/// The last `j` of [`power_series`]' sum: its first neglected term,
/// `|z|^22/22! · μ_11 / |S|` with `|z| ≤ √(3² + (π/2)²)` and `|S| ≥ 0.6`, is below 1e-10.
const SERIES_ORDER: f32 = 10.0;

/// The short interval's integral as a power series, free of transcendental functions but
/// two `exp` (and the centre's `cis` without `REDUCED`):
/// `∫_{−h}^{h} e^{−(m+t)²/(2σ²) − 2πiνt} dt = 2h e^{−m²/(2σ²)} Σ_j z^{2j}/(2j)! μ_j`, with
/// `z = −mh/σ² − 2πiνh` and `μ_j = ∫_0^1 s^{2j} e^{−εs²} ds`, `ε = h²/(2σ²) ≤ 1/32`
/// (expand `e^{zs}` over `s = t/h ∈ [−1, 1]`; the odd powers cancel). The moments follow
/// downward, `μ_j = (e^{−ε} + 2ε μ_{j+1})/(2j + 1)` (by parts; each step damps an error in
/// the start by `2ε/(2j+1) ≤ 1/16`), beside the Horner sum in `z²`. On the short domain
/// `|Im z| ≤ π/2` keeps the sum `S ≈ sinh z / z` away from cancellation: the sum of its
/// terms' magnitudes, about `sinh|z| / |z|`, is at most 2.3 times `|S|`. Eight-point
/// Gauss–Legendre costs eight `exp` and eight `cis`.
#[inline(always)]
fn power_series<R: Real, const REDUCED: bool>(mid: R, half: R, sigma: R, nu: R) -> Cx<R> {
    let c = R::splat;
    let inv_s2 = c(1.0) / (sigma * sigma);
    let eps = c(0.5) * half * half * inv_s2;
    let z = Cx::new(-mid * half * inv_s2, c(-2.0 * super::PI) * nu * half);
    let w = z * z;
    let e = (-eps).exp();
    let two_eps = c(2.0) * eps;
    // `odd` = 2j + 1 from j = SERIES_ORDER down to 0 (f32, exact); μ_{N+1} started at
    // e^{−ε}/(2N + 3), within ε of its value.
    let mut odd = 2.0 * SERIES_ORDER + 1.0;
    let mut mu = e * c(1.0 / (odd + 2.0));
    let mut sum = Cx::splat(0.0, 0.0);
    while odd > 0.0 {
        mu = (e + two_eps * mu) * c(1.0 / odd);
        sum = Cx::real(mu) + (w * sum).scale(c(1.0 / (odd * (odd + 1.0))));
        odd -= 2.0;
    }
    let scale = c(2.0) * half * (c(-0.5) * mid * mid * inv_s2).exp();
    if REDUCED {
        sum.scale(scale)
    } else {
        (cis_pi_lanes(c(-2.0) * nu * mid) * sum).scale(scale)
    }
}

/// The closed form through the Faddeeva function at the two ends (the module docs);
/// with `REDUCED`, without the centre's phase `e^{−2πiνm}`; with `FAR`, for arguments
/// known to lie in the domain of Faddeeva's asymptotic series ([`centered`]).
#[inline(always)]
fn faddeeva_form<R: Real, const REDUCED: bool, const FAR: bool>(
    mid: R,
    half: R,
    sigma: R,
    nu: R,
) -> Cx<R> {
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
    let (za, zb) = (endpoint_arg(xa, y), endpoint_arg(xb, y));
    let (wa, wb) = if FAR {
        (faddeeva_far_lanes(za), faddeeva_far_lanes(zb))
    } else {
        endpoint_faddeeva(za, zb, need_a, need_b)
    };
    // The phases e^{−2πiνa}, e^{−2πiνb} of the end terms. On one side of the window's
    // centre the ends may lie far out (|m| ≫ h) and the two terms nearly cancel (the
    // integrand is almost a pure oscillation there): rounding 2νa and 2νb separately would
    // put independent errors of ε·2|νm| half-turns into them (1.5e-3 relative at m = 189 µm,
    // ν = 2.4/µm; issue #20). So the centre's phase e^{−2πiνm} is factored out and the ends
    // carry e^{±2πiνh}. Across the centre |a|, |b| ≤ 2h and the plain phases are used.
    let ((pa, pb), common) = branch!(
        same_side,
        (
            {
                let p = cis_pi_lanes(c(2.0) * nu * half);
                (p, p.conj())
            },
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

    #[test]
    fn short_interval_power_series_matches_quadrature() {
        // Short intervals (len ≤ σ/2, |ν| len ≤ 0.5) with |m| h ≤ 3σ² take the power
        // series: over that whole domain (its edges included) against the f64 quadrature,
        // within 1e-6 of |I| plus the roundings of the window's exponent and of the
        // centre's phase 2νm. Eight-point Gauss–Legendre, which it replaces there, is
        // measured beside it.
        let sigma = 10.0f32;
        let (mut n, mut worst, mut worst_gl) = (0, 0.0f64, 0.0f64);
        for il in 0..=10 {
            let half = sigma * 0.25 * (0.001f32).powf(il as f32 / 10.0);
            for im in 0..=24 {
                let slope = SERIES_SLOPE * (im as f32 / 12.0 - 1.0);
                let mid = slope * sigma * sigma / half;
                for iq in 0..=8 {
                    let nu = (0.5 / (2.0 * half)) * (iq as f32 / 4.0 - 1.0);
                    let len = 2.0 * half;
                    if !(len <= 0.5 * sigma
                        && (nu.abs() * len) <= 0.5
                        && (mid.abs() * half) <= SERIES_SLOPE * sigma * sigma)
                    {
                        continue;
                    }
                    for reduced in [false, true] {
                        let (got, gl) = if reduced {
                            (
                                power_series::<f32, true>(mid, half, sigma, nu),
                                gauss_legendre::<f32, true>(mid, half, sigma, nu),
                            )
                        } else {
                            (
                                power_series::<f32, false>(mid, half, sigma, nu),
                                gauss_legendre::<f32, false>(mid, half, sigma, nu),
                            )
                        };
                        let (mut re, mut im_) = quadrature(mid, half, sigma, nu);
                        if reduced {
                            // put the centre's phase e^{2πiνm} back, in f64
                            let ph = 2.0 * core::f64::consts::PI * f64::from(nu) * f64::from(mid);
                            let (s, c) = (libm::sin(ph), libm::cos(ph));
                            (re, im_) = (re * c - im_ * s, re * s + im_ * c);
                        }
                        let mag = (re * re + im_ * im_).sqrt();
                        if mag < 1e-36 {
                            continue; // near or below f32's smallest normal number
                        }
                        let err = ((f64::from(got.re) - re).powi(2)
                            + (f64::from(got.im) - im_).powi(2))
                        .sqrt();
                        // The window's exponent m²/(2σ²) is rounded before `exp`
                        // amplifies it, as one ulp of m would (the conditioning).
                        let window = 4.0 * f64::from(f32::EPSILON) * f64::from(mid * mid)
                            / f64::from(sigma * sigma);
                        let phase = if reduced {
                            window
                        } else {
                            window
                                + 4.0
                                    * f64::from(f32::EPSILON)
                                    * (2.0 * f64::from(nu * mid)).abs()
                                    * core::f64::consts::PI
                        };
                        assert!(
                            err <= mag * (1.0e-6 + phase),
                            "m {mid} h {half} ν {nu} reduced {reduced}: {got:?} vs ({re}, {im_}), GL {gl:?}"
                        );
                        let gl_err = ((f64::from(gl.re) - re).powi(2)
                            + (f64::from(gl.im) - im_).powi(2))
                        .sqrt();
                        worst = worst.max(err / mag);
                        worst_gl = worst_gl.max(gl_err / mag);
                        n += 1;
                    }
                }
            }
        }
        // The whole domain was covered, and the series is as accurate as the quadrature it
        // replaces (worst 1.24e-5 against 1.11e-5, both the conditioning at large `m`).
        assert!(
            n >= 900 && worst <= 1.5 * worst_gl.max(1.0e-6),
            "{n} cases, worst relative {worst:.2e} (Gauss–Legendre {worst_gl:.2e})"
        );
    }

    #[test]
    fn narrow_interval_far_form_is_as_accurate_as_weidemans() {
        // Narrow intervals (len ≤ σ/2) that are not short take the Faddeeva form with the
        // asymptotic series. Over their whole range (centres to 7σ out on either side,
        // lengths to σ/2, |ν|·len from 0.5 to 60, both signs), reduced and not, its error
        // against the f64 quadrature must stay within twice the Weideman form's, or 2e-7
        // of the integrand's L1 norm, whichever is larger.
        let sigma = 10.0f32;
        let (mut n, mut worst) = (0, 0.0f64);
        for im in 0..29 {
            let mid = sigma * (-7.0 + 0.5 * im as f32);
            for il in 1..=8 {
                let half = sigma * 0.25 * il as f32 / 8.0;
                let len = 2.0 * half;
                for iq in 0..12 {
                    let q = 0.5001 * 120f32.powf(iq as f32 / 11.0);
                    let nu = if (im + il + iq) % 2 == 0 {
                        q / len
                    } else {
                        -q / len
                    };
                    assert!(len <= 0.5 * sigma && (nu.abs() * len) > 0.5);
                    let far = faddeeva_form::<f32, false, true>(mid, half, sigma, nu);
                    let weid = faddeeva_form::<f32, false, false>(mid, half, sigma, nu);
                    let (re, im_) = quadrature(mid, half, sigma, nu);
                    let err = |c: Cx<f32>| {
                        ((f64::from(c.re) - re).powi(2) + (f64::from(c.im) - im_).powi(2)).sqrt()
                    };
                    let l1 = quadrature(mid, half, sigma, 0.0).0;
                    let bound = (2.0 * err(weid)).max(2e-7 * l1);
                    assert!(
                        err(far) <= bound,
                        "m {mid} h {half} ν {nu}: far {far:?} off by {:.3e}, Weideman by {:.3e}",
                        err(far),
                        err(weid)
                    );
                    worst = worst.max(err(far) / l1);
                    n += 1;
                    // The reduced form (the exact window's V halves) the same way.
                    let far = faddeeva_form::<f32, true, true>(mid, half, sigma, nu);
                    let weid = faddeeva_form::<f32, true, false>(mid, half, sigma, nu);
                    let d = f64::from((far - weid).norm_sqr()).sqrt();
                    assert!(
                        d <= 4e-7 * l1 + 2.0 * err(weid),
                        "reduced: m {mid} h {half} ν {nu}"
                    );
                }
            }
        }
        // Every case ran (worst measured 1.1e-5 of ∫|f|, the conditioning at large `m`).
        assert!(
            n == 29 * 8 * 12 && worst <= 2.0e-5,
            "{n} cases, worst error {worst:.2e} of ∫|f|"
        );
    }
}
