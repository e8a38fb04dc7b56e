//! Adaptive shadow rays (`render.shadows: "adaptive"`) against a ray to every quadrature
//! node (`"all_nodes"`): a rough GHS plate under a sphere light, a card casting a soft
//! shadow, on both ray engines. A third render without the card classifies each pixel as
//! lit (equal to the unoccluded value), umbra (0) or penumbra. Outside the penumbra the two
//! modes must agree bitwise (the probes agree there and stand for every node, which is
//! what tracing every node finds); inside it they may differ only where every probe agrees
//! but some node does not, which must stay a small share of the penumbra. Adaptive must
//! also trace far fewer shadow rays.

use scratchwave_render::{Backend, render_scene, scene_file};
use serde_json::{Value, json};
use std::path::Path;

fn scene(shadows: &str, card: bool) -> Value {
    let mut objects = vec![
        json!({"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
        "normal": [0, 0, 1], "size": [6, 6], "material": "rough"}),
    ];
    if card {
        // A vertical card, edge-on to the camera (no pixel sees it), casting a soft shadow
        // on the plate at 0.28 < x < 1.9.
        objects.push(
            json!({"shape": "rectangle", "center": [0, 0, 0.8], "tangent": [0, 1, 0],
            "normal": [1, 0, 0], "size": [1.2, 1.0], "material": "rough"}),
        );
    }
    json!({
        "unit_um": 1000,
        "camera": {"type": "orthographic", "eye": [0, 0, 6], "target": [0, 0, 0], "up": [0, 1, 0],
                   "view_height": 4, "width_px": 64, "height_px": 64},
        "materials": {
            "rough": {"model": "ghs", "material": {"sigma_s_um": 0.1, "beta": 0.05, "p": 1.0,
                "b_um": 2.0, "c": 2.0, "ior": [1.5, 0.0], "layer": {"type": "plastic", "rho_d": 0.4}}}
        },
        "objects": objects,
        "lights": [{"type": "sphere", "center": [-2.5, 0, 3.0], "radius": 0.6, "radiance": 3.0}],
        "spectrum": {"mode": "single", "lambda_nm": 550},
        "render": {"spp": 1, "footprint": "none", "shadows": shadows}
    })
}

fn render(shadows: &str, card: bool, backend: Backend) -> (Vec<f32>, u64) {
    let s = scene_file::scene_from_value(&scene(shadows, card), "adaptive_shadows", Path::new("."))
        .expect("valid scene");
    let out = render_scene(&s, backend, &|_, _| {}).expect("renders");
    (
        out.image.rgb.iter().map(|p| p[0]).collect(),
        out.stats.shadow_rays,
    )
}

fn check(backend: Backend) {
    let (open, _) = render("all_nodes", false, backend);
    let (all, all_rays) = render("all_nodes", true, backend);
    let (adaptive, adaptive_rays) = render("adaptive", true, backend);
    let (mut lit, mut umbra, mut penumbra, mut differ) = (0, 0, 0, 0);
    let mut worst = 0.0f32;
    for k in 0..all.len() {
        let plate_lit = all[k].to_bits() == open[k].to_bits();
        if plate_lit || all[k] == 0.0 {
            assert_eq!(
                adaptive[k].to_bits(),
                all[k].to_bits(),
                "pixel {k} outside the penumbra: adaptive {} vs all nodes {}",
                adaptive[k],
                all[k]
            );
            if plate_lit {
                lit += 1;
            } else {
                umbra += 1;
            }
        } else {
            penumbra += 1;
            if adaptive[k].to_bits() != all[k].to_bits() {
                differ += 1;
                worst = worst.max((adaptive[k] - all[k]).abs() / open[k].max(f32::MIN_POSITIVE));
            }
        }
    }
    assert!(
        lit > 1000 && umbra > 20 && penumbra > 50,
        "lit {lit}, umbra {umbra}, penumbra {penumbra}"
    );
    assert!(
        differ * 5 <= penumbra,
        "{differ} of {penumbra} penumbra pixels differ"
    );
    assert!(
        adaptive_rays * 3 < all_rays,
        "adaptive {adaptive_rays} vs all nodes {all_rays} shadow rays"
    );
    println!(
        "{}: lit {lit}, umbra {umbra}, penumbra {penumbra} ({differ} differ, by up to {worst:.3} of the unshadowed value); shadow rays {adaptive_rays} adaptive vs {all_rays}",
        backend.name()
    );
}

#[test]
fn adaptive_shadows_differ_only_in_the_penumbra_on_the_portable_bvh() {
    check(Backend::Cpu);
}

#[test]
fn adaptive_shadows_differ_only_in_the_penumbra_on_embree() {
    check(Backend::Embree);
}
