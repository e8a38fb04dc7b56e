//! Domain sweep of the scratch models' sampling lobes (issue #20): the truncated logistic,
//! Cauchy and Gaussian mixtures of `bsdf::lobe1d` — mass, density and inverse CDF —
//! against the mpmath reference `reference/lobe1_sweep.py`, at the very f32 inputs it
//! evaluated. These are the one-dimensional factors of every scratch-model sampler
//! (`bsdf::lobes::DiskLobe`, Werner §5's base and scratch lobes as this crate builds them).
//!
//! A result is accepted when `err ≤ max(1e-4, 8κ)` (`κ`: the largest relative change of the
//! exact value under a one-ulp change of one input), the rule of the other sweeps
//! (`docs/stability.md`). The sample is compared as a point: its relative error. Densities
//! far below the lobe's mean are compared absolutely (`sweep_common::sampling::PDF_FLOOR`).
//!
//! The committed subset (`reference/golden/sweep/lobe1.csv`, 3 000 queries) runs by
//! default; a larger sample (`python3 reference/lobe1_sweep.py --count N --out DIR`) with
//! `LOBE1_SWEEP_DIR=DIR`.

mod sweep_common;

use sweep_common::sampling::{LOBE1_MIN, check_lobe1, lobe1_args, lobe1_of};
use sweep_common::{Table, check_size};

#[test]
fn lobe1_functions_are_within_their_bound_over_the_domain() {
    let table = Table::load("LOBE1_SWEEP_DIR", "reference/golden/sweep", "lobe1");
    check_size("LOBE1_SWEEP_DIR", &table, LOBE1_MIN);
    let bad = check_lobe1(&table, false, |_, r| {
        let l = lobe1_of(r, "");
        let (a, b, x, u) = lobe1_args(r);
        [
            l.mass(a, b),
            l.pdf(x, a, b),
            l.sample(u, a, b).unwrap_or(f32::NAN),
        ]
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
