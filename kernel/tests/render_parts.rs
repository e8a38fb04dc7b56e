//! Kernel render parts against independent values: the area-light quadrature's solid angle,
//! the CIE fit against tabulated CIE 1931 values, XYZ → sRGB of the D65 white, the camera's
//! pixel-centre formulas.

use scratchwave_kernel::glam::Vec3;
use scratchwave_kernel::render::area::{SceneLight, SceneLightKind, area_node, node_count};
use scratchwave_kernel::render::camera::{Camera, Projection};
use scratchwave_kernel::render::spectrum::{cie_xyz, xyz_to_linear_srgb};

#[test]
fn sphere_nodes_cover_the_cap_exactly() {
    let light = SceneLight {
        kind: SceneLightKind::Sphere as u32,
        p0: [0.3, -0.2, 4.0, 1.1],
        ..SceneLight::default()
    };
    let p = Vec3::new(0.1, 0.0, 0.0);
    let d = (Vec3::new(0.3, -0.2, 4.0) - p).length() as f64;
    let cos_a = (1.0 - (1.1 / d).powi(2)).sqrt();
    let exact = 2.0 * std::f64::consts::PI * (1.0 - cos_a);
    let mut sum = 0.0f64;
    for i in 0..node_count(&light) {
        let n = area_node(&light, p, i).unwrap();
        sum += f64::from(n.weight);
        // Every node direction lies inside the cap and its distance reaches the sphere.
        let q = p + n.dir * n.dist;
        let r = (q - Vec3::new(0.3, -0.2, 4.0)).length();
        assert!((r - 1.1).abs() < 1e-4, "node {i} at radius {r}");
    }
    assert!((sum - exact).abs() < 1e-5 * exact, "{sum} vs {exact}");
}

#[test]
fn triangle_nodes_converge_to_the_solid_angle() {
    // A right triangle seen from far away along its normal: Ω ≈ A/d² (to (size/d)²).
    let light = SceneLight {
        kind: SceneLightKind::Triangle as u32,
        p0: [0.0, 0.0, 100.0, 0.0],
        p1: [1.0, 0.0, 100.0, 0.0],
        p2: [0.0, 1.0, 100.0, 0.0],
        ..SceneLight::default()
    };
    let sum: f64 = (0..node_count(&light))
        .map(|i| f64::from(area_node(&light, Vec3::ZERO, i).unwrap().weight))
        .sum();
    let approx = 0.5 / 100.0f64.powi(2);
    assert!((sum - approx).abs() < 1e-4 * approx, "{sum} vs {approx}");
}

#[test]
fn cie_fit_matches_tabulated_values() {
    // CIE 1931 2° observer, tabulated (CIE 15:2004): (λ, x̄, ȳ, z̄).
    let table = [
        (450.0, 0.3362, 0.0380, 1.7721),
        (500.0, 0.0049, 0.3230, 0.2720),
        (555.0, 0.5121, 1.0000, 0.0057),
        (600.0, 1.0622, 0.6310, 0.0008),
        (650.0, 0.2835, 0.1070, 0.0000),
    ];
    for (l, x, y, z) in table {
        let c = cie_xyz(l);
        for (got, want) in c.iter().zip([x, y, z]) {
            // Wyman et al. report the multi-lobe fit within a few per cent of the peak.
            assert!(
                (f64::from(*got) - want).abs() < 0.04,
                "λ {l}: {c:?} vs {x} {y} {z}"
            );
        }
    }
}

#[test]
fn d65_white_is_rgb_one() {
    let rgb = xyz_to_linear_srgb([0.950_47, 1.0, 1.088_83]);
    for c in rgb {
        assert!((c - 1.0).abs() < 1e-3, "{rgb:?}");
    }
}

#[test]
fn camera_pixel_centres_follow_the_scene_format() {
    let cam = Camera::look_at(
        Projection::Perspective,
        [1.0, 2.0, 3.0],
        [1.0, 2.0, 0.0],
        [0.0, 1.0, 0.0],
        0.5,
        40,
        20,
    );
    // f = (0,0,−1), r = (1,0,0), u = (0,1,0); pixel (0, 0): s = (0.5/40 − 0.5)·0.5·2,
    // t = (0.5 − 0.5/20)·0.5.
    let (s, t) = (
        ((0.5 / 40.0) - 0.5) * 0.5 * 2.0f64,
        (0.5 - 0.5 / 20.0) * 0.5f64,
    );
    let n = (1.0 + s * s + t * t).sqrt();
    let rd = cam.ray(0.5, 0.5);
    let want = [s / n, t / n, -1.0 / n];
    for (g, w) in rd.ray.dir.iter().zip(want) {
        assert!(
            (f64::from(*g) - w).abs() < 1e-6,
            "{:?} vs {want:?}",
            rd.ray.dir
        );
    }
    assert_eq!(rd.ray.origin, [1.0, 2.0, 3.0]);
}
