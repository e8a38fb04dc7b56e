//! The pieces of the `tradeoff` binary (speed against accuracy of the scratch models on one
//! scene, `docs/tradeoff.md`) that need no renderer: the command line, the material
//! rewrite that makes each variant of a scene, and the error metrics against the truth.

use scratchwave_render::reference::{quantile_sorted, relative_error_floor};
use serde_json::{Map, Value};

/// A model choice applied to every scratch material of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Variant {
    /// Werner 2017's coherent sum (`werner`, or `werner_blended` with a smooth or GHS base).
    Werner,
    /// Velinov's incoherent sum with Werner's exact depth phase (area lights by the extent
    /// rule, the scene reader's default).
    Velinov,
    /// [`Variant::Velinov`] with this `"light_integral"` (a name of
    /// `scratchwave_spec::material::LIGHT_METHODS`).
    VelinovLight(String),
    /// `"model": "auto"` with this `"tolerance"`; `text` is the tolerance as written.
    Auto {
        /// The tolerance.
        tolerance: f64,
        /// The tolerance as given on the command line (for labels).
        text: String,
    },
}

impl Variant {
    /// `werner`, `velinov` or `auto:T` (T as written).
    pub fn label(&self) -> String {
        match self {
            Variant::Werner => "werner".into(),
            Variant::Velinov => "velinov".into(),
            Variant::VelinovLight(m) => format!("velinov:{m}"),
            Variant::Auto { text, .. } => format!("auto:{text}"),
        }
    }

    /// Whether this is an `auto:T` variant.
    pub fn is_auto(&self) -> bool {
        matches!(self, Variant::Auto { .. })
    }
}

/// Parses `werner,velinov,velinov:eq27,auto:0.01`: each name once, tolerances finite and
/// > 0, `velinov:M` with M a `"light_integral"` name.
pub fn parse_variants(s: &str) -> Result<Vec<Variant>, String> {
    let mut out: Vec<Variant> = Vec::new();
    for item in s.split(',') {
        let item = item.trim();
        let v = match item {
            "werner" => Variant::Werner,
            "velinov" => Variant::Velinov,
            _ if item.starts_with("velinov:") => {
                let m = &item["velinov:".len()..];
                let names = scratchwave_spec::material::LIGHT_METHODS.map(|(n, _)| n);
                if !names.contains(&m) {
                    return Err(format!(
                        "{item:?}: unknown light integral (expected one of {})",
                        names.join(", ")
                    ));
                }
                Variant::VelinovLight(m.to_string())
            }
            _ => match item.strip_prefix("auto:") {
                Some(t) => {
                    let tolerance: f64 = t
                        .parse()
                        .map_err(|_| format!("{item:?}: the tolerance is not a number"))?;
                    if !(tolerance.is_finite() && tolerance > 0.0) {
                        return Err(format!("{item:?}: the tolerance must be finite and > 0"));
                    }
                    Variant::Auto {
                        tolerance,
                        text: t.to_string(),
                    }
                }
                None => {
                    return Err(format!(
                        "unknown variant {item:?} (expected werner, velinov, velinov:M or auto:T)"
                    ));
                }
            },
        };
        if out.iter().any(|o| o.label() == v.label()) {
            return Err(format!("variant {item:?} given twice"));
        }
        out.push(v);
    }
    Ok(out)
}

/// Parses a comma-separated list of sample counts, each a multiple of 4 in 8..=2^24
/// (the reference draws passes of 4 samples and needs two passes for a standard error).
pub fn parse_spp_list(s: &str) -> Result<Vec<u32>, String> {
    s.split(',').map(|x| parse_spp(x.trim())).collect()
}

/// One sample count, see [`parse_spp_list`].
pub fn parse_spp(s: &str) -> Result<u32, String> {
    let n: u32 = s
        .parse()
        .map_err(|_| format!("{s:?} is not a sample count"))?;
    if !(8..=1 << 24).contains(&n) || !n.is_multiple_of(4) {
        return Err(format!(
            "{n}: must be a multiple of 4 in 8..=16777216 (samples come in passes of 4)"
        ));
    }
    Ok(n)
}

