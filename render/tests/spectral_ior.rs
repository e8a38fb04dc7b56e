//! Materials with a metal's measured spectral IOR (`"ior": "gold"`, …) render, at every
//! wavelength, as the constant IOR the kernel reads from its table there, bit for bit (the
//! scratch models and the GHS base alike: the material interface reads a GHS IOR at the
//! wavelength in nm, `ghs::Ghs::at_nm`); in RGB mode the gold plate comes out warm (red well
//! above blue), as the measured curve says.
//! Scene: `conformance/scenes/spectral_metals.json` (Velinov gold under a sphere and a point
//! light; Werner-blended copper on a GHS silver base).

use scratchwave_kernel::conductor::{self, Conductor};
use scratchwave_render::{Backend, render_scene, scene_file};
use serde_json::{Value, json};
use std::path::Path;

fn scene() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../conformance/scenes/spectral_metals.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn render(v: &Value) -> Vec<[f32; 3]> {
    let scene = scene_file::scene_from_value(v, "spectral_ior", Path::new(".")).unwrap();
    render_scene(&scene, Backend::Cpu, &|_, _| {})
        .unwrap()
        .image
        .rgb
}

/// `[n, k]` of `metal` at `nm`, as the kernel's table gives it.
fn constant(metal: Conductor, nm: f32) -> Value {
    let (n, k) = conductor::ior(metal, nm, 0.0, 0.0);
    json!([n, k])
}

#[test]
fn a_metal_name_renders_as_its_ior_at_each_wavelength() {
    for nm in [450.0f32, 555.0, 640.0] {
        let mut named = scene();
        named["spectrum"] = json!({"mode": "single", "lambda_nm": nm});
        let mut fixed = named.clone();
        let m = &mut fixed["materials"];
        m["gold"]["material"]["ior"] = constant(Conductor::Gold, nm);
        m["copper"]["material"]["ior"] = constant(Conductor::Copper, nm);
        m["copper"]["base"]["ior"] = constant(Conductor::Silver, nm);
        let (a, b) = (render(&named), render(&fixed));
        let lit = a.iter().filter(|p| p[0] > 0.0).count();
        assert!(
            lit > a.len() / 4,
            "{nm} nm: only {lit} of {} pixels lit",
            a.len()
        );
        let w = named["camera"]["width_px"].as_u64().unwrap() as usize;
        // Left half gold (Velinov), right half copper on a GHS silver base: identical bits.
        for (i, (p, q)) in a.iter().zip(&b).enumerate() {
            let half = if i % w < w / 2 { "left" } else { "right" };
            assert_eq!(
                p[0].to_bits(),
                q[0].to_bits(),
                "{nm} nm, pixel {i} ({half}): {p:?} vs {q:?}"
            );
        }
    }
}

#[test]
fn gold_is_warm_in_rgb() {
    let mut v = scene();
    v["spectrum"] = json!({"mode": "rgb"});
    let img = render(&v);
    let w = v["camera"]["width_px"].as_u64().unwrap() as usize;
    // Left half: the gold plate.
    let (mut r, mut b) = (0.0f64, 0.0f64);
    for (i, p) in img.iter().enumerate() {
        if i % w < w / 2 {
            r += f64::from(p[0]);
            b += f64::from(p[2]);
        }
    }
    assert!(r > 1.5 * b && b > 0.0, "gold: red sum {r}, blue sum {b}");
}
