//! The coherence window across a groove: frozen at the groove's centre line (Werner 2017
//! Eqs. 9–13, 17) or integrated exactly (issue #21).
//!
//! One segment's term is `S_k = ∫∫ G(p − x0) (1 − T(v)) e^{−2πi ξ·(p − x0)} du dv` over the
//! groove (`u` along, `v` across, `|v| ≤ W/2`). The isotropic Gaussian window factors in
//! the groove's frame, so `S_k = A · η_along` with the along-segment integral of
//! [`super::spatial_phase`] and, with the centre line `s_b` from `x0` across,
//!
//! `A = ∫_{−W/2}^{W/2} e^{−(v + s_b)²/(2σ²)} (1 − T(v)) e^{−2πiξ₂(v + s_b)} dv`.
//!
//! * **Frozen** (Werner): the window is taken at `v = 0` across the whole width,
//!   `A = e^{−s_b²/(2σ²) − 2πi s_b ξ₂} (M − P)` ([`super::profile`]). It errs by the
//!   window's variation over the width: a relative `O(W s_b/σ²)` and `O(W²/σ²)`
//!   (`docs/exact_window.md`).
//! * **Exact**: the rectangle's `1 − T = 1 − e^{iκ}` is constant, so
//!   `A = (1 − e^{iκ}) I(s_b, W/2, ξ₂)`, `I` the Gaussian-windowed Fourier integral over an
//!   interval ([`crate::math::gauss_fourier_centered`]). The V groove's phase
//!   `κ(1 − 2|v|/W)` is linear on each half, which shifts the half's frequency by
//!   `±κ/(πW)`: `A = I(s_b, W/2, ξ₂) − e^{iκ/2} e^{−2πi s_b ξ₂} [e^{−iπWξ₂/2} Ĩ(s_b + W/4,
//!   W/4, ξ₂ + κ/(πW)) + e^{iπWξ₂/2} Ĩ(s_b − W/4, W/4, ξ₂ − κ/(πW))]`, with `Ĩ` the
//!   integral without its centre's phase ([`crate::math::gauss_fourier_reduced_lanes`]):
//!   the halves' own phases `κ(1 ± 2s_b/W)` and `2πνm` are large for a narrow groove far
//!   from `x0` (`s_b/W` up to ~10³) but cancel analytically to `κ/2` and the centre
//!   line's `2π s_b ξ₂`, which is how they are formed.
//!
//! Both tend to each other as `W/σ → 0`. The scratch area density ρc takes the exact
//! window the same way: `∫ e^{−(v + s_b)²/(2σ²)} dv` across the width instead of
//! `W e^{−s_b²/(2σ²)}`.

use super::profile::Profile;
use crate::lane::{Cx, Real};
use crate::math;

gpu_enum! {
    /// How the coherence window is taken across a groove.
    pub enum Window {
        /// At the groove's centre line, across the whole width (Werner Eqs. 9–13):
        /// [`super::profile`]'s `M − P` times [`super::spatial_phase`]'s across factor.
        Frozen = 0,
        /// Integrated exactly across the width ([`exact_across_intervals`]; issue #21).
        Exact = 1,
    }
    fallback = Frozen;
}

/// The exact across-groove factor as `A = e^{−2πi s_b ξ₂} Σ_j w_j Ĩ_j` (module docs): the
/// intervals `Ĩ_j` (centre, half length, frequency in 1/µm) and their weights, `count` of
/// them (the rectangle 1, the V groove 3: its whole width and its two halves). The caller
/// evaluates them in one loop with its other interval integrals (one copy of the Faddeeva
/// path).
#[derive(Clone, Copy, Debug)]
pub struct AcrossIntervals<R> {
    /// Centres, relative to `x0` across the groove (µm).
    pub mid: [R; 3],
    /// Half lengths (µm).
    pub half: [R; 3],
    /// Frequencies (1/µm).
    pub nu: [R; 3],
    /// Weights.
    pub weight: [Cx<R>; 3],
    /// How many are used.
    pub count: usize,
}

/// [`AcrossIntervals`] of one segment: `s_b` its centre line's offset from `x0` across,
/// `xi2 = ξ·b`, the depth phase `κ/π = D · 2γ/λ` in half-turns. Any [`Real`]: one segment,
/// one query per lane.
#[inline(always)]
pub fn exact_across_intervals<R: Real>(
    profile: Profile,
    width: R,
    depth: R,
    half_turns_per_um: R,
    s_b: R,
    xi2: R,
) -> AcrossIntervals<R> {
    let c = R::splat;
    let kappa = depth * half_turns_per_um;
    let half = c(0.5) * width;
    let mut iv = AcrossIntervals {
        mid: [s_b; 3],
        half: [half; 3],
        nu: [xi2; 3],
        weight: [Cx::splat(1.0, 0.0); 3],
        count: 1,
    };
    match profile {
        Profile::Rect => iv.weight[0] = math::one_minus_cis_pi_lanes(kappa),
        Profile::Triangle => {
            // The halves' frequency shift ±κ/(πW) and, from their centres ±W/4 off the
            // centre line, the phases e^{∓iπWξ₂/2}, with the depth phase e^{iκ/2}.
            let quarter = c(0.5) * half;
            let shift = kappa / width;
            let deep = math::cis_pi_lanes(c(0.5) * kappa);
            let off = math::cis_pi_lanes(c(0.5) * width * xi2);
            iv.mid = [s_b, s_b + quarter, s_b - quarter];
            iv.half = [half, quarter, quarter];
            iv.nu = [xi2, xi2 + shift, xi2 - shift];
            iv.weight[1] = -(deep * off.conj());
            iv.weight[2] = -(deep * off);
            iv.count = 3;
        }
    }
    iv
}