/// The ray backend named on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendChoice {
    /// Embree 4.
    Embree,
    /// The portable kernel BVH.
    Cpu,
}

/// The command line of `tradeoff`.
#[derive(Clone, Debug, PartialEq)]
pub struct Args {
    /// The scene file.
    pub scene: String,
    /// Model variants, in order.
    pub variants: Vec<Variant>,
    /// Sample counts of the Monte Carlo curve (seed 2).
    pub reference_spp: Vec<u32>,
    /// Sample count of the truth (seed 1).
    pub truth_spp: u32,
    /// Renders per variant (the median time is kept).
    pub repeats: u32,
    /// Ray backend.
    pub backend: BackendChoice,
    /// Output directory.
    pub out_dir: String,
    /// Output file stem (default: the scene file's stem).
    pub name: String,
}

/// The usage line.
pub const USAGE: &str = "usage: tradeoff SCENE.json [--variants werner,velinov,velinov:eq27,velinov:eq27_eq29,velinov:hermite3,auto:0.1,auto:0.01,auto:0.001] \
[--reference-spp 16,64,256,1024] [--truth-spp 4096] [--repeats 3] [--backend embree|cpu] \
[--out-dir docs/tradeoff] [--name NAME]";

/// Parses the arguments (without the program name). An error is `(flag or argument, what)`.
pub fn parse_args(args: &[String]) -> Result<Args, (String, String)> {
    let mut scene: Option<String> = None;
    let mut seen: Vec<&str> = Vec::new();
    let mut a = Args {
        scene: String::new(),
        variants: parse_variants("werner,velinov,velinov:eq27,velinov:eq27_eq29,velinov:hermite3,auto:0.1,auto:0.01,auto:0.001")
            .expect("default variants"),
        reference_spp: vec![16, 64, 256, 1024],
        truth_spp: 4096,
        repeats: 3,
        backend: BackendChoice::Embree,
        out_dir: "docs/tradeoff".into(),
        name: String::new(),
    };
    let mut k = 0;
    while k < args.len() {
        let arg = args[k].as_str();
        if !arg.starts_with("--") {
            if scene.is_some() {
                return Err((
                    arg.into(),
                    "unexpected argument (one scene file only)".into(),
                ));
            }
            scene = Some(arg.into());
            k += 1;
            continue;
        }
        let flag = match arg {
            "--variants" | "--reference-spp" | "--truth-spp" | "--repeats" | "--backend"
            | "--out-dir" | "--name" => arg,
            _ => return Err((arg.into(), format!("unknown flag; {USAGE}"))),
        };
        if seen.contains(&flag) {
            return Err((flag.into(), "given twice".into()));
        }
        seen.push(flag);
        let val = match args.get(k + 1) {
            Some(v) if !v.starts_with("--") => v.as_str(),
            _ => return Err((flag.to_string(), "needs a value".to_string())),
        };
        let e = |m: String| (flag.to_string(), m);
        match flag {
            "--variants" => a.variants = parse_variants(val).map_err(e)?,
            "--reference-spp" => a.reference_spp = parse_spp_list(val).map_err(e)?,
            "--truth-spp" => a.truth_spp = parse_spp(val).map_err(e)?,
            "--repeats" => {
                a.repeats = match val.parse::<u32>() {
                    Ok(n) if (1..=1000).contains(&n) => n,
                    _ => return Err(e(format!("{val:?}: must be an integer in 1..=1000"))),
                }
            }
            "--backend" => {
                a.backend = match val {
                    "embree" => BackendChoice::Embree,
                    "cpu" => BackendChoice::Cpu,
                    _ => return Err(e(format!("{val:?}: expected embree or cpu"))),
                }
            }
            "--out-dir" => {
                if val.is_empty() {
                    return Err(e("must not be empty".into()));
                }
                a.out_dir = val.into();
            }
            _ => {
                if !valid_name(val) {
                    return Err(e(format!(
                        "{val:?}: use letters, digits, '_', '-' and '.' only (a file stem)"
                    )));
                }
                a.name = val.into();
            }
        }
        k += 2;
    }
    a.scene = scene.ok_or_else(|| ("SCENE.json".to_string(), format!("missing; {USAGE}")))?;
    if a.name.is_empty() {
        let stem = std::path::Path::new(&a.scene)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !valid_name(&stem) {
            return Err((
                a.scene.clone(),
                "the file stem is not a usable output name; give --name".into(),
            ));
        }
        a.name = stem;
    }
    Ok(a)
}

