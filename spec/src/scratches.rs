//! A material's `"scratches"`: a JSON array of sources, each an inline scratch, a file of
//! scratches (JSON or CSV), or a seeded pattern ([`scratchwave_host::pattern`]). The formats
//! are documented with examples in `docs/scratches.md`.
//!
//! All sources together may produce at most [`MAX_SEGMENTS`] segments; a pattern that could
//! exceed what is left is rejected before anything is allocated.

use crate::error::SpecError;
use crate::json::{self, Obj};
use crate::range;
use crate::spec::{point64, scratch, segment};
use scratchwave_host::pattern::{
    Count, Distribution, MAX_SEGMENTS, Orientation, PatternError, ProfileChoice, ScratchPattern,
    Shape,
};
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};
use serde_json::Value;
use std::path::Path;

/// Default `chord_tol_um` of a generated pattern (µm).
pub const DEFAULT_CHORD_TOL_UM: f64 = 0.1;

/// The CSV header a scratch file must start with.
pub const CSV_HEADER: &str = "x0,y0,x1,y1,width,depth,profile";

/// Largest seed accepted (2⁵³: every integer up to it is exact in JSON's doubles).
const MAX_SEED: f64 = 9_007_199_254_740_992.0;

/// Reads the array of scratch sources at `path` (e.g. `materials[0].scratches`) into scratch
/// segments, in source order; files are resolved relative to `base_dir`. At most
/// [`MAX_SEGMENTS`] segments in all (see [`scratch_sources_with_limit`]).
pub fn scratch_sources(v: &Value, path: &str, base_dir: &Path) -> Result<Vec<Scratch>, SpecError> {
    scratch_sources_with_limit(v, path, base_dir, MAX_SEGMENTS)
}

/// [`scratch_sources`] with a caller's segment budget `limit` (at most [`MAX_SEGMENTS`] is
/// useful; a larger value is clamped to it): a pattern that could exceed what is left of it
/// is rejected before anything is allocated. A service reading untrusted scenes (or the
/// fuzzer) passes a small budget so that a 200-byte spec cannot ask for a GiB of segments.
pub fn scratch_sources_with_limit(
    v: &Value,
    path: &str,
    base_dir: &Path,
    limit: usize,
) -> Result<Vec<Scratch>, SpecError> {
    let limit = limit.min(MAX_SEGMENTS);
    let sources = v
        .as_array()
        .ok_or_else(|| SpecError::field(path, "expected an array of scratch sources"))?;
    let mut out = Vec::new();
    for (i, s) in sources.iter().enumerate() {
        let p = format!("{path}[{i}]");
        let obj = s
            .as_object()
            .ok_or_else(|| SpecError::field(&p, "expected a JSON object (a scratch source)"))?;
        if obj.contains_key("file") {
            let o = Obj::new(s, &p, &["file"])?;
            let n = out.len();
            file(&o, base_dir, &mut out)?;
            if out.len() > limit {
                return Err(SpecError::field(
                    o.path_of("file"),
                    format!(
                        "{} scratches read, more than the {} left of the limit of {limit}",
                        out.len() - n,
                        limit - n
                    ),
                ));
            }
        } else if obj.contains_key("generate") {
            let o = Obj::new(s, &p, &["generate"])?;
            let gp = o.path_of("generate");
            let (mut pattern, seed) = pattern(o.req("generate")?, &gp)?;
            pattern.max_segments = limit - out.len();
            let mut rng = SplitMix64::new(seed);
            pattern
                .for_each_stroke(&mut rng, |st| {
                    out.extend(st.points.windows(2).map(|w| {
                        Scratch::from_endpoints(w[0], w[1], st.width, st.depth, st.profile)
                    }));
                })
                .map_err(|e| pattern_error(e, &gp))?;
        } else {
            if out.len() >= limit {
                return Err(SpecError::field(
                    &p,
                    format!("more than {limit} scratch segments in all"),
                ));
            }
            out.push(scratch(s, &p)?);
        }
    }
    Ok(out)
}

/// A [`PatternError`] as a field error under the `generate` object at `gp`.
fn pattern_error(e: PatternError, gp: &str) -> SpecError {
    match e {
        PatternError::Invalid { field, msg } => SpecError::field(format!("{gp}.{field}"), msg),
        e @ PatternError::TooManySegments { .. } => SpecError::field(gp, e.to_string()),
    }
}

