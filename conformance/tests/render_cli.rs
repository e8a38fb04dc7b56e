//! `scratchwave render` end to end: a good scene writes the EXR and PNG and reports its
//! final line; bad input exits 2 with `error: <path>: <what>`, nothing on stdout, and
//! nothing at `--out`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("scratchwave-render-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A directory of its own for a test that writes images successfully: their temporary
/// `.partial` files must not meet the "nothing left behind" checks of the tests that run
/// beside it in [`dir`].
fn out_dir(test: &str) -> PathBuf {
    let d = dir().join(test);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `scene` to `<name>.json` and runs `scratchwave render` on it with `args`.
fn render(name: &str, scene: &str, args: &[&str]) -> (Output, PathBuf) {
    let path = dir().join(format!("{name}.json"));
    std::fs::write(&path, scene).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_scratchwave"))
        .arg("render")
        .arg(&path)
        .args(args)
        .output()
        .unwrap();
    (out, path)
}

const GOOD: &str = r#"{
  "camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0],
             "view_height": 1, "width_px": 8, "height_px": 6},
  "materials": {"m": {"model": "werner", "material": {"F": 0.9},
    "scratches": [{"p0": [-300, 0], "p1": [300, 0], "width": 2, "depth": 0.3}]}},
  "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
               "normal": [0, 0, 1], "size": [2, 2], "material": "m"}],
  "lights": [{"type": "point", "position": [0, 0.1, 4], "intensity": 10}],
  "spectrum": {"mode": "rgb"},
  "render": {"spp": 1, "footprint": "none"}
}"#;

