//! The error of Werner's two approximations against the exact heightfield integral
//! (issue #21), charted from the independent reference.
//!
//! `cargo run -p scratchwave-benches --release --bin exact_window_chart` reads
//! `reference/golden/heightfield.json` (`python3 reference/heightfield_golden.py`), evaluates
//! the kernel's Werner model (`table::evaluate`, frozen window, crossings summed) at every
//! case's directions and writes
//!
//! - `docs/exact_window/window_error.svg`: single 1 mm grooves, the kernel against the exact
//!   window, by W/σ, one series per distance of the groove from the window centre;
//! - `docs/exact_window/crossing_error.svg`: crossing pairs, the kernel and the reference's
//!   other two approximate variants against exact window + deepest cut, by crossing angle;
//! - `docs/exact_window/window_cost.svg`: the cost of `window: exact` per query relative to
//!   `frozen`, scalar and SIMD on one thread, by scratches in the window (measured here, in
//!   one run: the best of several timings of each);
//! - `docs/exact_window/crossing_cost.svg`: the cost of `crossings: deepest` per query
//!   relative to `summed` (both with the exact window), by crossing pairs in the window, and
//!   the time per crossing pair (measured here, in one run).
//!
//! The window chart also carries the kernel's `window: exact` (pooled over the distances),
//! the crossing chart the kernel's `window: exact, crossings: deepest`.
//! Prints the points as tables. Errors are `|value/exact − 1|` over the directions at
//! least 1e-3 of the case's peak, pooled over the cases of a point (profiles, incidences,
//! depths); each point shows their median, 90th percentile and maximum.

use scratchwave_benches::svg::{Extras, HLine, Series, loglog_with};
use scratchwave_benches::{queries_near_specular, scratches_in_window, werner_window_params};
use scratchwave_cpu::{Backend, evaluate_table};
use scratchwave_kernel::scratch::{Crossings, Profile, Scratch, Window};
use scratchwave_kernel::table::TableParams;
use scratchwave_testkit::heightfield::{Case, Golden, Kind, quantile, rel_errors};
use std::process::ExitCode;
use std::time::Instant;

const COLORS: [&str; 4] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
const OUT_DIR: &str = "docs/exact_window";

/// Median, 90th percentile and maximum of a pool of errors.
fn point(x: f64, errors: &[f64]) -> (f64, f64, f64, f64) {
    (
        x,
        quantile(errors, 0.5),
        quantile(errors, 0.9),
        quantile(errors, 1.0),
    )
}

/// Spreads the points of series `index` sideways by the factor `step` per series, so that
/// series sharing an x stay legible; the tables print the true x.
fn dodge(series: &mut [Series], step: f64) {
    for (index, s) in series.iter_mut().enumerate() {
        let factor = step.powi(index as i32);
        for p in &mut s.points {
            p.0 *= factor;
        }
    }
}

/// A 1e-3 reference line and the whisker legend followed by `notes`.
fn extras(notes: &[&str]) -> Extras {
    let mut all = vec![
        "dot: median, bar: 90th pct,",
        "dashed to tick: max",
        "series nudged sideways",
    ];
    all.extend_from_slice(notes);
    Extras {
        hlines: vec![HLine {
            y: 1e-3,
            label: "1e-3".into(),
            color: "#888".into(),
        }],
        notes: all.into_iter().map(String::from).collect(),
        ..Extras::default()
    }
}

/// The errors of `values` against the case's exact/deepest values.
fn errors(case: &Case, values: &[f64]) -> Vec<f64> {
    rel_errors(values, case.truth(), &vec![true; values.len()])
}

fn print_table(title: &str, x_name: &str, series: &[Series]) {
    println!("\n{title}\n| series | {x_name} | median | p90 | max |\n|---|---:|---:|---:|---:|");
    for s in series {
        for p in &s.points {
            println!(
                "| {} | {:.3} | {:.2e} | {:.2e} | {:.2e} |",
                s.label, p.0, p.1, p.2, p.3
            );
        }
    }
}

