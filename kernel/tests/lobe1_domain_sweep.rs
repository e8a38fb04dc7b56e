//! Domain sweep of the scratch models' sampling lobes (issue #20): the truncated logistic,
//! Cauchy and Gaussian mixtures of `bsdf::lobe1d` — mass, density and inverse CDF —
//! against the mpmath reference `reference/lobe1_sweep.py`, at the very f32 inputs it
//! evaluated. These are the one-dimensional factors of every scratch-model sampler
//! (`bsdf::lobes::DiskLobe`, Werner §5's base and scratch lobes as this crate builds them).
//!
//! A result is accepted when `err ≤ max(1e-4, 8κ)` (`κ`: the largest relative change of the
//! exact value under a one-ulp change of one input), the rule of the other sweeps
//! (`docs/stability.md`). The sample is compared as a point: its relative error. Densities
//! far below the lobe's mean are compared absolutely ([`PDF_FLOOR`]).
//!
//! The committed subset (`reference/golden/sweep/lobe1.csv`, 3 000 queries) runs by
//! default; a larger sample (`python3 reference/lobe1_sweep.py --count N --out DIR`) with
//! `LOBE1_SWEEP_DIR=DIR`.

mod sweep_common;

use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use std::collections::BTreeMap;
use sweep_common::{Row, Stat, Table, check_size, rel, report};

/// The committed subset's size (the test refuses fewer).
const MIN_QUERIES: usize = 3000;

fn lobe(r: &Row) -> Lobe1 {
    let f = |c: &str, j: usize| r.f(&format!("{c}{j}"));
    Lobe1 {
        kind: Lobe1Kind::from_u32(r.u("kind")),
        count: r.u("count"),
        mu: [f("mu", 0), f("mu", 1), f("mu", 2)],
        scale: [f("s", 0), f("s", 1), f("s", 2)],
        weight: [f("w", 0), f("w", 1), f("w", 2)],
    }
}

/// Densities below this fraction of the truncated lobe's mean density `1/(b − a)` are
/// compared absolutely, at that level. The sampler maps an f32 `u`, which resolves
/// probabilities down to 2⁻²⁴ ≈ 6e-8 only: a point 1e-12 of the mean down a tail is never
/// drawn, and its density moves no estimate. And f32 cannot hold it where the lobe's
/// density has underflowed while the mass of an interval nearer the centre has not (a
/// Gaussian interval from z = −15.5 to −11.5 keeps its mass, 1.1e-30, while `e^{−z²/2}` at
/// z = −14.7 is below the smallest f32): 20 of the 30 000 queries of the further sample
/// and 1 of the committed subset, all below 1e-17 of the mean, read as 0 or as little.
const PDF_FLOOR: f64 = 1.0e-12;

const KIND_NAMES: [&str; 3] = ["logistic", "cauchy", "gaussian"];
const FUNCS: [&str; 3] = ["mass", "pdf", "sample"];

#[test]
fn lobe1_functions_are_within_their_bound_over_the_domain() {
    let table = Table::load("LOBE1_SWEEP_DIR", "reference/golden/sweep", "lobe1");
    check_size("LOBE1_SWEEP_DIR", &table, MIN_QUERIES);
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    let mut names = Vec::new();
    for k in KIND_NAMES {
        for f in FUNCS {
            names.push(&*Box::leak(format!("{k} {f}").into_boxed_str()));
        }
    }
    for r in table.rows() {
        let l = lobe(&r);
        let (a, b, x, u) = (r.f("a"), r.f("b"), r.f("x"), r.f("u"));
        let got = [
            l.mass(a, b),
            l.pdf(x, a, b),
            l.sample(u, a, b).unwrap_or(f32::NAN),
        ];
        let kind = r.u("kind") as usize;
        let pdf_floor = PDF_FLOOR / (f64::from(b) - f64::from(a));
        for (i, f) in FUNCS.iter().enumerate() {
            let want = r.d(&format!("{f}_ref"));
            let kappa = r.d(&format!("{f}_kappa"));
            let err = if i == 1 && want < pdf_floor {
                // See [`PDF_FLOOR`].
                if (f64::from(got[i]) - want).abs() <= pdf_floor {
                    0.0
                } else {
                    f64::INFINITY
                }
            } else {
                rel(got[i], want)
            };
            let err = if err.is_nan() { f64::INFINITY } else { err };
            stats
                .entry(((kind, i), names[3 * kind + i]))
                .or_default()
                .add(err, kappa, || {
                    format!(
                        "kernel {:e} exact {want:e} κ {kappa:e}: {}",
                        got[i],
                        r.text()
                    )
                });
        }
    }
    let bad = report(&stats, 17);
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
