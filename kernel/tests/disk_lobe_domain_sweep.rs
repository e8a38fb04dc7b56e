//! Domain sweep of the scratch models' two-dimensional sampling lobes (issue #20):
//! `bsdf::lobes::DiskLobe` — the base response's Gaussian and a scratch's logistic ×
//! Cauchy, each truncated to the projected disk — `pdf` and `sample` against the mpmath
//! reference `reference/disk_lobe_sweep.py`, at the very f32 inputs it evaluated.
//!
//! A result is accepted when `err ≤ max(1e-4, 8κ)` (`κ`: the largest change of the exact
//! value under a one-ulp change of one input, measured as the error is), the rule of the
//! other sweeps (`docs/stability.md`). The pdf's error is relative; the sample's is its
//! angle to the exact direction over the lobes' smallest scale (capped at 1).
//!
//! The committed subset (`reference/golden/sweep/disk_lobe.csv`, 1 500 queries) runs by
//! default; a larger sample (`python3 reference/disk_lobe_sweep.py --count N --out DIR`)
//! with `DISK_LOBE_SWEEP_DIR=DIR`.

mod sweep_common;

use sweep_common::sampling::{DISK_LOBE_MIN, check_disk_lobe, disk_lobe_of};
use sweep_common::{Table, check_size};

#[test]
fn disk_lobe_pdf_and_sample_are_within_their_bound_over_the_domain() {
    let table = Table::load("DISK_LOBE_SWEEP_DIR", "reference/golden/sweep", "disk_lobe");
    check_size("DISK_LOBE_SWEEP_DIR", &table, DISK_LOBE_MIN);
    let bad = check_disk_lobe(&table, |_, r| {
        let (l, wo, wi, u) = disk_lobe_of(r);
        (l.pdf(wo, wi), l.sample(wo, u))
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
