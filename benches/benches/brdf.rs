//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! BRDF evaluations/s, coherent (Werner) and incoherent (Velinov), with 1, 10 and 100
//! scratches in the window, on the scalar, SIMD (one thread) and SIMD + rayon paths; and
//! (group `brdf_window`) Werner with the coherence window across the grooves frozen and
//! exact (issue #21), scalar and SIMD on one thread.
//! `python3 benches/report.py` turns criterion's output into the README's ratio table.

use criterion::measurement::WallTime;
use criterion::{
    BenchmarkGroup, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main,
};
use scratchwave_benches::{queries_near_specular, scratches_in_window, werner_window_params};
use scratchwave_cpu::{Backend, evaluate_table};
use scratchwave_kernel::scratch::Window;
use scratchwave_kernel::table::{Model, TableParams, TableQuery};
use std::time::Duration;

/// A group of `queries.len()` evaluations per iteration, ten 2-s samples.
fn group<'a>(
    c: &'a mut Criterion,
    name: &str,
    queries: &[TableQuery],
) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(queries.len() as u64));
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    g
}

fn brdf(c: &mut Criterion) {
    let queries = queries_near_specular(4096, 7);
    for model in [Model::Werner, Model::Velinov] {
        let mut g = group(c, &format!("brdf_{model:?}").to_lowercase(), &queries);
        for n in [1usize, 10, 100] {
            let scratches = scratches_in_window(n, 10.0, n as u64);
            let params = TableParams {
                model: model as u32,
                sigma_um: 10.0,
                ..TableParams::default()
            };
            for (label, b) in [
                ("scalar", Backend::Scalar),
                ("simd", Backend::SimdSingleThread),
                ("simd+rayon", Backend::Simd),
            ] {
                g.bench_with_input(BenchmarkId::new(label, n), &n, |bench, _| {
                    bench.iter(|| evaluate_table(b, &params, &scratches, &queries))
                });
            }
        }
        g.finish();
    }
}

fn brdf_window(c: &mut Criterion) {
    let queries = queries_near_specular(4096, 7);
    let mut g = group(c, "brdf_window", &queries);
    for n in [1usize, 10, 100] {
        let scratches = scratches_in_window(n, 10.0, n as u64);
        for (backend, b) in [
            ("scalar", Backend::Scalar),
            ("simd", Backend::SimdSingleThread),
        ] {
            for (window, w) in [("frozen", Window::Frozen), ("exact", Window::Exact)] {
                let params = werner_window_params(w);
                let id = BenchmarkId::new(format!("{backend}_{window}"), n);
                g.bench_with_input(id, &n, |bench, _| {
                    bench.iter(|| evaluate_table(b, &params, &scratches, &queries))
                });
            }
        }
    }
    g.finish();
}

criterion_group!(benches, brdf, brdf_window);
criterion_main!(benches);
