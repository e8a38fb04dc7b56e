//! Timing of the closed-form area-light integrals (no criterion: it is not vendored here).
//!
//! `cargo bench -p scratchwave-benches --bench lights`: ns per query, single thread, for a
//! sphere and a 4-gon and a 16-gon, per Si method and band rule, over 4096 seeded views
//! (minimum of 9 passes).

use scratchwave_kernel::lights::{Light, SiMode};
use scratchwave_testkit::light_configs::{LightCase, Rng, SweepRanges, random_case};
use std::time::Instant;

/// ns per query: the fastest of 9 passes over `cases` (the machine is shared).
fn time(cases: &[LightCase], si: SiMode, bands: u32) -> f64 {
    (0..9)
        .map(|_| pass(cases, si, bands))
        .fold(f64::MAX, f64::min)
}

fn pass(cases: &[LightCase], si: SiMode, bands: u32) -> f64 {
    let t = Instant::now();
    let mut sink = 0.0f32;
    {
        for c in cases {
            sink += c.closed_form(si, bands);
        }
    }
    std::hint::black_box(sink);
    t.elapsed().as_nanos() as f64 / cases.len() as f64
}

fn main() {
    let mut rng = Rng::new(99);
    let sweep: Vec<LightCase> = (0..4096)
        .map(|_| {
            random_case(
                &mut rng,
                &SweepRanges {
                    polygon: 0.0,
                    ..SweepRanges::default()
                },
                1,
            )
        })
        .collect();
    let quad: Vec<LightCase> = sweep
        .iter()
        .map(|c| {
            let mut c = *c;
            c.query.light = Light::polygon(&[
                [-1.0, -1.0, 4.0],
                [1.0, -1.2, 4.0],
                [1.2, 1.0, 4.0],
                [-1.0, 1.0, 4.0],
            ]);
            c
        })
        .collect();
    let sixteen: Vec<LightCase> = sweep
        .iter()
        .map(|c| {
            let mut c = *c;
            let vs: Vec<[f32; 3]> = (0..16)
                .map(|k| {
                    let p = std::f32::consts::TAU * k as f32 / 16.0;
                    [1.5 * p.cos(), 1.5 * p.sin(), 4.0]
                })
                .collect();
            c.query.light = Light::polygon(&vs);
            c
        })
        .collect();
    println!("light kind | Si | bands | ns/query");
    for (name, cases) in [("sphere", &sweep), ("4-gon", &quad), ("16-gon", &sixteen)] {
        for (si, sname) in [
            (SiMode::Exact, "exact"),
            (SiMode::Velinov, "Eq. 29"),
            (SiMode::Fast, "fast"),
        ] {
            for bands in [1, 3, 5, 20] {
                println!("{name} | {sname} | {bands} | {:.0}", time(cases, si, bands));
            }
        }
    }
}
