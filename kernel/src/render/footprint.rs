//! Velinov 2018 §4: the pixel footprint in scratch space from the screen-space derivatives
//! of the hit position (ray differentials, Igehy 1999), and the incoherent model averaged
//! over it (Velinov Eqs. 13–18 with [`crate::footprint`]'s accurate averages).
//!
//! The hit-position derivative for a ray offset `(δo, δd)` hitting the tangent plane with
//! normal `n` at distance `t` along unit `d` is
//! `δP = δo + t δd − ((δo + t δd)·n / (d·n)) d`. Mapped to scratch space with the frame and
//! `um_per_unit` of the hit, the pixel square `[−½, ½]²` becomes a parallelogram with
//! columns `J = [∂x/∂px, ∂x/∂py]`; the footprint is the ellipse `J·{|v| ≤ 1/√π}` (the same
//! area `|det J|` as the parallelogram), whose semi-axes are `√λ_i/√π` for the
//! eigenvalues `λ_i` of `J Jᵀ`.
//!
//! The average: per scratch, the infinite-scratch form of Velinov Eq. 10 separates into
//! `|M − P|²(ξ₂) · e^{−4π²σ²ξ₁²} · |η_s(x)|²|_{ξ=0}`; only the last factor depends on the
//! position, and its footprint average is [`crate::footprint::eta_p_accurate`]
//! (Velinov Eq. 13's `η_P`). The Gaussian base uses `1 − ρ_P` (Velinov Eq. 18, accurate
//! form [`crate::footprint::rho_p_accurate`]).

use super::camera::RayDifferential;
use super::surface::SurfacePoint;
use crate::footprint::{Ellipse, eta_p_accurate, rho_p_accurate};
use crate::material::{Material, Reflectance};
use crate::math;
use crate::scratch::profile::mask_minus_profile;
use crate::scratch::response::CUTOFF_SIGMAS;
use crate::scratch::{DepthTerm, MAX_SPECTRAL, NearCursor, Profile, ScratchSet, base_response};
use crate::table::TableParams;
use crate::units::{depth_half_turns_per_um, direction, um_from_nm, xi_of};
use glam::{Vec2, Vec3};

/// The hit-position derivative for one ray offset (Igehy 1999, Eq. 10's transfer).
#[inline]
pub fn position_derivative(d_origin: Vec3, d_dir: Vec3, dir: Vec3, t: f32, n: Vec3) -> Vec3 {
    let dn = dir.dot(n);
    let v = d_origin + d_dir * t;
    if math::abs(dn) > 1.0e-12 {
        v - dir * (v.dot(n) / dn)
    } else {
        v
    }
}

/// The footprint ellipse (µm) of a primary ray with differentials `rd` hitting at `t` with
/// shading point `sp`; `scale` shrinks the pixel (`1/√spp` for `spp` samples).
pub fn footprint_ellipse(rd: &RayDifferential, t: f32, sp: &SurfacePoint, scale: f32) -> Ellipse {
    let dir = Vec3::from_array(rd.ray.dir);
    let n = sp.z;
    let dpx = position_derivative(rd.d_origin_dx, rd.d_dir_dx, dir, t, n) * scale;
    let dpy = position_derivative(rd.d_origin_dy, rd.d_dir_dy, dir, t, n) * scale;
    let cx = Vec2::new(
        dpx.dot(sp.x) * sp.um_per_unit.x,
        dpx.dot(sp.y) * sp.um_per_unit.y,
    );
    let cy = Vec2::new(
        dpy.dot(sp.x) * sp.um_per_unit.x,
        dpy.dot(sp.y) * sp.um_per_unit.y,
    );
    // J Jᵀ = [[a, b], [b, c]].
    let a = cx.x * cx.x + cy.x * cy.x;
    let b = cx.x * cx.y + cy.x * cy.y;
    let c = cx.y * cx.y + cy.y * cy.y;
    let half_diff = 0.5 * (a - c);
    let root = math::sqrt0(half_diff * half_diff + b * b);
    let mean = 0.5 * (a + c);
    let l1 = mean + root;
    let l2 = math::max(mean - root, 0.0);
    let angle = 0.5 * math::atan2(2.0 * b, a - c);
    let r = math::FRAC_1_SQRT_PI;
    // A degenerate footprint (an edge-on view) keeps a tiny positive axis.
    Ellipse {
        center: sp.x_um.to_array(),
        angle_rad: angle,
        a1: math::max(r * math::sqrt0(l1), 1.0e-6),
        a2: math::max(r * math::sqrt0(l2), 1.0e-6),
        pad: [0.0; 3],
    }
}