fn valid_name(s: &str) -> bool {
    !s.is_empty()
        && !s.starts_with('.')
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
}

/// Models the rewrite applies to; `ghs` materials (and anything else) are left alone.
pub const SCRATCH_MODELS: [&str; 4] = ["werner", "werner_blended", "velinov", "auto"];

/// A base that is a surface of its own: `"smooth"` or a GHS material object.
fn is_real_base(b: &Value) -> bool {
    b.is_object() || b.as_str() == Some("smooth")
}

/// The scene `scene` with every material of a model in [`SCRATCH_MODELS`] rewritten to
/// `variant`, and the number of materials rewritten. The scene reader
/// (`scene_file`, `spec::material::scene_material`) takes a smooth or GHS base as the
/// top-level `base` of `werner_blended` and `velinov`, `options.base` (`"none"` or
/// `"gaussian"`) and `options.eta` for `velinov` only:
///
/// * `werner`: with a smooth or GHS base (top-level `base`, or one written under
///   `options.base`) → `werner_blended` with it at the top level; otherwise `werner` without
///   any base. `options.eta` and `options.base` removed, `options.depth_term = "exact"`.
/// * `velinov`: `options.depth_term = "exact"` (Werner's depth phase); a smooth or GHS base
///   kept at the top level, otherwise `options.base = "gaussian"`.
/// * `velinov:M`: as `velinov`, with `"light_integral": M`.
/// * `auto:T`: `"model": "auto"`, `"tolerance": T`, everything else as written.
///
/// `tolerance` is removed by `werner` and `velinov`.
pub fn rewrite(scene: &Value, variant: &Variant) -> Result<(Value, usize), String> {
    let mut out = scene.clone();
    let mats = out
        .get_mut("materials")
        .and_then(Value::as_object_mut)
        .ok_or("materials: expected an object of named materials")?;
    let mut n = 0;
    for (name, m) in mats.iter_mut() {
        let Some(obj) = m.as_object_mut() else {
            return Err(format!("materials.{name}: expected an object"));
        };
        let model = obj.get("model").and_then(Value::as_str).unwrap_or("");
        if !SCRATCH_MODELS.contains(&model) {
            continue;
        }
        rewrite_material(obj, variant);
        n += 1;
    }
    Ok((out, n))
}

fn rewrite_material(obj: &mut Map<String, Value>, variant: &Variant) {
    if let Variant::Auto { tolerance, .. } = variant {
        obj.insert("model".into(), Value::from("auto"));
        obj.insert("tolerance".into(), Value::from(*tolerance));
        return;
    }
    obj.remove("tolerance");
    obj.remove("light_integral");
    if let Variant::VelinovLight(m) = variant {
        obj.insert("light_integral".into(), Value::from(m.as_str()));
    }
    let mut options = match obj.remove("options") {
        Some(Value::Object(o)) => o,
        _ => Map::new(),
    };
    let top_base = obj.remove("base");
    let opt_base = options.remove("base");
    let base = [top_base, opt_base.clone()]
        .into_iter()
        .flatten()
        .find(is_real_base);
    options.insert("depth_term".into(), Value::from("exact"));
    match variant {
        Variant::Werner => {
            options.remove("eta");
            match base {
                Some(b) => {
                    obj.insert("model".into(), Value::from("werner_blended"));
                    obj.insert("base".into(), b);
                }
                None => {
                    obj.insert("model".into(), Value::from("werner"));
                }
            }
        }
        _ => {
            obj.insert("model".into(), Value::from("velinov"));
            match base {
                Some(b) => {
                    obj.insert("base".into(), b);
                }
                None => {
                    options.insert("base".into(), Value::from("gaussian"));
                }
            }
        }
    }
    obj.insert("options".into(), Value::Object(options));
}

/// Errors of an image against the truth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// `sqrt(Σ (a − r)² / Σ r²)` over all pixels and channels.
    pub rel_rmse: f64,
    /// The 99th percentile over pixels of the largest channel's `|a − r| / max(|r|, floor)`.
    pub p99: f64,
}

