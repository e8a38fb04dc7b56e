//! Werner 2017 §6's numerical check: rasterise a scratched height field, Fourier-transform
//! `T·G` numerically, and compare with the analytic model on the tangential and
//! bitangential slices of a single scratch.
//!
//! The raster is 960² pixels of 0.125 µm (±60 µm = ±6σ). Each pixel's transfer function is
//! constant, so its Fourier integral is exact up to the Gaussian's variation inside the pixel
//! (a factor `sinc(πξ₁dx) sinc(πξ₂dx)` on the pixel-centre DFT). The model neglects the
//! Gaussian across the groove (Werner Eq. 11). Measured: the tangential slice agrees to
//! 5.6e-4; on the bitangential slice the side lobes, which come mostly from the groove's
//! edges where that Gaussian is `e^{−W²/(8σ²)} = 0.995`, are overestimated by ≈ 1 % (the
//! model error Werner §6 describes), rising to 2.6 % next to the sinc zeros, where the
//! numerical transform does not vanish. Tolerances: 1e-3 and 3e-2.

use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use std::f64::consts::PI;

const N: usize = 960;
const DX: f64 = 0.125;
const HALF: f64 = 60.0;
const SIGMA: f64 = 10.0;
const LAMBDA: f64 = 0.5;
const W: f64 = 2.0;
const D: f64 = 0.15;
/// The segment starts inside the window (x = −20 µm) and leaves it (x = 200 µm).
const X_START: f64 = -20.0;
const X_END: f64 = 200.0;

struct Raster {
    /// Gaussian window per pixel, row-major `[y][x]`.
    g: Vec<f64>,
    /// Gaussian window inside the groove, 0 outside.
    g_groove: Vec<f64>,
}

fn centre(i: usize) -> f64 {
    -HALF + (i as f64 + 0.5) * DX
}

fn raster() -> Raster {
    let mut g = vec![0.0; N * N];
    let mut g_groove = vec![0.0; N * N];
    for j in 0..N {
        for i in 0..N {
            let (x, y) = (centre(i), centre(j));
            let w = (-(x * x + y * y) / (2.0 * SIGMA * SIGMA)).exp();
            g[j * N + i] = w;
            if y.abs() < 0.5 * W && x > X_START && x < X_END {
                g_groove[j * N + i] = w;
            }
        }
    }
    Raster { g, g_groove }
}

/// `Σ f(x,y) e^{−2πi ξ·x} dx²` with exact per-pixel phase integration.
fn transform(f: &[f64], xi: (f64, f64)) -> (f64, f64) {
    let phase = |k: f64| -> Vec<(f64, f64)> {
        (0..N)
            .map(|i| {
                (
                    (-2.0 * PI * k * centre(i)).cos(),
                    (-2.0 * PI * k * centre(i)).sin(),
                )
            })
            .collect()
    };
    let (ex, ey) = (phase(xi.0), phase(xi.1));
    let (mut re, mut im) = (0.0, 0.0);
    for j in 0..N {
        let row = &f[j * N..(j + 1) * N];
        let (mut rr, mut ri) = (0.0, 0.0);
        for (v, e) in row.iter().zip(&ex) {
            rr += v * e.0;
            ri += v * e.1;
        }
        re += rr * ey[j].0 - ri * ey[j].1;
        im += rr * ey[j].1 + ri * ey[j].0;
    }
    let sinc = |x: f64| if x == 0.0 { 1.0 } else { x.sin() / x };
    let s = DX * DX * sinc(PI * xi.0 * DX) * sinc(PI * xi.1 * DX);
    (re * s, im * s)
}

/// Numerical BRDF for `wi = +z` and `wo` with direction cosines `λξ`.
fn numeric(r: &Raster, xi: (f64, f64)) -> f64 {
    let (a, b) = (LAMBDA * xi.0, LAMBDA * xi.1);
    let gamma = 1.0 + (1.0 - a * a - b * b).sqrt();
    let kappa = 2.0 * PI * gamma * D / LAMBDA; // T = e^{iκ} in the groove (h = −D)
    let base = transform(&r.g, xi);
    let groove = transform(&r.g_groove, xi);
    let (cr, ci) = (kappa.cos() - 1.0, kappa.sin());
    let re = base.0 + cr * groove.0 - ci * groove.1;
    let im = base.1 + cr * groove.1 + ci * groove.0;
    (re * re + im * im) / (PI * SIGMA * SIGMA * LAMBDA * LAMBDA)
}

fn model(xi: (f64, f64)) -> f64 {
    let s = [Scratch::from_endpoints(
        [X_START, 0.0],
        [X_END, 0.0],
        W as f32,
        D as f32,
        Profile::Rect,
    )];
    let p = TableParams {
        model: Model::Werner as u32,
        depth_term: 1,
        sigma_um: SIGMA as f32,
        ..Default::default()
    };
    let (a, b) = (LAMBDA * xi.0, LAMBDA * xi.1);
    let q = TableQuery {
        wi: [0.0, 0.0, 1.0],
        wo: [a as f32, b as f32, (1.0 - a * a - b * b).sqrt() as f32],
        lambda_nm: (LAMBDA * 1000.0) as f32,
        material: Material::constant(1.0),
        ..Default::default()
    };
    f64::from(evaluate(&p, &q, &ScratchSlice { scratches: &s }))
}

/// Compares a slice; returns the worst relative error over values ≥ `floor` × slice peak.
fn compare(r: &Raster, points: &[(f64, f64)], floor: f64) -> f64 {
    let num: Vec<f64> = points.iter().map(|&p| numeric(r, p)).collect();
    let peak = num.iter().cloned().fold(0.0, f64::max);
    let mut worst = 0.0f64;
    for (p, n) in points.iter().zip(&num) {
        let m = model(*p);
        if std::env::var("SW_DUMP").is_ok() {
            eprintln!(
                "{:?} model {m:.6e} numeric {n:.6e} rel {:.3e} frac {:.2e}",
                p,
                (m - n) / n,
                n / peak
            );
        }
        if *n >= floor * peak {
            worst = worst.max((m - n).abs() / n);
        } else {
            assert!(
                (m - n).abs() <= 2.0 * floor * peak,
                "ξ={p:?}: model {m} vs numeric {n}"
            );
        }
    }
    worst
}

#[test]
fn tangential_slice_matches_rasterised_transform() {
    let r = raster();
    let pts: Vec<(f64, f64)> = (-40..=40).map(|k| (k as f64 * 0.0015, 0.0)).collect();
    let worst = compare(&r, &pts, 1e-4);
    eprintln!("tangential slice: worst relative error {worst:.3e}");
    assert!(worst < 1e-3, "tangential slice: {worst}");
}

#[test]
fn bitangential_slice_matches_rasterised_transform() {
    let r = raster();
    // Beyond the base lobe the scratch's sinc² dominates; stop short of its 4th zero.
    let pts: Vec<(f64, f64)> = (0..=70).map(|k| (0.0, k as f64 * 0.025)).collect();
    let worst = compare(&r, &pts, 1e-4);
    eprintln!("bitangential slice: worst relative error {worst:.3e}");
    assert!(worst < 3e-2, "bitangential slice: {worst}");
}
