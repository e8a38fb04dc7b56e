//! Measures the rules of `"model": "auto"` (`kernel::render::model_choice`): the relative
//! difference between Werner's coherent model and Velinov's incoherent one (the same
//! scratches, reflectance and exact depth phase) under sphere lights of angular radius α and
//! under point lights, over random scratch configurations.
//!
//! Per configuration: a shading point among random straight scratches (Velinov's benchmark
//! density; brushed: orientations within ±3°; a hundredth of the density, in the same
//! lengths or 20× longer), a view direction, a light direction, one wavelength. The coherent value under the light is a midpoint product rule over the cone
//! with nodes 4× finer than the window's diffraction angle λ/(2πσ); the incoherent value is
//! the renderer's closed form (`shading::velinov_area_light`) and, to separate the closed
//! form's own error, the same product rule. For each tolerance τ the configurations that
//! `model_choice::choose` gives the incoherent model show the error that choice makes.
//! Prints a table; `--csv FILE` writes every configuration.
//!
//! `cargo run --release -p scratchwave-benches --bin auto_calibration [-- --configs 300 --csv out.csv]`

use rayon::prelude::*;
use scratchwave_host::ScratchLookup;
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::bsdf::Lookup;
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::glam::{Vec2, Vec3};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::render::area::{SceneLight, SceneLightKind};
use scratchwave_kernel::render::model_choice::{self, Choice, Reach};
use scratchwave_kernel::render::shading::{self, SceneModel, ShadeMaterial};
use scratchwave_kernel::render::surface::SurfacePoint;
use scratchwave_kernel::scratch::{DepthTerm, Profile, Scratch};
use scratchwave_kernel::table::{Model, TableParams};
use scratchwave_render::reference::quantile_sorted;
use std::io::Write;

const SIGMA: f32 = 8.0;
const TOLERANCES: [f32; 3] = [0.1, 0.03, 0.01];
const REGION: f64 = 600.0;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Pattern {
    Dense,
    Brushed,
    Isolated,
    IsolatedLong,
}

/// Random straight scratches over a `REGION`² square: Velinov's benchmark density
/// (`conformance/scenes/velinov_1e5_segments.json`: 10⁵ segments, lengths 20–300 µm, over
/// 4 mm × 4 mm), a tenth of it, or brushed (dense, orientations within ±3° of x).
fn scratches(pattern: Pattern, seed: u64) -> Vec<Scratch> {
    let mut r = SplitMix64::new(seed);
    let density = 1.0e5 / (4000.0 * 4000.0);
    let mut n = (density * REGION * REGION) as usize;
    if matches!(pattern, Pattern::Isolated | Pattern::IsolatedLong) {
        n /= 100;
    }
    if pattern == Pattern::IsolatedLong {
        // The same length per area in scratches 20× longer.
        n = (n * 160 / 3000).max(2);
    }
    (0..n)
        .map(|k| {
            let c = [r.range_f64(0.0, REGION), r.range_f64(0.0, REGION)];
            let len = if pattern == Pattern::IsolatedLong {
                r.range_f64(2000.0, 4000.0)
            } else {
                r.range_f64(20.0, 300.0)
            };
            let phi = if pattern == Pattern::Brushed {
                r.range_f64(-3.0, 3.0).to_radians()
            } else {
                r.range_f64(0.0, std::f64::consts::PI)
            };
            let (s, co) = phi.sin_cos();
            let h = 0.5 * len;
            let profile = if k % 2 == 0 {
                Profile::Rect
            } else {
                Profile::Triangle
            };
            Scratch::from_endpoints(
                [c[0] - h * co, c[1] - h * s],
                [c[0] + h * co, c[1] + h * s],
                r.range(0.5, 3.0),
                r.range(0.05, 0.4),
                profile,
            )
        })
        .collect()
}

fn material(model: SceneModel, table: Model, base_gaussian: u32) -> ShadeMaterial {
    ShadeMaterial {
        table: TableParams {
            model: table as u32,
            sigma_um: SIGMA,
            depth_term: DepthTerm::Exact as u32,
            base_gaussian,
            ..TableParams::default()
        },
        material: Material::constant(1.0),
        model: model as u32,
        tolerance: 0.01,
        ..ShadeMaterial::default()
    }
}

fn frame_point(x_um: Vec2) -> SurfacePoint {
    SurfacePoint {
        position: Vec3::ZERO,
        x: Vec3::X,
        y: Vec3::Y,
        z: Vec3::Z,
        x_um,
        um_per_unit: Vec2::ONE,
    }
}

