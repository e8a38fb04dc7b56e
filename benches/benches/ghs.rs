//! GHS BRDF throughput: evaluations/s and samples/s, scalar vs SIMD (single thread) vs
//! SIMD + rayon. Evaluation runs through `scratchwave_cpu::ghs::evaluate_ghs` (batches of 8
//! lanes on the SIMD backends), sampling through `scratchwave_cpu::parallel::map`.
//!
//! `cargo bench -p scratchwave-benches --bench ghs`
#![allow(missing_docs)] // criterion's macros generate undocumented public items

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use scratchwave_cpu::Backend;
use scratchwave_cpu::ghs::{GhsQuery, evaluate_ghs};
use scratchwave_cpu::parallel::map;
use scratchwave_kernel::ghs::{self, GhsParams, presets};
use scratchwave_kernel::glam::{Vec2, Vec3};
use scratchwave_kernel::sampling::ghs as gs;
use std::hint::black_box;

const N: usize = 16_384;

fn queries() -> Vec<(Vec3, Vec3, [f32; 3])> {
    let mut s = 0x9e37_79b9u32;
    let mut f = move || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        (s >> 8) as f32 / 16_777_216.0
    };
    (0..N)
        .map(|_| {
            let (ti, pi, to, po) = (
                f() * 1.5,
                f() * std::f32::consts::TAU,
                f() * 1.5,
                f() * std::f32::consts::TAU,
            );
            let wi = Vec3::new(ti.sin() * pi.cos(), ti.sin() * pi.sin(), ti.cos());
            let wo = Vec3::new(to.sin() * po.cos(), to.sin() * po.sin(), to.cos());
            (wi, wo, [f(), f(), f()])
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let q = queries();
    let materials: [(&str, GhsParams); 2] = [
        (
            "rough-gold",
            presets::channel(presets::ROUGH_METAL, &presets::GOLD, 1),
        ),
        ("plastic", presets::GLOSSY_PLASTIC),
    ];
    let backends = [
        ("scalar", Backend::Scalar),
        ("simd-1t", Backend::SimdSingleThread),
        ("simd-rayon", Backend::Simd),
    ];
    let eval_q: Vec<GhsQuery> = q
        .iter()
        .map(|&(wi, wo, _)| GhsQuery {
            wi,
            wo,
            lambda_um: 0.526,
        })
        .collect();
    for (mname, p) in materials {
        let mut g = c.benchmark_group(format!("ghs-eval/{mname}"));
        g.throughput(Throughput::Elements(N as u64));
        g.sample_size(10);
        for (bname, b) in backends {
            g.bench_function(bname, |bch| {
                bch.iter(|| evaluate_ghs(b, black_box(&p), &eval_q))
            });
        }
        // the same kernel source one query at a time but compiled for AVX2 + FMA (what
        // `simd-1t` was before the lane path: code generation alone)
        g.bench_function("avx2-codegen-1t", |bch| {
            bch.iter(|| {
                map(Backend::SimdSingleThread, &q, |&(wi, wo, _)| {
                    ghs::evaluate(black_box(&p), wi, wo, 0.526)
                })
            })
        });
        // the same with the material prepared once and σ_rel²(θi) hoisted (a renderer's
        // per-shading-point work), to show the per-direction cost
        let prepared = ghs::Ghs::new(&p, 0.526);
        let srel: Vec<f32> = q
            .iter()
            .map(|(wi, _, _)| prepared.sigma_rel_sq(*wi))
            .collect();
        let qi: Vec<(Vec3, Vec3, f32)> = q
            .iter()
            .zip(&srel)
            .map(|(&(a, b, _), &s)| (a, b, s))
            .collect();
        g.bench_function("scalar-hoisted", |bch| {
            bch.iter(|| {
                map(Backend::Scalar, &qi, |&(wi, wo, s)| {
                    black_box(&prepared).eval_with_sigma_rel(wi, wo, s)
                })
            })
        });
        g.finish();
        let mut g = c.benchmark_group(format!("ghs-sample/{mname}"));
        g.throughput(Throughput::Elements(N as u64));
        g.sample_size(10);
        for (bname, b) in backends {
            g.bench_function(bname, |bch| {
                bch.iter(|| {
                    map(b, &q, |&(wi, _, u)| {
                        gs::sample(black_box(&p), wi, u[0], Vec2::new(u[1], u[2]), 0.526)
                            .map_or(0.0, |s| s.weight)
                    })
                })
            });
        }
        g.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
