//! Deterministic workloads shared by the benchmarks (so every backend times the same input),
//! and the speed-vs-accuracy charts:
//!
//! * `light_chart` (binary): error against cost of the area-light integrals — closed form
//!   with exact Si, Eq. 29's Si and the fast Si, one band or Gauss–Hermite bands, and Monte
//!   Carlo with N samples — over a seeded sweep, against the adaptive reference.
//! * `benches/lights.rs`: timing of the closed forms per light kind and method.

pub mod svg;

use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_kernel::table::{Material, TableQuery};

/// SplitMix64 uniform in [0, 1).
pub struct Rng(pub u64);

impl Rng {
    /// Next uniform sample.
    pub fn u(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `n` scratches crossing the coherence window around the origin (all within 2σ), random
/// orientations, widths 0.5–3 µm, depths 0.05–0.5 µm, both profiles.
pub fn scratches_in_window(n: usize, sigma: f32, seed: u64) -> Vec<Scratch> {
    let mut r = Rng(seed);
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * r.u();
            let c = [(r.u() - 0.5) * 2.0 * sigma, (r.u() - 0.5) * 2.0 * sigma];
            let h = sigma * (1.0 + 4.0 * r.u());
            Scratch {
                center: c,
                tangent: [a.cos(), a.sin()],
                half_len: h,
                width: 0.5 + 2.5 * r.u(),
                depth: 0.05 + 0.45 * r.u(),
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
    let mut r = Rng(seed);
    (0..n)
        .map(|_| {
            let (a, b) = (0.5 + 0.2 * (r.u() - 0.5), 0.2 * (r.u() - 0.5));
            TableQuery {
                wi: [-0.5, 0.0, 0.866_025_4],
                wo: [a, b, (1.0 - a * a - b * b).sqrt()],
                lambda_nm: 380.0 + 400.0 * r.u(),
                x: [r.u() - 0.5, r.u() - 0.5],
                material: Material::constant(0.9),
                ..TableQuery::default()
            }
        })
        .collect()
}
