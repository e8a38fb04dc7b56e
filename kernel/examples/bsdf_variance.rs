//! Variance per sample of the directional-albedo estimator `f·cosθi/pdf` for four ways of
//! drawing `wi` given `wo`: uniform hemisphere, cosine-weighted, Werner 2017 §5 as published
//! (Gaussian base, vMF ring with uniform azimuth, balance heuristic) and this crate's
//! disk-product lobes (`bsdf::sample`). The table in `docs/bsdf.md` is this program's
//! output:
//!
//! `cargo run --release -p scratchwave-kernel --example bsdf_variance`

use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::{self, BsdfMaterial, ShadingPoint, Strategy, Wavelengths};
use scratchwave_kernel::ghs::presets;
use scratchwave_kernel::material::Material;
use scratchwave_kernel::sampling::warp;
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};

const N: usize = 100_000;
/// Samples for the footprint case (each `eval` averages every scratch over the footprint).
const N_FOOTPRINT: usize = 10_000;

/// SplitMix64, uniform f32 in [0, 1).
struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 * (1.0 / 16_777_216.0)
    }
}

fn random_scratches(r: &mut Rng, n: usize, sigma: f32, profile: Option<Profile>) -> Vec<Scratch> {
    (0..n)
        .map(|_| {
            let rad = 3.0 * sigma * r.f().sqrt();
            let a = std::f32::consts::TAU * r.f();
            let phi = std::f32::consts::PI * r.f();
            let (c, t) = (
                [(rad * a.cos()) as f64, (rad * a.sin()) as f64],
                [phi.cos() as f64, phi.sin() as f64],
            );
            let h = 20.0 + 200.0 * r.f() as f64;
            let p = profile.unwrap_or(if r.f() < 0.5 {
                Profile::Rect
            } else {
                Profile::Triangle
            });
            Scratch::from_endpoints(
                [c[0] - h * t[0], c[1] - h * t[1]],
                [c[0] + h * t[0], c[1] + h * t[1]],
                0.5 + 2.5 * r.f(),
                0.05 + 0.5 * r.f(),
                p,
            )
        })
        .collect()
}

fn stats(n: usize, mut draw: impl FnMut(&mut Rng) -> f64, seed: u64) -> (f64, f64, f64) {
    let mut r = Rng(seed);
    let (mut s1, mut s2) = (0.0, 0.0);
    let t = std::time::Instant::now();
    for _ in 0..n {
        let w = draw(&mut r);
        s1 += w;
        s2 += w * w;
    }
    let ns = t.elapsed().as_secs_f64() * 1e9 / n as f64;
    let mean = s1 / n as f64;
    (mean, s2 / n as f64 - mean * mean, ns)
}