/// `{"file": "name.json" | "name.csv"}`: appends the file's scratches to `out`. Errors name
/// the field `…file` and, in the message, the file and the index or line.
fn file(o: &Obj, base_dir: &Path, out: &mut Vec<Scratch>) -> Result<(), SpecError> {
    let fp = o.path_of("file");
    let name = o
        .req("file")?
        .as_str()
        .ok_or_else(|| SpecError::field(&fp, "expected a file name (string)"))?;
    let ext = Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let is_csv = match ext.as_deref() {
        Some("csv") => true,
        Some("json") => false,
        _ => {
            return Err(SpecError::field(
                &fp,
                format!("{name}: expected a .json or .csv file"),
            ));
        }
    };
    let text = std::fs::read_to_string(base_dir.join(name))
        .map_err(|e| SpecError::field(&fp, format!("{name}: cannot read: {e}")))?;
    let inner = if is_csv {
        csv(&text, out)
    } else {
        json_file(&text, out)
    };
    inner.map_err(|e| SpecError::field(&fp, format!("{name}{e}")))
}

/// A JSON file: an array of inline scratches. Errors are `": [i].field: msg"` (the caller
/// prefixes the file name).
fn json_file(text: &str, out: &mut Vec<Scratch>) -> Result<(), String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!(": malformed JSON: {e}"))?;
    let a = v.as_array().ok_or(": expected a JSON array of scratches")?;
    for (i, s) in a.iter().enumerate() {
        out.push(scratch(s, &format!("[{i}]")).map_err(|e| format!(": {e}"))?);
    }
    Ok(())
}

/// A CSV file: the header [`CSV_HEADER`] (spaces around names and a UTF-8 byte order mark
/// allowed), then one scratch per line (blank lines skipped, `\r\n` accepted),
/// with the checks of an inline scratch. Errors are `":line: column: msg"`.
fn csv(text: &str, out: &mut Vec<Scratch>) -> Result<(), String> {
    let mut lines = text.lines().enumerate();
    let header = lines
        .next()
        .map(|(_, l)| l.trim_start_matches('\u{feff}').trim())
        .unwrap_or_default();
    let header: Vec<&str> = header.split(',').map(str::trim).collect();
    if header.join(",") != CSV_HEADER {
        return Err(format!(":1: expected the header {CSV_HEADER:?}"));
    }
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        out.push(csv_row(line).map_err(|e| format!(":{}: {e}", i + 1))?);
    }
    Ok(())
}

/// One CSV row; errors name the column.
fn csv_row(line: &str) -> Result<Scratch, SpecError> {
    let cols: Vec<&str> = line.split(',').map(str::trim).collect();
    let names: Vec<&str> = CSV_HEADER.split(',').collect();
    if cols.len() != names.len() {
        return Err(SpecError::field(
            "(line)",
            format!("expected {} columns, got {}", names.len(), cols.len()),
        ));
    }
    let mut x = [0.0f64; 6];
    for k in 0..6 {
        x[k] = cols[k].parse().map_err(|_| {
            SpecError::field(names[k], format!("expected a number, got {:?}", cols[k]))
        })?;
    }
    let profile = match cols[6] {
        "rect" => Profile::Rect,
        "triangle" => Profile::Triangle,
        other => {
            return Err(SpecError::field(
                "profile",
                format!("unknown value {other:?} (expected one of: rect, triangle)"),
            ));
        }
    };
    scratch_from_row(x, profile, "")
}

/// One scratch from the numbers of a CSV row, `[x0, y0, x1, y1, width, depth]` (µm): end
/// points finite and within f32 range, width and depth ≥ 0. Errors name the column, after
/// `prefix` (`""` for a CSV row, `"segments[3]."` for the Python binding's array rows).
pub fn scratch_from_row(x: [f64; 6], profile: Profile, prefix: &str) -> Result<Scratch, SpecError> {
    let names: Vec<&str> = CSV_HEADER.split(',').collect();
    let name = |k: usize| format!("{prefix}{}", names[k]);
    for (k, v) in x.iter().enumerate() {
        if !v.is_finite() {
            return Err(SpecError::field(name(k), "must be finite"));
        }
        if k < 4 {
            json::to_f32(*v, &name(k))?;
        }
    }
    let width = range::WIDTH_UM.check(x[4], &name(4))?;
    let depth = range::DEPTH_UM.check(x[5], &name(5))?;
    segment([x[0], x[1]], [x[2], x[3]], width, depth, profile, &name(2))
}