fn window_chart(golden: &Golden) -> String {
    let singles: Vec<&Case> = golden
        .cases
        .iter()
        .filter(|c| c.kind == Kind::Single { long: true })
        .collect();
    let mut offsets: Vec<f64> = singles.iter().map(|c| c.offset_sigma).collect();
    offsets.sort_by(f64::total_cmp);
    offsets.dedup();
    let mut widths: Vec<f64> = singles.iter().map(|c| c.w_over_sigma).collect();
    widths.sort_by(f64::total_cmp);
    widths.dedup();
    // One point per width: the kernel with `params` on the grooves that `keep` selects.
    let points = |params: &TableParams, keep: &dyn Fn(&Case) -> bool| -> Vec<_> {
        widths
            .iter()
            .map(|&w| {
                let pool: Vec<f64> = singles
                    .iter()
                    .filter(|c| c.w_over_sigma == w && keep(c))
                    .flat_map(|c| errors(c, &c.kernel(params, golden.material)))
                    .collect();
                point(w, &pool)
            })
            .collect()
    };
    let mut series: Vec<Series> = offsets
        .iter()
        .zip(COLORS)
        .map(|(&offset, color)| Series {
            label: format!("groove {offset}σ from the centre"),
            color: color.into(),
            line: true,
            points: points(&golden.params, &|c| c.offset_sigma == offset),
        })
        .collect();
    let mut exact_params = golden.params;
    exact_params.window = Window::Exact as u32;
    series.push(Series {
        label: "kernel, window: exact (all distances)".into(),
        color: COLORS[offsets.len().min(COLORS.len() - 1)].into(),
        line: true,
        points: points(&exact_params, &|_| true),
    });
    print_table(
        "Werner's frozen window (kernel) and the kernel's exact window vs the exact window, single 1 mm grooves",
        "W/σ",
        &series,
    );
    // Leftwards: the widest groove sits on the last decade's edge.
    dodge(&mut series, 0.96);
    let extras = extras(&[
        "pooled over rect and V grooves,",
        "θi 0/30/60/80°; directions",
        "≥ 1e-3 of each case's peak",
    ]);
    loglog_with(
        "Frozen and exact coherence window: error against the exact integral",
        "groove width W / σ",
        "relative error",
        &series,
        &extras,
    )
}

fn crossing_chart(golden: &Golden) -> String {
    let crossings: Vec<&Case> = golden
        .cases
        .iter()
        // the W/σ = 0.3 pairs the chart is titled for (not the wide ones at 360 nm)
        .filter(|c| matches!(c.kind, Kind::Crossing { .. }) && c.w_over_sigma == 0.3)
        .collect();
    let angle = |c: &Case| match c.kind {
        Kind::Crossing { angle_deg, .. } => angle_deg,
        Kind::Single { .. } => f64::NAN,
    };
    let mut angles: Vec<f64> = crossings.iter().map(|c| angle(c)).collect();
    angles.sort_by(|a, b| b.total_cmp(a));
    angles.dedup();
    let variants: [(&str, Option<&str>); 4] = [
        ("kernel: frozen, summed", None),
        ("exact window, summed", Some("exact_summed")),
        ("frozen window, deepest cut", Some("frozen_deepest")),
        ("kernel: exact window, deepest cut", Some("kernel")),
    ];
    let deepest = TableParams {
        window: Window::Exact as u32,
        crossings: Crossings::Deepest as u32,
        ..golden.params
    };
    let mut series: Vec<Series> = variants
        .iter()
        .zip(COLORS)
        .map(|((label, variant), color)| Series {
            label: (*label).into(),
            color: color.into(),
            line: true,
            points: angles
                .iter()
                .map(|&a| {
                    let pool: Vec<f64> = crossings
                        .iter()
                        .filter(|c| angle(c) == a)
                        .flat_map(|c| match variant {
                            None => errors(c, &c.kernel(&golden.params, golden.material)),
                            Some("kernel") => errors(c, &c.kernel(&deepest, golden.material)),
                            Some(v) => errors(c, c.variant(v).unwrap_or(&[])),
                        })
                        .collect();
                    // x: the overlap area relative to a right-angle crossing, 1/sin α.
                    point(1.0 / a.to_radians().sin(), &pool)
                })
                .collect(),
        })
        .collect();
    print_table(
        "Crossing pairs (W/σ = 0.3) vs exact window + deepest cut; x = 1/sin(angle): 90° → 1, 45° → 1.41, 10° → 5.76",
        "1/sin α",
        &series,
    );
    dodge(&mut series, 1.04);
    let extras = extras(&[
        "angles 90°, 45°, 10°; pooled",
        "over rect/V, equal/unequal",
        "depths, θi 0/30°",
    ]);
    loglog_with(
        "Two crossing grooves: error against exact window + deepest cut",
        "1 / sin(crossing angle)  (overlap area relative to 90°)",
        "relative error",
        &series,
        &extras,
    )
}