fn main() {
    let sigma = 10.0;
    let f = Material::constant(1.0);
    let mut r = Rng(2017);
    let one_rect = vec![Scratch::from_endpoints(
        [-300.0, 2.0],
        [300.0, 2.0],
        2.0,
        0.3,
        Profile::Rect,
    )];
    let one_tri = vec![Scratch::from_endpoints(
        [-300.0, -1.0],
        [300.0, 1.0],
        3.0,
        0.8,
        Profile::Triangle,
    )];
    let few = random_scratches(&mut r, 4, sigma, None);
    let many = random_scratches(&mut r, 24, sigma, None);
    let fp = scratchwave_kernel::footprint::Ellipse {
        center: [0.0; 2],
        angle_rad: 0.3,
        a1: 40.0,
        a2: 15.0,
        pad: [0.0; 3],
    };
    let cases: Vec<(&str, BsdfMaterial, Vec<Scratch>, f32, ShadingPoint)> = vec![
        (
            "Werner, 1 rect scratch, θo 30°",
            BsdfMaterial::werner(sigma, f),
            one_rect.clone(),
            30.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Werner, 1 V-groove, θo 30°",
            BsdfMaterial::werner(sigma, f),
            one_tri.clone(),
            30.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Werner, 4 scratches, θo 60°",
            BsdfMaterial::werner(sigma, f),
            few.clone(),
            60.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Werner, 24 scratches, θo 80°",
            BsdfMaterial::werner(sigma, f),
            many.clone(),
            80.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Werner blended (GHS), 4 scratches, θo 45°",
            BsdfMaterial::werner_blended(sigma, f, presets::ROUGH_METAL),
            few.clone(),
            45.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Velinov, 1 rect scratch, θo 30°",
            BsdfMaterial::velinov(sigma, f),
            one_rect.clone(),
            30.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Velinov, 24 scratches, θo 60°",
            BsdfMaterial::velinov(sigma, f),
            many.clone(),
            60.0,
            ShadingPoint::at([0.0; 2]),
        ),
        (
            "Velinov footprint 40×15 µm, 24 scratches, θo 60°",
            BsdfMaterial::velinov(sigma, f),
            many.clone(),
            60.0,
            ShadingPoint::with_footprint([0.0; 2], fp),
        ),
    ];
    let wl = Wavelengths::single(550.0);
    println!(
        "N = {N} samples per cell ({N_FOOTPRINT} with a footprint), σ = {sigma} µm, λ = 550 nm, F = 1; variance per sample of f·cosθi/pdf (estimate of the albedo in brackets)\n"
    );
    println!(
        "| configuration | uniform | cosine | Werner §5 | disk product | Werner §5 / disk product |"
    );
    println!("|---|---|---|---|---|---|");
    for (k, (name, m, sc, theta, sp)) in cases.iter().enumerate() {
        let set = ScratchSlice { scratches: sc };
        let lk = bsdf::Lookup::new(&set);
        let th = theta.to_radians();
        let wo = Vec3::new(th.sin(), 0.0, th.cos());
        let seed = 100 + k as u64;
        let n = if sp.footprint().is_some() {
            N_FOOTPRINT
        } else {
            N
        };
        let uniform = stats(
            n,
            |r| {
                let (u1, u2) = (r.f(), r.f());
                let z = u1;
                let s = (1.0 - z * z).max(0.0).sqrt();
                let wi = Vec3::new(
                    s * (std::f32::consts::TAU * u2).cos(),
                    s * (std::f32::consts::TAU * u2).sin(),
                    z,
                );
                (bsdf::eval(m, sp, wi, wo, &wl, &lk).v[0] * wi.z) as f64 * std::f64::consts::TAU
            },
            seed,
        );
        let cosine = stats(
            n,
            |r| {
                let wi = warp::cosine_hemisphere(Vec2::new(r.f(), r.f()));
                if !(wi.z > 0.0) {
                    return 0.0;
                }
                (bsdf::eval(m, sp, wi, wo, &wl, &lk).v[0] / warp::cosine_hemisphere_pdf(wi) * wi.z)
                    as f64
            },
            seed,
        );
        let strat = |s: Strategy| {
            stats(
                n,
                |r| {
                    let (us, u) = (r.f(), Vec2::new(r.f(), r.f()));
                    bsdf::sample_with(s, m, sp, wo, &wl, us, u, &lk)
                        .map_or(0.0, |x| x.weight.v[0] as f64)
                },
                seed,
            )
        };
        let werner = strat(Strategy::Werner2017);
        let disk = strat(Strategy::DiskProduct);
        let cell = |(mean, var, _): (f64, f64, f64)| format!("{var:.3e} ({mean:.4})");
        println!(
            "| {name} | {} | {} | {} | {} | {:.1} |",
            cell(uniform),
            cell(cosine),
            cell(werner),
            cell(disk),
            werner.1 / disk.1
        );
        eprintln!(
            "  {name}: ns/sample uniform {:.0}, cosine {:.0}, Werner §5 {:.0}, disk {:.0}",
            uniform.2, cosine.2, werner.2, disk.2
        );
    }
}
