//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! Samples/s of the scratch models' one-dimensional sampling lobes (`bsdf::lobe1d`): each
//! kind on the intervals the disk-product lobes use (a chord of the unit disk around the
//! centre, scales 1e-3 – 1) and on narrow intervals (width 1e-3 of the scale, up to 3
//! scales off the centre), where the inverse CDF refines by Newton's method. And Werner
//! §5's von Mises–Fisher ring (`bsdf::lobes::vmf_ring_sample`, `vmf_ring_pdf`) at
//! concentrations 1e-5 – 1e7 (log-uniform), and the disk lobes (`bsdf::lobes::DiskLobe`:
//! the base Gaussian², scales 4e-4 – 0.1; a scratch's logistic × Cauchy), directions above
//! the surface at random.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use scratchwave_benches::Rng;
use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use scratchwave_kernel::bsdf::lobes::{DiskLobe, vmf_ring_pdf, vmf_ring_sample};
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

/// A direction above the surface, cosθ uniform in [0.005, 1].
fn above(next: &mut impl FnMut() -> f32) -> Vec3 {
    let z = 0.005 + 0.995 * next();
    let phi = std::f32::consts::TAU * next();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// `n` (tangent, κ, wo, wi, u_ring, u) draws from a fixed seed.
#[allow(clippy::type_complexity)]
fn ring_cases(n: usize) -> Vec<(Vec2, f32, Vec3, Vec3, f32, Vec2)> {
    let mut r = Rng::new(23);
    let mut next = move || r.next_f32();
    (0..n)
        .map(|_| {
            let phi = std::f32::consts::TAU * next();
            let t = Vec2::new(phi.cos(), phi.sin());
            let kappa = 10f32.powf(-5.0 + 12.0 * next());
            let (wo, wi) = (above(&mut next), above(&mut next));
            (t, kappa, wo, wi, next(), Vec2::new(next(), next()))
        })
        .collect()
}

fn vmf_ring(c: &mut Criterion) {
    let mut g = c.benchmark_group("vmf_ring");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    let n = 4096;
    g.throughput(Throughput::Elements(n as u64));
    let cs = ring_cases(n);
    g.bench_function("sample", |bench| {
        bench.iter(|| {
            let mut acc = 0.0f32;
            for (t, k, wo, _, ur, u) in &cs {
                acc += vmf_ring_sample(*t, *k, *wo, *ur, *u).map_or(0.0, |d| d.z);
            }
            black_box(acc)
        })
    });
    g.bench_function("pdf", |bench| {
        bench.iter(|| {
            let mut acc = 0.0f32;
            for (t, k, wo, wi, _, _) in &cs {
                acc += vmf_ring_pdf(*t, *k, *wo, *wi);
            }
            black_box(acc)
        })
    });
    g.finish();
}

/// `n` (lobe, wo, wi, u) draws from a fixed seed: base lobes or scratch lobes.
fn disk_cases(scratch: bool, n: usize) -> Vec<(DiskLobe, Vec3, Vec3, Vec2)> {
    let mut r = Rng::new(29);
    let mut next = move || r.next_f32();
    (0..n)
        .map(|_| {
            let lobe = if scratch {
                let phi = std::f32::consts::TAU * next();
                DiskLobe {
                    e1: Vec2::new(phi.cos(), phi.sin()),
                    l1: Lobe1::single(Lobe1Kind::Logistic, 0.0, 10f32.powf(-3.7 + 5.7 * next())),
                    l2: Lobe1::single(Lobe1Kind::Cauchy, 0.0, 10f32.powf(-2.6 + 3.0 * next())),
                }
            } else {
                let l = Lobe1::single(Lobe1Kind::Gaussian, 0.0, 10f32.powf(-3.4 + 2.4 * next()));
                DiskLobe {
                    e1: Vec2::X,
                    l1: l,
                    l2: l,
                }
            };
            let (wo, wi) = (above(&mut next), above(&mut next));
            (lobe, wo, wi, Vec2::new(next(), next()))
        })
        .collect()
}

fn disk_lobe(c: &mut Criterion) {
    let mut g = c.benchmark_group("disk_lobe");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    let n = 4096;
    g.throughput(Throughput::Elements(n as u64));
    for (name, scratch) in [("base", false), ("scratch", true)] {
        let cs = disk_cases(scratch, n);
        g.bench_with_input(BenchmarkId::new("sample", name), &cs, |bench, cs| {
            bench.iter(|| {
                let mut acc = 0.0f32;
                for (l, wo, _, u) in cs {
                    acc += l.sample(*wo, *u).map_or(0.0, |d| d.z);
                }
                black_box(acc)
            })
        });
        g.bench_with_input(BenchmarkId::new("pdf", name), &cs, |bench, cs| {
            bench.iter(|| {
                let mut acc = 0.0f32;
                for (l, wo, wi, _) in cs {
                    acc += l.pdf(*wo, *wi);
                }
                black_box(acc)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, lobes, vmf_ring, disk_lobe);
criterion_main!(benches);
