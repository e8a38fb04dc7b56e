//! Importance sampling of the GHS BRDF (H&P §4.5), with the exact pdf of the mixture.
//!
//! 1. Lobe selection (Eqs. 50–57): glossy vs diffuse with `p_C = E_C / (E_C + E_D)`,
//!    `E_C = F0`; within the glossy lobes, micro-facet with probability
//!    `A_imp = exp(−(2π σs/λ cosθi)²)`, else diffraction. One uniform number `u_lobe` makes
//!    both choices (it is rescaled after the first).
//! 2. Micro-facet: `h` from the NDF's slope distribution (`φh = 2π u₀`, `tanθh =
//!    β Q⁻¹(1/p, u₁)^{1/(2p)}`; Eq. 59 with the exponent corrected from `c/2`), `wo = reflect(wi, h)`,
//!    pdf `D(h) cosθh / (4 wi·h)`.
//! 3. Diffraction (Eqs. 60–63): `d_p = o_p + i_p` drawn in polar coordinates about the
//!    mirror point `−i_p`: radius from the K-correlation radial CDF truncated at
//!    `1 + sinθi` (Eqs. 60–61), angle uniform within the arc that keeps `o_p` in the unit
//!    disk (Eq. 62). That arc is centred on the direction of `+i_p` (towards the disk
//!    centre) with `wi` pointing away from the surface; Eq. 63's `φi + π` holds for an
//!    incident direction pointing *into* the surface. pdf in the projected disk
//!    `π k(r) / (M φmax(r))`, times `cosθo` for solid angle. (The paper's "multiply by
//!    φmax/π" is this pdf's angular factor only.)
//! 4. Diffuse layer: cosine-weighted, pdf `cosθo/π`.

use super::Sample;
use super::warp;
use crate::ghs::spread::{KCorrelation, phi_max};
use crate::ghs::{Ghs, GhsParams, Layer, energy, layers, ndf::GenBeckmann};
use crate::math;
use glam::{Vec2, Vec3};

/// Lobe index: micro-facet.
pub const LOBE_MICROFACET: u32 = 0;
/// Lobe index: diffraction.
pub const LOBE_DIFFRACTION: u32 = 1;
/// Lobe index: diffuse layer.
pub const LOBE_DIFFUSE: u32 = 2;

/// Selection probabilities `[micro-facet, diffraction, diffuse]` for `wi` (sum 1).
pub fn lobe_probabilities(g: &Ghs, wi: Vec3) -> [f32; 3] {
    let e_c = energy::normal_reflectance(g.n, g.k);
    let e_d = match g.layer {
        Layer::None => 0.0,
        Layer::Plastic => layers::plastic_energy(g.n, g.k, g.layer_albedo, g.layer_form),
        Layer::Subsurface => layers::subsurface_energy(g.n, g.k, g.layer_albedo, g.layer_form),
    };
    let total = e_c + e_d;
    let p_c = if total > 0.0 && total.is_finite() {
        e_c / total
    } else {
        1.0
    };
    let a = energy::sampling_split(g.sigma_over_lambda, math::max(wi.z, 0.0));
    [p_c * a, p_c * (1.0 - a), 1.0 - p_c]
}

/// Half vector from `u` (slope-distribution sampling of the generalized Beckmann NDF).
#[inline]
pub fn sample_half_vector(ndf: &GenBeckmann, u: Vec2) -> Vec3 {
    let phi = math::TAU * u.x;
    let tan = ndf.sample_tan(u.y);
    let cos = 1.0 / math::sqrt(1.0 + tan * tan);
    // sinθ = tanθ cosθ, not √(1 − cos²θ): that cancels to 0 for narrow lobes (cosθh rounds
    // to 1 below tanθh = 2.4e-4) and put tanθh off by up to 100 % (`docs/ghs.md`). Beyond
    // tanθ = 1e18 (u → 0; tan² may overflow) the direction is the horizon.
    let sin = if tan < 1.0e18 {
        math::min(tan * cos, 1.0)
    } else {
        1.0
    };
    Vec3::new(sin * math::cos(phi), sin * math::sin(phi), cos)
}

