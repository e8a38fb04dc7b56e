//! (criterion's macros generate undocumented items)
#![allow(missing_docs)]
//! Footprint averages/s by method: Velinov Eq. 15, Eq. 16 (π restored) and the accurate
//! quadrature, over ellipses from A_P/A_C = 0.01 to 100 (the cost side of
//! `benches/footprint_chart.py`). The accurate quadrature twice: `accurate` is the kernel's
//! default (each panel's 8 nodes in one `Lanes<8>` on the CPU), `accurate-one-node` the same
//! formula one node at a time (what SPIR-V runs), so their ratio is the lanes' speed-up.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use scratchwave_benches::Rng;
use scratchwave_kernel::footprint::{
    Ellipse, Nodes, eta_p_accurate, eta_p_accurate_by, eta_p_eq15, eta_p_eq16,
};
use scratchwave_kernel::scratch::{Profile, Scratch};
use std::hint::black_box;
use std::time::Duration;

fn footprint(c: &mut Criterion) {
    let sigma = 10.0f32;
    let mut r = Rng::new(11);
    let cases: Vec<(Scratch, Ellipse)> = (0..1024)
        .map(|_| {
            let a = std::f64::consts::TAU * f64::from(r.next_f32());
            let h = [30.0, 300.0, 5000.0][(r.next_f32() * 3.0) as usize % 3];
            let s = Scratch::from_endpoints(
                [-h * a.cos(), -h * a.sin()],
                [h * a.cos(), h * a.sin()],
                1.0,
                0.2,
                Profile::Rect,
            );
            let ratio = 10f32.powf(4.0 * r.next_f32() - 2.0); // A_P/A_C in [0.01, 100]
            let aspect = 1.0 + 7.0 * r.next_f32();
            let ab = ratio * sigma * sigma; // a1 a2 = ratio σ²
            let e = Ellipse {
                center: [sigma * (r.next_f32() - 0.5), sigma * (r.next_f32() - 0.5)],
                angle_rad: 3.0 * r.next_f32(),
                a1: (ab * aspect).sqrt(),
                a2: (ab / aspect).sqrt(),
                ..Ellipse::default()
            };
            (s, e)
        })
        .collect();
    let mut g = c.benchmark_group("footprint");
    g.throughput(Throughput::Elements(cases.len() as u64));
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("eq15", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|(s, e)| eta_p_eq15(black_box(s), e, sigma))
                .sum::<f32>()
        })
    });
    g.bench_function("eq16", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|(s, e)| eta_p_eq16(black_box(s), e, sigma))
                .sum::<f32>()
        })
    });
    g.bench_function("accurate", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|(s, e)| eta_p_accurate(black_box(s), e, sigma))
                .sum::<f32>()
        })
    });
    g.bench_function("accurate-one-node", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|(s, e)| eta_p_accurate_by(black_box(s), e, sigma, Nodes::OneAtATime))
                .sum::<f32>()
        })
    });
    g.finish();
}

criterion_group!(benches, footprint);
criterion_main!(benches);
