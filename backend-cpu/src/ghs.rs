//! GHS BRDF on the CPU: batch evaluation and directional albedo (white-furnace) estimates,
//! both through [`map`] so the scalar and SIMD paths run the same kernel source.

use crate::lanes::{LANES, LaneFn, map_lanes};
use crate::parallel::{Backend, map};
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::ghs::{self, Ghs, GhsParams};
use scratchwave_kernel::glam::{Vec2, Vec3};
use scratchwave_kernel::lane::{Lanes, V3};
use scratchwave_kernel::sampling::ghs::sample_prepared;

/// One BRDF query: directions in the local frame and the wavelength in µm.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GhsQuery {
    /// Towards the light.
    pub wi: Vec3,
    /// Towards the viewer.
    pub wo: Vec3,
    /// Wavelength (µm).
    pub lambda_um: f32,
}

/// `ρ(wi, wo)` for every query.
/// The SIMD backends run it in batches of [`LANES`] ([`map_lanes`]).
pub fn evaluate_ghs(backend: Backend, params: &GhsParams, queries: &[GhsQuery]) -> Vec<f32> {
    map_lanes(backend, queries, &GhsBatch(params))
}

/// [`ghs::evaluate`] as a [`LaneFn`].
struct GhsBatch<'a>(&'a GhsParams);

impl LaneFn for GhsBatch<'_> {
    type In = GhsQuery;
    type Out = f32;
    #[inline(always)]
    fn lanes(&self, q: &[GhsQuery; LANES]) -> [f32; LANES] {
        ghs::evaluate_lanes(
            self.0,
            G1Table::BUILTIN,
            V3::from_vecs(q.map(|q| q.wi)),
            V3::from_vecs(q.map(|q| q.wo)),
            Lanes(q.map(|q| q.lambda_um)),
        )
        .0
    }
    fn one(&self, q: &GhsQuery) -> f32 {
        ghs::evaluate(self.0, q.wi, q.wo, q.lambda_um)
    }
}

/// Directional albedo `a(θi) = ∫ ρ cosθo dωo` for each `θi`, estimated with the model's own
/// importance sampler on an `n × n` stratified grid (lobe choice by a Weyl sequence).
pub fn directional_albedo(
    backend: Backend,
    params: &GhsParams,
    lambda_um: f32,
    theta_i: &[f32],
    n: u32,
) -> Vec<f32> {
    let g = Ghs::new(params, lambda_um);
    let rows: Vec<(f32, u32)> = theta_i
        .iter()
        .flat_map(|&t| (0..n).map(move |r| (t, r)))
        .collect();
    let sums = map(backend, &rows, |&(t, r)| {
        let wi = Vec3::new(t.sin(), 0.0, t.cos());
        let mut s = 0.0f64;
        for c in 0..n {
            let k = (r * n + c) as f32;
            let u = Vec2::new((r as f32 + 0.5) / n as f32, (c as f32 + 0.5) / n as f32);
            let ul = (k * 0.618_034).fract();
            if let Some(smp) = sample_prepared(&g, wi, ul, u) {
                s += smp.weight as f64;
            }
        }
        s
    });
    theta_i
        .iter()
        .enumerate()
        .map(|(i, _)| {
            let tot: f64 = sums[i * n as usize..(i + 1) * n as usize].iter().sum();
            (tot / (n as f64 * n as f64)) as f32
        })
        .collect()
}
