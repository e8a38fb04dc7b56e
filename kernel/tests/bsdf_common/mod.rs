//! Shared helpers of the BSDF tests: seeded configurations over every material, scratch
//! count, profile and viewing angle, and a χ² goodness-of-fit test whose expected bin counts
//! come from Gauss–Legendre integration of the pdf under test.
#![allow(dead_code)]

#[path = "../ghs_common/mod.rs"]
mod ghs_common;

pub use ghs_common::{Pcg, gamma_q64};

use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::{BsdfMaterial, ShadingPoint, Wavelengths};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::{Layer, layers::LayerForm, presets};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};

/// One test configuration.
#[derive(Clone, Debug)]
pub struct Config {
    pub name: String,
    pub m: BsdfMaterial,
    pub sp: ShadingPoint,
    pub wo: Vec3,
    pub wl: Wavelengths,
    pub scratches: Vec<Scratch>,
}

impl Config {
    pub fn set(&self) -> ScratchSlice<'_> {
        ScratchSlice {
            scratches: &self.scratches,
        }
    }
}

pub const MODEL_NAMES: [&str; 5] = ["werner", "werner_blended", "velinov", "velinov_fp", "ghs"];

pub fn dir(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// Random scratches around the origin: centres within `3σ`, any orientation.
pub fn scratches(r: &mut Pcg, count: usize, sigma: f32, profile: Option<Profile>) -> Vec<Scratch> {
    (0..count)
        .map(|_| {
            let rad = 3.0 * sigma * r.f().sqrt();
            let a = std::f32::consts::TAU * r.f();
            let c = [(rad * a.cos()) as f64, (rad * a.sin()) as f64];
            let phi = std::f32::consts::PI * r.f();
            let h = (2.0 + 98.0 * r.f()) as f64;
            let t = [phi.cos() as f64, phi.sin() as f64];
            let prof = profile.unwrap_or(if r.f() < 0.5 {
                Profile::Rect
            } else {
                Profile::Triangle
            });
            Scratch::from_endpoints(
                [c[0] - h * t[0], c[1] - h * t[1]],
                [c[0] + h * t[0], c[1] + h * t[1]],
                0.5 + 2.5 * r.f(),
                0.05 + 0.55 * r.f(),
                prof,
            )
        })
        .collect()
}

/// The `i`-th configuration of a seeded sweep over the five material kinds (i mod 5), 1, 4
/// or 16 scratches ((i / 5) mod 3), rect, triangle or mixed profiles, single, RGB or
/// spectral wavelengths and viewing angles from 3° to 86°.
pub fn config(i: usize, sigma: f32) -> Config {
    let mut r = Pcg::new(0xb5df_0000 + i as u64);
    let kind = i % 5;
    let count = [1, 4, 16][(i / 5) % 3];
    let profile = match (i / 15) % 3 {
        0 => Some(Profile::Rect),
        1 => Some(Profile::Triangle),
        _ => None,
    };
    let theta = [3.0f32, 30.0, 55.0, 75.0, 86.0][(i / 3) % 5].to_radians();
    let wo = dir(theta, std::f32::consts::TAU * r.f());
    let wl = match i % 4 {
        0 | 1 => Wavelengths::single(400.0 + 300.0 * r.f()),
        2 => Wavelengths::rgb(),
        _ => Wavelengths::sample_visible(r.f()),
    };
    let material = if r.f() < 0.5 {
        Material::constant(0.9)
    } else {
        Material::ior(0.3, 3.0, FresnelAngle::ThetaD)
    };
    let ghs = match r.next_u32() % 3 {
        0 => presets::ROUGH_METAL,
        1 => presets::GLOSSY_PLASTIC.with_layer(Layer::Plastic, LayerForm::EnergyConserving, 0.5),
        _ => scratchwave_kernel::ghs::GhsParams::new(0.05, 0.15, 0.9, 3.0, 2.5, 1.8, 0.5),
    };
    let m = match kind {
        0 => BsdfMaterial::werner(sigma, material),
        1 => BsdfMaterial::werner_blended(sigma, material, ghs),
        2 | 3 => BsdfMaterial::velinov(sigma, material),
        _ => BsdfMaterial::ghs(ghs),
    };
    let sp = if kind == 3 {
        let a1 = 3.0 + 17.0 * r.f();
        ShadingPoint::with_footprint(
            [0.0, 0.0],
            Ellipse {
                center: [0.0, 0.0],
                angle_rad: 3.0 * r.f(),
                a1,
                a2: a1 * (0.1 + 0.9 * r.f()),
                pad: [0.0; 3],
            },
        )
    } else {
        ShadingPoint::at([0.0, 0.0])
    };
    let sc = scratches(&mut r, count, sigma, profile);
    let name = format!(
        "#{i} {} n={count} prof={profile:?} θo={:.0}° λ={:?}",
        MODEL_NAMES[kind],
        theta.to_degrees(),
        &wl.nm[..wl.len()]
    );
    Config {
        name,
        m,
        sp,
        wo,
        wl,
        scratches: sc,
    }
}

/// χ² bins over the hemisphere: `NT` in θ × `NP` in φ.
pub const NT: usize = 48;
pub const NP: usize = 96;
/// Sub-cells per bin side, each integrated by 3-point Gauss–Legendre.
const SUB: usize = 2;
const GL3_X: [f64; 3] = [-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4];
const GL3_W: [f64; 3] = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];