/// The `generate` object at `gp` → the pattern (with [`MAX_SEGMENTS`] as its limit) and
/// its seed.
fn pattern(v: &Value, gp: &str) -> Result<(ScratchPattern, u64), SpecError> {
    let g = Obj::new(
        v,
        gp,
        &[
            "seed",
            "count",
            "density_per_mm2",
            "region",
            "shape",
            "orientation",
            "width",
            "depth",
            "profile",
            "chord_tol_um",
        ],
    )?;
    let seed = g.integer("seed", MAX_SEED)?;
    let count = match (g.get("count"), g.get("density_per_mm2")) {
        (Some(_), Some(_)) => {
            return Err(SpecError::field(
                gp,
                "give either \"count\" or \"density_per_mm2\", not both",
            ));
        }
        (None, None) => {
            return Err(SpecError::field(
                gp,
                "needs \"count\" or \"density_per_mm2\"",
            ));
        }
        (Some(_), None) => Count::Exact(g.integer("count", MAX_SEED)?),
        (None, Some(_)) => {
            let d = g.num("density_per_mm2")?;
            if d < 0.0 {
                return Err(SpecError::field(
                    g.path_of("density_per_mm2"),
                    format!("must be >= 0, got {d}"),
                ));
            }
            Count::PerMm2(d)
        }
    };
    let rp = g.path_of("region");
    let r = Obj::new(g.req("region")?, &rp, &["min", "max"])?;
    let (min, max) = (point64(&r, "min")?, point64(&r, "max")?);
    if min[0] > max[0] || min[1] > max[1] {
        return Err(SpecError::field(
            r.path_of("max"),
            format!("must be >= min in each coordinate, got {max:?} < {min:?}"),
        ));
    }
    let shape = shape(g.req("shape")?, &g.path_of("shape"))?;
    let orientation = match g.get("orientation") {
        Some(o) => orientation(o, &g.path_of("orientation"))?,
        None => Orientation::Random,
    };
    let width = distribution(&g, "width", true, range::WIDTH_UM.hi, 1.0)?;
    let depth = distribution(&g, "depth", true, range::DEPTH_UM.hi, 1.0)?;
    let profile = match g.opt_choice("profile", &["rect", "triangle", "alternate"])? {
        Some("triangle") => ProfileChoice::Only(Profile::Triangle),
        Some("alternate") => ProfileChoice::Alternate,
        _ => ProfileChoice::Only(Profile::Rect),
    };
    let chord_tol_um = match g.opt_num("chord_tol_um")? {
        Some(t) => {
            json::positive(t, &g.path_of("chord_tol_um"), false)?;
            t
        }
        None => DEFAULT_CHORD_TOL_UM,
    };
    let pattern = ScratchPattern {
        min,
        max,
        count,
        shape,
        orientation,
        width,
        depth,
        profile,
        chord_tol_um,
        max_segments: MAX_SEGMENTS,
    };
    pattern.validate().map_err(|e| pattern_error(e, gp))?;
    Ok((pattern, seed))
}

