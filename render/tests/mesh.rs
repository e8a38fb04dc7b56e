//! OBJ meshes: a two-triangle square read from OBJ renders like the same square given as a
//! rectangle (Velinov with the footprint ellipse, so frames, scratch space and its scale per
//! scene unit are all compared; scratch space shifted by the UV origin), and broken mesh files
//! are rejected with the field path.

use scratchwave_render::{Backend, render_scene, scene_file};
use std::path::PathBuf;

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("scratchwave-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The square [−2, 2]² at z = 0 with u = (x + 2)/4, v = (y + 2)/4.
const SQUARE: &str = "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

fn scene(object: &str, shift: f64) -> String {
    // 31 scratches 120 µm apart across the square (every footprint sees some), and one
    // diagonal.
    let mut scratches: Vec<String> = (0..31)
        .map(|k| {
            let y = -1800.0 + 120.0 * f64::from(k);
            format!(
                r#"{{"p0": [{}, {}], "p1": [{}, {}], "width": 3, "depth": 0.4}}"#,
                -2000.0 + shift,
                y + shift,
                2000.0 + shift,
                y + 40.0 + shift
            )
        })
        .collect();
    scratches.push(format!(
        r#"{{"p0": [{}, {}], "p1": [{}, {}], "width": 2, "depth": 0.3, "profile": "triangle"}}"#,
        -1000.0 + shift,
        1200.0 + shift,
        1100.0 + shift,
        -1300.0 + shift
    ));
    format!(
        r#"{{
  "camera": {{"type": "perspective", "eye": [0.3, -5, 4], "target": [0, 0, 0], "up": [0, 0, 1],
             "fov_y_deg": 30, "width_px": 32, "height_px": 24}},
  "materials": {{"m": {{"model": "velinov", "sigma_um": 10, "material": {{"F": 0.9}},
    "scratches": [{}]}}}},
  "objects": [{object}],
  "lights": [{{"type": "point", "position": [0.5, 3, 3], "intensity": 20}}],
  "spectrum": {{"mode": "single", "lambda_nm": 550}},
  "render": {{"spp": 1, "footprint": "ellipse"}}
}}"#,
        scratches.join(", ")
    )
}

#[test]
fn obj_square_renders_like_the_rectangle() {
    let d = dir();
    std::fs::write(d.join("square.obj"), SQUARE).unwrap();
    let rect = scene(
        r#"{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1], "size": [4, 4], "material": "m"}"#,
        0.0,
    );
    let mesh = scene(
        r#"{"shape": "mesh", "file": "square.obj", "uv_um": 4000, "material": "m"}"#,
        2000.0,
    );
    let read = |t: &str| {
        let v: serde_json::Value = serde_json::from_str(t).unwrap();
        scene_file::scene_from_value(&v, "t", &d).unwrap()
    };
    for backend in [Backend::Cpu, Backend::Embree] {
        if backend == Backend::Embree && scratchwave_embree::Device::new().is_err() {
            continue;
        }
        let a = render_scene(&read(&rect), backend, &|_, _| {})
            .unwrap()
            .image;
        let b = render_scene(&read(&mesh), backend, &|_, _| {})
            .unwrap()
            .image;
        let peak = a.rgb.iter().map(|p| p[0]).fold(0.0f32, f32::max);
        assert!(peak > 0.0);
        let mut lit = 0;
        for (k, (p, q)) in a.rgb.iter().zip(&b.rgb).enumerate() {
            if p[0] > 0.0 {
                lit += 1;
            }
            // The UV interpolation rounds x at ulp(4000 µm) = 2.4e-4 µm, against σ = 10 µm.
            let rel = (p[0] - q[0]).abs() / p[0].abs().max(q[0].abs()).max(1e-6 * peak);
            assert!(
                rel < 1e-3,
                "{backend:?} pixel {k}: rectangle {} mesh {}",
                p[0],
                q[0]
            );
        }
        // Away from the scratches' diffraction (ξ₁ ≉ 0) the values underflow to 0 in both.
        assert!(lit > 40, "{lit} lit pixels");
        eprintln!("{backend:?}: {lit} non-zero pixels");
    }
}

#[test]
fn broken_meshes_are_rejected_with_the_field_path() {
    let d = dir();
    std::fs::write(d.join("no_uv.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(d.join("garbage.obj"), "v 0 0 zero\nf 1 2 3\n").unwrap();
    std::fs::write(d.join("empty.obj"), "# nothing\n").unwrap();
    for (file, msg) in [
        ("missing.obj", "objects[0].file: cannot read mesh"),
        ("no_uv.obj", "objects[0].file: mesh"),
        ("garbage.obj", "objects[0].file: cannot read mesh"),
        ("empty.obj", "objects[0].file: "),
    ] {
        let t = scene(
            &format!(r#"{{"shape": "mesh", "file": "{file}", "uv_um": 4000, "material": "m"}}"#),
            0.0,
        );
        let v: serde_json::Value = serde_json::from_str(&t).unwrap();
        let e = scene_file::scene_from_value(&v, "t", &d)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(msg), "{file}: {e}");
    }
}
