//! The two multi-layer variants (H&P §4.4): a diffuse base under a varnish (`plastic`,
//! Eq. 49, after Weidlich & Wilkie 2007) and a participating medium below the interface
//! (`subsurface`, Eqs. 45–48, Jensen et al. 2001's BRDF approximation). The interface
//! transmits with `T = (1 − F(θi))(1 − F(θo))` (Eq. 44), treated as flat.
//!
//! Each variant has two forms, selected by [`LayerForm`]:
//! * `Published`: the equations as printed.
//! * `EnergyConserving`: corrections found by the white-furnace test
//!   (`backend-cpu/tests/ghs_furnace.rs`, chart `docs/ghs-albedo.svg`):
//!   - plastic: radiance entering a denser medium is compressed by `1/η²` and the
//!     inter-reflection series is `Σ (ρd F_dr(1/η))ⁿ`, giving
//!     `T ρd / (π η² (1 − ρd F_dr(1/η)))`. The printed `T ρd/π (1 − ρd/π F_dr(1/η))⁻¹` has
//!     a spurious `1/π` inside the series and no `1/η²`; for a white base it reflects
//!     more than it receives (albedo > 1 at normal incidence, see the report).
//!   - subsurface: Jensen's boundary term is `A = (1 + F_dr)/(1 − F_dr)`
//!     (internal `F_dr`); Eq. 46 prints its reciprocal.
//!
//! `F_dr(η)` is the hemispherical (cosine-weighted) Fresnel reflectance for light arriving
//! from outside onto relative index `η` (so `F_dr(1/η)` is the internal one), from the
//! degree-5 polynomial fits of the first Fresnel moment by d'Eon & Irving 2011 (their
//! "rational approximation", H&P §4.4): `F_dr(η) = 2 C1(1/η)`. Fit error vs quadrature is
//! reported by `reference/ghs/generate.py` (`golden/fresnel_dr.json`).

use crate::fresnel::fresnel;
use crate::lane::Real;
use crate::math;

gpu_enum! {
    /// Which form of the layer equations to evaluate.
    pub enum LayerForm {
        /// As printed in the paper.
        Published = 0,
        /// With the corrections listed in the module documentation.
        EnergyConserving = 1,
    }
    fallback = Published;
}

/// First Fresnel moment `C1(η) = ∫₀¹ F(μ; η) μ dμ` (d'Eon & Irving 2011 fit; `η` is the
/// ratio incident-side / transmitted-side index).
#[inline(always)]
fn fresnel_moment1<R: Real>(e: R) -> R {
    let c = R::splat;
    let e2 = e * e;
    let e3 = e2 * e;
    let e4 = e3 * e;
    let e5 = e4 * e;
    let below = c(0.45966) - c(1.73965) * e + c(3.37668) * e2 - c(3.904945) * e3 + c(2.49277) * e4
        - c(0.68441) * e5;
    let above = c(-4.61686) + c(11.1136) * e - c(10.4646) * e2 + c(5.11455) * e3 - c(1.27198) * e4
        + c(0.12746) * e5;
    R::select(e.lt(c(1.0)), below, above)
}

/// `F_dr(η)`: diffuse (cosine-weighted hemispherical) reflectance of a flat interface for
/// light arriving from outside onto relative index `η` (H&P notation; `F_dr(1/η)` is the
/// reflectance seen from inside). Valid for `η ∈ [1/3, 3]` (clamped).
#[inline(always)]
pub fn fresnel_diffuse_reflectance<R: Real>(eta: R) -> R {
    let c = R::splat;
    let e = math::clamp(eta, c(1.0 / 3.0), c(3.0));
    math::clamp(c(2.0) * fresnel_moment1(c(1.0) / e), c(0.0), c(1.0))
}

/// Interface transmittance `T` (Eq. 44).
#[inline(always)]
pub fn transmittance<R: Real>(cos_i: R, cos_o: R, n: R, k: R) -> R {
    let one = R::splat(1.0);
    (one - fresnel(cos_i, n, k)) * (one - fresnel(cos_o, n, k))
}

