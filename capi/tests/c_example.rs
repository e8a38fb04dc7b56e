//! `examples/eval.c` compiled with the system C compiler against the static library and
//! run: every value it prints equals, bit for bit, the Rust batch core's and the kernel's
//! `bsdf::eval`/`pdf`/`sample` on the same inputs; rejected inputs return the status and a
//! message naming the field.

use scratchwave_capi::{Bsdf, Queries};
use scratchwave_kernel::bsdf::{self, Lookup, ShadingPoint, Wavelengths};
use scratchwave_kernel::glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The directory cargo put the library in (the test binary lives in its `deps/`).
fn artifact_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>")
        .to_path_buf()
}

/// The cargo profile this test was built with, named as `--profile` takes it: the artifact
/// directory's name (`release`, or a custom profile's), `debug` being the `dev` profile's.
fn cargo_profile() -> String {
    let dir = artifact_dir();
    let name = dir
        .file_name()
        .and_then(|n| n.to_str())
        .expect("profile directory name");
    if name == "debug" { "dev" } else { name }.to_string()
}

/// Parses C's `%a` output (`0x1.8p-3`, `-0x0p+0`).
fn hex_float(s: &str) -> f32 {
    let (neg, t) = s.strip_prefix('-').map_or((false, s), |t| (true, t));
    let t = t.strip_prefix("0x").expect("hex float");
    let (mant, exp) = t.split_once('p').expect("exponent");
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    let mut m = u64::from_str_radix(int, 16).expect("integer part") as f64;
    let mut scale = 1.0 / 16.0;
    for c in frac.chars() {
        m += f64::from(c.to_digit(16).expect("hex digit")) * scale;
        scale /= 16.0;
    }
    let v = m * 2f64.powi(exp.parse::<i32>().expect("exponent"));
    (if neg { -v } else { v }) as f32
}

const MATERIAL: &str = r#"{"model": "velinov", "sigma_um": 10, "material": {"F": 0.9},
 "scratches": [{"p0": [-100, 0], "p1": [100, 0], "width": 2, "depth": 0.3},
               {"p0": [0, -80], "p1": [5, 80], "width": 1.5, "depth": 0.2, "profile": "triangle"}]}"#;

#[test]
fn c_example_matches_rust_bitwise() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    // `cargo test` links the tests with the rlib only: build the static library (the same
    // sources and profile; the outer cargo has released the build directory by now).
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let st = Command::new(&cargo)
        .args([
            "build",
            "--quiet",
            "--lib",
            "-p",
            "scratchwave-capi",
            "--profile",
        ])
        .arg(cargo_profile())
        .current_dir(dir)
        .status()
        .expect("run cargo");
    assert!(st.success(), "cargo build -p scratchwave-capi failed");
    let lib = artifact_dir().join("libscratchwave_capi.a");
    assert!(lib.exists(), "{} missing", lib.display());
    let exe = artifact_dir().join("capi_example_eval");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let st = Command::new(&cc)
        .args(["-O2", "-Wall", "-Wextra", "-Werror", "-std=c11"])
        .arg("-I")
        .arg(dir.join("include"))
        .arg(dir.join("examples/eval.c"))
        .arg(&lib)
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&exe)
        .status()
        .expect("run the C compiler");
    assert!(st.success(), "{cc} failed on examples/eval.c");
    let out = Command::new(&exe).output().expect("run the C example");
    assert!(
        out.status.success(),
        "C example failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let mut vals: HashMap<String, Vec<f32>> = HashMap::new();
    let mut words: HashMap<String, String> = HashMap::new();
    for line in text.lines() {
        let mut it = line.splitn(3, ' ');
        let (name, _i, v) = (it.next().unwrap(), it.next().unwrap(), it.next().unwrap());
        if v.contains("0x") {
            vals.entry(name.into()).or_default().push(hex_float(v));
        } else {
            words.insert(name.into(), v.into());
        }
    }
    let get = |k: &str| vals.get(k).unwrap_or_else(|| panic!("{k} missing")).clone();
    let (wo, wi, x, u) = (get("wo"), get("wi"), get("x"), get("u"));
    let n = wo.len() / 3;
    assert_eq!(n, 64);
    assert_eq!(words["scratch_count"], "2");

    // The Rust batch core on the same inputs.
    let m = Bsdf::from_json(MATERIAL, None, None).expect("material");
    let q = Queries {
        wo: &wo,
        wi: Some(&wi),
        x_um: Some(&x),
        ..Queries::default()
    };
    let mut f = vec![0.0; 3 * n];
    m.eval(&q, &mut f).unwrap();
    let mut pdf = vec![0.0; n];
    m.pdf(&q, &mut pdf).unwrap();
    let (mut swi, mut sw, mut sp) = (vec![0.0; 3 * n], vec![0.0; 3 * n], vec![0.0; n]);
    m.sample(&q, &u, &mut swi, &mut sw, &mut sp).unwrap();
    let lambda = get("lambda");
    let q1 = Queries {
        lambda_nm: Some(&lambda),
        lambda_count: 1,
        ..q
    };
    let mut f1 = vec![0.0; n];
    m.eval(&q1, &mut f1).unwrap();

    let bits = |a: &[f32]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for (name, rust) in [
        ("eval", &f),
        ("pdf", &pdf),
        ("sample_wi", &swi),
        ("sample_weight", &sw),
        ("sample_pdf", &sp),
        ("eval_spectral", &f1),
    ] {
        assert_eq!(bits(&get(name)), bits(rust), "{name}: C and Rust differ");
    }
    // The values are not trivial: some of every kind are positive.
    assert!(f.iter().filter(|v| **v > 0.0).count() > n);
    assert!(sp.iter().filter(|v| **v > 0.0).count() > n / 2);

    // The kernel called directly, query by query, gives the same bits.
    let set_owner = scratchwave_host::ScratchLookup::new(
        &scratchwave_spec::spec::scratch_list(
            &serde_json::from_str::<serde_json::Value>(MATERIAL).unwrap()["scratches"],
            "scratches",
        )
        .unwrap(),
        10.0,
    );
    let set = set_owner.set();
    let lk = Lookup::new(&set);
    let v3 = |a: &[f32], i: usize| Vec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
    for i in 0..n {
        let pt = ShadingPoint::at([x[2 * i], x[2 * i + 1]]);
        let wl = Wavelengths::rgb();
        let k = bsdf::eval(m.material(), &pt, v3(&wi, i), v3(&wo, i), &wl, &lk);
        assert_eq!(bits(&k.v[..3]), bits(&f[3 * i..3 * i + 3]), "eval {i}");
        let p = bsdf::pdf(m.material(), &pt, v3(&wo, i), v3(&wi, i), &wl, &lk);
        assert_eq!(p.to_bits(), pdf[i].to_bits(), "pdf {i}");
        let s = bsdf::sample(
            m.material(),
            &pt,
            v3(&wo, i),
            &wl,
            u[3 * i],
            Vec2::new(u[3 * i + 1], u[3 * i + 2]),
            &lk,
        );
        assert_eq!(
            s.map_or(0.0, |s| s.pdf).to_bits(),
            sp[i].to_bits(),
            "sample {i}"
        );
    }

    // Rejections: status codes and messages naming the field.
    assert_eq!(words["bad_status"], "2");
    assert_eq!(
        words["bad_message"],
        "material.sigma_um: must be > 0, got -1"
    );
    assert_eq!(words["bad_handle"], "1");
    assert_eq!(words["short_status"], "1");
    assert_eq!(words["short_message"], "out: expected 192 values, got 191");
}
