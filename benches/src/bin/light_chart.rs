//! Error against evaluation cost of the area-light integrals (the project's first
//! speed-vs-accuracy chart).
//!
//! `cargo run -p scratchwave-benches --release --bin light_chart [-- CASES [SEED]]`
//! (defaults 200, 5) writes `docs/lights/{sweep.csv,methods.md,error_vs_cost.svg,
//! error_vs_size.svg}` and
//! prints the summary tables of `docs/lights.md`.
//!
//! Cases: the seeded sweep of `scratchwave_testkit::light_configs` (spheres with asin/atan cones
//! and jittered 3–8-gons, α 0.05–0.6 rad, centre elevation from −0.7α (partly below the
//! horizon) to 1.5 rad, distances 1–100, all scratch orientations, λ 380–780 nm, W 0.2–5 µm,
//! infinite scratch, σ = 10 µm), each with the band crossing the light. Error: |value/ref − 1|
//! against the adaptive reference (its own estimate ≤ 1e-4 relative; cases it cannot settle
//! are dropped and counted). Cost: single-thread ns per query on this machine (minimum of 7 runs: the machine is shared).

use rayon::prelude::*;
use scratchwave_benches::svg::{Series, loglog};
use scratchwave_kernel::lights::SiMode;
use scratchwave_testkit::light_configs::{LightCase, Rng, SweepRanges, random_case};
use scratchwave_testkit::light_mc::light_mc;
use scratchwave_testkit::light_reference::light_reference_budget;
use std::fmt::Write;
use std::time::Instant;

const METHODS: [(SiMode, u32, &str, &str); 9] = [
    (SiMode::Exact, 1, "Eq. 27, exact Si", "#1f77b4"),
    (SiMode::Velinov, 1, "Eq. 27, Eq. 29 Si", "#d62728"),
    (SiMode::Fast, 1, "Eq. 27, fast Si", "#2ca02c"),
    (SiMode::Exact, 3, "3 bands, exact Si", "#9467bd"),
    (SiMode::Fast, 3, "3 bands, fast Si", "#8c564b"),
    (SiMode::Velinov, 3, "3 bands, Eq. 29 Si", "#e377c2"),
    (SiMode::Exact, 5, "5 bands, exact Si", "#17becf"),
    (SiMode::Exact, 20, "extent rule, exact Si", "#bcbd22"),
    (SiMode::Fast, 20, "extent rule, fast Si", "#7f7f7f"),
];
/// Index in [`METHODS`] of the extent rule with the exact Si.
const EXTENT: usize = 7;
const MC_N: [usize; 7] = [16, 64, 256, 1024, 4096, 16384, 65536];

fn closed(c: &LightCase, si: SiMode, bands: u32) -> f64 {
    f64::from(c.closed_form(si, bands))
}

struct Stats {
    median: f64,
    p90: f64,
    p99: f64,
    max: f64,
    within_1pct: f64,
}

fn stats(errs: &[f64]) -> Stats {
    let mut e = errs.to_vec();
    e.sort_by(f64::total_cmp);
    let q = |f: f64| e[((e.len() - 1) as f64 * f).round() as usize];
    Stats {
        median: q(0.5),
        p90: q(0.9),
        p99: q(0.99),
        max: q(1.0),
        within_1pct: e.iter().filter(|x| **x <= 0.01).count() as f64 / e.len() as f64,
    }
}

/// A named filter over cases.
type Subset = Box<dyn Fn(&LightCase) -> bool>;

