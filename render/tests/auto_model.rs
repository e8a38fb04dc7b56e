//! `"model": "auto"` (`kernel::render::model_choice`): every hit–light pair is shaded with
//! exactly one of the two fixed models and counted; a pixel whose pairs all chose one model
//! equals that model's own render bit for bit; the scene reader checks `tolerance`.

use scratchwave_render::render::Image;
use scratchwave_render::scene_file::scene_from_value_with_limit;
use scratchwave_render::{Backend, Scene, render_scene};
use serde_json::{Value, json};
use std::path::Path;

/// A plate with a grating of close parallel scratches on the left, two crossing scratches
/// on the right and bare metal between, under a sphere light and a point light.
fn scene(model: Value, extra: Value) -> Value {
    let mut grating: Vec<Value> = (0..134)
        .map(|k| {
            let y = -400.0 + 6.0 * f64::from(k);
            json!({"p0": [-900, y], "p1": [-300, y + 4.0], "width": 2, "depth": 0.2})
        })
        .collect();
    grating.push(json!({"p0": [300, -400], "p1": [800, 300], "width": 2.5, "depth": 0.3, "profile": "triangle"}));
    grating.push(json!({"p0": [300, 300], "p1": [800, -350], "width": 1.5, "depth": 0.25}));
    let mut material = json!({"model": model, "sigma_um": 10, "material": {"ior": [2.5, 3.5]},
                              "scratches": grating});
    if let (Some(m), Some(e)) = (material.as_object_mut(), extra.as_object()) {
        for (k, v) in e {
            m.insert(k.clone(), v.clone());
        }
    }
    json!({
        "camera": {"type": "orthographic", "eye": [0, -1.2, 5], "target": [0, 0, 0], "up": [0, 1, 0],
                   "view_height": 1.2, "width_px": 48, "height_px": 24},
        "materials": {"plate": material},
        "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
                     "normal": [0, 0, 1], "size": [4, 4], "material": "plate"}],
        "lights": [{"type": "sphere", "center": [0.4, 2.5, 4], "radius": 0.6, "radiance": 3},
                   {"type": "point", "position": [-0.5, 1.5, 4], "intensity": 20}],
        "spectrum": {"mode": "rgb"},
        "render": {"spp": 1, "footprint": "none"}
    })
}

fn read(v: &Value) -> Result<Scene, scratchwave_spec::SpecError> {
    scene_from_value_with_limit(v, "auto", Path::new("."), 1 << 30)
}

/// The reader's error for a scene it must refuse.
fn read_err(v: &Value) -> String {
    read(v).unwrap_err().to_string()
}

fn render(v: &Value) -> (Image, scratchwave_render::render::RenderStats) {
    let r = render_scene(&read(v).unwrap(), Backend::Cpu, &|_, _| {}).unwrap();
    (r.image, r.stats)
}

#[test]
fn every_hit_light_pair_is_counted_once() {
    let (img, st) = render(&scene(json!("auto"), json!({"tolerance": 0.01})));
    let pixels = (img.width * img.height) as usize;
    assert_eq!(img.model_choice.len(), pixels);
    // The plate fills the view: every pixel has one hit and two lights.
    for (k, c) in img.model_choice.iter().enumerate() {
        assert_eq!(c[0] + c[1], 2, "pixel {k}: {c:?}");
    }
    let sum = |i: usize| {
        img.model_choice
            .iter()
            .map(|c| u64::from(c[i]))
            .sum::<u64>()
    };
    assert_eq!((sum(0), sum(1)), (st.auto_coherent, st.auto_incoherent));
    assert!(st.auto_coherent > 0 && st.auto_incoherent > 0, "{st:?}");
    // A fixed model has no map.
    let (img, st) = render(&scene(json!("werner"), json!({})));
    assert!(img.model_choice.is_empty());
    assert_eq!((st.auto_coherent, st.auto_incoherent), (0, 0));
}

