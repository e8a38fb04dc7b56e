//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! Scratch-lookup queries/s ("every scratch within 6σ of x0") over 10^3…10^6 scratches at a
//! constant density (about 8 scratches in each window), BVH vs brute force.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec2;
use scratchwave_benches::Rng;
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::scratch::{Scratch, ScratchSet, ScratchSlice};
use std::time::Duration;

fn field(n: usize, extent: f32, r: &mut Rng) -> Vec<Scratch> {
    (0..n)
        .map(|_| {
            let c = [extent * r.next_f32(), extent * r.next_f32()];
            let a = std::f32::consts::TAU * r.next_f32();
            let h = 100.0 * r.next_f32();
            Scratch {
                center: c,
                tangent: [a.cos(), a.sin()],
                half_len: h,
                width: 1.0,
                depth: 0.2,
                ..Scratch::default()
            }
        })
        .collect()
}

fn count<S: ScratchSet>(s: &S, pts: &[Vec2]) -> usize {
    let mut k = 0;
    for p in pts {
        s.for_each_near(*p, 60.0, |_| k += 1);
    }
    k
}

fn lookup(c: &mut Criterion) {
    let mut g = c.benchmark_group("lookup");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let mut r = Rng::new(n as u64);
        let extent = (n as f32 * 2_000.0).sqrt(); // constant density
        let scratches = field(n, extent, &mut r);
        let pts: Vec<Vec2> = (0..1024)
            .map(|_| Vec2::new(extent * r.next_f32(), extent * r.next_f32()))
            .collect();
        let built = ScratchLookup::new(&scratches, 10.0);
        g.throughput(Throughput::Elements(pts.len() as u64));
        g.bench_with_input(BenchmarkId::new("bvh", n), &n, |b, _| {
            b.iter(|| count(&built.set(), &pts))
        });
        if n <= 100_000 {
            let slice = ScratchSlice {
                scratches: &scratches,
            };
            g.bench_with_input(BenchmarkId::new("brute", n), &n, |b, _| {
                b.iter(|| count(&slice, &pts))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, lookup);
criterion_main!(benches);
