//! Scene conformance: every scene under `conformance/scenes/` rendered with the portable
//! kernel BVH (`cpu`) and with Embree, compared pixel by pixel.
//!
//! Per pixel and channel the relative difference is `|a − b| / max(|a|, |b|, floor)` with
//! `floor = 1e-6 ×` the image's largest value (dark pixels are compared absolutely at that
//! scale). A scene passes when at most `max_bad_pixels` pixels exceed its `rel_tol`; both
//! come from the scene's `"conformance"` object with the reason (`"why"`).

use scratchwave_render::{Backend, render_scene, scene_file};
use scratchwave_spec::SpecError;
use scratchwave_spec::json::Obj;
use std::path::{Path, PathBuf};

/// One scene's comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneReport {
    /// Scene name (file stem).
    pub name: String,
    /// Image size.
    pub size: (u32, u32),
    /// Declared per-pixel relative tolerance.
    pub rel_tol: f64,
    /// Pixels allowed beyond it (edge ties, grazing hits).
    pub max_bad_pixels: usize,
    /// Why the tolerance is what it is.
    pub why: String,
    /// Worst relative difference.
    pub worst: f64,
    /// 99.9th percentile of the per-pixel relative difference.
    pub p999: f64,
    /// Pixels beyond `rel_tol`.
    pub bad_pixels: usize,
    /// Render seconds (cpu, embree).
    pub seconds: (f64, f64),
    /// Whether it passed.
    pub pass: bool,
    /// A failure to render, if any.
    pub error: Option<String>,
}

/// The `*.json` scenes of `dir`, sorted.
pub fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// `(rel_tol, max_bad_pixels, why)` from the scene file's `"conformance"` object.
pub fn tolerance(path: &Path) -> Result<(f64, usize, String), SpecError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SpecError::Io {
        path: file.clone(),
        msg: e.to_string(),
    })?;
    let v = scratchwave_spec::json::parse(&text, &file)?;
    let c = v
        .get("conformance")
        .ok_or_else(|| SpecError::field("conformance", "missing required field"))?;
    let o = Obj::new(c, "conformance", &["rel_tol", "max_bad_pixels", "why"])?;
    let rel = o.num("rel_tol")?;
    let bad = if o.get("max_bad_pixels").is_some() {
        o.integer("max_bad_pixels", 1e9)? as usize
    } else {
        0
    };
    let why = o
        .req("why")?
        .as_str()
        .ok_or_else(|| SpecError::field("conformance.why", "expected a string"))?
        .to_string();
    Ok((rel, bad, why))
}

/// Per-pixel relative differences (the largest over R, G, B) of two images.
pub fn pixel_differences(a: &[[f32; 3]], b: &[[f32; 3]]) -> Vec<f64> {
    let peak = a
        .iter()
        .chain(b)
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, &x| m.max(f64::from(x).abs()));
    let floor = (peak * 1e-6).max(f64::MIN_POSITIVE);
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            (0..3)
                .map(|c| {
                    let (x, y) = (f64::from(p[c]), f64::from(q[c]));
                    (x - y).abs() / x.abs().max(y.abs()).max(floor)
                })
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Renders and compares one scene.
pub fn compare_scene(path: &Path) -> SceneReport {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut r = SceneReport {
        name,
        size: (0, 0),
        rel_tol: 0.0,
        max_bad_pixels: 0,
        why: String::new(),
        worst: f64::NAN,
        p999: f64::NAN,
        bad_pixels: 0,
        seconds: (0.0, 0.0),
        pass: false,
        error: None,
    };
    let result = (|| -> Result<(), String> {
        let (rel, bad, why) = tolerance(path).map_err(|e| e.to_string())?;
        (r.rel_tol, r.max_bad_pixels, r.why) = (rel, bad, why);
        let scene = scene_file::read_scene(path).map_err(|e| e.to_string())?;
        let a = render_scene(&scene, Backend::Cpu, &|_, _| {}).map_err(|e| e.to_string())?;
        let b = render_scene(&scene, Backend::Embree, &|_, _| {}).map_err(|e| e.to_string())?;
        r.size = (a.image.width, a.image.height);
        r.seconds = (a.stats.seconds, b.stats.seconds);
        let mut d = pixel_differences(&a.image.rgb, &b.image.rgb);
        r.bad_pixels = d.iter().filter(|&&x| !(x <= rel)).count();
        d.sort_by(f64::total_cmp);
        r.worst = d.last().copied().unwrap_or(0.0);
        let k = ((d.len() as f64) * 0.999).ceil() as usize;
        r.p999 = d.get(k.saturating_sub(1)).copied().unwrap_or(0.0);
        r.pass = r.bad_pixels <= r.max_bad_pixels;
        Ok(())
    })();
    if let Err(e) = result {
        r.error = Some(e);
        r.pass = false;
    }
    r
}

/// A Markdown table of scene reports.
pub fn markdown(reports: &[SceneReport]) -> String {
    let mut s = String::from(
        "## Scenes: cpu (kernel BVH) vs embree, per pixel\n\n| scene | size | worst rel | 99.9 % rel | beyond tol | allowed | rel_tol | cpu s | embree s | pass |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        s += &format!(
            "| {} | {}x{} | {:.3e} | {:.3e} | {} | {} | {:.0e} | {:.3} | {:.3} | {} |\n",
            r.name,
            r.size.0,
            r.size.1,
            r.worst,
            r.p999,
            r.bad_pixels,
            r.max_bad_pixels,
            r.rel_tol,
            r.seconds.0,
            r.seconds.1,
            if r.pass { "yes" } else { "**no**" }
        );
        if let Some(e) = &r.error {
            s += &format!("\n{}: error: {e}\n", r.name);
        }
    }
    for r in reports {
        s += &format!("\n- {}: {}", r.name, r.why);
    }
    s.push('\n');
    s
}
