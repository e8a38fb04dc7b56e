//! spp 1, footprint none: every pixel equals the `table` command's function
//! (`scratchwave_kernel::table::evaluate`) for that pixel's (wi, wo, x, λ), times
//! `cos θi · I / d²`. The test derives the queries itself, in f64, from the scene-file
//! formulas (camera pixel centres, rectangle scratch space, point light), independently of
//! the renderer's f32 camera, intersection and frame code.
//!
//! Tolerance: relative 2e-5 per pixel, scaled by `max(1, |ln v|/10)` for small values `v`
//! (a value `e^{−a}` from an exponent `a` computed from inputs a few ULP apart differs by
//! `~a·ε` relative: the Gaussian tails of the lobe reach `a ≈ 87`); absolute
//! `f32::MIN_POSITIVE` below f32's normal range, where values carry fewer bits. The renderer computes `s`, `t`, the hit and `wi` in
//! f32 (a few ULP from the f64 derivation: `x` within ~3e-5 µm of the test's, `wi` within
//! ~2 ULP), and the coherent BRDF turns such input differences into relative changes of
//! its value of the same order times its conditioning (measured worst here: see the
//! assertion message); `I/d²` and `cos θi` differ by rounding only. Bitwise equality would
//! need the test to repeat the renderer's f32 operation order, which would no longer be an
//! independent derivation.

use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{DepthTerm, Profile, Scratch, ScratchSlice};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use scratchwave_render::{Backend, render_scene, scene_file};
use std::path::Path;

const SCENE: &str = r#"{
  "unit_um": 1000,
  "camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0],
             "view_height": 0.4, "width_px": 40, "height_px": 30},
  "materials": {"m": {"model": "werner", "sigma_um": 10, "material": {"ior": [2.5, 3.5]},
    "scratches": [
      {"p0": [-250, -30], "p1": [250, 60], "width": 2, "depth": 0.3, "profile": "triangle"},
      {"p0": [-150, 140], "p1": [200, -150], "width": 3, "depth": 0.25},
      {"p0": [20, -200], "p1": [-10, 200], "width": 1.5, "depth": 0.4, "profile": "triangle"}
    ]}},
  "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
               "normal": [0, 0, 1], "size": [4, 4], "material": "m"}],
  "lights": [{"type": "point", "position": [0.4, 0.3, 3], "intensity": 7}],
  "spectrum": {"mode": "single", "lambda_nm": 550},
  "render": {"spp": 1, "footprint": "none"}
}"#;

const W: usize = 40;
const H: usize = 30;
const REL_TOL: f64 = 2.0e-5;

/// The expected pixel values, from the formulas of `docs/render.md`.
fn expected() -> Vec<f64> {
    let scratches = [
        Scratch::from_endpoints([-250.0, -30.0], [250.0, 60.0], 2.0, 0.3, Profile::Triangle),
        Scratch::from_endpoints([-150.0, 140.0], [200.0, -150.0], 3.0, 0.25, Profile::Rect),
        Scratch::from_endpoints([20.0, -200.0], [-10.0, 200.0], 1.5, 0.4, Profile::Triangle),
    ];
    // A scene's Werner material uses the exact depth phase by default (docs/render.md).
    let params = TableParams {
        model: Model::Werner as u32,
        sigma_um: 10.0,
        depth_term: DepthTerm::Exact as u32,
        ..TableParams::default()
    };
    let (h, light, intensity) = (0.4f64, [0.4f64, 0.3, 3.0], 7.0f64);
    let mut out = Vec::new();
    for j in 0..H {
        for i in 0..W {
            // Camera: f = (0,0,−1), r = f × up = (1,0,0), u = r × f = (0,1,0).
            let s = ((i as f64 + 0.5) / W as f64 - 0.5) * h * W as f64 / H as f64;
            let t = (0.5 - (j as f64 + 0.5) / H as f64) * h;
            // The ray from (s, t, 5) along −z meets the plane z = 0 at (s, t, 0): frame
            // x = tangent, y = normal × tangent = (0, 1, 0), scratch space (a, b)·1000 µm.
            let p = [s, t, 0.0];
            let d = [light[0] - p[0], light[1] - p[1], light[2] - p[2]];
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let len = d2.sqrt();
            let wi = [d[0] / len, d[1] / len, d[2] / len];
            let q = TableQuery {
                wi: wi.map(|c| c as f32),
                lambda_nm: 550.0,
                wo: [0.0, 0.0, 1.0],
                x: [(s * 1000.0) as f32, (t * 1000.0) as f32],
                material: Material::ior(2.5, 3.5, FresnelAngle::ThetaD),
                ..TableQuery::default()
            };
            let f = f64::from(evaluate(
                &params,
                &q,
                &ScratchSlice {
                    scratches: &scratches,
                },
            ));
            out.push(f * wi[2] * intensity / d2);
        }
    }
    out
}

fn check(backend: Backend) {
    let v: serde_json::Value = serde_json::from_str(SCENE).unwrap();
    let scene = scene_file::scene_from_value(&v, "table_equality", Path::new(".")).unwrap();
    let out = render_scene(&scene, backend, &|_, _| {}).unwrap();
    let want = expected();
    assert_eq!(out.image.rgb.len(), want.len());
    let mut worst = 0.0f64;
    let mut lit = 0;
    for (k, (px, w)) in out.image.rgb.iter().zip(&want).enumerate() {
        assert!(
            px[0] == px[1] && px[1] == px[2],
            "single mode writes R = G = B"
        );
        let got = f64::from(px[0]);
        // Values below f32's normal range (far from the lobe and the diffraction lines)
        // carry fewer significant bits: compare them absolutely at that scale.
        let tiny = f64::from(f32::MIN_POSITIVE);
        let rel = if w.abs() < tiny {
            if (got - w).abs() <= tiny {
                0.0
            } else {
                f64::INFINITY
            }
        } else {
            lit += 1;
            (got - w).abs() / w.abs() / (w.abs().ln().abs() / 10.0).max(1.0)
        };
        worst = worst.max(rel);
        assert!(
            rel <= REL_TOL,
            "{backend:?} pixel ({}, {}): rendered {got}, table {w} (rel {rel:e})",
            k % W,
            k / W
        );
    }
    // The Werner lobe and the scratches' diffraction cover part of the view; make sure the
    // comparison is not mostly zeros.
    assert!(
        lit > W * H / 3,
        "too few non-zero pixels ({lit} of {})",
        W * H
    );
    eprintln!(
        "{backend:?}: worst relative difference {worst:e}, {lit} of {} pixels non-zero",
        W * H
    );
}

#[test]
fn cpu_pixels_equal_table_values() {
    check(Backend::Cpu);
}

#[test]
fn embree_pixels_equal_table_values() {
    if scratchwave_embree::Device::new().is_err() {
        eprintln!("Embree not available: skipped");
        return;
    }
    check(Backend::Embree);
}
