//! `eval`: the BRDF of a [`BsdfMaterial`] for every wavelength of a [`Wavelengths`] set.
//!
//! The scratch models walk the scratch lookup once for all wavelengths
//! ([`scratch_response_spectral`], which also gathers ρc when the model needs it) and finish
//! each wavelength with [`model_value`] ([`scratch_point_values`]; the table interface's
//! `table::evaluate` is that function at one wavelength). GHS is [`ghs::brdf`], the GHS
//! table's function too; the `(1 − ρc)` GHS base of WernerBlended and Velinov follows
//! Werner §5. With a footprint, Velinov's model is averaged over it
//! ([`velinov_footprint_brdf_spectral`], Velinov §4, one walk for all wavelengths); the
//! coherent models and GHS are point-sampled at its centre.

use super::scratch_models::model_value;
use super::{BsdfMaterial, Lookup, ShadingFrame, ShadingPoint, Spectrum, Wavelengths};
use crate::ghs::{self, g1::G1Table};
use crate::material::Reflectance;
use crate::math;
use crate::render::footprint::velinov_footprint_brdf_spectral;
use crate::render::shading::SceneModel;
use crate::scratch::{
    MAX_SPECTRAL, ScratchSet, SpectralInputs, scratch_area_density, scratch_response_spectral,
};
use crate::units::{depth_half_turns_per_um, direction, um_from_nm, xi_of};
use glam::{Vec2, Vec3};

/// The BRDF (1/sr, **without** the cosine) for local `wi` (towards the light) and `wo`
/// (towards the viewer), per wavelength. Zero below the horizon.
pub fn eval<S: ScratchSet>(
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wi: Vec3,
    wo: Vec3,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> Spectrum {
    let set = &lk.scratches;
    let n = wl.len();
    // A plain local array, stored to by run-time index (see `scratch_response_spectral`).
    let mut vals = [0.0; MAX_SPECTRAL];
    let Some((wi, wo)) = upper_directions(wi, wo) else {
        return Spectrum::ZERO;
    };
    if m.scene_model() == SceneModel::Ghs {
        let mut j = 0;
        while j < MAX_SPECTRAL && j < n {
            vals[j] = ghs_value(m, lk.g1, wi, wo, wl.nm[j]);
            j += 1;
        }
        return Spectrum { v: vals };
    }
    let sigma = m.sigma_um;
    if !(sigma > 0.0) {
        return Spectrum::ZERO;
    }
    let ghs_base = m.has_ghs_base();
    let rho = match (m.scene_model(), sp.footprint()) {
        (SceneModel::Velinov, Some(e)) => {
            let params = m.table_params();
            vals =
                velinov_footprint_brdf_spectral(&params, &m.material, wi, wo, &e, &wl.nm, n, set);
            // The renderer weights a GHS base by 1 − ρc at the footprint centre.
            if ghs_base {
                scratch_area_density(set, sp.x(), sigma, m.window(), m.crossings())
            } else {
                0.0
            }
        }
        _ => {
            let (v, rho) = scratch_point_values(m, sp.x(), wi, wo, wl, set);
            vals = v;
            rho
        }
    };
    if ghs_base {
        let w = math::max(1.0 - rho, 0.0);
        let mut j = 0;
        while j < MAX_SPECTRAL && j < n {
            let g = ghs_value(m, lk.g1, wi, wo, wl.nm[j]);
            if g > 0.0 {
                vals[j] += w * g;
            }
            j += 1;
        }
    }
    Spectrum { v: vals }
}

/// `wi` and `wo` normalised as every interface reads them ([`direction`]), or `None` when
/// either is not above the horizon (or degenerate).
#[inline]
pub fn upper_directions(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    let wi = direction(wi.to_array());
    let wo = direction(wo.to_array());
    if wi.z > 0.0 && wo.z > 0.0 {
        Some((wi, wo))
    } else {
        None
    }
}

/// A scratch model's values at the point `x` (µm, no footprint) per wavelength, without a
/// GHS base, and ρc at `x` (0 unless the model or its GHS base needs it): one scratch walk
/// ([`scratch_response_spectral`]) finished per wavelength by [`model_value`]. `wi`, `wo`
/// come from [`upper_directions`]; zeros when σ is not positive. For model `Ghs` (no
/// scratch model) this is Werner's.
pub fn scratch_point_values<S: ScratchSet>(
    m: &BsdfMaterial,
    x: Vec2,
    wi: Vec3,
    wo: Vec3,
    wl: &Wavelengths,
    set: &S,
) -> ([f32; MAX_SPECTRAL], f32) {
    let mut vals = [0.0; MAX_SPECTRAL];
    let sigma = m.sigma_um;
    if !(sigma > 0.0) {
        return (vals, 0.0);
    }
    let n = wl.len();
    let model = m.table_model();
    let (xi, depth) = spectral_phases(m, wi, wo, wl);
    let q = SpectralInputs {
        x0: x,
        xi,
        depth_half_turns_per_um: depth,
        count: n as u32,
        sigma,
        eta: m.eta_mode(),
        window: m.window(),
        crossings: m.crossings(),
        area_density: m.needs_area_density(),
    };
    let terms = scratch_response_spectral(set, &q);
    let mut reflectance = Reflectance::new(&m.material, wi, wo);
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        vals[j] = model_value(
            model,
            m.base_gaussian == 1,
            &terms[j],
            xi[j],
            sigma,
            reflectance.at(wl.nm[j]),
            um_from_nm(wl.nm[j]),
        );
        j += 1;
    }
    (vals, terms[0].area_density)
}

/// [`eval`] for world directions in `frame`.
pub fn eval_world<S: ScratchSet>(
    m: &BsdfMaterial,
    frame: &ShadingFrame,
    sp: &ShadingPoint,
    wi: Vec3,
    wo: Vec3,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> Spectrum {
    eval(m, sp, frame.to_local(wi), frame.to_local(wo), wl, lk)
}

/// The GHS BRDF at one wavelength (nm): [`ghs::brdf`].
#[inline]
pub(crate) fn ghs_value(m: &BsdfMaterial, g1: G1Table, wi: Vec3, wo: Vec3, lambda_nm: f32) -> f32 {
    ghs::brdf(&m.ghs, g1, wi, wo, lambda_nm)
}

/// `ξ` and the depth phase per wavelength for one direction pair.
pub(crate) fn spectral_phases(
    m: &BsdfMaterial,
    wi: Vec3,
    wo: Vec3,
    wl: &Wavelengths,
) -> ([Vec2; MAX_SPECTRAL], [f32; MAX_SPECTRAL]) {
    let gamma = m.depth_term().gamma(wi.z + wo.z);
    let mut xi = [Vec2::ZERO; MAX_SPECTRAL];
    let mut depth = [0.0; MAX_SPECTRAL];
    let n = wl.len();
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        xi[j] = xi_of(wi, wo, wl.nm[j]);
        depth[j] = depth_half_turns_per_um(gamma, wl.nm[j]);
        j += 1;
    }
    (xi, depth)
}