/// Inverse of [`sample_half_vector`].
#[inline]
pub fn half_vector_inverse(ndf: &GenBeckmann, h: Vec3) -> Vec2 {
    let mut phi = math::atan2(h.y, h.x) * (1.0 / math::TAU);
    if phi < 0.0 {
        phi += 1.0;
    }
    let sin = math::sqrt(h.x * h.x + h.y * h.y);
    let tan = if h.z > 0.0 { sin / h.z } else { f32::MAX };
    Vec2::new(phi, ndf.invert_tan(tan))
}

/// pdf of a half vector drawn by [`sample_half_vector`]: `D(h) cosθh` (solid angle of `h`).
#[inline]
pub fn half_vector_pdf(ndf: &GenBeckmann, h: Vec3) -> f32 {
    ndf.d(h) * math::max(h.z, 0.0)
}

/// Micro-facet lobe: `wo = reflect(wi, h)`; `None` below the horizon.
#[inline]
pub fn sample_microfacet(ndf: &GenBeckmann, wi: Vec3, u: Vec2) -> Option<Vec3> {
    let h = sample_half_vector(ndf, u);
    let d = wi.dot(h);
    if !(d > 0.0) {
        return None;
    }
    let wo = h * (2.0 * d) - wi;
    if wo.z > 0.0 { Some(wo) } else { None }
}

/// Solid-angle pdf of [`sample_microfacet`] at `wo`.
#[inline]
pub fn microfacet_pdf(ndf: &GenBeckmann, wi: Vec3, wo: Vec3) -> f32 {
    match crate::ghs::half_vector(wi, wo) {
        Some((h, cos_d)) if cos_d > 0.0 => half_vector_pdf(ndf, h) / (4.0 * cos_d),
        _ => 0.0,
    }
}

/// `sinθi = |i_p|` from the components (at most 1): `√(1 − cos²θi)` cancels near normal
/// incidence (0 for `cosθi` rounded to 1), which misplaced the lobe centre `−i_p`: sampled
/// `o_p` were off by up to 1.1 % of their distance from it before this form (`docs/ghs.md`).
#[inline]
fn sin_incident(wi: Vec3) -> f32 {
    math::min(math::sqrt(wi.x * wi.x + wi.y * wi.y), 1.0)
}

/// Frame of the projected incident direction: unit `e1` along `+i_p`, `e2 ⟂ e1`, and
/// `s = sinθi`.
#[inline]
fn incident_frame(wi: Vec3) -> (Vec2, Vec2, f32) {
    let (c, s_az) = warp::azimuth(wi);
    let e1 = Vec2::new(c, s_az);
    (e1, Vec2::new(-e1.y, e1.x), sin_incident(wi))
}

/// Diffraction lobe (Eqs. 60–63, arc centred towards the disk centre); `None` when the
/// drawn point leaves the disk by rounding.
pub fn sample_diffraction(spread: &KCorrelation, wi: Vec3, u: Vec2) -> Option<Vec3> {
    let (e1, e2, s) = incident_frame(wi);
    let m = spread.cdf(1.0 + s);
    if !(m > 0.0) {
        return None;
    }
    let r = math::min(spread.radius_from_cdf(m * u.x), 1.0 + s);
    let pm = phi_max(r, s);
    let alpha = (2.0 * u.y - 1.0) * pm;
    let d = (e1 * math::cos(alpha) + e2 * math::sin(alpha)) * r;
    let ip = e1 * s;
    let op = d - ip;
    let z2 = 1.0 - op.dot(op);
    if !(z2 > 0.0) {
        return None;
    }
    Some(Vec3::new(op.x, op.y, math::sqrt(z2)))
}