fn sphere_light(dir: Vec3, alpha: f32) -> SceneLight {
    SceneLight {
        kind: SceneLightKind::Sphere as u32,
        p0: [dir.x, dir.y, dir.z, alpha.sin()],
        emission: 1.0,
        ..SceneLight::default()
    }
}

/// An orthonormal frame around unit `c`.
fn basis(c: Vec3) -> (Vec3, Vec3) {
    let a = if c.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    let u = c.cross(a).normalize();
    (u, c.cross(u))
}

struct Row {
    pattern: Pattern,
    alpha: f32,
    lambda_um: f32,
    reach: Reach,
    /// Whether `model_choice::choose` takes the incoherent model at each of [`TOLERANCES`].
    incoherent_for: [bool; 3],
    coherent: f64,
    incoherent_closed: f64,
    incoherent_quad: f64,
}

fn measure(pattern: Pattern, alpha: f32, seed: u64, set_seed: u64) -> Option<Row> {
    let list = scratches(pattern, set_seed);
    let lookup = ScratchLookup::new(&list, SIGMA);
    let set = lookup.set();
    let lk = Lookup::new(set);
    let mut r = SplitMix64::new(seed);
    let x0 = Vec2::new(
        r.range(0.35 * REGION as f32, 0.65 * REGION as f32),
        r.range(0.35 * REGION as f32, 0.65 * REGION as f32),
    );
    let lambda_um = [0.44f32, 0.52, 0.70][(r.next_u64() % 3) as usize];
    let (to, po) = (r.range(0.0, 1.05), r.range(0.0, std::f32::consts::TAU));
    let wo = Vec3::new(to.sin() * po.cos(), to.sin() * po.sin(), to.cos());
    let (tl, pl) = (r.range(0.0, 1.2), r.range(0.0, std::f32::consts::TAU));
    let c = Vec3::new(tl.sin() * pl.cos(), tl.sin() * pl.sin(), tl.cos());
    if c.z - alpha.sin() <= 0.02 {
        return None;
    }
    let coh = material(SceneModel::Werner, Model::Werner, 0);
    let inc = material(SceneModel::Velinov, Model::Velinov, 1);
    let sp = frame_point(x0);
    let reach = model_choice::reach(&set, x0, SIGMA, &Ellipse::default());
    let lam_nm = lambda_um * 1e3;
    let light = if alpha == 0.0 {
        SceneLight {
            kind: SceneLightKind::Point as u32,
            p0: [c.x, c.y, c.z, 0.0],
            emission: 1.0,
            ..SceneLight::default()
        }
    } else {
        sphere_light(c, alpha)
    };
    let incoherent_for = TOLERANCES.map(|t| {
        let m = ShadeMaterial {
            tolerance: t,
            ..coh
        };
        model_choice::choose(&m, &sp, wo, &light, &reach, lam_nm) == Choice::Incoherent
    });
    if alpha == 0.0 {
        let f = |m: &ShadeMaterial| f64::from(shading::brdf(m, c, wo, x0, lam_nm, &set) * c.z);
        return Some(Row {
            pattern,
            alpha,
            lambda_um,
            reach,
            incoherent_for,
            coherent: f(&coh),
            incoherent_closed: f(&inc),
            incoherent_quad: f(&inc),
        });
    }
    let grain = lambda_um / (std::f32::consts::TAU * SIGMA);
    let rings = ((3.0 * alpha / grain).ceil() as usize).clamp(8, 80);
    let sectors = (rings * 4).max(16);
    let (u, v) = basis(c);
    let cos_a = alpha.cos();
    let d_omega = f64::from(std::f32::consts::TAU * (1.0 - cos_a)) / (rings * sectors) as f64;
    let (mut qc, mut qi) = (0.0f64, 0.0f64);
    for i in 0..rings {
        let ct = 1.0 - (1.0 - cos_a) * (i as f32 + 0.5) / rings as f32;
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        for k in 0..sectors {
            let p = std::f32::consts::TAU * (k as f32 + 0.5) / sectors as f32;
            let wi = c * ct + (u * p.cos() + v * p.sin()) * st;
            if wi.z <= 0.0 {
                continue;
            }
            qc += f64::from(shading::brdf(&coh, wi, wo, x0, lam_nm, &set) * wi.z);
            qi += f64::from(shading::brdf(&inc, wi, wo, x0, lam_nm, &set) * wi.z);
        }
    }
    let mut lambdas = [0.0f32; 4];
    lambdas[0] = lam_nm;
    let closed =
        shading::velinov_area_light(&inc, &sp, wo, &light, &lambdas, 1, &lk, &Ellipse::default());
    Some(Row {
        pattern,
        alpha,
        lambda_um,
        reach,
        incoherent_for,
        coherent: qc * d_omega,
        incoherent_closed: f64::from(closed[0]),
        incoherent_quad: qi * d_omega,
    })
}