fn bin_of(w: Vec3) -> Option<usize> {
    if !(w.z > 0.0) || !w.is_finite() {
        return None;
    }
    let th = (w.z as f64).min(1.0).acos();
    let mut ph = (w.y as f64).atan2(w.x as f64);
    if ph < 0.0 {
        ph += std::f64::consts::TAU;
    }
    let i = ((th / std::f64::consts::FRAC_PI_2) * NT as f64) as usize;
    let j = ((ph / std::f64::consts::TAU) * NP as f64) as usize;
    Some(i.min(NT - 1) * NP + j.min(NP - 1))
}

/// Bin probabilities `∫_bin pdf dω` (f64 sums of the f32 pdf).
pub fn bin_integrals(pdf: &(dyn Fn(Vec3) -> f32 + Sync)) -> Vec<f64> {
    let dth = std::f64::consts::FRAC_PI_2 / (NT * SUB) as f64;
    let dph = std::f64::consts::TAU / (NP * SUB) as f64;
    let rows: Vec<Vec<f64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2)
            .map(|part| {
                scope.spawn(move || {
                    let mut out = Vec::new();
                    for bi in (part..NT).step_by(2) {
                        let mut row = vec![0.0; NP];
                        for it in bi * SUB..(bi + 1) * SUB {
                            for (gx, gw) in GL3_X.iter().zip(GL3_W) {
                                let th = (it as f64 + 0.5 + 0.5 * gx) * dth;
                                let wth = 0.5 * gw * dth * th.sin();
                                for ip in 0..NP * SUB {
                                    for (hx, hw) in GL3_X.iter().zip(GL3_W) {
                                        let ph = (ip as f64 + 0.5 + 0.5 * hx) * dph;
                                        let w = Vec3::new(
                                            (th.sin() * ph.cos()) as f32,
                                            (th.sin() * ph.sin()) as f32,
                                            th.cos() as f32,
                                        );
                                        row[ip / SUB] += pdf(w) as f64 * wth * 0.5 * hw * dph;
                                    }
                                }
                            }
                        }
                        out.push((bi, row));
                    }
                    out
                })
            })
            .collect();
        let mut rows = vec![Vec::new(); NT];
        for h in handles {
            for (bi, row) in h.join().unwrap() {
                rows[bi] = row;
            }
        }
        rows
    });
    rows.concat()
}

/// Result of one χ² test.
#[derive(Clone, Debug)]
pub struct Chi2 {
    pub p: f64,
    pub stat: f64,
    pub dof: usize,
    /// `∫ pdf dω` over the hemisphere.
    pub integral: f64,
    /// Samples in bins whose expected count is 0 (a sampler/pdf mismatch by itself).
    pub impossible: f64,
}

/// χ² test of `n` draws (None = no sample, its own category with expectation
/// `n (1 − ∫pdf)`) against the pdf; bins with expected count < 5 are pooled.
pub fn chi2(
    n: usize,
    seed: u64,
    sampler: &(dyn Fn(&mut Pcg) -> Option<Vec3> + Sync),
    pdf: &(dyn Fn(Vec3) -> f32 + Sync),
) -> Chi2 {
    let nb = NT * NP;
    let obs: Vec<f64> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2u64)
            .map(|part| {
                scope.spawn(move || {
                    let mut obs = vec![0.0f64; nb + 1];
                    let mut rng = Pcg::new(seed.wrapping_mul(31).wrapping_add(part));
                    for _ in 0..n / 2 + (part as usize) * (n % 2) {
                        match sampler(&mut rng).and_then(bin_of) {
                            Some(b) => obs[b] += 1.0,
                            None => obs[nb] += 1.0,
                        }
                    }
                    obs
                })
            })
            .collect();
        let mut total = vec![0.0; nb + 1];
        for h in handles {
            for (t, o) in total.iter_mut().zip(h.join().unwrap()) {
                *t += o;
            }
        }
        total
    });
    let probs = bin_integrals(pdf);
    let integral: f64 = probs.iter().sum();
    let mut exp: Vec<f64> = probs.iter().map(|p| p * n as f64).collect();
    exp.push((n as f64 * (1.0 - integral)).max(0.0));
    let mut idx: Vec<usize> = (0..exp.len()).collect();
    idx.sort_by(|&a, &b| exp[a].total_cmp(&exp[b]));
    let (mut pool_e, mut pool_o, mut stat, mut dof, mut impossible) = (0.0, 0.0, 0.0, 0usize, 0.0);
    for &i in &idx {
        // (Failed draws, category `nb`, are not samples: with `∫pdf` at 1 up to the
        // quadrature's error, their expectation may round to 0.)
        if exp[i] == 0.0 && obs[i] > 0.0 && i != nb {
            impossible += obs[i];
        }
        if exp[i] < 5.0 {
            pool_e += exp[i];
            pool_o += obs[i];
        } else {
            stat += (obs[i] - exp[i]).powi(2) / exp[i];
            dof += 1;
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    let dof = dof.saturating_sub(1).max(1);
    let p = gamma_q64(dof as f64 / 2.0, stat / 2.0);
    Chi2 {
        p,
        stat,
        dof,
        integral,
        impossible,
    }
}

/// Holm–Bonferroni at family level `alpha`: the names of the rejected tests.
pub fn holm(results: &[(String, f64)], alpha: f64) -> Vec<String> {
    let mut order: Vec<usize> = (0..results.len()).collect();
    order.sort_by(|&a, &b| results[a].1.total_cmp(&results[b].1));
    let m = results.len();
    let mut rejected = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        if results[i].1 < alpha / (m - k) as f64 {
            rejected.push(results[i].0.clone());
        } else {
            break;
        }
    }
    rejected
}

/// Three uniform numbers for `sample`: `(u_select, u)`.
pub fn draw(r: &mut Pcg) -> (f32, Vec2) {
    (r.f(), Vec2::new(r.f(), r.f()))
}