/// The floor of relative errors: 1e-3 of the 99.9th percentile of the truth pixels'
/// largest channel (the rule of `render/src/stat_compare.rs` and the reference commands).
pub fn floor_of(truth: &[[f32; 3]]) -> f64 {
    relative_error_floor(truth.iter().map(|p| p.map(f64::from)))
}

/// Errors of `a` against the truth `r` (same length), `floor` from [`floor_of`].
pub fn errors(a: &[[f32; 3]], r: &[[f32; 3]], floor: f64) -> Errors {
    deviations(r, floor, |k, c| f64::from(a[k][c]) - f64::from(r[k][c]))
}

/// The truth's own noise in the same two measures: `sqrt(Σ se² / Σ r²)` and the 99th
/// percentile over pixels of the largest channel's `se / max(|r|, floor)`. Errors below
/// these are not resolved by the truth.
pub fn noise(r: &[[f32; 3]], stderr: &[[f32; 3]], floor: f64) -> Errors {
    deviations(r, floor, |k, c| f64::from(stderr[k][c]))
}

fn deviations(r: &[[f32; 3]], floor: f64, d: impl Fn(usize, usize) -> f64) -> Errors {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    let mut rel = Vec::with_capacity(r.len());
    for (k, px) in r.iter().enumerate() {
        let mut worst: f64 = 0.0;
        for (c, &rc) in px.iter().enumerate() {
            let (dv, rv) = (d(k, c), f64::from(rc));
            num += dv * dv;
            den += rv * rv;
            let scale = rv.abs().max(floor);
            let e = if scale > 0.0 {
                dv.abs() / scale
            } else if dv != 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
            worst = worst.max(e);
        }
        rel.push(worst);
    }
    rel.sort_by(f64::total_cmp);
    Errors {
        rel_rmse: if den > 0.0 {
            (num / den).sqrt()
        } else if num > 0.0 {
            f64::INFINITY
        } else {
            0.0
        },
        p99: quantile_sorted(&rel, 0.99),
    }
}