#[test]
fn the_grating_is_coherent_and_bare_metal_incoherent() {
    let (img, _) = render(&scene(json!("auto"), json!({"tolerance": 0.01})));
    let w = img.width as usize;
    // Scratch space x = (i + 0.5 − 24)/48·2.4 mm: the grating spans −0.9..−0.3 mm
    // (columns 6–17), the bare strip −0.2..0.2 mm (columns 20–27) holds no scratch
    // within 6σ = 60 µm.
    let row = img.height as usize / 2;
    for i in 8..16 {
        let c = img.model_choice[row * w + i];
        assert_eq!(c[0], 2, "grating column {i}: {c:?}");
    }
    for i in 21..27 {
        let c = img.model_choice[row * w + i];
        assert_eq!(c, [0, 2], "bare column {i}");
    }
}

#[test]
fn pure_pixels_equal_the_fixed_models_bit_for_bit() {
    let (auto, _) = render(&scene(json!("auto"), json!({"tolerance": 0.01})));
    let (coherent, _) = render(&scene(json!("werner"), json!({})));
    let (incoherent, _) = render(&scene(
        json!("velinov"),
        json!({"options": {"depth_term": "exact", "base": "gaussian"}}),
    ));
    let (mut n_coh, mut n_inc) = (0, 0);
    for (k, c) in auto.model_choice.iter().enumerate() {
        let bits = |p: [f32; 3]| p.map(f32::to_bits);
        if c[1] == 0 {
            assert_eq!(bits(auto.rgb[k]), bits(coherent.rgb[k]), "pixel {k}");
            n_coh += 1;
        } else if c[0] == 0 {
            assert_eq!(bits(auto.rgb[k]), bits(incoherent.rgb[k]), "pixel {k}");
            n_inc += 1;
        }
    }
    assert!(
        n_coh > 20 && n_inc > 20,
        "{n_coh} coherent, {n_inc} incoherent pixels"
    );
}

#[test]
fn tolerance_is_checked_and_belongs_to_auto() {
    let err = |v: &Value| {
        let e = read_err(v);
        assert!(e.contains("materials.plate.tolerance"), "{e}");
        e
    };
    for t in [json!(0), json!(1), json!(-0.1), json!(2.0)] {
        let e = err(&scene(json!("auto"), json!({"tolerance": t})));
        assert!(e.contains("(0, 1)"), "{e}");
    }
    err(&scene(json!("auto"), json!({"tolerance": "small"})));
    let e = err(&scene(json!("werner"), json!({"tolerance": 0.01})));
    assert!(e.contains("auto"), "{e}");
    // Options of Velinov's model alone are not taken by auto.
    let e = read_err(&scene(
        json!("auto"),
        json!({"options": {"eta": "infinite"}}),
    ));
    assert!(e.contains("materials.plate.options.eta"), "{e}");
    // The default tolerance.
    let s = read(&scene(json!("auto"), json!({}))).unwrap();
    assert_eq!(
        s.materials[0].shade.tolerance,
        scratchwave_spec::material::DEFAULT_TOLERANCE
    );
}

/// `options.<option> = value` is refused with velinov and auto (naming the field and the
/// models that take it), reaches werner and werner_blended's table as `stored` (read by
/// `field`), and `bad` is refused naming the field.
fn coherent_option(
    option: &str,
    value: &str,
    bad: &str,
    field: impl Fn(&scratchwave_kernel::table::TableParams) -> u32,
    stored: u32,
) {
    let path = format!("materials.plate.options.{option}");
    let set = json!({"options": {option: value}});
    for model in ["velinov", "auto"] {
        let e = read_err(&scene(json!(model), set.clone()));
        assert!(e.contains(&path), "{model}: {e}");
        assert!(e.contains("werner_blended"), "{model}: {e}");
    }
    for model in ["werner", "werner_blended"] {
        let s = read(&scene(json!(model), set.clone())).unwrap();
        assert_eq!(field(&s.materials[0].shade.table), stored, "{model}");
    }
    let e = read_err(&scene(json!("werner"), json!({"options": {option: bad}})));
    assert!(e.contains(&path), "{e}");
}

#[test]
fn the_exact_window_belongs_to_the_coherent_models() {
    let exact = scratchwave_kernel::scratch::Window::Exact as u32;
    coherent_option("window", "exact", "wide", |t| t.window, exact);
}

#[test]
fn deepest_crossings_belong_to_the_coherent_models() {
    let deepest = scratchwave_kernel::scratch::Crossings::Deepest as u32;
    coherent_option("crossings", "deepest", "once", |t| t.crossings, deepest);
}
