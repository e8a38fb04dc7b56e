//! The band integral of one scratch's incoherent response (Velinov 2018 Eqs. 25–29).
//!
//! With `ξ = (wi + wo)_xy / λ` in 1/µm, the projected solid angle is `cos θi dωi =
//! d(wi_x) d(wi_y) = λ² dξ₁ dξ₂` (Eqs. 23–24; the paper's ξ is dimensionless, so its Jacobian
//! is 1). The per-scratch BRDF `F/(A_C λ²) |S_k|²` therefore integrates to
//! `(F/A_C) ∫∫ |S_k|² dξ₁ dξ₂` — the λ² cancels. For the rectangular groove
//! `|S_k|² = |1 − e^{iκ}|² W² sinc²(πWξ₂) |η(ξ₁)|²` separates; the light is cut along the
//! line ξ₁ = 0 (the band) and the ξ₁ integral is taken over ℝ:
//!
//! * across the scratch (this file): `W² ∫_{q0}^{q1} sinc²(πWξ₂) dξ₂ = A(q1) − A(q0)`,
//!   `A(q) = W (Si(2πWq) − πWq sinc²(πWq)) / π`. This is Eq. 27's `W² N(ξ, q)` without the
//!   ξ₁ factor and with q in 1/µm (the paper's `q = λ q_here`; its
//!   `2 Si(kWq)/(kW) − 4 sin²(kWq/2)/(k²W²q)` is `λ (Si(2πWq)/(πW) − sin²(πWq)/(π²W²q))`),
//!   written so that `W → 0` and `q → 0` are exact (no division by W or q).
//! * along the scratch (see [`super::integrate`]): `∫ |η|² dξ₁` by Parseval, which for the
//!   infinite scratch is Eq. 27's `√π/(σk)` factor (times `2πσ² e^{−s_b²/σ²}`, in 1/µm).

use crate::math;
use crate::math::quadrature::{GL8_W, GL8_X};

use super::si_fast::si_fast_split;

gpu_enum! {
    /// Which sine integral the band integral uses.
    pub enum SiMode {
        /// [`math::si`], exact to f32.
        Exact = 0,
        /// Velinov's Eq. 29 ([`math::si_velinov`]).
        Velinov = 1,
        /// [`si_fast`](super::si_fast::si_fast) (|error| ≤ 6e-5, cheaper than `Exact`).
        Fast = 2,
    }
    fallback = Exact;
}

impl SiMode {
    /// `Si(x)` by this method.
    #[inline]
    pub fn si(self, x: f32) -> f32 {
        let (asymptote, rest) = self.si_split(x);
        asymptote - rest
    }

    /// `Si(x) = asymptote − rest` by this method, with `asymptote = ±π/2` and a small
    /// `rest` far out.
    #[inline]
    pub fn si_split(self, x: f32) -> (f32, f32) {
        match self {
            SiMode::Exact => math::si_split(x),
            SiMode::Velinov => math::si_velinov_split(x),
            SiMode::Fast => si_fast_split(x),
        }
    }
}

/// `A(q) = W² ∫_0^q sinc²(πWt) dt = W (Si(2πWq) − πWq sinc²(πWq)) / π` (µm, q in 1/µm),
/// returned as `(asymptote, rest)` with `A = W/π · (asymptote − rest)`: far out,
/// `asymptote = ±π/2` and `rest` is the small tail `W⁻¹π ∫_q^{±∞}`, so two values on the
/// same far side subtract without cancelling against `W/2`.
#[inline]
fn band_antiderivative_split(width: f32, q: f32, si: SiMode) -> (f32, f32) {
    let x = math::PI * width * q;
    let s = math::sinc(x);
    let (asymptote, rest) = si.si_split(2.0 * x);
    (asymptote, rest + x * s * s)
}

/// `A(q) = W² ∫_0^q sinc²(πWt) dt = W (Si(2πWq) − πWq sinc²(πWq)) / π` (µm, q in 1/µm).
#[inline]
pub fn band_antiderivative(width: f32, q: f32, si: SiMode) -> f32 {
    let (asymptote, rest) = band_antiderivative_split(width, q, si);
    width * (asymptote - rest) / math::PI
}

/// Widest interval, in radians of the sinc's argument (`πW|q1 − q0|`), that
/// [`band_integral_len`] sums by Gauss–Legendre instead of differencing `A`: there the 8-point
/// rule is exact to ~1e-13 of `sinc²`'s scale, while `A(q1) − A(q0)` loses the digits the
/// two values share.
const DIRECT_SPAN: f32 = 2.0;

/// `W² ∫_{q0}^{q1} sinc²(πWξ₂) dξ₂` (Velinov Eq. 27's `N(ξ, q1) − N(ξ, q0)` across the
/// scratch); negative when `q1 < q0`: [`band_integral_len`] with `len = q1 − q0`.
#[inline]
pub fn band_integral(width: f32, q0: f32, q1: f32, si: SiMode) -> f32 {
    band_integral_len(width, q0, q1 - q0, si)
}

/// `W² ∫_{q0}^{q0 + len} sinc²(πWξ₂) dξ₂`, the length passed apart from the start so that a
/// short interval far from ξ₂ = 0 keeps the digits its ends share (the caller forms `len`
/// from its own, better-conditioned parameters). Far out on one side the asymptotes cancel
/// exactly and only the tails are subtracted (relative error `~ε` instead of `~ε·πW|q|`).
/// An interval shorter than 2 rad of the sinc's argument (a band that crosses a small light, or only
/// clips a corner of a large one) is integrated directly: the difference of two
/// antiderivatives of size `~W/2` would keep only `ε W/2` of absolute accuracy, 4–11 % off
/// on chords of 5e-5 – 3e-4 rad in the light sweep (`reference/light_sweep.py`).
/// [`SiMode::Velinov`] keeps Eq. 29 as printed.
#[inline]
pub fn band_integral_len(width: f32, q0: f32, len: f32, si: SiMode) -> f32 {
    let half = 0.5 * math::PI * width * len;
    if si != SiMode::Velinov && math::abs(half) <= 0.5 * DIRECT_SPAN {
        // W² ∫ sinc²(πWq) dq = (W/π) ∫ sinc²(x) dx, x = πWq, by 8-point Gauss–Legendre.
        let mid = math::PI * width * (q0 + 0.5 * len);
        let mut acc = 0.0;
        let mut k = 0;
        while k < 4 {
            let (a, b) = (
                math::sinc(mid - half * GL8_X[k]),
                math::sinc(mid + half * GL8_X[k]),
            );
            acc += GL8_W[k] * (a * a + b * b);
            k += 1;
        }
        return width * half * acc / math::PI;
    }
    let (a0, r0) = band_antiderivative_split(width, q0, si);
    let (a1, r1) = band_antiderivative_split(width, q0 + len, si);
    width * ((a1 - a0) + (r0 - r1)) / math::PI
}