/// The fastest of 7 runs of `f` (ns): the machine is shared, the minimum is the cost.
fn min_time<F: FnMut()>(mut f: F) -> f64 {
    (0..7)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_nanos() as f64
        })
        .fold(f64::MAX, f64::min)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(200);
    let seed: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(5);
    let ranges = SweepRanges::default();
    let mut rng = Rng::new(seed);
    let cases: Vec<LightCase> = (0..n).map(|_| random_case(&mut rng, &ranges, 1)).collect();
    let t0 = Instant::now();
    let refs: Vec<_> = cases
        .par_iter()
        .map(|c| light_reference_budget(&c.params, &c.query, &c.scratch, 1e-5, 1500))
        .collect();
    eprintln!("references: {:.1} s", t0.elapsed().as_secs_f64());
    let kept: Vec<(LightCase, f64, f64)> = cases
        .iter()
        .zip(&refs)
        .filter(|(_, r)| r.value > 0.0 && r.err <= 1e-4 * r.value)
        .map(|(c, r)| (*c, r.value, r.err))
        .collect();
    let dropped = n - kept.len();
    let m = kept.len();

    // Closed forms: errors and single-thread cost.
    let mut summary = String::new();
    let mut series = Vec::new();
    let mut per_case: Vec<Vec<f64>> = vec![Vec::new(); m];
    let _ = writeln!(
        summary,
        "| method | ns/query | median | p90 | p99 | max | ≤ 1 % |\n|---|---|---|---|---|---|---|"
    );
    let mut row = |label: &str, ns: f64, s: &Stats| {
        let _ = writeln!(
            summary,
            "| {label} | {ns:.0} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.1} % |",
            s.median,
            s.p90,
            s.p99,
            s.max,
            100.0 * s.within_1pct
        );
    };
    let mut method_errs = Vec::new();
    for (si, bands, label, color) in METHODS {
        let errs: Vec<f64> = kept
            .iter()
            .map(|(c, r, _)| (closed(c, si, bands) / r - 1.0).abs())
            .collect();
        let ns = min_time(|| {
            let mut sink = 0.0;
            for (c, _, _) in &kept {
                sink += closed(c, si, bands);
            }
            std::hint::black_box(sink);
        }) / m as f64;
        let s = stats(&errs);
        row(label, ns, &s);
        series.push(Series {
            label: label.into(),
            color: color.into(),
            points: vec![(ns, s.median.max(1e-8), s.p90.max(1e-8), s.max.max(1e-8))],
            line: false,
        });
        for (i, e) in errs.iter().enumerate() {
            per_case[i].push(*e);
        }
        method_errs.push(errs);
    }
    // Monte Carlo with N light samples.
    let mut mc_points = Vec::new();
    for nmc in MC_N {
        let errs: Vec<f64> = kept
            .iter()
            .enumerate()
            .map(|(i, (c, r, _))| {
                let mut rng = Rng::new(1000 + i as u64);
                (light_mc(&c.params, &c.query, &c.scratch, nmc, &mut rng) / r - 1.0).abs()
            })
            .collect();
        // Cost on the first 16 cases (MC cost does not depend on the case much).
        let sub = &kept[..m.min(16)];
        let ns = min_time(|| {
            let mut rng = Rng::new(7);
            let mut sink = 0.0;
            for (c, _, _) in sub {
                sink += light_mc(&c.params, &c.query, &c.scratch, nmc, &mut rng);
            }
            std::hint::black_box(sink);
        }) / sub.len() as f64;
        let s = stats(&errs);
        row(&format!("Monte Carlo, N = {nmc}"), ns, &s);
        mc_points.push((ns, s.median, s.p90, s.max));
        for (i, e) in errs.iter().enumerate() {
            per_case[i].push(*e);
        }
    }
    series.push(Series {
        label: "Monte Carlo, N = 16…65536".into(),
        color: "#7f7f7f".into(),
        points: mc_points,
        line: true,
    });

    // Spheres vs polygons, partly below the horizon.
    let mut split = String::from(
        "| subset | n | Eq. 27 exact Si: median / p90 / max | extent rule exact Si: median / p90 / max |\n|---|---|---|---|\n",
    );
    let subsets: [(&str, Subset); 4] = [
        ("spheres", Box::new(|c: &LightCase| c.meta.vertices == 0)),
        ("polygons", Box::new(|c: &LightCase| c.meta.vertices > 0)),
        ("α ≥ 0.25", Box::new(|c: &LightCase| c.meta.alpha >= 0.25)),
        (
            "partly below horizon",
            Box::new(|c: &LightCase| c.meta.elevation < c.meta.alpha),
        ),
    ];
    for (name, f) in &subsets {
        let idx: Vec<usize> = (0..m).filter(|&i| f(&kept[i].0)).collect();
        if idx.is_empty() {
            continue;
        }
        let pick = |k: usize| stats(&idx.iter().map(|&i| method_errs[k][i]).collect::<Vec<_>>());
        let (a, b) = (pick(0), pick(EXTENT));
        let _ = writeln!(
            split,
            "| {name} | {} | {:.1e} / {:.1e} / {:.1e} | {:.1e} / {:.1e} / {:.1e} |",
            idx.len(),
            a.median,
            a.p90,
            a.max,
            b.median,
            b.p90,
            b.max
        );
    }
    // Worst cases of Eq. 27, the 3-band rule and the extent rule (exact Si).
    let mut worst = String::from(
        "| method | rel. error | kind | α (rad) | elevation (rad) | scratch angle (rad) |\n|---|---|---|---|---|---|\n",
    );
    for k in [0usize, 3, EXTENT] {
        let mut idx: Vec<usize> = (0..m).collect();
        idx.sort_by(|&a, &b| method_errs[k][b].total_cmp(&method_errs[k][a]));
        for &i in idx.iter().take(5) {
            let c = &kept[i].0;
            let signed = closed(c, METHODS[k].0, METHODS[k].1) / kept[i].1 - 1.0;
            let kind = if c.meta.vertices == 0 {
                "sphere".to_string()
            } else {
                format!("{}-gon", c.meta.vertices)
            };
            let _ = writeln!(
                worst,
                "| {} | {signed:+.2e} | {kind} | {:.3} | {:+.3} | {:.2} |",
                METHODS[k].2, c.meta.alpha, c.meta.elevation, c.meta.scratch_angle
            );
        }
    }

    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/lights");
    std::fs::create_dir_all(&dir).expect("create docs/lights");
    let mut csv =
        String::from("kind,vertices,alpha,elevation,scratch_angle,reference,reference_err");
    for (_, _, label, _) in METHODS {
        csv += &format!(",\"{label}\"");
    }
    for nmc in MC_N {
        csv += &format!(",MC {nmc}");
    }
    csv.push('\n');
    for (i, (c, r, e)) in kept.iter().enumerate() {
        let kind = if c.meta.vertices == 0 {
            "sphere"
        } else {
            "polygon"
        };
        csv += &format!(
            "{kind},{},{:.5},{:.5},{:.4},{r:.9e},{e:.2e}",
            c.meta.vertices, c.meta.alpha, c.meta.elevation, c.meta.scratch_angle
        );
        for v in &per_case[i] {
            csv += &format!(",{v:.3e}");
        }
        csv.push('\n');
    }
    std::fs::write(dir.join("sweep.csv"), csv).expect("write sweep.csv");
    std::fs::write(
        dir.join("methods.md"),
        format!("{summary}\n{split}\n{worst}"),
    )
    .expect("write methods.md");
    let svg = loglog(
        &format!("Area-light integral: error vs cost ({m} configurations)"),
        "cost per query (ns, one core)",
        "relative error vs adaptive reference",
        &series,
    );
    std::fs::write(dir.join("error_vs_cost.svg"), svg).expect("write svg");
    // Where the band model fails: per-case error against the light's angular radius.
    let scatter = |k: usize, color: &str| Series {
        label: METHODS[k].2.into(),
        color: color.into(),
        points: (0..m)
            .map(|i| {
                let e = method_errs[k][i].max(1e-8);
                (kept[i].0.meta.alpha, e, e, e)
            })
            .collect(),
        line: false,
    };
    let svg = loglog(
        "Per-configuration error vs light size (σ = 10 µm)",
        "angular radius α of the light (rad)",
        "relative error vs adaptive reference",
        &[scatter(0, "#1f77b4"), scatter(3, "#9467bd")],
    );
    std::fs::write(dir.join("error_vs_size.svg"), svg).expect("write svg");
    println!(
        "{m} cases ({dropped} dropped: reference unsettled), seed {seed}\n\n{summary}\n{split}\n{worst}"
    );
}
