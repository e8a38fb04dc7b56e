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

use crate::lane::{Cx, Real, branch};
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
    mask_transform_pi(width, width * xi2)
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
    profile_transform_pi(profile, width, width * xi2, depth * half_turns_per_um).into()
}

/// `M` from `β/π = Wξ₂`.
#[inline(always)]
fn mask_transform_pi<R: Real>(width: R, beta: R) -> R {
    width * math::sinc_pi_lanes(beta)
}

/// [`profile_transform`] from `β/π = Wξ₂` and `κ/π`.
#[inline(always)]
fn profile_transform_pi<R: Real>(profile: Profile, width: R, beta: R, kappa: R) -> Cx<R> {
    let c = R::splat;
    match profile {
        Profile::Rect => math::cis_pi_lanes(kappa).scale(width * math::sinc_pi_lanes(beta)),
        Profile::Triangle => {
            let a = math::cis_pi_lanes(c(0.5) * beta)
                .scale(math::sinc_pi_lanes(c(0.5) * (beta - kappa)));
            let b = math::cis_pi_lanes(c(-0.5) * beta)
                .scale(math::sinc_pi_lanes(c(0.5) * (beta + kappa)));
            (math::cis_pi_lanes(c(0.5) * kappa) * (a + b)).scale(c(0.5) * width)
        }
    }
}

/// `M − P`: what one scratch subtracts from the base reflection per unit spatial phase
/// (the bracket of Werner Eq. 17). Both profiles use cancellation-free forms, so shallow
/// grooves keep full relative accuracy: the rectangle `(1 − e^{iκ}) M`, the triangle
/// [`triangle_mask_minus_profile`].
pub fn mask_minus_profile(
    profile: Profile,
    width: f32,
    depth: f32,
    half_turns_per_um: f32,
    xi2: f32,
) -> C32 {
    mask_minus_profile_lanes(profile, width, depth, half_turns_per_um, xi2).into()
}

/// [`mask_minus_profile`] for any [`Real`] (the one formula).
#[inline(always)]
pub fn mask_minus_profile_lanes<R: Real>(
    profile: Profile,
    width: R,
    depth: R,
    half_turns_per_um: R,
    xi2: R,
) -> Cx<R> {
    let kappa = depth * half_turns_per_um;
    match profile {
        Profile::Rect => {
            math::one_minus_cis_pi_lanes(kappa).scale(mask_transform_pi(width, width * xi2))
        }
        Profile::Triangle => triangle_lanes(width, width * xi2, kappa),
    }
}

/// Where `||β| − |κ||/π` is below this (and `max(|β|, |κ|)/π` above [`TRI_SERIES_BELOW`]) the
/// triangle's `M − P` is formed as the plain difference, which does not cancel there.
const TRI_NEAR_POLE: f32 = 0.25;
/// Below this `max(|β|, |κ|)/π` the divided difference of the triangle's real part is summed
/// as its Taylor series.
const TRI_SERIES_BELOW: f32 = 0.5;

/// Triangle `M − P` (Werner Eqs. 26, 29–31 corrected; see the module docs) without the
/// cancellation of the plain difference. The arguments are in half-turns, `beta` = `β/π =
/// Wξ₂` and `kappa` = `κ/π = 2γD/λ`; the formulas below are in radians.
///
/// With `u = 2|b|/W`, `M − P = W ∫₀¹ (1 − e^{iκ(1−u)}) cos(βu) du`, which integrates to
///
/// `M − P = W [κ² Δ − i (κ/2) sinc((β+κ)/2) sinc((β−κ)/2)]`,
/// `Δ = (sinc κ − sinc β)/(β² − κ²)` (`sinc x = sin x / x`).
///
/// The plain difference `M − P` of two values of size `W/β` is `O(κ W/β²)` for a shallow
/// groove, so it loses `β/κ` of its relative accuracy (up to 10⁵ over the documented range:
/// a 25 µm wide, 3 nm deep groove seen at `Wξ₂ = 62` was 1.3 % off; issue #20). Here the
/// imaginary part is a product, and `Δ`, the divided difference of the even entire function
/// `sinc √x` at `x = β², κ²`, is its Taylor series for small arguments
/// (`Δ = Σ_{n≥1} (−1)^{n+1} h_{n−1}(β², κ²)/(2n+1)!`, `h` the complete homogeneous
/// polynomial) and the quotient of differences elsewhere; only near the removable poles
/// `β = ±κ` with `|κ| ≥ π/4`, where `|M − P| ≈ |P| ≈ W/2` does not cancel, is the plain
/// difference used.
pub fn triangle_mask_minus_profile(width: f32, beta: f32, kappa: f32) -> C32 {
    triangle_lanes(width, beta, kappa).into()
}

