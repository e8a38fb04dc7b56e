//! Domain sweep of Werner §5's scratch sampler (issue #20): the von Mises–Fisher ring of
//! `bsdf::lobes` — `vmf_ring_pdf` and `vmf_ring_sample` — against the mpmath reference
//! `reference/vmf_ring_sweep.py`, at the very f32 inputs it evaluated.
//!
//! A result is accepted when `err ≤ max(1e-4, 8κ)` (`κ`: the largest change of the exact
//! value under a one-ulp change of one input, measured as the error is), the rule of the
//! other sweeps (`docs/stability.md`). The pdf's error is relative; the sample's is its
//! angle to the exact direction over the lobe's angular width `min(1, 1/√κ_vMF)`.
//!
//! The committed subset (`reference/golden/sweep/vmf_ring.csv`, 2 000 queries) runs by
//! default; a larger sample (`python3 reference/vmf_ring_sweep.py --count N --out DIR`)
//! with `VMF_RING_SWEEP_DIR=DIR`.

mod sweep_common;

use scratchwave_kernel::bsdf::lobes::{vmf_ring_pdf, vmf_ring_sample};
use sweep_common::sampling::{VMF_RING_MIN, check_vmf_ring, vmf_ring_of};
use sweep_common::{Table, check_size};

#[test]
fn vmf_ring_pdf_and_sample_are_within_their_bound_over_the_domain() {
    let table = Table::load("VMF_RING_SWEEP_DIR", "reference/golden/sweep", "vmf_ring");
    check_size("VMF_RING_SWEEP_DIR", &table, VMF_RING_MIN);
    let bad = check_vmf_ring(&table, |_, r| {
        let q = vmf_ring_of(r);
        (
            vmf_ring_pdf(q.t, q.kappa, q.wo, q.wi),
            vmf_ring_sample(q.t, q.kappa, q.wo, q.u_ring, q.u),
        )
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
