//! BRDF tables and footprint tables on the CPU.

use crate::parallel::{Backend, map};
use crate::scratch_lookup::ScratchLookup;
use scratchwave_kernel::footprint::{self, Ellipse};
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

/// One footprint-table row: the footprint average of `|η_s|²` by each method and ρ_P.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FootprintRow {
    /// Velinov Eq. 15.
    pub eq15: f32,
    /// Velinov Eq. 16 (π restored).
    pub eq16: f32,
    /// Accurate quadrature (this crate).
    pub accurate: f32,
    /// ρ_P by Velinov Eq. 18 (factor 2 removed).
    pub rho_p: f32,
}

/// Evaluates footprint queries `(scratch, ellipse)`.
pub fn footprint_table(
    backend: Backend,
    sigma: f32,
    queries: &[(Scratch, Ellipse)],
) -> Vec<FootprintRow> {
    map(backend, queries, |(s, e)| FootprintRow {
        eq15: footprint::eta_p_eq15(s, e, sigma),
        eq16: footprint::eta_p_eq16(s, e, sigma),
        accurate: footprint::eta_p_accurate(s, e, sigma),
        rho_p: footprint::rho_p_eq18(s, e),
    })
}

/// Evaluates every query of a GHS table.
pub fn evaluate_ghs_table(
    backend: Backend,
    params: &GhsParams,
    queries: &[TableQuery],
) -> Vec<f32> {
    map(backend, queries, |q| evaluate_ghs(params, q))
}
