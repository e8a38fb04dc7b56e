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

use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::lobes::{vmf_ring_pdf, vmf_ring_sample};
use std::collections::BTreeMap;
use sweep_common::{Row, Stat, Table, angle, check_size, rel, report};

/// The committed subset's size (the test refuses fewer).
const MIN_QUERIES: usize = 2000;

/// The concentration bands the report groups by (upper ends).
const BANDS: [(f64, &str); 4] = [
    (1.0, "κ < 1"),
    (1.0e3, "κ 1 – 1e3"),
    (1.0e5, "κ 1e3 – 1e5"),
    (f64::INFINITY, "κ ≥ 1e5"),
];

fn v3(r: &Row, name: &str) -> Vec3 {
    Vec3::from(r.a3(name))
}

#[test]
fn vmf_ring_pdf_and_sample_are_within_their_bound_over_the_domain() {
    let table = Table::load("VMF_RING_SWEEP_DIR", "reference/golden/sweep", "vmf_ring");
    check_size("VMF_RING_SWEEP_DIR", &table, MIN_QUERIES);
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    let mut names = Vec::new();
    for f in ["pdf", "sample"] {
        for (_, b) in BANDS {
            names.push(&*Box::leak(format!("{f}, {b}").into_boxed_str()));
        }
    }
    for r in table.rows() {
        let t = Vec2::new(r.f("t_x"), r.f("t_y"));
        let kappa = r.f("kappa");
        let (wo, wi) = (v3(&r, "wo"), v3(&r, "wi"));
        let u = Vec2::new(r.f("u_x"), r.f("u_y"));
        let band = BANDS
            .iter()
            .position(|(hi, _)| f64::from(kappa) < *hi)
            .unwrap();
        let p = vmf_ring_pdf(t, kappa, wo, wi);
        let (p_ref, p_kappa) = (r.d("pdf_ref"), r.d("pdf_kappa"));
        let err = rel(p, p_ref);
        let err = if err.is_nan() { f64::INFINITY } else { err };
        stats
            .entry(((0, band), names[band]))
            .or_default()
            .add(err, p_kappa, || {
                format!("kernel {p:e} exact {p_ref:e} κ {p_kappa:e}: {}", r.text())
            });
        let exact = [r.d("sample_x"), r.d("sample_y"), r.d("sample_z")];
        let width = (1.0 / f64::from(kappa).sqrt()).min(1.0);
        let got = vmf_ring_sample(t, kappa, wo, r.f("u_ring"), u);
        let err = got.map_or(f64::INFINITY, |d| {
            angle(d.to_array().map(f64::from), exact) / width
        });
        let err = if err.is_nan() { f64::INFINITY } else { err };
        let s_kappa = r.d("sample_kappa");
        stats
            .entry(((1, band), names[BANDS.len() + band]))
            .or_default()
            .add(err, s_kappa, || {
                format!(
                    "kernel {got:?} exact {exact:?} err {err:e} κ {s_kappa:e}: {}",
                    r.text()
                )
            });
    }
    let bad = report(&stats, 18);
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