/// Solid-angle pdf of [`sample_diffraction`] at `wo`.
pub fn diffraction_pdf(spread: &KCorrelation, wi: Vec3, wo: Vec3) -> f32 {
    if !(wo.z > 0.0) {
        return 0.0;
    }
    let s = sin_incident(wi);
    let d = crate::ghs::direction_sum(wi, wo);
    let r = math::sqrt(d.x * d.x + d.y * d.y);
    let pm = phi_max(r, s);
    let m = spread.cdf(1.0 + s);
    if !(pm > 0.0) || !(m > 0.0) {
        return 0.0;
    }
    math::PI * spread.density(r) / (m * pm) * wo.z
}

/// Inverse of [`sample_diffraction`].
pub fn diffraction_inverse(spread: &KCorrelation, wi: Vec3, wo: Vec3) -> Vec2 {
    let (e1, e2, s) = incident_frame(wi);
    let d = Vec2::new(wi.x + wo.x, wi.y + wo.y);
    let r = d.length();
    let m = spread.cdf(1.0 + s);
    let pm = phi_max(r, s);
    let alpha = math::atan2(d.dot(e2), d.dot(e1));
    let ux = if m > 0.0 { spread.cdf(r) / m } else { 0.0 };
    let uy = if pm > 0.0 {
        0.5 * (alpha / pm + 1.0)
    } else {
        0.5
    };
    Vec2::new(ux, uy)
}

/// Mixture pdf of [`sample`] for a prepared material.
pub fn pdf_prepared(g: &Ghs, wi: Vec3, wo: Vec3) -> f32 {
    if !(wi.z > 0.0) || !(wo.z > 0.0) {
        return 0.0;
    }
    let pr = lobe_probabilities(g, wi);
    let mut p = 0.0;
    if pr[0] > 0.0 {
        p += pr[0] * microfacet_pdf(&g.ndf, wi, wo);
    }
    if pr[1] > 0.0 {
        p += pr[1] * diffraction_pdf(&g.spread, wi, wo);
    }
    if pr[2] > 0.0 {
        p += pr[2] * warp::cosine_hemisphere_pdf(wo);
    }
    if p.is_finite() { p } else { 0.0 }
}

/// Draws `wo` for a prepared material: `u_lobe` picks the lobe, `u` drives its warp.
pub fn sample_prepared(g: &Ghs, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<Sample> {
    if !(wi.z > 0.0) {
        return None;
    }
    let pr = lobe_probabilities(g, wi);
    let (wo, lobe) = if u_lobe < pr[0] {
        (sample_microfacet(&g.ndf, wi, u)?, LOBE_MICROFACET)
    } else if u_lobe < pr[0] + pr[1] {
        (sample_diffraction(&g.spread, wi, u)?, LOBE_DIFFRACTION)
    } else {
        (warp::cosine_hemisphere(u), LOBE_DIFFUSE)
    };
    let pdf = pdf_prepared(g, wi, wo);
    if !(pdf > 0.0) || !(wo.z > 0.0) {
        return None;
    }
    let value = g.eval(wi, wo);
    let weight = value * wo.z / pdf;
    if !weight.is_finite() {
        return None;
    }
    Some(Sample {
        wo,
        pdf,
        value,
        weight,
        lobe,
    })
}

/// Samples the GHS BRDF at wavelength `lambda_um`: `u_lobe` selects the lobe, `u` drives its
/// warp; returns the direction, the mixture pdf (equal to [`pdf`]), the BRDF value and the
/// weight `ρ cosθo / pdf`. `None` when the drawn direction is below the horizon.
pub fn sample(
    params: &GhsParams,
    wi: Vec3,
    u_lobe: f32,
    u: Vec2,
    lambda_um: f32,
) -> Option<Sample> {
    sample_prepared(&Ghs::new(params, lambda_um), wi, u_lobe, u)
}

/// Solid-angle pdf with which [`sample`] produces `wo`.
pub fn pdf(params: &GhsParams, wi: Vec3, wo: Vec3, lambda_um: f32) -> f32 {
    pdf_prepared(&Ghs::new(params, lambda_um), wi, wo)
}