/// Runs a bad scene (GOOD with `from` replaced by `to`) and checks exit 2, the exact
/// message prefix, empty stdout and no file at `--out`.
fn rejects(name: &str, from: &str, to: &str, message_prefix: &str) {
    assert!(GOOD.contains(from), "{from} not in the good scene");
    let scene = GOOD.replacen(from, to, 1);
    let out_path = dir().join(format!("{name}.exr"));
    let _ = std::fs::remove_file(&out_path);
    let (out, path) = render(name, &scene, &["--out", out_path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    let expected = message_prefix.replace("FILE", path.to_str().unwrap());
    assert!(
        stderr.starts_with(&format!("error: {expected}")),
        "{name}: got {stderr:?}, expected it to start with {expected:?}"
    );
    assert!(out.stdout.is_empty(), "{name}: stdout not empty");
    assert!(!out_path.exists(), "{name}: --out was created");
    assert!(
        no_partial_files(&dir()),
        "{name}: a temporary file was left behind"
    );
}

fn no_partial_files(d: &Path) -> bool {
    std::fs::read_dir(d).unwrap().all(|e| {
        !e.unwrap()
            .file_name()
            .to_string_lossy()
            .ends_with(".partial")
    })
}

#[test]
fn good_scene_writes_exr_and_png_and_reports() {
    let exr = out_dir("good").join("good.exr");
    let png = out_dir("good").join("good.png");
    let (out, _) = render(
        "good",
        GOOD,
        &[
            "--out",
            exr.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(out.stdout.is_empty());
    let last = stderr.lines().last().unwrap();
    assert!(
        last.starts_with("rendered 8x6 in ")
            && last.contains("Mrays/s")
            && last.ends_with("shading evaluations (cpu)"),
        "{last}"
    );
    let img = scratchwave_render::output::read_exr(&exr).unwrap();
    assert_eq!((img.width, img.height), (8, 6));
    assert!(
        img.rgb.iter().any(|p| p[0] > 0.0),
        "the plate under the light is lit"
    );
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn unknown_light_type() {
    rejects(
        "light_type",
        r#""type": "point""#,
        r#""type": "laser""#,
        "lights[0].type: unknown value \"laser\"",
    );
}

#[test]
fn unknown_material() {
    rejects(
        "material_name",
        r#""material": "m""#,
        r#""material": "gold""#,
        "objects[0].material: unknown material \"gold\"",
    );
}

#[test]
fn nan_and_non_numbers() {
    // JSON has no NaN: a bare NaN is malformed JSON (the file is named), a string is not a
    // number (the field is named), and 1e999 overflows.
    rejects(
        "nan_bare",
        r#""view_height": 1"#,
        r#""view_height": NaN"#,
        "FILE: malformed JSON",
    );
    rejects(
        "nan_string",
        r#""view_height": 1"#,
        r#""view_height": "NaN""#,
        "camera.view_height: expected a number",
    );
    rejects(
        "nan_overflow",
        r#""intensity": 10"#,
        r#""intensity": 1e999"#,
        "FILE: malformed JSON",
    );
}

#[test]
fn zero_and_absurd_image_sizes() {
    rejects(
        "zero_width",
        r#""width_px": 8"#,
        r#""width_px": 0"#,
        "camera.width_px: must be an integer in 1..=32768, got 0",
    );
    rejects(
        "huge_height",
        r#""height_px": 6"#,
        r#""height_px": 1e9"#,
        "camera.height_px: must be an integer in 1..=32768",
    );
    // 32768 × 32768 pixels: within the edge limit, beyond the memory limit.
    rejects(
        "memory",
        r#""width_px": 8, "height_px": 6"#,
        r#""width_px": 32768, "height_px": 32768"#,
        "camera.width_px: the scene needs about",
    );
}

#[test]
fn bad_polygon_and_unknown_fields() {
    rejects(
        "collinear_polygon",
        r#"{"type": "point", "position": [0, 0.1, 4], "intensity": 10}"#,
        r#"{"type": "polygon", "vertices": [[0, 0, 3], [1, 0, 3], [2, 0, 3]], "radiance": 1}"#,
        "lights[0].vertices: not a simple polygon with non-zero area",
    );
    rejects(
        "unknown_field",
        r#""size": [2, 2]"#,
        r#""size": [2, 2], "colour": 1"#,
        "objects[0].colour: unknown field",
    );
}

#[test]
fn unwritable_out_leaves_nothing() {
    let target = dir().join("no_such_dir").join("x.exr");
    let (out, _) = render("unwritable", GOOD, &["--out", target.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with(&format!("error: {}: cannot", target.display())),
        "{stderr}"
    );
    assert!(!target.exists());
}

#[test]
fn missing_and_malformed_meshes() {
    let mesh = |file: &str| {
        format!(r#"{{"shape": "mesh", "file": "{file}", "uv_um": 1000, "material": "m"}}"#)
    };
    let rect = r#"{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
               "normal": [0, 0, 1], "size": [2, 2], "material": "m"}"#;
    std::fs::write(dir().join("broken.obj"), "v 0 0 0\nf 1 2 three\n").unwrap();
    rejects(
        "missing_mesh",
        rect,
        &mesh("does_not_exist.obj"),
        "objects[0].file: cannot read mesh",
    );
    rejects(
        "malformed_mesh",
        rect,
        &mesh("broken.obj"),
        "objects[0].file: cannot read mesh",
    );
}

/// `"model": "auto"`: the EXR gets the `auto.coherent`/`auto.incoherent` channels, stderr a
/// line with the counts, `--model-map` a PNG; `--model-map` on a scene without `auto`
/// exits 2 naming the flag and writes nothing.
#[test]
fn auto_model_writes_its_map_and_counts() {
    let auto = GOOD.replacen(
        r#""model": "werner""#,
        r#""model": "auto", "tolerance": 0.01"#,
        1,
    );
    let exr = out_dir("auto").join("auto.exr");
    let map = out_dir("auto").join("auto-map.png");
    let (out, _) = render(
        "auto",
        &auto,
        &[
            "--out",
            exr.to_str().unwrap(),
            "--model-map",
            map.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let line = stderr.lines().find(|l| l.starts_with("auto: ")).unwrap();
    // 8×6 pixels, one light: 48 hit–light pairs.
    assert!(line.contains(" of 48 hit-light pairs coherent"), "{line}");
    let ch = scratchwave_render::layered_exr::Channels::read(&exr).unwrap();
    let (c, i) = (
        ch.channel("auto.coherent").unwrap(),
        ch.channel("auto.incoherent").unwrap(),
    );
    assert!(c.iter().zip(i).all(|(a, b)| a + b == 1.0), "{c:?} {i:?}");
    assert!(std::fs::read(&map).unwrap().starts_with(b"\x89PNG"));

    let exr = out_dir("no-auto").join("no-auto.exr");
    let map = out_dir("no-auto").join("no-auto-map.png");
    let (out, _) = render(
        "no-auto",
        GOOD,
        &[
            "--out",
            exr.to_str().unwrap(),
            "--model-map",
            map.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.starts_with("error: --model-map: "), "{stderr}");
    assert!(!exr.exists() && !map.exists());
}
