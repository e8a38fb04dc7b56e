//! Deterministic workloads shared by the benchmarks (so every backend times the same input),
//! and the speed-vs-accuracy charts:
//!
//! * `light_chart` (binary): error against cost of the area-light integrals — closed form
//!   with exact Si, Eq. 29's Si and the fast Si, one band or Gauss–Hermite bands, and Monte
//!   Carlo with N samples — over a seeded sweep, against the adaptive reference.
//! * `benches/lights.rs`: timing of the closed forms per light kind and method.

pub mod svg;

pub use scratchwave_cpu::fixtures::SplitMix64 as Rng;
use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_kernel::table::{Material, TableQuery};

/// `n` scratches crossing the coherence window around the origin (all within 2σ), random
/// orientations, widths 0.5–3 µm, depths 0.05–0.5 µm, both profiles.
pub fn scratches_in_window(n: usize, sigma: f32, seed: u64) -> Vec<Scratch> {
    let mut r = Rng::new(seed);
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * r.next_f32();
            let c = [
                (r.next_f32() - 0.5) * 2.0 * sigma,
                (r.next_f32() - 0.5) * 2.0 * sigma,
            ];
            let h = sigma * (1.0 + 4.0 * r.next_f32());
            Scratch {
                center: c,
                tangent: [a.cos(), a.sin()],
                half_len: h,
                width: 0.5 + 2.5 * r.next_f32(),
                depth: 0.05 + 0.45 * r.next_f32(),
                profile: if i % 2 == 0 {
                    Profile::Rect as u32
                } else {
                    Profile::Triangle as u32
                },
            }
        })
        .collect()
}

/// `n` queries around the specular direction of a 30° incidence (where diffraction is).
pub fn queries_near_specular(n: usize, seed: u64) -> Vec<TableQuery> {
    let mut r = Rng::new(seed);
    (0..n)
        .map(|_| {
            let (a, b) = (0.5 + 0.2 * (r.next_f32() - 0.5), 0.2 * (r.next_f32() - 0.5));
            TableQuery {
                wi: [-0.5, 0.0, 0.866_025_4],
                wo: [a, b, (1.0 - a * a - b * b).sqrt()],
                lambda_nm: 380.0 + 400.0 * r.next_f32(),
                x: [r.next_f32() - 0.5, r.next_f32() - 0.5],
                material: Material::constant(0.9),
                ..TableQuery::default()
            }
        })
        .collect()
}
