//! The footprint-averaged Velinov BRDF against the point model: a footprint much smaller
//! than the coherence area gives the point value of the infinite-scratch model (the
//! `table` function with `eta: infinite`), and a large footprint gives the area average of
//! point values (computed here by brute-force sampling of the ellipse).

use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::glam::{Vec2, Vec3};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::render::footprint::velinov_footprint_brdf;
use scratchwave_kernel::scratch::{EtaMode, Profile, Scratch, ScratchSlice};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};

fn setup() -> (TableParams, [Scratch; 2]) {
    let params = TableParams {
        model: Model::Velinov as u32,
        eta: EtaMode::Infinite as u32,
        sigma_um: 10.0,
        ..TableParams::default()
    };
    let s = [
        Scratch::from_endpoints([-5000.0, -3.0], [5000.0, 4.0], 3.0, 0.4, Profile::Rect),
        Scratch::from_endpoints(
            [-4000.0, 2000.0],
            [4000.0, -2000.0],
            2.0,
            0.3,
            Profile::Triangle,
        ),
    ];
    (params, s)
}

fn point(params: &TableParams, s: &[Scratch], wi: Vec3, wo: Vec3, x: Vec2) -> f32 {
    let q = TableQuery {
        wi: wi.to_array(),
        wo: wo.to_array(),
        lambda_nm: 550.0,
        x: x.to_array(),
        material: Material::constant(0.8),
        ..TableQuery::default()
    };
    evaluate(params, &q, &ScratchSlice { scratches: s })
}

#[test]
fn tiny_footprint_equals_the_point_model() {
    let (params, s) = setup();
    let wi = Vec3::new(0.1, 0.3, 0.95).normalize();
    let wo = Vec3::new(-0.05, -0.2, 0.97).normalize();
    for x in [
        Vec2::new(0.0, 1.0),
        Vec2::new(100.0, 8.0),
        Vec2::new(-300.0, -12.0),
    ] {
        let e = Ellipse {
            center: x.to_array(),
            angle_rad: 0.3,
            a1: 0.02,
            a2: 0.01,
            ..Ellipse::default()
        };
        let set = ScratchSlice { scratches: &s };
        let f = velinov_footprint_brdf(&params, &Material::constant(0.8), wi, wo, &e, 550.0, &set);
        let p = point(&params, &s, wi, wo, x);
        assert!(p > 0.0);
        assert!((f - p).abs() <= 1e-3 * p, "x {x}: footprint {f}, point {p}");
    }
}

#[test]
fn large_footprint_is_the_area_average_of_point_values() {
    let (params, s) = setup();
    let wi = Vec3::new(0.0, 0.3, 0.95).normalize();
    let wo = Vec3::new(0.0, -0.25, 0.97).normalize();
    let e = Ellipse {
        center: [20.0, 5.0],
        angle_rad: 0.4,
        a1: 60.0,
        a2: 25.0,
        ..Ellipse::default()
    };
    let set = ScratchSlice { scratches: &s };
    let f = velinov_footprint_brdf(&params, &Material::constant(0.8), wi, wo, &e, 550.0, &set);
    // Midpoint rule over a polar grid of the ellipse, in f64.
    let (n_r, n_t) = (400, 400);
    let (sn, cs) = (0.4f64.sin(), 0.4f64.cos());
    let mut sum = 0.0f64;
    let mut wsum = 0.0f64;
    for i in 0..n_r {
        let r = (i as f64 + 0.5) / n_r as f64;
        for j in 0..n_t {
            let t = std::f64::consts::TAU * (j as f64 + 0.5) / n_t as f64;
            let (u, v) = (60.0 * r * t.cos(), 25.0 * r * t.sin());
            let x = Vec2::new(
                (20.0 + u * cs - v * sn) as f32,
                (5.0 + u * sn + v * cs) as f32,
            );
            sum += f64::from(point(&params, &s, wi, wo, x)) * r;
            wsum += r;
        }
    }
    let avg = sum / wsum;
    assert!(avg > 0.0);
    let rel = (f64::from(f) - avg).abs() / avg;
    assert!(
        rel < 2e-3,
        "footprint {f}, sampled average {avg} (rel {rel:e})"
    );
}
