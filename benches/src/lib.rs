//! Deterministic workloads shared by the benchmarks (so every backend times the same input),
//! and the speed-vs-accuracy charts:
//!
//! * `light_chart` (binary): error against cost of the area-light integrals — closed form
//!   with exact Si, Eq. 29's Si and the fast Si, one band or Gauss–Hermite bands, and Monte
//!   Carlo with N samples — over a seeded sweep, against the adaptive reference.
//! * `benches/lights.rs`: timing of the closed forms per light kind and method.

pub mod svg;
pub mod tradeoff;

use scratchwave_host::generate::{HalfLength, ProfileMix, ScratchRecipe, Uniform};
pub use scratchwave_host::rng::SplitMix64 as Rng;
use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{Scratch, Window};
use scratchwave_kernel::table::{Model, TableParams, TableQuery};

/// `n` scratches crossing the coherence window around the origin (all within 2σ), random
/// orientations, half lengths 1–5σ, widths 0.5–3 µm, depths 0.05–0.5 µm, both profiles.
pub fn scratches_in_window(n: usize, sigma: f32, seed: u64) -> Vec<Scratch> {
    ScratchRecipe {
        count: n,
        unit: sigma,
        center: [0.0, 0.0],
        side: 2.0,
        outliers: None,
        half_length: HalfLength::Uniform(Uniform::new(1.0, 4.0)),
        width: Uniform::new(0.5, 2.5),
        depth: Uniform::new(0.05, 0.45),
        profile: ProfileMix::Alternate,
    }
    .generate(&mut Rng::new(seed))
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

/// The window-cost workload's table (the criterion group `brdf_window` and
/// `exact_window_chart`): Werner at σ = 10 µm with the coherence window `window`.
pub fn werner_window_params(window: Window) -> TableParams {
    TableParams {
        model: Model::Werner as u32,
        sigma_um: 10.0,
        window: window as u32,
        ..TableParams::default()
    }
}
