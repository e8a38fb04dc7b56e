//! One record in, one record out: `eval` and `pdf` at a given `wi`, and `sample`, of the
//! kernel's BSDF interface (`scratchwave_kernel::bsdf`). The [`crate::bsdf`] entry point and
//! the CPU reference run this same [`evaluate`].

use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::{self, BsdfMaterial, Lookup, ShadingPoint, Strategy, Wavelengths};
use scratchwave_kernel::glam;
use scratchwave_kernel::scratch::ScratchSet;

/// One BSDF query. GPU-visible: 144 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BsdfQuery {
    /// Scratch-space position and optional footprint.
    pub sp: ShadingPoint,
    /// The wavelengths.
    pub wl: Wavelengths,
    /// Direction towards the viewer (local frame).
    pub wo: [f32; 3],
    /// The sample's selection number.
    pub u_select: f32,
    /// Direction towards the light for `eval` and `pdf` (local frame).
    pub wi: [f32; 3],
    /// A [`Strategy`] as `u32`.
    pub strategy: u32,
    /// The sample's warp numbers.
    pub u: [f32; 2],
    /// Explicit padding.
    pub pad: [f32; 2],
}

const _: () = assert!(core::mem::size_of::<BsdfQuery>() == 144);

/// What [`evaluate`] returns. GPU-visible: 64 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BsdfResult {
    /// `eval` at the query's `wi`.
    pub eval: [f32; 4],
    /// `pdf` at the query's `wi`.
    pub pdf: f32,
    /// 1 when `sample` returned a direction.
    pub sampled: u32,
    /// The sample's lobe.
    pub lobe: u32,
    /// The sample's wavelength index.
    pub wavelength: u32,
    /// The sampled direction.
    pub sample_wi: [f32; 3],
    /// The sample's pdf.
    pub sample_pdf: f32,
    /// The sample's weight `f·cosθi/pdf`.
    pub sample_weight: [f32; 4],
}

const _: () = assert!(core::mem::size_of::<BsdfResult>() == 64);

/// `eval`, `pdf` and `sample` of one query.
pub fn evaluate<S: ScratchSet>(m: &BsdfMaterial, lk: &Lookup<'_, S>, q: &BsdfQuery) -> BsdfResult {
    let strategy = Strategy::from_u32(q.strategy);
    let wo = Vec3::from_array(q.wo);
    let wi = Vec3::from_array(q.wi);
    let f = bsdf::eval(m, &q.sp, wi, wo, &q.wl, lk);
    let p = bsdf::pdf_with(strategy, m, &q.sp, wo, wi, &q.wl, lk);
    let mut r = BsdfResult {
        eval: f.v,
        pdf: p,
        ..BsdfResult::default()
    };
    if let Some(s) = bsdf::sample_with(
        strategy,
        m,
        &q.sp,
        wo,
        &q.wl,
        q.u_select,
        Vec2::from_array(q.u),
        lk,
    ) {
        r.sampled = 1;
        r.lobe = s.lobe;
        r.wavelength = s.wavelength;
        r.sample_wi = s.wi.to_array();
        r.sample_pdf = s.pdf;
        r.sample_weight = s.weight.v;
    }
    r
}
