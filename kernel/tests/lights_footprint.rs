//! The area-light integral averaged over a pixel footprint
//! (`lights::light_integral_footprint`) against an independent average: the point closed
//! form (`light_integral`, infinite-scratch η, itself checked against mpmath) evaluated on a
//! dense polar grid over the ellipse and averaged. The two share the band integral; what
//! is checked is the footprint average of the spatial factor (`η_P/(2√π σ)` against the
//! grid mean of `√π σ e^{−s_b²/σ²}`), the candidate radius and the centring on `q.x`.

use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::lights::{
    BandRule, Cone, Light, LightParams, LightQuery, SiMode, light_integral,
    light_integral_footprint,
};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{EtaMode, Scratch, ScratchSlice};

/// Long scratches (the footprint never reaches their ends), W = 2 µm, D = 0.2 µm.
fn scratches() -> [Scratch; 3] {
    let s = |center: [f32; 2], angle: f32| Scratch {
        center,
        tangent: [angle.cos(), angle.sin()],
        half_len: 2000.0,
        width: 2.0,
        depth: 0.2,
        profile: 0,
    };
    [
        s([0.0, 4.0], 0.1),
        s([0.0, -30.0], 0.35),
        s([0.0, 55.0], -0.2),
    ]
}

fn params() -> LightParams {
    LightParams {
        sigma_um: 10.0,
        eta: EtaMode::Infinite as u32,
        si_mode: SiMode::Exact as u32,
        bands: BandRule::Extent as u32,
        ..LightParams::default()
    }
}

fn query(x: [f32; 2], light: Light) -> LightQuery {
    LightQuery {
        wo: [0.0, 0.0, 1.0],
        lambda_nm: 550.0,
        x,
        material: Material::constant(0.8),
        light,
        ..LightQuery::default()
    }
}

/// Mean of the point form over the ellipse: polar grid in the unit disc (midpoint rule in
/// r² and angle), mapped by the ellipse's axes.
fn grid_mean(e: &Ellipse, light: Light, set: &ScratchSlice) -> f64 {
    let (nr, nt) = (80, 160);
    let (s, c) = e.angle_rad.sin_cos();
    let mut sum = 0.0f64;
    for i in 0..nr {
        let r = ((i as f64 + 0.5) / nr as f64).sqrt();
        for j in 0..nt {
            let t = std::f64::consts::TAU * (j as f64 + 0.5) / nt as f64;
            let (u, v) = (r * t.cos() * e.a1 as f64, r * t.sin() * e.a2 as f64);
            let x = [
                e.center[0] + (u * c as f64 - v * s as f64) as f32,
                e.center[1] + (u * s as f64 + v * c as f64) as f32,
            ];
            sum += f64::from(light_integral(&params(), &query(x, light), set));
        }
    }
    sum / (nr * nt) as f64
}

#[test]
fn footprint_average_matches_grid_mean_of_point_form() {
    let list = scratches();
    let set = ScratchSlice { scratches: &list };
    // A light along the mirror direction's neighbourhood so that the scratches' bands cross
    // it (bands of scratches at angle a pass through directions perpendicular to them).
    let lights = [
        Light::sphere([0.05, 0.02, 1.0], 0.08, Cone::Asin),
        Light::polygon(&[[-0.1, -0.12, 1.0], [0.15, -0.1, 1.0], [0.02, 0.14, 1.0]]),
    ];
    let ellipses = [(35.0, 12.0, 0.3), (80.0, 50.0, -1.0), (20.0, 20.0, 0.0)];
    let (mut checked, mut worst) = (0, 0.0f64);
    for light in lights {
        for &(a1, a2, angle) in &ellipses {
            let e = Ellipse {
                center: [3.0, -2.0],
                angle_rad: angle,
                a1,
                a2,
                pad: [0.0; 3],
            };
            let got = light_integral_footprint(&params(), &query(e.center, light), &e, &set);
            let want = grid_mean(&e, light, &set);
            assert!(want > 0.0, "light misses every band: {light:?}");
            let rel = (f64::from(got) - want).abs() / want;
            assert!(
                rel < 3e-4,
                "a1 {a1} a2 {a2}: footprint {got} vs grid {want} ({rel:.2e})"
            );
            worst = worst.max(rel);
            checked += 1;
        }
    }
    assert_eq!(checked, 6);
    println!("worst relative difference from the grid mean: {worst:.2e}");
}

#[test]
fn tiny_footprint_is_the_point_form_and_zero_axes_are_the_point_form_exactly() {
    let list = scratches();
    let set = ScratchSlice { scratches: &list };
    let light = Light::sphere([0.05, 0.02, 1.0], 0.08, Cone::Asin);
    let x = [3.0, -2.0];
    let point = light_integral(&params(), &query(x, light), &set);
    let zero = light_integral_footprint(&params(), &query(x, light), &Ellipse::default(), &set);
    assert_eq!(point.to_bits(), zero.to_bits());
    let tiny = Ellipse {
        center: [1e6, 1e6], // not read: the footprint is centred on q.x
        angle_rad: 0.4,
        a1: 0.05,
        a2: 0.02,
        pad: [0.0; 3],
    };
    let got = light_integral_footprint(&params(), &query(x, light), &tiny, &set);
    assert!(
        ((got - point) / point).abs() < 1e-4,
        "tiny footprint {got} vs point {point}"
    );
}
