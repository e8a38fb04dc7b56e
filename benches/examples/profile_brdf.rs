//! Runs the BRDF workload of `benches/brdf.rs` in a loop for profilers
//! (`perf record`, `valgrind --tool=callgrind`):
//! `cargo run --release -p scratchwave-benches --example profile_brdf -- [werner|velinov] [scratches] [repeats] [scalar|simd] [frozen|exact]`
//! (`simd`: the SIMD backend on one thread; `exact`: the exact across-groove window).

use scratchwave_benches::{queries_near_specular, scratches_in_window};
use scratchwave_cpu::{Backend, evaluate_table};
use scratchwave_kernel::scratch::Window;
use scratchwave_kernel::table::{Model, TableParams};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let model = if args.first().map(String::as_str) == Some("velinov") {
        Model::Velinov
    } else {
        Model::Werner
    };
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10);
    let repeats: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(20);
    let backend = if args.get(3).map(String::as_str) == Some("simd") {
        Backend::SimdSingleThread
    } else {
        Backend::Scalar
    };
    let window = if args.get(4).map(String::as_str) == Some("exact") {
        Window::Exact
    } else {
        Window::Frozen
    };
    let scratches = scratches_in_window(n, 10.0, n as u64);
    let queries = queries_near_specular(4096, 7);
    let params = TableParams {
        model: model as u32,
        sigma_um: 10.0,
        window: window as u32,
        ..TableParams::default()
    };
    let t = std::time::Instant::now();
    let mut sum = 0.0f64;
    for _ in 0..repeats {
        sum += evaluate_table(backend, &params, &scratches, &queries)
            .iter()
            .map(|v| f64::from(*v))
            .sum::<f64>();
    }
    let dt = t.elapsed().as_secs_f64();
    println!(
        "{model:?} n={n} {backend:?}: {:.0} evals/s (checksum {sum:.6e})",
        (repeats * queries.len()) as f64 / dt
    );
}
