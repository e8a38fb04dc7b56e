//! The three sampling sweeps (`reference/lobe1_sweep.py`, `disk_lobe_sweep.py`,
//! `vmf_ring_sweep.py`): their inputs as kernel values and their acceptance checks, given
//! the evaluated results, so that the kernel's tests (CPU) and the SPIR-V backend's lobe
//! probe hold the same numbers to the same rule. Each `check_*` prints the per-group report
//! and returns one line per group with queries over the bound.

use super::{Row, Stat, Table, angle, rel, report};
use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use scratchwave_kernel::bsdf::lobes::DiskLobe;
use scratchwave_kernel::glam::{Vec2, Vec3};
use std::collections::BTreeMap;

/// The committed subsets' sizes (a test refuses fewer).
pub const LOBE1_MIN: usize = 3000;
pub const DISK_LOBE_MIN: usize = 1500;
pub const VMF_RING_MIN: usize = 2000;

/// The lobe of columns `{prefix}kind`, `{prefix}count`, `{prefix}mu0`, … `{prefix}w2`.
pub fn lobe1_of(r: &Row, prefix: &str) -> Lobe1 {
    let f = |c: &str, j: usize| r.f(&format!("{prefix}{c}{j}"));
    Lobe1 {
        kind: Lobe1Kind::from_u32(r.u(&format!("{prefix}kind"))),
        count: r.u(&format!("{prefix}count")),
        mu: [f("mu", 0), f("mu", 1), f("mu", 2)],
        scale: [f("s", 0), f("s", 1), f("s", 2)],
        weight: [f("w", 0), f("w", 1), f("w", 2)],
    }
}

/// A `lobe1` row's interval, density point and sampler input: `(a, b, x, u)`.
pub fn lobe1_args(r: &Row) -> (f32, f32, f32, f32) {
    (r.f("a"), r.f("b"), r.f("x"), r.f("u"))
}

/// A `disk_lobe` row's lobe, `wo`, `wi` and sampler input.
pub fn disk_lobe_of(r: &Row) -> (DiskLobe, Vec3, Vec3, Vec2) {
    let l = DiskLobe {
        e1: Vec2::new(r.f("e1_x"), r.f("e1_y")),
        l1: lobe1_of(r, "l1_"),
        l2: lobe1_of(r, "l2_"),
    };
    let wo = Vec3::from(r.a3("wo"));
    let wi = Vec3::from(r.a3("wi"));
    (l, wo, wi, Vec2::new(r.f("u_x"), r.f("u_y")))
}

/// A `vmf_ring` row's inputs.
pub struct VmfInputs {
    pub t: Vec2,
    pub kappa: f32,
    pub wo: Vec3,
    pub wi: Vec3,
    pub u_ring: f32,
    pub u: Vec2,
}

