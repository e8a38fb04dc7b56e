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
#[cfg(not(target_arch = "spirv"))]
use crate::lane::Lanes;
use crate::lane::{Real, V3, branch};
use crate::material::Material;
use crate::math;
use crate::scratch::{
    DepthTerm, EtaMode, ResponseInputs, ScratchSet, ScratchTerms, base_response_lanes,
    scratch_response,
};
#[cfg(not(target_arch = "spirv"))]
use crate::scratch::{LaneUse, scratch_response_batch};
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
    let Some(p) = Prepared::of(params, q) else {
        return 0.0;
    };
    let inputs = Prepared::response_inputs(params, [p.x0.x, p.x0.y], [p.xi.x, p.xi.y], p.depth);
    let terms = scratch_response(set, &inputs);
    model_value(
        Model::from_u32(params.model),
        params.base_gaussian == 1,
        &terms,
        p.xi,
        params.sigma_um,
        p.f,
        p.lambda,
    )
}

/// [`evaluate`] for `N` queries at once (the SIMD backend's batch; CPU only): one walk over
/// the scratches near all `N` shading points ([`scratch_response_batch`]), the scratch
/// terms and the model in lanes, the per-query set-up (directions, ξ, reflectance) one
/// query at a time as in [`evaluate`]. A query whose shading point is not finite is
/// evaluated on its own by [`evaluate`] (it has no place in the batch's lookup circle).
#[cfg(not(target_arch = "spirv"))]
pub fn evaluate_batch<S: ScratchSet, const N: usize>(
    params: &TableParams,
    qs: &[TableQuery; N],
    set: &S,
    lane_use: &mut LaneUse,
) -> [f32; N] {
    let prepared = qs.each_ref().map(|q| Prepared::of(params, q));
    let in_lanes = |p: &Prepared| p.x0.is_finite();
    let Some(first) = prepared.iter().flatten().copied().find(in_lanes) else {
        return qs.each_ref().map(|q| evaluate(params, q, set));
    };
    // Lanes without a query for the walk compute the first one's value (and report their
    // own).
    let p = prepared.map(|p| p.filter(in_lanes).unwrap_or(first));
    let lanes = |f: fn(&Prepared) -> f32| Lanes(p.each_ref().map(f));
    let xi = [lanes(|p| p.xi.x), lanes(|p| p.xi.y)];
    let inputs = Prepared::response_inputs(
        params,
        [lanes(|p| p.x0.x), lanes(|p| p.x0.y)],
        xi,
        lanes(|p| p.depth),
    );
    let terms = scratch_response_batch(set, &inputs, lane_use);
    let v = model_value_lanes(
        Model::from_u32(params.model),
        params.base_gaussian == 1,
        &terms,
        xi,
        params.sigma_um,
        lanes(|p| p.f),
        lanes(|p| p.lambda),
    );
    core::array::from_fn(|i| match prepared[i] {
        None => 0.0,
        Some(p) if in_lanes(&p) => v.0[i],
        Some(_) => evaluate(params, &qs[i], set),
    })
}

/// A table query's set-up, shared by [`evaluate`] and [`evaluate_batch`].
#[derive(Clone, Copy, Debug)]
struct Prepared {
    /// Shading point (µm).
    x0: Vec2,
    /// ξ (1/µm).
    xi: Vec2,
    /// The depth phase per µm of depth.
    depth: f32,
    /// Reflectance F.
    f: f32,
    /// λ (µm).
    lambda: f32,
}

impl Prepared {
    /// The set-up, or `None` for a query whose value is 0 (below the horizon, degenerate
    /// direction, σ or λ not positive).
    #[inline]
    fn of(params: &TableParams, q: &TableQuery) -> Option<Prepared> {
        let wi = direction(q.wi);
        let wo = direction(q.wo);
        let lambda = um_from_nm(q.lambda_nm);
        if !(wi.z > 0.0 && wo.z > 0.0 && params.sigma_um > 0.0 && lambda > 0.0) {
            return None;
        }
        Some(Prepared {
            x0: Vec2::from_array(q.x),
            xi: xi_of(wi, wo, q.lambda_nm),
            depth: depth_half_turns_per_um(
                DepthTerm::from_u32(params.depth_term).gamma(wi.z + wo.z),
                q.lambda_nm,
            ),
            f: q.material.reflectance(wi, wo, q.lambda_nm),
            lambda,
        })
    }

    /// The scratch response's inputs (the lanes' `x0`, `ξ` and depth phase given).
    #[inline(always)]
    fn response_inputs<R: Real>(
        params: &TableParams,
        x0: [R; 2],
        xi: [R; 2],
        depth: R,
    ) -> ResponseInputs<R> {
        let model = Model::from_u32(params.model);
        ResponseInputs {
            x0,
            xi,
            depth_half_turns_per_um: depth,
            sigma: params.sigma_um,
            eta: if model == Model::Velinov {
                EtaMode::from_u32(params.eta)
            } else {
                EtaMode::Finite
            },
            area_density: model == Model::Velinov && params.base_gaussian == 1,
        }
    }
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
    model_value_lanes(model, base_gaussian, terms, [xi.x, xi.y], sigma, f, lambda)
}

/// [`model_value`] for one query per lane (the one formula).
#[inline(always)]
pub fn model_value_lanes<R: Real>(
    model: Model,
    base_gaussian: bool,
    terms: &ScratchTerms<R>,
    xi: [R; 2],
    sigma: f32,
    f: R,
    lambda: R,
) -> R {
    let c = R::splat;
    let area = math::PI * sigma * sigma;
    let norm = f / (c(area) * lambda * lambda);
    let v = match model {
        Model::Werner => terms
            .coherent
            .subtracted_from_lanes(base_response_lanes(xi, sigma))
            .norm_sqr(),
        Model::WernerBlended => terms.coherent.total_lanes().norm_sqr(),
        Model::Velinov => {
            let base = if base_gaussian {
                let b = base_response_lanes(xi, sigma);
                math::max(c(1.0) - terms.area_density, c(0.0)) * b * b
            } else {
                c(0.0)
            };
            terms.incoherent + base
        }
    };
    let r = norm * v;
    R::select(r.is_finite() & r.gt(c(0.0)), r, c(0.0))
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
