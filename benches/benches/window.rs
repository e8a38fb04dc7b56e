//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! The cost of the exact across-groove window (issue #21) against Werner's frozen one:
//! `werner` evaluations/s with `window` frozen and exact, 1, 10 and 100 scratches in the
//! window (both profiles, alternating), scalar and SIMD on one thread. The workload is
//! `benches/brdf.rs`'s.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use scratchwave_benches::{queries_near_specular, scratches_in_window};
use scratchwave_cpu::{Backend, evaluate_table};
use scratchwave_kernel::scratch::Window;
use scratchwave_kernel::table::{Model, TableParams};
use std::time::Duration;

fn window(c: &mut Criterion) {
    let queries = queries_near_specular(4096, 7);
    let mut g = c.benchmark_group("window");
    g.throughput(Throughput::Elements(queries.len() as u64));
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for n in [1usize, 10, 100] {
        let scratches = scratches_in_window(n, 10.0, n as u64);
        for (backend_label, b) in [
            ("scalar", Backend::Scalar),
            ("simd", Backend::SimdSingleThread),
        ] {
            for (window_label, w) in [("frozen", Window::Frozen), ("exact", Window::Exact)] {
                let params = TableParams {
                    model: Model::Werner as u32,
                    sigma_um: 10.0,
                    window: w as u32,
                    ..TableParams::default()
                };
                let id = BenchmarkId::new(format!("{backend_label}_{window_label}"), n);
                g.bench_with_input(id, &n, |bench, _| {
                    bench.iter(|| evaluate_table(b, &params, &scratches, &queries))
                });
            }
        }
    }
    g.finish();
}

criterion_group!(benches, window);
criterion_main!(benches);