/// The median of `v` (mean of the middle two for an even count; 0 when empty).
pub fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    match s.len() {
        0 => 0.0,
        n if n % 2 == 1 => s[n / 2],
        n => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn mat(scene: &Value, name: &str) -> Value {
        scene["materials"][name].clone()
    }

    fn scene() -> Value {
        json!({"materials": {
            "ghs_base": {"model": "auto", "tolerance": 0.01, "sigma_um": 10,
                         "base": {"sigma_s_um": 0.1, "beta": 0.05, "p": 1.0, "b_um": 2.0, "c": 2.0, "ior": [1.5, 0.0]},
                         "scratches": []},
            "smooth": {"model": "velinov", "base": "smooth", "options": {"eta": "infinite"}},
            "gauss": {"model": "velinov", "options": {"base": "gaussian", "eta": "finite"}},
            "plain": {"model": "werner"},
            "ball": {"model": "ghs", "material": {"sigma_s_um": 0.05}}
        }})
    }

    #[test]
    fn werner_with_ghs_base_becomes_werner_blended() {
        let (v, n) = rewrite(&scene(), &Variant::Werner).unwrap();
        assert_eq!(n, 4);
        let m = mat(&v, "ghs_base");
        assert_eq!(m["model"], "werner_blended");
        assert!(m["base"].is_object());
        assert!(m.get("tolerance").is_none());
        assert_eq!(m["options"], json!({"depth_term": "exact"}));
        assert_eq!(mat(&v, "smooth")["model"], "werner_blended");
        assert_eq!(mat(&v, "smooth")["base"], "smooth");
        let g = mat(&v, "gauss");
        assert_eq!(g["model"], "werner");
        assert!(g.get("base").is_none());
        assert_eq!(g["options"], json!({"depth_term": "exact"}));
        assert_eq!(mat(&v, "plain")["model"], "werner");
        assert_eq!(mat(&v, "ball"), mat(&scene(), "ball"));
    }

    #[test]
    fn velinov_keeps_real_bases_and_adds_gaussian_otherwise() {
        let (v, _) = rewrite(&scene(), &Variant::Velinov).unwrap();
        let m = mat(&v, "ghs_base");
        assert_eq!(m["model"], "velinov");
        assert!(m["base"].is_object());
        assert_eq!(m["options"], json!({"depth_term": "exact"}));
        assert_eq!(
            mat(&v, "smooth")["options"],
            json!({"depth_term": "exact", "eta": "infinite"})
        );
        let p = mat(&v, "plain");
        assert_eq!(p["model"], "velinov");
        assert_eq!(
            p["options"],
            json!({"depth_term": "exact", "base": "gaussian"})
        );
    }

    #[test]
    fn auto_sets_model_and_tolerance_only() {
        let vs = parse_variants("auto:0.001").unwrap();
        let (v, _) = rewrite(&scene(), &vs[0]).unwrap();
        let p = mat(&v, "gauss");
        assert_eq!(p["model"], "auto");
        assert_eq!(p["tolerance"], 0.001);
        assert_eq!(p["options"], mat(&scene(), "gauss")["options"]);
        assert_eq!(vs[0].label(), "auto:0.001");
    }

    #[test]
    fn velinov_light_sets_the_light_integral_and_werner_drops_it() {
        let vs = parse_variants("velinov:eq27_eq29,werner").unwrap();
        assert_eq!(vs[0].label(), "velinov:eq27_eq29");
        let (v, _) = rewrite(&scene(), &vs[0]).unwrap();
        let p = mat(&v, "plain");
        assert_eq!(p["model"], "velinov");
        assert_eq!(p["light_integral"], "eq27_eq29");
        let (w, _) = rewrite(&v, &vs[1]).unwrap();
        assert!(mat(&w, "plain").get("light_integral").is_none());
        let e = parse_variants("velinov:eq28").unwrap_err();
        assert!(e.contains("hermite5"), "{e}");
    }

    #[test]
    fn rel_rmse_and_p99() {
        let r: Vec<[f32; 3]> = (0..100).map(|k| [k as f32, 1.0, 2.0]).collect();
        let f = floor_of(&r);
        let same = errors(&r, &r, f);
        assert_eq!(
            same,
            Errors {
                rel_rmse: 0.0,
                p99: 0.0
            }
        );
        let double: Vec<[f32; 3]> = r.iter().map(|p| p.map(|x| 2.0 * x)).collect();
        let e = errors(&double, &r, f);
        assert!((e.rel_rmse - 1.0).abs() < 1e-12);
        assert!((e.p99 - 1.0).abs() < 1e-12);
        let zero = vec![[0.0f32; 3]; 100];
        assert_eq!(noise(&r, &zero, f).rel_rmse, 0.0);
    }

    /// Every variant of the committed scenes reads with the renderer's scene reader.
    #[test]
    fn committed_scenes_read_in_every_variant() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/tradeoff");
        let variants =
            parse_variants("werner,velinov,velinov:eq27_eq29,auto:0.1,auto:0.001").unwrap();
        for name in ["velinov_benchmark", "werner_closeup", "ghs_scratches"] {
            let text = std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap();
            let v: Value = serde_json::from_str(&text).unwrap();
            for var in &variants {
                let (rv, n) = rewrite(&v, var).unwrap();
                assert_eq!(n, 1, "{name}");
                scratchwave_render::scene_file::scene_from_value(&rv, name, &dir)
                    .unwrap_or_else(|e| panic!("{name} {}: {e}", var.label()));
            }
        }
    }

    #[test]
    fn flags() {
        let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let a = parse_args(&s(&["x/scene.json"])).unwrap();
        assert_eq!(a.name, "scene");
        assert_eq!(a.variants.len(), 8);
        assert_eq!(
            parse_args(&s(&["s.json", "--truth-spp", "10"]))
                .unwrap_err()
                .0,
            "--truth-spp"
        );
        assert_eq!(
            parse_args(&s(&["s.json", "--variants", "werner,phong"]))
                .unwrap_err()
                .0,
            "--variants"
        );
        assert_eq!(
            parse_args(&s(&["s.json", "--repeats"])).unwrap_err().0,
            "--repeats"
        );
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
    }
}
