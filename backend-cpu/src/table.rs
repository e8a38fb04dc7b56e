//! BRDF tables and footprint tables on the CPU.

use crate::parallel::{Backend, map};
use scratchwave_host::{FootprintRow, ScratchLookup};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::scratch::Scratch;
use scratchwave_kernel::table::{TableParams, TableQuery, evaluate, evaluate_ghs};

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
pub fn evaluate_ghs_table(
    backend: Backend,
    params: &GhsParams,
    queries: &[TableQuery],
) -> Vec<f32> {
    map(backend, queries, |q| evaluate_ghs(params, q))
}