/// The nearest-rank `q`-quantile of `v` (sorted in place; the renderer's
/// [`quantile_sorted`], the definition of every p99 the reference comparisons print), NaN
/// when empty.
fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    quantile_sorted(v, q)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let get = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let configs: u64 = get("--configs").and_then(|s| s.parse().ok()).unwrap_or(200);
    let alphas = [0.0f32, 0.003, 0.01, 0.03, 0.1];
    let patterns = [
        Pattern::Dense,
        Pattern::Brushed,
        Pattern::Isolated,
        Pattern::IsolatedLong,
    ];
    let jobs: Vec<(Pattern, f32, u64)> = patterns
        .iter()
        .flat_map(|&p| {
            alphas
                .iter()
                .flat_map(move |&a| (0..configs).map(move |k| (p, a, k)))
        })
        .collect();
    let rows: Vec<Row> = jobs
        .par_iter()
        .filter_map(|&(p, a, k)| measure(p, a, 1000 + k, k % 8))
        .collect();
    if let Some(path) = get("--csv") {
        let mut f = std::io::BufWriter::new(std::fs::File::create(&path).expect("csv"));
        writeln!(
            f,
            "pattern,alpha,lambda_um,count,strongest,second,nearest_end,incoherent_0.1,incoherent_0.03,incoherent_0.01,coherent,incoherent_closed,incoherent_quad"
        )
        .unwrap();
        for r in &rows {
            let b = r.incoherent_for.map(u8::from);
            writeln!(
                f,
                "{:?},{},{},{},{},{},{},{},{},{},{:e},{:e},{:e}",
                r.pattern,
                r.alpha,
                r.lambda_um,
                r.reach.count,
                r.reach.strongest,
                r.reach.second,
                r.reach.nearest_end,
                b[0],
                b[1],
                b[2],
                r.coherent,
                r.incoherent_closed,
                r.incoherent_quad
            )
            .unwrap();
        }
    }
    println!(
        "relative difference |incoherent (closed form under the light, point value under a point light) − coherent| / max(coherent, floor),"
    );
    println!(
        "floor = 1e-3 × the 99.9 % coherent value of the group; per tolerance τ: the configurations model_choice::choose makes incoherent"
    );
    print!(
        "{:12} {:>6} {:>4} | {:>8} {:>8}",
        "pattern", "alpha", "n", "all p50", "all p99"
    );
    for t in TOLERANCES {
        print!(" | τ={t:<5} {:>4} {:>8} {:>8}", "n", "p99", "max");
    }
    println!(" | closed vs quad p99");
    for &p in &patterns {
        for &a in &alphas {
            let group: Vec<&Row> = rows
                .iter()
                .filter(|r| r.pattern == p && r.alpha == a)
                .collect();
            let mut peak: Vec<f64> = group.iter().map(|r| r.coherent).collect();
            let floor = 1e-3 * quantile(&mut peak, 0.999);
            let rel = |r: &Row| (r.incoherent_closed - r.coherent).abs() / r.coherent.max(floor);
            let mut all: Vec<f64> = group.iter().map(|r| rel(r)).collect();
            let mut cq: Vec<f64> = group
                .iter()
                .map(|r| {
                    (r.incoherent_closed - r.incoherent_quad).abs() / r.incoherent_quad.max(floor)
                })
                .collect();
            print!(
                "{:12} {:>6} {:>4} | {:>8.1e} {:>8.1e}",
                format!("{p:?}"),
                a,
                group.len(),
                quantile(&mut all.clone(), 0.5),
                quantile(&mut all, 0.99)
            );
            for i in 0..TOLERANCES.len() {
                let mut chosen: Vec<f64> = group
                    .iter()
                    .filter(|r| r.incoherent_for[i])
                    .map(|r| rel(r))
                    .collect();
                let max = chosen.iter().cloned().fold(0.0, f64::max);
                print!(
                    " |         {:>4} {:>8.1e} {:>8.1e}",
                    chosen.len(),
                    quantile(&mut chosen, 0.99),
                    max
                );
            }
            println!(" | {:.1e}", quantile(&mut cq, 0.99));
        }
    }
}
