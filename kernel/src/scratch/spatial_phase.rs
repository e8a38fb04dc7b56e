//! The Gaussian-weighted spatial phase η of one segment (Werner 2017 Eq. 12, App. A;
//! Velinov 2018 Eqs. 5, 8).
//!
//! `η = ∫_{−L/2}^{L/2} ds G(c + s t) exp(−2πi ξ·(c + s t − x0))`. With the centre offset
//! `(s_t, s_b)` from `x0` and `u = s + s_t`:
//! `η = exp(−s_b²/(2σ²) − 2πi s_b ξ₂) ∫_{s_t−L/2}^{s_t+L/2} exp(−u²/(2σ²) − 2πi ξ₁ u) du`,
//! whose last factor is [`crate::math::gauss_fourier_centered`] (overflow-free form of
//! App. A's `c0 [erf(·) − erf(·)]`).

use super::record::SegmentFrame;
use crate::math::{self, C32};
use glam::Vec2;

gpu_enum! {
    /// Which spatial phase to use.
    pub enum EtaMode {
        /// Finite segment (Werner App. A; Velinov Eq. 5).
        Finite = 0,
        /// Infinitely long scratch through the segment (Velinov Eq. 8).
        Infinite = 1,
    }
    fallback = Finite;
}

/// `(ξ₁, ξ₂) = (ξ·t, ξ·b)`: ξ in the segment's frame (Werner Eq. 13).
#[inline]
pub fn xi_local(frame: &SegmentFrame, xi: Vec2) -> (f32, f32) {
    (xi.dot(frame.tangent), xi.dot(frame.bitangent))
}

/// The across-scratch factor `exp(−s_b²/(2σ²) − 2πi s_b ξ₂)`.
#[inline]
fn across(s_b: f32, xi2: f32, sigma: f32) -> C32 {
    let g = math::exp(-0.5 * s_b * s_b / (sigma * sigma));
    math::cscale(math::cis_pi(-2.0 * s_b * xi2), g)
}

/// Finite-segment η (Werner App. A, Eqs. 23–24, overflow-free).
pub fn eta_finite(frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    let (s_t, s_b) = frame.offset_from(x0);
    let (xi1, xi2) = xi_local(frame, xi);
    let along = math::gauss_fourier_centered(s_t, frame.half_len, sigma, xi1);
    across(s_b, xi2, sigma) * along
}

/// Infinite-scratch η (Velinov Eq. 8): `√(2π) σ exp(−s_b²/(2σ²) − 2π²σ²ξ₁² − 2πi s_b ξ₂)`.
pub fn eta_infinite(frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    let (_, s_b) = frame.offset_from(x0);
    let (xi1, xi2) = xi_local(frame, xi);
    let along =
        SQRT_TAU * sigma * math::exp(-2.0 * math::PI * math::PI * sigma * sigma * xi1 * xi1);
    math::cscale(across(s_b, xi2, sigma), along)
}

/// √(2π).
const SQRT_TAU: f32 = 2.506_628_274_631_000_5;

/// η for the chosen mode.
#[inline]
pub fn eta(mode: EtaMode, frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    match mode {
        EtaMode::Finite => eta_finite(frame, x0, xi, sigma),
        EtaMode::Infinite => eta_infinite(frame, x0, xi, sigma),
    }
}
