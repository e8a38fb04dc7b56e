//! Generalized Beckmann normal distribution (H&P Eqs. 38–39) and its slope sampling.
//!
//! `D(θ) = χ(θ) P22(tan²θ) / cos⁴θ`, `P22(x) = p / (π β² Γ(1/p)) · exp(−(x/β²)^p)`.
//! `P22` is the slope density, so `∫ D cosθ dω = ∫ P22 d²(slope) = 1` (projected-area
//! normalisation; checked by quadrature in `kernel/tests/ghs_golden.rs`). `p = 1` is
//! Beckmann with `α = β`.
//!
//! Sampling: with `y = (tan²θ/β²)^p`, the slope density makes `y ~ Gamma(1/p, 1)`, so
//! `tanθ = β · y^{1/(2p)}`, `y = Q⁻¹(1/p, u)` (H&P Eq. 59 prints the exponent as `c/2`; it is
//! `1/(2p)` — erratum, confirmed by the χ² test of this warp).

use crate::lane::{Real, V3, branch};
use crate::math;
use glam::Vec3;

/// The NDF's two shape parameters with the normalisation folded into one log constant.
#[derive(Clone, Copy, Debug)]
pub struct GenBeckmann {
    /// Width `β` (slope scale).
    pub beta: f32,
    /// Kurtosis exponent `p`.
    pub p: f32,
    /// `ln(p / (π β² Γ(1/p)))`.
    ln_norm: f32,
}

impl GenBeckmann {
    /// Builds the distribution; the caller passes already-clamped `β > 0`, `p > 0`.
    pub fn new(beta: f32, p: f32) -> GenBeckmann {
        let ln_norm = math::ln(p / (math::PI * beta * beta)) - math::lgamma(1.0 / p);
        GenBeckmann { beta, p, ln_norm }
    }

    /// Slope density `P22(tan²θ)` (Eq. 39).
    #[inline(always)]
    pub fn p22<R: Real>(&self, tan2: R) -> R {
        let x = tan2 / R::splat(self.beta * self.beta);
        let y = branch!(
            x.gt(R::splat(0.0)),
            (R::splat(self.p) * x.ln()).exp(),
            R::splat(0.0),
        );
        (R::splat(self.ln_norm) - y).exp()
    }

    /// `D(h)` (H&P Eq. 38) for a half vector `h` of any length (≥ 1e-18) with `h_z > 0`; 0
    /// otherwise.
    ///
    /// `tan²θh = |h_xy|²/h_z²` and `1/cos⁴θh = (1 + tan²θh)²` come from the components, never
    /// from `cosθh`: `(1 − cos²θh)/cos²θh` loses its digits exactly where a narrow lobe lives
    /// (`cosθh` rounds to 1 for `tanθh` < 2.4e-4). From `cosθh`, β = 0.005, p = 1.7 was off by
    /// up to 1.8 % against Eq. 38 at the same f32 `h` (2.3e-4 at β = 0.05); from the
    /// components, 1.3e-5 (`docs/ghs.md`, "Numerical stability"). Scale-invariant, so an
    /// unnormalised half vector may be passed.
    #[inline]
    pub fn d(&self, h: Vec3) -> f32 {
        self.d_lanes(h.into())
    }

    /// [`Self::d`] for any [`Real`] (the one formula).
    #[inline(always)]
    pub fn d_lanes<R: Real>(&self, h: V3<R>) -> R {
        let zero = R::splat(0.0);
        let tan2 = (h.x * h.x + h.y * h.y) / (h.z * h.z);
        let p22 = self.p22(tan2);
        let sec2 = R::splat(1.0) + tan2;
        let v = p22 * sec2 * sec2;
        R::select(h.z.gt(zero) & p22.gt(zero) & v.is_finite(), v, zero)
    }

    /// `tanθh` of a sampled microfacet normal for `u ∈ [0, 1)` (upper-tail inverse, so
    /// `u → 0` gives the steepest slopes).
    #[inline]
    pub fn sample_tan(&self, u: f32) -> f32 {
        let y = math::gamma_q_inv(1.0 / self.p, math::clamp(u, 0.0, 1.0));
        if !(y > 0.0) {
            return 0.0;
        }
        self.beta * math::exp(math::ln(y) * (0.5 / self.p))
    }

    /// Inverse of [`Self::sample_tan`]: the `u` that produces `tan`.
    #[inline]
    pub fn invert_tan(&self, tan: f32) -> f32 {
        let x = tan / self.beta;
        if !(x > 0.0) {
            return 1.0;
        }
        let y = math::exp(2.0 * self.p * math::ln(x));
        if !y.is_finite() {
            return 0.0;
        }
        math::gamma_q(1.0 / self.p, y)
    }
}