/// The inputs of a `vmf_ring` row.
pub fn vmf_ring_of(r: &Row) -> VmfInputs {
    VmfInputs {
        t: Vec2::new(r.f("t_x"), r.f("t_y")),
        kappa: r.f("kappa"),
        wo: Vec3::from(r.a3("wo")),
        wi: Vec3::from(r.a3("wi")),
        u_ring: r.f("u_ring"),
        u: Vec2::new(r.f("u_x"), r.f("u_y")),
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
pub const PDF_FLOOR: f64 = 1.0e-12;

const KIND_NAMES: [&str; 3] = ["logistic", "cauchy", "gaussian"];
const LOBE1_FUNCS: [&str; 3] = ["mass", "pdf", "sample"];

/// The `lobe1` family: `got(i, row)` is `[mass, pdf, sample]` of row `i` (a sampler's
/// `None` as NaN). Each relative, the density absolutely below [`PDF_FLOOR`]. With
/// `flushes_subnormals` (a device that flushes subnormal f32 to zero, as Vulkan allows and
/// lavapipe does) a density whose exact numerator `Σ w_j f_j(x)` is itself below the
/// smallest normal f32 may come out as 0: such zeros are accepted, counted and printed.
pub fn check_lobe1(
    table: &Table,
    flushes_subnormals: bool,
    mut got: impl FnMut(usize, &Row) -> [f32; 3],
) -> Vec<String> {
    let mut flushed = 0;
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    let mut names = Vec::new();
    for k in KIND_NAMES {
        for f in LOBE1_FUNCS {
            names.push(&*Box::leak(format!("{k} {f}").into_boxed_str()));
        }
    }
    for (row, r) in table.rows().enumerate() {
        let (a, b, _, _) = lobe1_args(&r);
        let got = got(row, &r);
        let kind = r.u("kind") as usize;
        let pdf_floor = PDF_FLOOR / (f64::from(b) - f64::from(a));
        for (i, f) in LOBE1_FUNCS.iter().enumerate() {
            let want = r.d(&format!("{f}_ref"));
            let kappa = r.d(&format!("{f}_kappa"));
            let is_flushed = i == 1
                && flushes_subnormals
                && got[i] == 0.0
                && want * r.d("mass_ref") < f64::from(f32::MIN_POSITIVE);
            flushed += usize::from(is_flushed);
            let err = if is_flushed {
                0.0
            } else if i == 1 && want < pdf_floor {
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
    if flushes_subnormals {
        println!("{flushed} densities 0 where their exact numerator is subnormal (flushed)");
    }
    report(&stats, 17)
}

/// The lobes' angular size: their smallest scale, capped at 1.
fn disk_width(l: &DiskLobe) -> f64 {
    let min = |l: &Lobe1| {
        l.scale[..l.count as usize]
            .iter()
            .fold(f64::INFINITY, |m, s| m.min(f64::from(*s)))
    };
    min(&l.l1).min(min(&l.l2)).min(1.0)
}

/// A pdf's relative error (NaN as infinite).
fn pdf_err(p: f32, want: f64) -> f64 {
    let err = rel(p, want);
    if err.is_nan() { f64::INFINITY } else { err }
}

/// A sampled direction's angle to the exact one over `width` (`None` or NaN as infinite).
fn sample_err(got: Option<Vec3>, exact: [f64; 3], width: f64) -> f64 {
    let err = got.map_or(f64::INFINITY, |d| {
        angle(d.to_array().map(f64::from), exact) / width
    });
    if err.is_nan() { f64::INFINITY } else { err }
}

/// The pdf and sample rows of one group.
fn add_pdf_and_sample<O: Ord>(
    stats: &mut BTreeMap<(O, &'static str), Stat>,
    keys: [(O, &'static str); 2],
    r: &Row,
    (p, s): (f32, Option<Vec3>),
    width: f64,
) {
    let [pdf_key, sample_key] = keys;
    let (p_ref, p_kappa) = (r.d("pdf_ref"), r.d("pdf_kappa"));
    stats
        .entry(pdf_key)
        .or_default()
        .add(pdf_err(p, p_ref), p_kappa, || {
            format!("kernel {p:e} exact {p_ref:e} κ {p_kappa:e}: {}", r.text())
        });
    let exact = [r.d("sample_x"), r.d("sample_y"), r.d("sample_z")];
    let err = sample_err(s, exact, width);
    let s_kappa = r.d("sample_kappa");
    stats.entry(sample_key).or_default().add(err, s_kappa, || {
        format!(
            "kernel {s:?} exact {exact:?} err {err:e} κ {s_kappa:e}: {}",
            r.text()
        )
    });
}

/// The `disk_lobe` family: `got(i, row)` is `(pdf(wo, wi), sample(wo, u))` of row `i`. The
/// pdf relative; the sample as its angle to the exact direction over the lobes' smallest
/// scale (capped at 1).
pub fn check_disk_lobe(
    table: &Table,
    mut got: impl FnMut(usize, &Row) -> (f32, Option<Vec3>),
) -> Vec<String> {
    let names = [
        ["pdf, base (Gaussian²)", "sample, base (Gaussian²)"],
        [
            "pdf, scratch (logistic × Cauchy)",
            "sample, scratch (logistic × Cauchy)",
        ],
    ];
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    for (row, r) in table.rows().enumerate() {
        let (l, ..) = disk_lobe_of(&r);
        let g = usize::from(l.l1.kind != Lobe1Kind::Gaussian);
        let keys = [((g, 0), names[g][0]), ((g, 1), names[g][1])];
        add_pdf_and_sample(&mut stats, keys, &r, got(row, &r), disk_width(&l));
    }
    report(&stats, 35)
}

/// The concentration bands the vMF report groups by (upper ends).
const VMF_BANDS: [(f64, &str); 4] = [
    (1.0, "κ < 1"),
    (1.0e3, "κ 1 – 1e3"),
    (1.0e5, "κ 1e3 – 1e5"),
    (f64::INFINITY, "κ ≥ 1e5"),
];

/// The `vmf_ring` family: `got(i, row)` is `(pdf(t, κ, wo, wi), sample(t, κ, wo, u_ring,
/// u))` of row `i`. The pdf relative; the sample as its angle to the exact direction over
/// the lobe's angular width `min(1, 1/√κ)`.
pub fn check_vmf_ring(
    table: &Table,
    mut got: impl FnMut(usize, &Row) -> (f32, Option<Vec3>),
) -> Vec<String> {
    let mut stats: BTreeMap<((usize, usize), &'static str), Stat> = BTreeMap::new();
    let mut names = Vec::new();
    for f in ["pdf", "sample"] {
        for (_, b) in VMF_BANDS {
            names.push(&*Box::leak(format!("{f}, {b}").into_boxed_str()));
        }
    }
    for (row, r) in table.rows().enumerate() {
        let kappa = r.f("kappa");
        let band = VMF_BANDS
            .iter()
            .position(|(hi, _)| f64::from(kappa) < *hi)
            .unwrap();
        let keys = [
            ((0, band), names[band]),
            ((1, band), names[VMF_BANDS.len() + band]),
        ];
        let width = (1.0 / f64::from(kappa).sqrt()).min(1.0);
        add_pdf_and_sample(&mut stats, keys, &r, got(row, &r), width);
    }
    report(&stats, 18)
}
