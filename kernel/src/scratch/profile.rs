//! Fourier transforms of the mask and of the groove's transfer function across the scratch
//! (Werner 2017 Eqs. 14, 26–31, App. B).
//!
//! Transfer function `T(b) = exp(−2πi γ h(b)/λ)` with height `h ≤ 0` inside a groove and
//! `γ = γi + γo` (see ARCHITECTURE.md for the sign). With `β = πWξ₂` and the depth phase
//! `κ = 2πγD/λ`:
//! * mask: `M = W sinc(β)` (Eq. 14; Eq. 19's extra `/λ` is an erratum when ξ is in 1/µm);
//! * rectangle (`h = −D`): `P = e^{iκ} W sinc(β)`, so `M − P = (1 − e^{iκ}) W sinc(β)`;
//! * triangle (`h = −D(1 − 2|b|/W)`):
//!   `P = (W/2) e^{iκ/2} [e^{iβ/2} sinc((β−κ)/2) + e^{−iβ/2} sinc((β+κ)/2)]`.
//!   This is Eqs. 29–31 with their typos fixed (B's exponent lacks a `W`, B's denominator
//!   has `W²` where `Wλ` belongs) and the removable poles at `β = ±κ` folded into `sinc`,
//!   so it is finite everywhere. It reduces to the mask when `D = 0`.
//!
//! The phases are carried in half-turns, `β/π = Wξ₂` and `κ/π = 2γD/λ`, and evaluated by
//! [`math::sin_cos_pi`] and friends, whose argument reduction is exact: a groove whose depth
//! phase is near a whole number of waves (`|1 − e^{iκ}|` small) keeps its relative accuracy.

use crate::math::{self, C32};

gpu_enum! {
    /// Groove cross-section.
    pub enum Profile {
        /// Flat-bottomed groove of constant depth.
        Rect = 0,
        /// V-shaped groove, deepest on the centre line.
        Triangle = 1,
    }
    fallback = Rect;
}

gpu_enum! {
    /// How the depth phase depends on the directions.
    pub enum DepthTerm {
        /// `γ = γi + γo` replaced by 2 (normal incidence; Velinov 2018 Eq. 4, Eq. 11).
        SmallAngle = 0,
        /// The exact `γ = γi + γo` (Werner Eq. 20 with the corrected sign).
        Exact = 1,
    }
    fallback = SmallAngle;
}

impl DepthTerm {
    /// The `γ` to use in the depth phase given the true `γi + γo`.
    #[inline]
    pub fn gamma(self, gamma: f32) -> f32 {
        match self {
            DepthTerm::SmallAngle => 2.0,
            DepthTerm::Exact => gamma,
        }
    }
}

/// Mask transform `M(ξ₂) = W sinc(πWξ₂)` (Werner Eq. 14/26).
#[inline]
pub fn mask_transform(width: f32, xi2: f32) -> f32 {
    width * math::sinc_pi(width * xi2)
}

/// Groove transform `P(ξ₂)` for the given profile (Werner Eqs. 27–31, corrected).
/// `half_turns_per_um` is `2γ/λ` (1/µm, γ the effective `γi + γo`), so that the depth
/// phase is `κ = π · depth · half_turns_per_um` (Werner Eq. 20).
pub fn profile_transform(
    profile: Profile,
    width: f32,
    depth: f32,
    half_turns_per_um: f32,
    xi2: f32,
) -> C32 {
    // β/π and κ/π.
    let beta = width * xi2;
    let kappa = depth * half_turns_per_um;
    match profile {
        Profile::Rect => math::cscale(math::cis_pi(kappa), width * math::sinc_pi(beta)),
        Profile::Triangle => {
            let a = math::cscale(
                math::cis_pi(0.5 * beta),
                math::sinc_pi(0.5 * (beta - kappa)),
            );
            let b = math::cscale(
                math::cis_pi(-0.5 * beta),
                math::sinc_pi(0.5 * (beta + kappa)),
            );
            math::cscale(math::cis_pi(0.5 * kappa) * (a + b), 0.5 * width)
        }
    }
}

/// `M − P`: what one scratch subtracts from the base reflection per unit spatial phase
/// (the bracket of Werner Eq. 17). The rectangle uses the cancellation-free
/// `1 − e^{iκ}` form so shallow grooves keep full relative accuracy.
pub fn mask_minus_profile(
    profile: Profile,
    width: f32,
    depth: f32,
    half_turns_per_um: f32,
    xi2: f32,
) -> C32 {
    match profile {
        Profile::Rect => {
            let kappa = depth * half_turns_per_um;
            math::cscale(math::one_minus_cis_pi(kappa), mask_transform(width, xi2))
        }
        Profile::Triangle => {
            C32::new(mask_transform(width, xi2), 0.0)
                - profile_transform(profile, width, depth, half_turns_per_um, xi2)
        }
    }
}
