//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! BRDF evaluations/s, coherent (Werner) and incoherent (Velinov), with 1, 10 and 100
//! scratches in the window, on the scalar, SIMD (one thread) and SIMD + rayon paths.
//! `python3 benches/report.py` turns criterion's output into the README's ratio table.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use scratchwave_benches::{queries_near_specular, scratches_in_window};
use scratchwave_cpu::{Backend, evaluate_table};
use scratchwave_kernel::table::{Model, TableParams};
use std::time::Duration;

fn brdf(c: &mut Criterion) {
    let queries = queries_near_specular(4096, 7);
    for model in [Model::Werner, Model::Velinov] {
        let mut g = c.benchmark_group(format!("brdf_{model:?}").to_lowercase());
        g.throughput(Throughput::Elements(queries.len() as u64));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_secs(2));
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

criterion_group!(benches, brdf);
criterion_main!(benches);