/// Inter-reflection factor of the plastic layer (the bracket of Eq. 49 / its correction).
#[inline(always)]
fn plastic_series<R: Real>(rho_d: f32, n: R, form: LayerForm) -> R {
    let c = R::splat;
    let f_int = fresnel_diffuse_reflectance(c(1.0) / n);
    match form {
        LayerForm::Published => c(1.0) / (c(1.0) - c(rho_d) * c(1.0 / math::PI) * f_int),
        // a white base under total internal reflection (F_int → 1) traps light: bound the
        // geometric series at 10⁴ bounces' worth
        LayerForm::EnergyConserving => {
            c(1.0) / (n * n * math::max(c(1.0) - c(rho_d) * f_int, c(1.0e-4)))
        }
    }
}

/// `ρ_plastic` (Eq. 49) for diffuse reflectance `rho_d` under an interface of index `n + ik`.
#[inline(always)]
pub fn plastic<R: Real>(cos_i: R, cos_o: R, n: R, k: R, rho_d: f32, form: LayerForm) -> R {
    transmittance(cos_i, cos_o, n, k)
        * R::splat(rho_d)
        * R::splat(1.0 / math::PI)
        * plastic_series(rho_d, n, form)
}

/// `E_D` of the plastic layer (Eq. 52) for lobe selection.
pub fn plastic_energy(n: f32, k: f32, rho_d: f32, form: LayerForm) -> f32 {
    let t0 = 1.0 - super::energy::normal_reflectance(n, k);
    t0 * t0 * rho_d * plastic_series(rho_d, n, form)
}

/// Jensen's diffuse reflectance `R_d` of the medium (Eq. 47 / 54 without `T/π`), `α` the
/// single-scattering albedo.
#[inline(always)]
fn subsurface_rd<R: Real>(n: R, albedo: f32, form: LayerForm) -> R {
    let c = R::splat;
    let f_dr = fresnel_diffuse_reflectance(c(1.0) / n);
    let a_f = match form {
        LayerForm::Published => (c(1.0) - f_dr) / (c(1.0) + f_dr),
        LayerForm::EnergyConserving => (c(1.0) + f_dr) / math::max(c(1.0) - f_dr, c(1.0e-6)),
    };
    let sigma_tr = math::sqrt0(3.0 * (1.0 - albedo));
    c(albedo * 0.5 * math::exp(-sigma_tr)) * (c(1.0) + (c(-(4.0 / 3.0)) * a_f * c(sigma_tr)).exp())
}

/// `ρ_SSS = single + multi` (Eqs. 45–48); the refracted cosines use the real part `n`.
#[inline(always)]
pub fn subsurface<R: Real>(cos_i: R, cos_o: R, n: R, k: R, albedo: f32, form: LayerForm) -> R {
    let c = R::splat;
    let t = transmittance(cos_i, cos_o, n, k);
    let inv_n2 = c(1.0) / (n * n);
    let cti = math::sqrt0(c(1.0) - (c(1.0) - cos_i * cos_i) * inv_n2);
    let cto = math::sqrt0(c(1.0) - (c(1.0) - cos_o * cos_o) * inv_n2);
    let single = c(albedo) * t * c(0.25 / math::PI) / math::max(cti + cto, c(1.0e-6));
    let multi = t * c(1.0 / math::PI) * subsurface_rd(n, albedo, form);
    single + multi
}

/// `E_D` of the subsurface layer (Eqs. 53–54) for lobe selection.
pub fn subsurface_energy(n: f32, k: f32, albedo: f32, form: LayerForm) -> f32 {
    let t0 = 1.0 - super::energy::normal_reflectance(n, k);
    // Eq. 53: α (1 − F0)² (1 + R_d)/2 with Eq. 54's R_d = 2 subsurface_rd / α.
    let rd = if albedo > 0.0 {
        2.0 * subsurface_rd(n, albedo, form) / albedo
    } else {
        0.0
    };
    albedo * t0 * t0 * 0.5 * (1.0 + rd)
}
