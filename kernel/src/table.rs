//! BRDF-table queries: the `Pod` records every backend uploads, and the one function that
//! evaluates a query, shared by the scalar, SIMD/rayon and SPIR-V backends.
//!
//! Every value is the BRDF in 1/sr **without** the cosine factor:
//! * `werner`: `F/(πσ²λ²) |B − S|²` (Werner Eq. 15 without γi; a flat mirror's directional
//!   albedo is then F);
//! * `werner_blended`: `F/(πσ²λ²) |S|²` (Werner §5; the caller adds `(1 − ρc) f_base`);
//! * `velinov`: `F/(A_C λ²) [Σ|S_k|² + (1 − ρc)|B|²·[base = gaussian]]` (Velinov Eqs. 6–7).

use crate::ghs::g1::G1Table;
use crate::ghs::{self, GhsParams};
use crate::lane::{Real, V3, branch};
use crate::material::Material;
use crate::math;
use crate::scratch::{
    DepthTerm, EtaMode, ResponseInputs, ScratchSet, ScratchTerms, base_response, scratch_response,
};
use crate::units::{depth_half_turns_per_um, direction, um_from_nm, xi_of};
use bytemuck::{Pod, Zeroable};
use glam::Vec2;

gpu_enum! {
    /// Which model a table evaluates.
    pub enum Model {
        /// Coherent base + scratches (Werner Eq. 15).
        Werner = 0,
        /// Coherent scratches only, for blending with another base BRDF (Werner §5).
        WernerBlended = 1,
        /// Incoherent sum of single-scratch responses (Velinov Eq. 7).
        Velinov = 2,
    }
    fallback = Werner;
}

/// One table query. GPU-visible: 64 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct TableQuery {
    /// Direction towards the light (normalised by the kernel).
    pub wi: [f32; 3],
    /// Wavelength (nm).
    pub lambda_nm: f32,
    /// Direction towards the viewer (normalised by the kernel).
    pub wo: [f32; 3],
    /// Explicit padding.
    pub pad0: f32,
    /// Shading point (µm).
    pub x: [f32; 2],
    /// Explicit padding.
    pub pad1: [f32; 2],
    /// Material of this query.
    pub material: Material,
}

const _: () = assert!(core::mem::size_of::<TableQuery>() == 80);

/// Model choice and options, shared by every query of a table. GPU-visible: 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct TableParams {
    /// A [`Model`] as `u32`.
    pub model: u32,
    /// An [`EtaMode`] as `u32` (velinov only).
    pub eta: u32,
    /// A [`DepthTerm`] as `u32`.
    pub depth_term: u32,
    /// 1: add the Gaussian base `(1 − ρc)|B|²` to velinov.
    pub base_gaussian: u32,
    /// Coherence σ (µm).
    pub sigma_um: f32,
    /// Explicit padding.
    pub pad: [u32; 3],
}

const _: () = assert!(core::mem::size_of::<TableParams>() == 32);

/// Evaluates one query: the BRDF (1/sr, no cosine). Directions below the horizon (or
/// degenerate) give 0; the result is finite and non-negative for every input.
pub fn evaluate<S: ScratchSet>(params: &TableParams, q: &TableQuery, set: &S) -> f32 {
    let wi = direction(q.wi);
    let wo = direction(q.wo);
    let sigma = params.sigma_um;
    let lambda = um_from_nm(q.lambda_nm);
    if !(wi.z > 0.0 && wo.z > 0.0 && sigma > 0.0 && lambda > 0.0) {
        return 0.0;
    }
    let xi = xi_of(wi, wo, q.lambda_nm);
    let model = Model::from_u32(params.model);
    let eta = if model == Model::Velinov {
        EtaMode::from_u32(params.eta)
    } else {
        EtaMode::Finite
    };
    let inputs = ResponseInputs {
        x0: Vec2::from_array(q.x),
        xi,
        depth_half_turns_per_um: depth_half_turns_per_um(
            DepthTerm::from_u32(params.depth_term).gamma(wi.z + wo.z),
            q.lambda_nm,
        ),
        sigma,
        eta,
        area_density: model == Model::Velinov && params.base_gaussian == 1,
    };
    let terms = scratch_response(set, &inputs);
    let f = q.material.reflectance(wi, wo);
    model_value(
        model,
        params.base_gaussian == 1,
        &terms,
        xi,
        sigma,
        f,
        lambda,
    )
}

/// The BRDF (1/sr, no cosine) of a scratch model from the scratch terms of one wavelength:
/// `F/(πσ²λ²)` times `|B − S|²` (Werner Eq. 15), `|S|²` (Werner §5) or
/// `Σ|S_k|² + (1 − ρc)|B|²·[base_gaussian]` (Velinov Eqs. 6–7), by [`Model`]. `f` is the
/// reflectance F, `lambda` in µm; 0 unless the result is finite and positive.
#[inline]
pub fn model_value(
    model: Model,
    base_gaussian: bool,
    terms: &ScratchTerms,
    xi: Vec2,
    sigma: f32,
    f: f32,
    lambda: f32,
) -> f32 {
    let area = math::PI * sigma * sigma;
    let norm = f / (area * lambda * lambda);
    let v = match model {
        Model::Werner => terms
            .coherent
            .subtracted_from(base_response(xi, sigma))
            .norm_sqr(),
        Model::WernerBlended => terms.coherent.total().norm_sqr(),
        Model::Velinov => {
            let base = if base_gaussian {
                let b = base_response(xi, sigma);
                math::max(1.0 - terms.area_density, 0.0) * b * b
            } else {
                0.0
            };
            terms.incoherent + base
        }
    };
    let r = norm * v;
    if r.is_finite() && r > 0.0 { r } else { 0.0 }
}

/// Evaluates one query of a GHS table (Holzschuch & Pacanowski): the query's directions and
/// wavelength through [`ghs::evaluate`]; the query's shading point and material are not used
/// (the material is `p`). Below the horizon, 0.
pub fn evaluate_ghs(p: &GhsParams, q: &TableQuery) -> f32 {
    evaluate_ghs_with_g1_table(p, G1Table::BUILTIN, q)
}

/// [`evaluate_ghs`] reading G1 from `g1_table` (the GPU entry point's storage buffer).
pub fn evaluate_ghs_with_g1_table(p: &GhsParams, g1_table: G1Table, q: &TableQuery) -> f32 {
    evaluate_ghs_lanes(
        p,
        g1_table,
        direction(q.wi).into(),
        direction(q.wo).into(),
        q.lambda_nm,
    )
}

/// [`evaluate_ghs_with_g1_table`] for one query per lane, with the directions already
/// through [`direction`] (the SIMD backend's batch entry point; the one formula).
#[inline(always)]
pub fn evaluate_ghs_lanes<R: Real>(
    p: &GhsParams,
    g1_table: G1Table,
    wi: V3<R>,
    wo: V3<R>,
    lambda_nm: R,
) -> R {
    let zero = R::splat(0.0);
    branch!(
        wi.z.gt(zero) & wo.z.gt(zero) & lambda_nm.gt(zero),
        {
            let r = ghs::evaluate_lanes(p, g1_table, wi, wo, um_from_nm(lambda_nm));
            R::select(r.is_finite() & r.gt(zero), r, zero)
        },
        zero,
    )
}