/// Seconds of the fastest of `repeats` evaluations of the query set.
fn best_time(repeats: usize, mut run: impl FnMut() -> Vec<f32>) -> f64 {
    (0..repeats)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(run());
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The best of three rounds of two timings, interleaved so that a change in the machine's
/// The two timed backends, and for each an empty line series labelled `"{backend}: {ratio}"`.
fn ratio_series(ratio: &str) -> ([(&'static str, Backend); 2], Vec<Series>) {
    let backends = [
        ("scalar", Backend::Scalar),
        ("SIMD, one thread", Backend::SimdSingleThread),
    ];
    let series = backends
        .iter()
        .zip(COLORS)
        .map(|((label, _), color)| Series {
            label: format!("{label}: {ratio}"),
            color: color.into(),
            line: true,
            points: Vec::new(),
        })
        .collect();
    (backends, series)
}

/// load touches both.
fn interleaved(mut a: impl FnMut() -> f64, mut b: impl FnMut() -> f64) -> (f64, f64) {
    let (mut ta, mut tb) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..3 {
        ta = ta.min(a());
        tb = tb.min(b());
    }
    (ta, tb)
}

/// `window: exact` per query over `frozen` (the criterion group `brdf_window`'s workload:
/// Werner, σ = 10 µm, 4 096 queries near the specular direction), by scratches in the window.
fn cost_chart() -> String {
    let queries = queries_near_specular(4096, 7);
    let (backends, mut series) = ratio_series("exact / frozen");
    for n in [1usize, 10, 100] {
        let scratches = scratches_in_window(n, 10.0, n as u64);
        for ((_, backend), s) in backends.iter().zip(&mut series) {
            let time = |window: Window| {
                let params = werner_window_params(window);
                best_time(7, || {
                    evaluate_table(*backend, &params, &scratches, &queries)
                })
            };
            let (frozen, exact) = interleaved(|| time(Window::Frozen), || time(Window::Exact));
            let ratio = exact / frozen;
            s.points.push((n as f64, ratio, ratio, ratio));
        }
    }
    println!("\nCost of window: exact per query relative to frozen (Werner, 4 096 queries)");
    println!("| backend | scratches in window | exact / frozen |\n|---|---:|---:|");
    for s in &series {
        for p in &s.points {
            println!("| {} | {} | {:.2} |", s.label, p.0, p.1);
        }
    }
    let extras = Extras {
        hlines: vec![HLine {
            y: 2.0,
            label: "2× (issue #21's target)".into(),
            color: "#888".into(),
        }],
        notes: vec![
            "Werner, σ = 10 µm, 4 096 queries".into(),
            "near the specular direction;".into(),
            "best of 21 timings each".into(),
        ],
        whiskers: false,
        y_headroom: 1.5,
        ..Extras::default()
    };
    loglog_with(
        "Cost of the exact across-groove window per query",
        "scratches in the coherence window",
        "time, exact / frozen",
        &series,
        &extras,
    )
}

/// `k` long grooves along x and `k` along y, 9 µm apart, centred on the queries' shading
/// points: `k²` crossing pairs in the window (σ = 10 µm), rect and V grooves alternating,
/// depths 0.2 and 0.1 µm.
fn crossing_grid(k: usize) -> Vec<Scratch> {
    let mut out = Vec::new();
    for i in 0..k {
        let c = (i as f32 - 0.5 * (k as f32 - 1.0)) * 9.0;
        let profile = if i % 2 == 0 {
            Profile::Rect
        } else {
            Profile::Triangle
        } as u32;
        for (center, tangent, depth) in [([0.0, c], [1.0, 0.0], 0.2), ([c, 0.0], [0.0, 1.0], 0.1)] {
            out.push(Scratch {
                center,
                tangent,
                half_len: 500.0,
                width: 3.0,
                depth,
                profile,
            });
        }
    }
    out
}

/// `crossings: deepest` per query over `summed` (both with the exact window, the model the
/// reference integrates), by crossing pairs in the window; also prints the time per pair.
fn crossing_cost_chart() -> String {
    let queries = queries_near_specular(1024, 11);
    let (backends, mut series) = ratio_series("deepest / summed");
    let mut per_pair = Vec::new();
    for k in [1usize, 3, 10] {
        let scratches = crossing_grid(k);
        for ((label, backend), s) in backends.iter().zip(&mut series) {
            let time = |crossings: Crossings| {
                let params = TableParams {
                    crossings: crossings as u32,
                    ..werner_window_params(Window::Exact)
                };
                best_time(5, || {
                    evaluate_table(*backend, &params, &scratches, &queries)
                })
            };
            let (summed, deepest) =
                interleaved(|| time(Crossings::Summed), || time(Crossings::Deepest));
            let pairs = (k * k) as f64;
            let ratio = deepest / summed;
            s.points.push((pairs, ratio, ratio, ratio));
            let us = (deepest - summed) / (queries.len() as f64 * pairs) * 1e6;
            per_pair.push((label.to_string(), k * k, summed, deepest, us));
        }
    }
    println!(
        "\nCost of crossings: deepest per query relative to summed (Werner, exact window, 1 024 queries)"
    );
    println!(
        "| backend | crossing pairs in window | summed µs/query | deepest µs/query | deepest / summed | µs per pair and query |\n|---|---:|---:|---:|---:|---:|"
    );
    for (label, pairs, summed, deepest, us) in &per_pair {
        let n = queries.len() as f64;
        println!(
            "| {label} | {pairs} | {:.2} | {:.2} | {:.2} | {us:.2} |",
            summed / n * 1e6,
            deepest / n * 1e6,
            deepest / summed
        );
    }
    let extras = Extras {
        notes: vec![
            "Werner, exact window, σ = 10 µm,".into(),
            "k × k crossing 3 µm grooves 9 µm apart,".into(),
            "1 024 queries; best of 15 timings".into(),
        ],
        whiskers: false,
        y_headroom: 1.5,
        ..Extras::default()
    };
    loglog_with(
        "Cost of cutting crossings once per query",
        "crossing pairs in the coherence window",
        "time, deepest / summed",
        &series,
        &extras,
    )
}

fn main() -> ExitCode {
    let golden = match Golden::load() {
        Ok(g) => g,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let dir = format!("{root}/{OUT_DIR}");
    let charts = [
        ("window_error.svg", window_chart(&golden)),
        ("crossing_error.svg", crossing_chart(&golden)),
        ("window_cost.svg", cost_chart()),
        ("crossing_cost.svg", crossing_cost_chart()),
    ];
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("error: creating {dir}: {e}");
        return ExitCode::FAILURE;
    }
    for (name, svg) in charts {
        let path = format!("{dir}/{name}");
        if let Err(e) = std::fs::write(&path, svg) {
            eprintln!("error: writing {path}: {e}");
            return ExitCode::FAILURE;
        }
        println!("wrote {OUT_DIR}/{name}");
    }
    ExitCode::SUCCESS
}
