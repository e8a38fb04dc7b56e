//! BRDF-table queries: the `Pod` records every backend uploads, and the one function that
//! evaluates a query, shared by the scalar, SIMD/rayon and SPIR-V backends.
//!
//! Every value is the BRDF in 1/sr **without** the cosine factor:
//! * `werner`: `F/(πσ²λ²) |B − S|²` (Werner Eq. 15 without γi; a flat mirror's directional
//!   albedo is then F);
//! * `werner_blended`: `F/(πσ²λ²) |S|²` (Werner §5; the caller adds `(1 − ρc) f_base`);
//! * `velinov`: `F/(A_C λ²) [Σ|S_k|² + (1 − ρc)|B|²·[base = gaussian]]` (Velinov Eqs. 6–7).

use crate::fresnel::fresnel;
use crate::ghs::g1::G1Table;
use crate::ghs::{self, GhsParams};
use crate::math;
use crate::scratch::{
    DepthTerm, EtaMode, ResponseInputs, ScratchSet, base_response, scratch_response,
};
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

/// Which model a table evaluates.
// `repr(u32)`: with three variants the default tag is a `u8`, which SPIR-V only has with
// the Int8 capability (rust-gpu rejects the table entry points without it).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// Coherent base + scratches (Werner Eq. 15).
    Werner = 0,
    /// Coherent scratches only, for blending with another base BRDF (Werner §5).
    WernerBlended = 1,
    /// Incoherent sum of single-scratch responses (Velinov Eq. 7).
    Velinov = 2,
}

impl Model {
    /// Decodes a `u32` (unknown → `Werner`; the std side validates first).
    #[inline]
    pub fn from_u32(v: u32) -> Model {
        match v {
            1 => Model::WernerBlended,
            2 => Model::Velinov,
            _ => Model::Werner,
        }
    }
}

/// Which angle the Fresnel term is evaluated at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum FresnelAngle {
    /// θd: between `wi` and the half vector (default).
    ThetaD = 0,
    /// θi: between `wi` and the normal.
    ThetaI = 1,
    /// Normal incidence.
    Normal = 2,
}

/// Material of one query: a constant reflectance or a complex IOR.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Material {
    /// 0: constant `f`; 1: Fresnel of `n + ik`.
    pub kind: u32,
    /// A [`FresnelAngle`] as `u32` (kind 1 only).
    pub fresnel_angle: u32,
    /// Constant reflectance (kind 0).
    pub f: f32,
    /// Real part of the IOR (kind 1).
    pub n: f32,
    /// Imaginary part of the IOR (kind 1).
    pub k: f32,
    /// Explicit padding.
    pub pad: [u32; 3],
}

const _: () = assert!(core::mem::size_of::<Material>() == 32);

impl Material {
    /// A constant reflectance `F`.
    pub const fn constant(f: f32) -> Material {
        Material {
            kind: 0,
            fresnel_angle: 0,
            f,
            n: 0.0,
            k: 0.0,
            pad: [0; 3],
        }
    }

    /// Fresnel reflectance of `n + ik` at the given angle.
    pub const fn ior(n: f32, k: f32, angle: FresnelAngle) -> Material {
        Material {
            kind: 1,
            fresnel_angle: angle as u32,
            f: 0.0,
            n,
            k,
            pad: [0; 3],
        }
    }

    /// The reflectance for unit directions `wi`, `wo`.
    #[inline]
    pub fn reflectance(&self, wi: Vec3, wo: Vec3) -> f32 {
        if self.kind == 0 {
            return self.f;
        }
        let cos = match self.fresnel_angle {
            1 => wi.z,
            2 => 1.0,
            _ => wi.dot((wi + wo).normalize_or_zero()),
        };
        fresnel(cos, self.n, self.k)
    }
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

/// Directions whose squared length is within this of 1 are used as given (an f32-rounded
/// unit vector is within 2^-23); others are normalised. Readers apply the same rule, so a
/// direction that arrives as f32 values is never rounded twice (the mpmath reference mirrors
/// it in `reference/refcore.py`).
pub const UNIT_TOLERANCE: f32 = 4.0e-7;

/// `v` as a unit vector under the [`UNIT_TOLERANCE`] rule (zero for a zero or non-finite
/// vector).
#[inline]
pub fn direction(v: [f32; 3]) -> Vec3 {
    let v = Vec3::from_array(v);
    let l2 = v.length_squared();
    if math::abs(l2 - 1.0) <= UNIT_TOLERANCE {
        v
    } else {
        v.normalize_or_zero()
    }
}

/// λ in µm from λ in nm, for the prefactors and band widths (`λ_nm · 0.001_f32`: its
/// 4.7e-8 relative error is harmless there; the phases use [`xi_of`] and
/// [`depth_half_turns_per_um`], which divide by `λ_nm` instead).
#[inline]
pub fn um_from_nm(lambda_nm: f32) -> f32 {
    lambda_nm * 1.0e-3
}

/// `ξ = (wi + wo)_xy / λ` (1/µm; zero in the mirror direction) from λ in nm.
///
/// Written `1000 (wi + wo)_xy / λ_nm`: a division by the run-time `λ_nm`, which every
/// target rounds correctly. The product `λ_nm · 0.001_f32` would put `0.001_f32`'s 4.7e-8
/// relative error into every phase of a query with the same sign, an error the coherent sum
/// does not average out (and spirv-opt rewrites a division by the constant 1000 into that
/// product).
#[inline]
pub fn xi_of(wi: Vec3, wo: Vec3, lambda_nm: f32) -> Vec2 {
    Vec2::new(wi.x + wo.x, wi.y + wo.y) * 1000.0 / lambda_nm
}

/// The depth phase per µm of groove depth in half-turns, `κ/(πD) = 2γ/λ` (1/µm), from `γ`
/// and λ in nm, as `2000 γ / λ_nm` (a run-time division; see [`xi_of`]).
#[inline]
pub fn depth_half_turns_per_um(gamma: f32, lambda_nm: f32) -> f32 {
    2000.0 * gamma / lambda_nm
}

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
    let area = math::PI * sigma * sigma;
    let norm = f / (area * lambda * lambda);
    let v = match model {
        Model::Werner => terms
            .coherent
            .subtracted_from(base_response(xi, sigma))
            .norm_sqr(),
        Model::WernerBlended => terms.coherent.total().norm_sqr(),
        Model::Velinov => {
            let base = if params.base_gaussian == 1 {
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
    let wi = direction(q.wi);
    let wo = direction(q.wo);
    if !(wi.z > 0.0 && wo.z > 0.0 && q.lambda_nm > 0.0) {
        return 0.0;
    }
    let r = ghs::evaluate_with_g1_table(p, g1_table, wi, wo, um_from_nm(q.lambda_nm));
    if r.is_finite() && r > 0.0 { r } else { 0.0 }
}
