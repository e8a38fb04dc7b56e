//! The reference commands end to end: `render --integrator reference` writes the mean,
//! `stderr.*` and `spp` channels; `compare` and `reference-check` report and write the
//! z-score EXR and heat map (exit 0: a measurement); bad input exits 2 naming the flag,
//! file or channel.

use std::path::PathBuf;
use std::process::{Command, Output};

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("scratchwave-reference-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scratchwave"))
        .args(args)
        .output()
        .unwrap()
}

const SCENE: &str = r#"{
  "camera": {"type": "orthographic", "eye": [0, -3, 4], "target": [0, 0, 0], "up": [0, 0, 1],
             "view_height": 2, "width_px": 8, "height_px": 6},
  "materials": {"m": {"model": "ghs", "material": {"sigma_s_um": 0.1, "beta": 0.05, "p": 1.0,
                "b_um": 2.0, "c": 2.0, "ior": [1.5, 0.0]}}},
  "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
               "normal": [0, 0, 1], "size": [8, 8], "material": "m"}],
  "lights": [{"type": "sphere", "center": [0.5, 1.5, 2.0], "radius": 0.5, "radiance": 3.0}],
  "spectrum": {"mode": "rgb"},
  "render": {"spp": 1, "footprint": "none"}
}"#;

fn scene() -> String {
    let p = dir().join("scene.json");
    std::fs::write(&p, SCENE).unwrap();
    p.to_str().unwrap().to_string()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn reference_render_compare_and_check() {
    let s = scene();
    let d = dir();
    let (r, a) = (d.join("ref.exr"), d.join("analytic.exr"));
    let o = run(&[
        "render",
        &s,
        "--integrator",
        "reference",
        "--backend",
        "cpu",
        "--out",
        r.to_str().unwrap(),
        "--min-spp",
        "32",
        "--max-spp",
        "64",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("reference 8x6: "), "{}", stderr(&o));
    let o = run(&["render", &s, "--out", a.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = d.join("cmp");
    let o = run(&[
        "compare",
        a.to_str().unwrap(),
        r.to_str().unwrap(),
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report = String::from_utf8_lossy(&o.stdout);
    assert!(report.contains("within 3 SE"), "{report}");
    assert!(out.join("analytic-zscore.exr").is_file());
    assert!(out.join("analytic-zscore.png").is_file());
    let chk = d.join("chk");
    let o = run(&[
        "reference-check",
        &s,
        "--backend",
        "cpu",
        "--min-spp",
        "16",
        "--max-spp",
        "32",
        "--out-dir",
        chk.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for f in ["analytic.exr", "reference.exr", "zscore.exr", "zscore.png"] {
        assert!(chk.join(format!("scene-{f}")).is_file(), "{f}");
    }
}

/// Exit 2 and the message's first words.
fn rejects(args: &[&str], prefix: &str) {
    let o = run(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    assert!(
        stderr(&o).starts_with(&format!("error: {prefix}")),
        "{args:?}: {}",
        stderr(&o)
    );
    assert!(o.stdout.is_empty());
}

#[test]
fn bad_input_exits_2_naming_it() {
    let s = scene();
    let r = ["render", s.as_str(), "--integrator", "reference"];
    rejects(&[&r[..], &["--rel-stderr", "0"]].concat(), "--rel-stderr: ");
    rejects(&[&r[..], &["--max-spp", "x"]].concat(), "--max-spp: ");
    rejects(&[&r[..], &["--pixel", "disk"]].concat(), "--pixel: ");
    rejects(&[&r[..], &["--spectral", "rgb"]].concat(), "--spectral: ");
    rejects(&[&r[..], &["--backend", "spirv"]].concat(), "--backend: ");
    rejects(
        &["render", &s, "--integrator", "mc"],
        "unknown --integrator",
    );
    rejects(
        &["render", &s, "--max-spp", "8"],
        "--max-spp needs --integrator reference",
    );
    let missing = dir().join("missing.json");
    rejects(
        &["reference-check", missing.to_str().unwrap()],
        &format!("{}: cannot read", missing.display()),
    );
    // An analytic EXR has no stderr channels.
    let a = dir().join("plain.exr");
    let o = run(&["render", &s, "--out", a.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let a = a.to_str().unwrap();
    rejects(
        &["compare", a, a],
        &format!("{a}: channel stderr.R: missing"),
    );
}
