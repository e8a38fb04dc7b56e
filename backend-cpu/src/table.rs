//! BRDF tables and footprint tables on the CPU.

use crate::lanes::{LANES, LaneFn, map_lanes, map_lanes_baseline};
use crate::parallel::{Backend, map};
use scratchwave_host::{FootprintRow, ScratchLookup};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::lane::{Lanes, V3};
use scratchwave_kernel::scratch::Scratch;
use scratchwave_kernel::table::{
    TableParams, TableQuery, evaluate, evaluate_ghs, evaluate_ghs_lanes,
};
use scratchwave_kernel::units::direction;

/// Evaluates every query against the scratch set (through the BVH lookup, built once).
pub fn evaluate_table(
    backend: Backend,
    params: &TableParams,
    scratches: &[Scratch],
    queries: &[TableQuery],
) -> Vec<f32> {
    let lookup = ScratchLookup::new(scratches, params.sigma_um);
    let set = lookup.set();
    map(backend, queries, |q| evaluate(params, q, &set))
}

/// Evaluates footprint queries `(scratch, ellipse)`.
pub fn footprint_table(
    backend: Backend,
    sigma: f32,
    queries: &[(Scratch, Ellipse)],
) -> Vec<FootprintRow> {
    map(backend, queries, |(s, e)| FootprintRow::of(s, e, sigma))
}

/// Evaluates every query of a GHS table.
/// The SIMD backends run it in batches of [`LANES`] ([`map_lanes`]).
pub fn evaluate_ghs_table(
    backend: Backend,
    params: &GhsParams,
    queries: &[TableQuery],
) -> Vec<f32> {
    map_lanes(backend, queries, &GhsTable(params))
}

/// [`evaluate_ghs_table`]'s lane path on one thread with the baseline instruction set (the
/// run-time dispatch's fallback; see [`crate::lanes::map_lanes_baseline`]).
pub fn evaluate_ghs_table_baseline(params: &GhsParams, queries: &[TableQuery]) -> Vec<f32> {
    map_lanes_baseline(queries, &GhsTable(params))
}

/// [`evaluate_ghs`] as a [`LaneFn`].
struct GhsTable<'a>(&'a GhsParams);

impl LaneFn for GhsTable<'_> {
    type In = TableQuery;
    type Out = f32;
    #[inline(always)]
    fn lanes(&self, q: &[TableQuery; LANES]) -> [f32; LANES] {
        evaluate_ghs_lanes(
            self.0,
            G1Table::BUILTIN,
            V3::from_vecs(q.map(|q| direction(q.wi))),
            V3::from_vecs(q.map(|q| direction(q.wo))),
            Lanes(q.map(|q| q.lambda_nm)),
        )
        .0
    }
    fn one(&self, q: &TableQuery) -> f32 {
        evaluate_ghs(self.0, q)
    }
}