/// A distribution at field `key` of `o`: a number, `{"uniform": [lo, hi]}` or
/// `{"log_uniform": [lo, hi]}`, checked in the JSON's units (values `> 0`, or `≥ 0` when
/// `allow_zero`, and `≤ max`), then multiplied by `scale`.
fn distribution(
    o: &Obj,
    key: &str,
    allow_zero: bool,
    max: f64,
    scale: f64,
) -> Result<Distribution, SpecError> {
    let path = o.path_of(key);
    let v = o.req(key)?;
    let d = if v.is_number() {
        Distribution::Constant(json::number(v, &path)?)
    } else {
        let d = Obj::new(v, &path, &["uniform", "log_uniform"])?;
        match (d.get("uniform"), d.get("log_uniform")) {
            (Some(_), None) => {
                let [lo, hi] = d.vec::<2>("uniform")?;
                Distribution::Uniform { lo, hi }
            }
            (None, Some(_)) => {
                let [lo, hi] = d.vec::<2>("log_uniform")?;
                Distribution::LogUniform { lo, hi }
            }
            _ => {
                return Err(SpecError::field(
                    &path,
                    "expected a number, {\"uniform\": [lo, hi]} or {\"log_uniform\": [lo, hi]}",
                ));
            }
        }
    };
    d.check("", allow_zero, max).map_err(|e| match e {
        PatternError::Invalid { msg, .. } => SpecError::field(&path, msg),
        e => SpecError::field(&path, e.to_string()),
    })?;
    Ok(match d {
        Distribution::Constant(x) => Distribution::Constant(x * scale),
        Distribution::Uniform { lo, hi } => Distribution::Uniform {
            lo: lo * scale,
            hi: hi * scale,
        },
        Distribution::LogUniform { lo, hi } => Distribution::LogUniform {
            lo: lo * scale,
            hi: hi * scale,
        },
    })
}

/// A number in `[lo, hi]` at field `key` of `o`.
fn ranged(o: &Obj, key: &str, lo: f64, hi: f64, lo_open: bool) -> Result<f64, SpecError> {
    let x = o.num(key)?;
    let ok = if lo_open { x > lo } else { x >= lo } && x <= hi;
    if ok {
        Ok(x)
    } else {
        let l = if lo_open { "(" } else { "[" };
        Err(SpecError::field(
            o.path_of(key),
            format!("must be in {l}{lo}, {hi}], got {x}"),
        ))
    }
}

/// `{"type": "straight" | "arc" | "walk", …}`.
fn shape(v: &Value, path: &str) -> Result<Shape, SpecError> {
    let any = Obj::new(
        v,
        path,
        &[
            "type",
            "length",
            "radius",
            "sweep_deg",
            "step_um",
            "turn_sd_deg",
        ],
    )?;
    Ok(match any.choice("type", &["straight", "arc", "walk"])? {
        "arc" => {
            let o = Obj::new(v, path, &["type", "radius", "sweep_deg"])?;
            Shape::Arc {
                radius: distribution(&o, "radius", false, 1.0e7, 1.0)?,
                sweep_rad: distribution(&o, "sweep_deg", false, 360.0, 1f64.to_radians())?,
            }
        }
        "walk" => {
            let o = Obj::new(v, path, &["type", "length", "step_um", "turn_sd_deg"])?;
            Shape::Walk {
                length: distribution(&o, "length", false, 1.0e7, 1.0)?,
                step_um: ranged(&o, "step_um", 0.0, 1.0e7, true)?,
                turn_sd_rad: ranged(&o, "turn_sd_deg", 0.0, 360.0, false)?.to_radians(),
            }
        }
        _ => {
            let o = Obj::new(v, path, &["type", "length"])?;
            Shape::Straight {
                length: distribution(&o, "length", false, 1.0e7, 1.0)?,
            }
        }
    })
}

/// `{"type": "random"} | {"type": "brushed", "angle_deg", "spread_deg"} |
/// {"type": "circular", "center": [x, y]}`.
fn orientation(v: &Value, path: &str) -> Result<Orientation, SpecError> {
    let any = Obj::new(v, path, &["type", "angle_deg", "spread_deg", "center"])?;
    Ok(
        match any.choice("type", &["random", "brushed", "circular"])? {
            "brushed" => {
                let o = Obj::new(v, path, &["type", "angle_deg", "spread_deg"])?;
                Orientation::Brushed {
                    angle_rad: ranged(&o, "angle_deg", -360.0, 360.0, false)?.to_radians(),
                    spread_rad: ranged(&o, "spread_deg", 0.0, 360.0, false)?.to_radians(),
                }
            }
            "circular" => {
                let o = Obj::new(v, path, &["type", "center"])?;
                Orientation::Circular {
                    center_um: point64(&o, "center")?,
                }
            }
            _ => {
                Obj::new(v, path, &["type"])?;
                Orientation::Random
            }
        },
    )
}
