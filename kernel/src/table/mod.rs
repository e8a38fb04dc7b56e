//! BRDF-table queries: the `Pod` records every backend uploads, and the function that
//! evaluates a query, shared by the scalar, SIMD/rayon and SPIR-V backends. The table is
//! built on the material interface: a scratch-model query is
//! [`bsdf::eval::scratch_point_values`] of [`BsdfMaterial::from_table`] at the query's one
//! wavelength, a GHS query is [`ghs::brdf`] (both what [`bsdf::eval()`] calls); the SIMD
//! batch (`batch`, CPU only) shares their set-up and formula in lanes.
//!
//! Every value is the BRDF in 1/sr **without** the cosine factor:
//! * `werner`: `F/(πσ²λ²) |B − S|²` (Werner Eq. 15 without γi; a flat mirror's directional
//!   albedo is then F);
//! * `werner_blended`: `F/(πσ²λ²) |S|²` (Werner §5; the caller adds `(1 − ρc) f_base`);
//! * `velinov`: `F/(A_C λ²) [Σ|S_k|² + (1 − ρc)|B|²·[base = gaussian]]` (Velinov Eqs. 6–7).

#[cfg(not(target_arch = "spirv"))]
mod batch;

pub use crate::bsdf::scratch_models::Model;
use crate::bsdf::{self, BsdfMaterial, Wavelengths};
use crate::ghs::g1::G1Table;
use crate::ghs::{self, GhsParams};
use crate::material::Material;
use crate::scratch::ScratchSet;
use crate::units::direction;
#[cfg(not(target_arch = "spirv"))]
pub use batch::evaluate_batch;
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

/// One table query. GPU-visible: 80 bytes.
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
    /// An [`EtaMode`](crate::scratch::EtaMode) as `u32` (velinov only).
    pub eta: u32,
    /// A [`DepthTerm`](crate::scratch::DepthTerm) as `u32`.
    pub depth_term: u32,
    /// 1: add the Gaussian base `(1 − ρc)|B|²` to velinov.
    pub base_gaussian: u32,
    /// Coherence σ (µm).
    pub sigma_um: f32,
    /// A [`Window`](crate::scratch::Window) as `u32`: the coherence window across a groove.
    pub window: u32,
    /// A [`Crossings`](crate::scratch::Crossings) as `u32`: how overlapping grooves cut.
    pub crossings: u32,
    /// Explicit padding.
    pub pad: [u32; 1],
}

const _: () = assert!(core::mem::size_of::<TableParams>() == 32);

/// Evaluates one query: the BRDF (1/sr, no cosine). Directions below the horizon (or
/// degenerate) give 0; the result is finite and non-negative for every input. The material
/// interface's point values at the query's wavelength
/// ([`bsdf::eval::scratch_point_values`] of [`BsdfMaterial::from_table`]).
pub fn evaluate<S: ScratchSet>(params: &TableParams, q: &TableQuery, set: &S) -> f32 {
    let Some((wi, wo)) =
        bsdf::eval::upper_directions(Vec3::from_array(q.wi), Vec3::from_array(q.wo))
    else {
        return 0.0;
    };
    let m = BsdfMaterial::from_table(params, q.material);
    let wl = Wavelengths::single(q.lambda_nm);
    bsdf::eval::scratch_point_values(&m, Vec2::from_array(q.x), wi, wo, &wl, set).0[0]
}

/// Evaluates one query of a GHS table (Holzschuch & Pacanowski): the query's directions and
/// wavelength through [`ghs::brdf`]; the query's shading point and material are not used
/// (the material is `p`). Below the horizon, 0.
pub fn evaluate_ghs(p: &GhsParams, q: &TableQuery) -> f32 {
    evaluate_ghs_with_g1_table(p, G1Table::BUILTIN, q)
}

/// [`evaluate_ghs`] reading G1 from `g1_table` (the GPU entry point's storage buffer).
pub fn evaluate_ghs_with_g1_table(p: &GhsParams, g1_table: G1Table, q: &TableQuery) -> f32 {
    ghs::brdf(p, g1_table, direction(q.wi), direction(q.wo), q.lambda_nm)
}
