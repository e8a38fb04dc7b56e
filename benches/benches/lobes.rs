//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! Samples/s of the scratch models' one-dimensional sampling lobes (`bsdf::lobe1d`): each
//! kind on the intervals the disk-product lobes use (a chord of the unit disk around the
//! centre, scales 1e-3 – 1) and on narrow intervals (width 1e-3 of the scale, up to 3
//! scales off the centre), where the inverse CDF refines by Newton's method.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use scratchwave_benches::Rng;
use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use std::hint::black_box;
use std::time::Duration;

/// `n` (lobe, u, a, b) draws from a fixed seed.
fn cases(kind: Lobe1Kind, narrow: bool, n: usize) -> Vec<(Lobe1, f32, f32, f32)> {
    let mut r = Rng::new(17);
    let mut next = move || r.next_f32();
    (0..n)
        .map(|_| {
            let scale = 10f32.powf(-3.0 + 3.0 * next());
            let lobe = Lobe1::single(kind, 0.0, scale);
            let (a, b) = if narrow {
                let c = scale * (6.0 * next() - 3.0);
                (c, c + 1e-3 * scale)
            } else {
                let c = 1.8 * next() - 0.9;
                (c - 1.0, c + 1.0)
            };
            (lobe, next(), a, b)
        })
        .collect()
}

fn lobes(c: &mut Criterion) {
    let mut g = c.benchmark_group("lobe1_sample");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    let n = 4096;
    g.throughput(Throughput::Elements(n as u64));
    for (name, kind) in [
        ("logistic", Lobe1Kind::Logistic),
        ("cauchy", Lobe1Kind::Cauchy),
        ("gaussian", Lobe1Kind::Gaussian),
    ] {
        for (interval, narrow) in [("chord", false), ("narrow", true)] {
            let cs = cases(kind, narrow, n);
            g.bench_with_input(BenchmarkId::new(name, interval), &cs, |bench, cs| {
                bench.iter(|| {
                    let mut acc = 0.0f32;
                    for (l, u, a, b) in cs {
                        acc += l.sample(*u, *a, *b).unwrap_or(0.0);
                    }
                    black_box(acc)
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, lobes);
criterion_main!(benches);