/// Velinov's incoherent BRDF (1/sr, no cosine) averaged over footprint `e`, the Gaussian
/// base included when `params.base_gaussian` is 1. `wi`, `wo` in the shading frame.
/// [`velinov_footprint_brdf_spectral`] at one wavelength.
pub fn velinov_footprint_brdf<S: ScratchSet>(
    params: &TableParams,
    material: &Material,
    wi: Vec3,
    wo: Vec3,
    e: &Ellipse,
    lambda_nm: f32,
    set: &S,
) -> f32 {
    let mut lambdas = [0.0; MAX_SPECTRAL];
    lambdas[0] = lambda_nm;
    velinov_footprint_brdf_spectral(params, material, wi, wo, e, &lambdas, 1, set)[0]
}

/// [`velinov_footprint_brdf`] at the first `count` of `lambdas_nm`, in one scratch walk:
/// each scratch's footprint integrals (`η_P`, and `ρ_P` for the base) do not depend on λ
/// and are computed once for all wavelengths. Each value equals a one-wavelength walk bit
/// for bit.
#[allow(clippy::too_many_arguments)]
pub fn velinov_footprint_brdf_spectral<S: ScratchSet>(
    params: &TableParams,
    material: &Material,
    wi: Vec3,
    wo: Vec3,
    e: &Ellipse,
    lambdas_nm: &[f32; MAX_SPECTRAL],
    count: usize,
    set: &S,
) -> [f32; MAX_SPECTRAL] {
    let mut out = [0.0; MAX_SPECTRAL];
    let n = if count < MAX_SPECTRAL {
        count
    } else {
        MAX_SPECTRAL
    };
    let wi = direction(wi.to_array());
    let wo = direction(wo.to_array());
    let sigma = params.sigma_um;
    if !(wi.z > 0.0 && wo.z > 0.0 && sigma > 0.0) {
        return out;
    }
    let mut xi = [Vec2::ZERO; MAX_SPECTRAL];
    let mut half_turns = [0.0; MAX_SPECTRAL];
    let gamma = DepthTerm::from_u32(params.depth_term).gamma(wi.z + wo.z);
    let mut j = 0;
    while j < n {
        xi[j] = xi_of(wi, wo, lambdas_nm[j]);
        half_turns[j] = depth_half_turns_per_um(gamma, lambdas_nm[j]);
        j += 1;
    }
    let centre = Vec2::from_array(e.center);
    let radius = math::max(e.a1, e.a2) + CUTOFF_SIGMAS * sigma;
    let mut sum = [0.0; MAX_SPECTRAL];
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    let base = params.base_gaussian == 1;
    while let Some(s) = set.next_near(&mut cursor, centre, radius) {
        if let Some(frame) = s.frame() {
            let eta = eta_p_accurate(&s, e, sigma);
            if base {
                rho += rho_p_accurate(&s, e, sigma);
            }
            let profile = Profile::from_u32(s.profile);
            let mut j = 0;
            while j < n {
                let xi1 = xi[j].dot(frame.tangent);
                let xi2 = xi[j].dot(frame.bitangent);
                let mp = mask_minus_profile(profile, s.width, s.depth, half_turns[j], xi2);
                let along = math::exp(-4.0 * math::PI * math::PI * sigma * sigma * xi1 * xi1);
                sum[j] += mp.norm_sqr() * along * eta;
                j += 1;
            }
        }
    }
    let mut reflectance = Reflectance::new(material, wi, wo);
    let mut j = 0;
    while j < n {
        let lambda = um_from_nm(lambdas_nm[j]);
        if lambda > 0.0 {
            let f = reflectance.at(lambdas_nm[j]);
            let mut total = sum[j];
            if base {
                let b = base_response(xi[j], sigma);
                total += math::max(1.0 - rho, 0.0) * b * b;
            }
            let r = f * total / (math::PI * sigma * sigma * lambda * lambda);
            out[j] = if r.is_finite() && r > 0.0 { r } else { 0.0 };
        }
        j += 1;
    }
    out
}

/// `ρ_P = Σ_k (1/A_P) ∫_P ρ_k(x) dx`, the scratches' area density averaged over footprint
/// `e` ([`rho_p_accurate`], Velinov Eq. 18's quantity), over the scratches within
/// `max(a1, a2) + 6σ` of its centre.
pub fn footprint_density<S: ScratchSet>(sigma: f32, e: &Ellipse, set: &S) -> f32 {
    let centre = Vec2::from_array(e.center);
    let radius = math::max(e.a1, e.a2) + CUTOFF_SIGMAS * sigma;
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, centre, radius) {
        rho += rho_p_accurate(&s, e, sigma);
    }
    rho
}
