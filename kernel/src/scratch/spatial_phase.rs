//! The Gaussian-weighted spatial phase η of one segment (Werner 2017 Eq. 12, App. A;
//! Velinov 2018 Eqs. 5, 8).
//!
//! `η = ∫_{−L/2}^{L/2} ds G(c + s t) exp(−2πi ξ·(c + s t − x0))`. With the centre offset
//! `(s_t, s_b)` from `x0` and `u = s + s_t`:
//! `η = exp(−s_b²/(2σ²) − 2πi s_b ξ₂) ∫_{s_t−L/2}^{s_t+L/2} exp(−u²/(2σ²) − 2πi ξ₁ u) du`,
//! whose last factor is [`crate::math::gauss_fourier_centered`] (overflow-free form of
//! App. A's `c0 [erf(·) − erf(·)]`).

use super::record::SegmentFrame;
use crate::lane::{Cx, Real};
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
    xi_local_lanes(frame, [xi.x, xi.y])
}

/// [`xi_local`] for any [`Real`] (one segment, one `ξ` per lane).
#[inline(always)]
pub fn xi_local_lanes<R: Real>(frame: &SegmentFrame, xi: [R; 2]) -> (R, R) {
    (dot(xi, frame.tangent), dot(xi, frame.bitangent))
}

/// `v·d` for a vector of lanes and a fixed direction (glam's order of operations).
#[inline(always)]
pub(super) fn dot<R: Real>(v: [R; 2], d: Vec2) -> R {
    v[0] * R::splat(d.x) + v[1] * R::splat(d.y)
}

/// The across-scratch factor `exp(−s_b²/(2σ²) − 2πi s_b ξ₂)`: the coherence window and
/// phase at the centre line (Werner's frozen window, [`super::window`]).
#[inline(always)]
fn frozen_across_lanes<R: Real>(s_b: R, xi2: R, sigma: R) -> Cx<R> {
    let g = (R::splat(-0.5) * s_b * s_b / (sigma * sigma)).exp();
    math::cis_pi_lanes(R::splat(-2.0) * s_b * xi2).scale(g)
}

/// Finite-segment η (Werner App. A, Eqs. 23–24, overflow-free).
pub fn eta_finite(frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    eta_lanes(EtaMode::Finite, frame, [x0.x, x0.y], [xi.x, xi.y], sigma).into()
}

/// Infinite-scratch η (Velinov Eq. 8): `√(2π) σ exp(−s_b²/(2σ²) − 2π²σ²ξ₁² − 2πi s_b ξ₂)`.
pub fn eta_infinite(frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    eta_lanes(EtaMode::Infinite, frame, [x0.x, x0.y], [xi.x, xi.y], sigma).into()
}

/// √(2π).
const SQRT_TAU: f32 = 2.506_628_274_631_000_5;

/// η for the chosen mode.
#[inline]
pub fn eta(mode: EtaMode, frame: &SegmentFrame, x0: Vec2, xi: Vec2, sigma: f32) -> C32 {
    eta_lanes(mode, frame, [x0.x, x0.y], [xi.x, xi.y], sigma).into()
}

/// [`eta`] for any [`Real`]: one segment and σ, one `x0` and `ξ` per lane (the one
/// formula for both modes).
#[inline(always)]
pub fn eta_lanes<R: Real>(
    mode: EtaMode,
    frame: &SegmentFrame,
    x0: [R; 2],
    xi: [R; 2],
    sigma: f32,
) -> Cx<R> {
    let (s_t, s_b) = frame.offset_from_lanes(x0);
    let (xi1, xi2) = xi_local_lanes(frame, xi);
    let sigma = R::splat(sigma);
    match mode {
        EtaMode::Finite => {
            let along =
                math::gauss_fourier_centered_lanes(s_t, R::splat(frame.half_len), sigma, xi1);
            frozen_across_lanes(s_b, xi2, sigma) * along
        }
        EtaMode::Infinite => {
            frozen_across_lanes(s_b, xi2, sigma).scale(infinite_along_lanes(sigma, xi1))
        }
    }
}

/// The infinite scratch's along factor `√(2π) σ exp(−2π²σ²ξ₁²)` (Velinov Eq. 8).
#[inline(always)]
pub fn infinite_along_lanes<R: Real>(sigma: R, xi1: R) -> R {
    R::splat(SQRT_TAU)
        * sigma
        * (R::splat(-2.0 * math::PI * math::PI) * sigma * sigma * xi1 * xi1).exp()
}
