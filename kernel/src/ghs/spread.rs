//! The diffraction lobe: K-correlation angle-spread function `S′` (H&P Eqs. 22, 43),
//! renormalised over the visible disk by `σ_rel²` (Eqs. 25–26).
//!
//! All lengths in the projected-direction plane are dimensionless: `r = λ |f| =
//! |i_p + o_p|`, and `B = b/λ`. The K-correlation PSD (Eq. 22) divided by `σ_s²` is a unit
//! density in `f`; mapped to the unit disk of projected directions (`d²o_p = cosθo dωo`,
//! `d²f = d²o_p / λ²`) it becomes
//!
//! `k(r) = (c − 1) B² / (2π) · (1 + B² r²)^{−(c+1)/2}` (1/sr, integrates to 1 over ℝ²),
//!
//! and `S′ = k / σ_rel²` with `σ_rel² = ∫_{|o_p| ≤ 1} k d²o_p ∈ (0, 1]`, so the lobe has unit
//! albedo before `(1 − A)`, `G` and its colour. Eq. 43 as printed also multiplies by `σ_s²`
//! (µm²), which is dimensionally a BRDF only if `σ_rel²` is the un-normalised PSD integral
//! (µm², ∝ σ_s²); with Eq. 26's normalisation (`σ0² = 1`) the factor cancels. Either reading
//! gives the `S′` above.
//!
//! `σ_rel²` is computed exactly in the kernel instead of the paper's 3-D look-up table: in
//! polar coordinates about the lobe centre `−i_p` (distance `s = sinθi` from the disk centre),
//! `σ_rel² = W(1 − s) + ∫_{1−s}^{1+s} (φmax(r)/π) dW(r)` with `W` the radial CDF and
//! `φmax` the half-angle of the arc inside the disk (Eq. 62). The remaining integral runs
//! over the CDF variable (which flattens the lobe's peak, however sharp `B` makes it) after
//! a `1 − cos t` substitution (which removes the square-root endpoints of `φmax`), by a
//! 20-point Gauss–Legendre rule. Error vs mpmath: see `reference/ghs/golden/` and
//! `kernel/tests/ghs_golden.rs`.

use super::tables::gauss_legendre::{GL_N, GL_WS, GL_XI};
use crate::lane::{Real, branch};
use crate::math;

/// K-correlation lobe in the projected-direction plane, `B = b/λ`, falloff `c > 1`. `B` is a
/// [`Real`] (one wavelength per lane in the SIMD backend); `f32` by default.
#[derive(Clone, Copy, Debug)]
pub struct KCorrelation<R = f32> {
    /// `b/λ`.
    pub b: R,
    /// Falloff exponent `c`.
    pub c: f32,
}

impl<R: Real> KCorrelation<R> {
    /// `L(r) = ln(1 + B² r²)`.
    #[inline(always)]
    fn log_arg(&self, r: R) -> R {
        let br = self.b * r;
        math::ln1p(br * br)
    }

    /// `k(r)`: the unit-normalised 2-D density (1/sr in the projected-disk measure).
    #[inline(always)]
    pub fn density(&self, r: R) -> R {
        R::splat(self.c - 1.0)
            * self.b
            * self.b
            * R::splat(0.5 / math::PI)
            * (R::splat(-0.5 * (self.c + 1.0)) * self.log_arg(r)).exp()
    }

    /// Radial CDF `W(r) = 1 − (1 + B²r²)^{−(c−1)/2}`.
    #[inline(always)]
    pub fn cdf(&self, r: R) -> R {
        -math::expm1(R::splat(-0.5 * (self.c - 1.0)) * self.log_arg(r))
    }

    /// The radius `r` with `ln(1 + B² r²) = l`.
    #[inline(always)]
    fn radius_from_log_arg(&self, l: R) -> R {
        math::sqrt0(math::expm1(l)) / self.b
    }

    /// Radius for the CDF value `w` (`W⁻¹`; Eq. 60 with `w = M u`).
    #[inline(always)]
    pub fn radius_from_cdf(&self, w: R) -> R {
        let l = R::splat(-2.0 / (self.c - 1.0)) * math::ln1p(-math::min(w, R::splat(1.0)));
        self.radius_from_log_arg(l)
    }

    /// `σ_rel²(sinθi)`: the fraction of the lobe centred at distance `s` from the disk
    /// centre that falls inside the unit disk.
    #[inline(always)]
    pub fn sigma_rel_sq(&self, s: R) -> R {
        let c = R::splat;
        let s = math::clamp(s, c(0.0), c(1.0));
        let h = 0.5 * (self.c - 1.0);
        let l0 = self.log_arg(c(1.0) - s);
        let l1 = self.log_arg(c(1.0) + s);
        let w0 = -math::expm1(-c(h) * l0);
        branch!(s.lt(c(1.0e-6)), w0, {
            let v0 = (-c(h) * l0).exp();
            let frac = -math::expm1(-c(h) * (l1 - l0)); // Δ / v0
            let delta = v0 * frac;
            branch!(!delta.gt(c(0.0)), w0, {
                let mut sum = c(0.0);
                let mut k = 0;
                while k < GL_N {
                    let l = l0 - math::ln1p(-frac * c(GL_XI[k])) / c(h);
                    let r = self.radius_from_log_arg(l);
                    sum = sum + c(GL_WS[k]) * phi_max(r, s);
                    k += 1;
                }
                sum = sum * c(1.0 / math::PI);
                math::clamp(w0 + delta * sum, c(0.0), c(1.0))
            })
        })
    }
}

/// Half-angle of the arc of the circle of radius `r` about the lobe centre (at distance `s`
/// from the disk centre) that lies inside the unit disk (Eq. 62): π for `r ≤ 1 − s`, 0 for
/// `r ≥ 1 + s`. Any [`Real`].
#[inline(always)]
pub fn phi_max<R: Real>(r: R, s: R) -> R {
    let c = R::splat;
    let rs = r * s;
    branch!(
        !rs.gt(c(1.0e-12)),
        R::select(r.lt(c(1.0)), c(math::PI), c(0.0)),
        {
            let arg = (r * r + s * s - c(1.0)) / (c(2.0) * rs);
            branch!(
                arg.gt(c(-1.0)) & arg.lt(c(1.0)),
                math::acos(arg),
                R::select(arg.le(c(-1.0)), c(math::PI), c(0.0)),
            )
        },
    )
}