/// [`triangle_mask_minus_profile`] for any [`Real`].
#[inline(always)]
fn triangle_lanes<R: Real>(width: R, beta: R, kappa: R) -> Cx<R> {
    let c = R::splat;
    let (ab, ak) = (beta.abs(), kappa.abs());
    let big = math::max(ab, ak);
    branch!(
        big.gt(c(TRI_SERIES_BELOW)) & (ab - ak).abs().lt(c(TRI_NEAR_POLE)),
        Cx::real(mask_transform_pi(width, beta))
            - profile_transform_pi(Profile::Triangle, width, beta, kappa),
        {
            let im = c(0.5)
                * c(math::PI)
                * kappa
                * math::sinc_pi_lanes(c(0.5) * (beta + kappa))
                * math::sinc_pi_lanes(c(0.5) * (beta - kappa));
            let re = branch!(
                big.le(c(TRI_SERIES_BELOW)),
                {
                    let (x, y) = (
                        (c(math::PI) * beta) * (c(math::PI) * beta),
                        (c(math::PI) * kappa) * (c(math::PI) * kappa),
                    );
                    // Σ_{n=1}^{8} c_n h_{n−1}(x, y), h_k = x h_{k−1} + y^k; x, y ≤ π²/4: the
                    // first omitted term is below 1e-12 of the sum (which is ≥ 1/6 − π²/240).
                    let mut h = c(1.0);
                    let mut yk = c(1.0);
                    let mut sum = c(0.0);
                    let mut n = 0;
                    while n < TRI_SERIES.len() {
                        if n > 0 {
                            yk = yk * y;
                            h = x * h + yk;
                        }
                        sum = sum + c(TRI_SERIES[n]) * h;
                        n += 1;
                    }
                    y * sum
                },
                kappa * kappa * (math::sinc_pi_lanes(kappa) - math::sinc_pi_lanes(beta))
                    / ((beta - kappa) * (beta + kappa))
            );
            Cx::new(re, -im).scale(width)
        }
    )
}

/// `(−1)^{n+1}/(2n+1)!`, `n = 1 … 8`.
const TRI_SERIES: [f32; 8] = [
    1.0 / 6.0,
    -1.0 / 120.0,
    1.0 / 5040.0,
    -1.0 / 362_880.0,
    1.0 / 39_916_800.0,
    -1.0 / 6_227_020_800.0,
    1.0 / 1_307_674_368_000.0,
    -1.0 / 355_687_428_096_000.0,
];

#[cfg(test)]
mod tests {
    use super::*;

    /// `(M − P)/W = ∫₀¹ (1 − e^{iκ(1−u)}) cos(βu) du` (radians) by composite Gauss–Legendre
    /// in f64, from the defining integral (not from any closed form).
    fn triangle_quadrature(beta_pi: f64, kappa_pi: f64) -> (f64, f64) {
        use core::f64::consts::PI;
        let (c, a) = (PI * beta_pi, PI * kappa_pi);
        // 5-point Gauss–Legendre on [-1, 1]
        const X: [f64; 5] = [
            0.0,
            -0.538_469_310_105_683,
            0.538_469_310_105_683,
            -0.906_179_845_938_664,
            0.906_179_845_938_664,
        ];
        const W: [f64; 5] = [
            0.568_888_888_888_889,
            0.478_628_670_499_366,
            0.478_628_670_499_366,
            0.236_926_885_056_189,
            0.236_926_885_056_189,
        ];
        let panels = 4000;
        let (mut re, mut im) = (0.0, 0.0);
        for p in 0..panels {
            let (lo, hi) = (p as f64 / panels as f64, (p + 1) as f64 / panels as f64);
            for (x, w) in X.iter().zip(W) {
                let u = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
                let g = w * 0.5 * (hi - lo) * libm::cos(c * u);
                let ph = a * (1.0 - u);
                re += g * (1.0 - libm::cos(ph));
                im -= g * libm::sin(ph);
            }
        }
        (re, im)
    }

    #[test]
    fn triangle_mask_minus_profile_keeps_relative_accuracy_for_shallow_grooves() {
        // (β/π, κ/π): shallow grooves far out in ξ₂ (where M − P ≪ M cancels), the series
        // region, the divided-difference region, near the poles β = ±κ and deep grooves.
        let cases = [
            (-62.2_f32, 0.0335_f32),
            (100.5, 0.001),
            (7.3, 0.002),
            (0.3, 0.1),
            (0.02, 0.01),
            (0.49, 0.5),
            (0.7, 0.0001),
            (2.3, 2.4),
            (-3.1, 3.0),
            (7.1, 2.3),
            (0.2, 41.7),
        ];
        for (beta, kappa) in cases {
            let got = triangle_mask_minus_profile(1.0, beta, kappa);
            let (re, im) = triangle_quadrature(f64::from(beta), f64::from(kappa));
            let err = ((f64::from(got.re) - re).powi(2) + (f64::from(got.im) - im).powi(2)).sqrt()
                / (re * re + im * im).sqrt();
            assert!(
                err < 2.0e-6,
                "β/π {beta}, κ/π {kappa}: {got:?} vs ({re}, {im}): {err:e}"
            );
        }
    }

    #[test]
    fn triangle_forms_agree_where_the_difference_does_not_cancel() {
        // Deep grooves near the first diffraction orders: |M − P| ~ |P|, so the plain
        // difference is accurate there and must agree with the cancellation-free form.
        for beta in [-4.0_f32, -1.3, 0.4, 0.9, 2.6, 5.5] {
            for kappa in [0.8_f32, 1.7, 3.3] {
                let plain = C32::new(mask_transform_pi(1.0, beta), 0.0)
                    - C32::from(profile_transform_pi(Profile::Triangle, 1.0, beta, kappa));
                let ours = triangle_mask_minus_profile(1.0, beta, kappa);
                let d = (ours - plain).norm() / plain.norm();
                assert!(d < 2.0e-6, "β/π {beta}, κ/π {kappa}: {d:e}");
            }
        }
    }
}
