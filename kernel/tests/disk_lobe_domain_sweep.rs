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

use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use scratchwave_kernel::bsdf::lobes::DiskLobe;
use std::collections::BTreeMap;
use sweep_common::{Row, Stat, Table, angle, check_size, rel, report};

/// The committed subset's size (the test refuses fewer).
const MIN_QUERIES: usize = 1500;

fn lobe(r: &Row, name: &str) -> Lobe1 {
    let f = |c: &str, j: usize| r.f(&format!("{name}_{c}{j}"));
    Lobe1 {
        kind: Lobe1Kind::from_u32(r.u(&format!("{name}_kind"))),
        count: r.u(&format!("{name}_count")),
        mu: [f("mu", 0), f("mu", 1), f("mu", 2)],
        scale: [f("s", 0), f("s", 1), f("s", 2)],
        weight: [f("w", 0), f("w", 1), f("w", 2)],
    }
}

/// The lobes' angular size: their smallest scale, capped at 1.
fn width(l: &DiskLobe) -> f64 {
    let min = |l: &Lobe1| {
        l.scale[..l.count as usize]
            .iter()
            .fold(f64::INFINITY, |m, s| m.min(f64::from(*s)))
    };
    min(&l.l1).min(min(&l.l2)).min(1.0)
}

#[test]
fn disk_lobe_pdf_and_sample_are_within_their_bound_over_the_domain() {
    let table = Table::load("DISK_LOBE_SWEEP_DIR", "reference/golden/sweep", "disk_lobe");
    check_size("DISK_LOBE_SWEEP_DIR", &table, MIN_QUERIES);
    let names = [
        ["pdf, base (Gaussian²)", "sample, base (Gaussian²)"],
        [
            "pdf, scratch (logistic × Cauchy)",
            "sample, scratch (logistic × Cauchy)",
        ],
    ];
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    for r in table.rows() {
        let l = DiskLobe {
            e1: Vec2::new(r.f("e1_x"), r.f("e1_y")),
            l1: lobe(&r, "l1"),
            l2: lobe(&r, "l2"),
        };
        let group = usize::from(l.l1.kind != Lobe1Kind::Gaussian);
        let wo = Vec3::from(r.a3("wo"));
        let wi = Vec3::from(r.a3("wi"));
        let u = Vec2::new(r.f("u_x"), r.f("u_y"));
        let p = l.pdf(wo, wi);
        let (p_ref, p_kappa) = (r.d("pdf_ref"), r.d("pdf_kappa"));
        let err = rel(p, p_ref);
        let err = if err.is_nan() { f64::INFINITY } else { err };
        stats
            .entry(((group, 0), names[group][0]))
            .or_default()
            .add(err, p_kappa, || {
                format!("kernel {p:e} exact {p_ref:e} κ {p_kappa:e}: {}", r.text())
            });
        let exact = [r.d("sample_x"), r.d("sample_y"), r.d("sample_z")];
        let got = l.sample(wo, u);
        let err = got.map_or(f64::INFINITY, |d| {
            angle(d.to_array().map(f64::from), exact) / width(&l)
        });
        let err = if err.is_nan() { f64::INFINITY } else { err };
        let s_kappa = r.d("sample_kappa");
        stats
            .entry(((group, 1), names[group][1]))
            .or_default()
            .add(err, s_kappa, || {
                format!(
                    "kernel {got:?} exact {exact:?} err {err:e} κ {s_kappa:e}: {}",
                    r.text()
                )
            });
    }
    let bad = report(&stats, 35);
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
