//! The conformance run: every committed case on every available backend, compared with the
//! case's high-precision reference values (where it has them) and pairwise across backends.

use crate::format::g;
use crate::generate::random_spec;
use crate::light_case::random_light_batch;
use scratchwave_host::{CaseBatch, TableBackend};
use scratchwave_spec::spec::table_spec;
use scratchwave_spec::{SpecError, json};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// Default relative tolerance of a case, applied where the reference side is above
/// [`FLOOR`] times the case's maximum: the f32 kernel's accuracy target (issue #2).
pub const DEFAULT_REL_TOL: f64 = 1e-4;
/// Values below this fraction of a case's maximum are compared in absolute terms, relative
/// to the maximum.
pub const FLOOR: f64 = 1e-6;

/// A committed case: a table spec (given or generated), optional reference values and the
/// tolerance it declares, with the reason.
pub struct Case {
    /// File name.
    pub name: String,
    /// What the case exercises.
    pub description: String,
    /// The expanded spec.
    pub spec: CaseBatch,
    /// Reference values (mpmath), one per query, if the case has them.
    pub expected: Option<Vec<f64>>,
    /// Relative tolerance above the floor.
    pub rel_tol: f64,
    /// Why that tolerance.
    pub why: String,
}

/// Agreement between two value lists.
#[derive(Clone, Copy, Debug, Default)]
pub struct Agreement {
    /// Largest |a − b|.
    pub max_abs: f64,
    /// Largest |a − b| / |b| over values with |b| ≥ FLOOR · max|b|.
    pub max_rel: f64,
    /// Largest |a − b| / max|b| over the rest.
    pub max_floor: f64,
    /// ULP-distance histogram (f32): 0, 1, 2–4, 5–16, 17–256, > 256.
    pub ulps: [usize; 6],
}

/// Distance in units in the last place between two f32 (0 for equal bits or ±0).
pub fn ulp_distance(a: f32, b: f32) -> u64 {
    let key = |x: f32| -> i64 {
        let bits = x.to_bits() as i32;
        i64::from(if bits < 0 { i32::MIN - bits } else { bits })
    };
    if a.is_nan() || b.is_nan() {
        u64::MAX
    } else {
        key(a).abs_diff(key(b))
    }
}

/// Compares `a` against `b` (the reference side).
pub fn agreement(a: &[f64], b: &[f64]) -> Agreement {
    let peak = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut r = Agreement::default();
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        r.max_abs = r.max_abs.max(d);
        if y.abs() >= FLOOR * peak && y.abs() > 0.0 {
            r.max_rel = r.max_rel.max(d / y.abs());
        } else if peak > 0.0 {
            r.max_floor = r.max_floor.max(d / peak);
        }
        let u = ulp_distance(*x as f32, *y as f32);
        let bin = match u {
            0 => 0,
            1 => 1,
            2..=4 => 2,
            5..=16 => 3,
            17..=256 => 4,
            _ => 5,
        };
        r.ulps[bin] += 1;
    }
    r
}

fn io_err(path: &Path, e: std::io::Error) -> SpecError {
    SpecError::Io {
        path: path.display().to_string(),
        msg: e.to_string(),
    }
}

/// Loads every `*.json` case in each directory (sorted by name within a directory).
pub fn load_cases(dirs: &[PathBuf]) -> Result<Vec<Case>, SpecError> {
    let mut cases = Vec::new();
    for dir in dirs {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| io_err(dir, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        files.sort();
        for f in files {
            cases.push(load_case(&f)?);
        }
    }
    Ok(cases)
}

/// Loads one case file: `{"description", "tolerance": {"rel", "why"}?, "spec" | "random" |
/// "random_lights", "expected"?}`.
pub fn load_case(f: &Path) -> Result<Case, SpecError> {
    let name = f
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = std::fs::read_to_string(f).map_err(|e| io_err(f, e))?;
    let v = json::parse(&text, &f.display().to_string())?;
    // `expected_log10` (log10 of values too small for f64 in the reference) is informational.
    let o = json::Obj::new(
        &v,
        &name,
        &[
            "description",
            "tolerance",
            "spec",
            "random",
            "random_lights",
            "expected",
            "expected_log10",
        ],
    )?;
    let spec = match (o.get("spec"), o.get("random"), o.get("random_lights")) {
        (Some(s), None, None) => {
            CaseBatch::Table(table_spec(s).map_err(|e| prefix(e, &o.path_of("spec")))?)
        }
        (None, Some(r), None) => CaseBatch::Table(random_spec(r, &o.path_of("random"))?),
        (None, None, Some(r)) => {
            CaseBatch::Light(random_light_batch(r, &o.path_of("random_lights"))?)
        }
        _ => {
            return Err(SpecError::field(
                name,
                "needs exactly one of \"spec\", \"random\" and \"random_lights\"",
            ));
        }
    };
    let expected = match o.get("expected") {
        None => None,
        Some(e) => {
            let arr = e
                .as_array()
                .ok_or_else(|| SpecError::field(o.path_of("expected"), "expected an array"))?;
            let vals = arr
                .iter()
                .enumerate()
                .map(|(i, x)| json::number(x, &format!("{}[{i}]", o.path_of("expected"))))
                .collect::<Result<Vec<_>, _>>()?;
            if vals.len() != spec.len() {
                return Err(SpecError::field(
                    o.path_of("expected"),
                    format!("{} values for {} queries", vals.len(), spec.len()),
                ));
            }
            Some(vals)
        }
    };
    let (rel_tol, why) = match o.get("tolerance") {
        None => (
            DEFAULT_REL_TOL,
            "default: the f32 kernel's accuracy target".to_string(),
        ),
        Some(t) => {
            let t = json::Obj::new(t, &o.path_of("tolerance"), &["rel", "why"])?;
            let rel = t.num("rel")?;
            let why = t.req("why")?.as_str().unwrap_or_default().to_string();
            (rel, why)
        }
    };
    let description = o
        .get("description")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    Ok(Case {
        name,
        description,
        spec,
        expected,
        rel_tol,
        why,
    })
}

fn prefix(e: SpecError, path: &str) -> SpecError {
    match e {
        SpecError::Field { field, msg } => SpecError::field(format!("{path}.{field}"), msg),
        other => other,
    }
}

/// One comparison row of a case.
pub struct Row {
    /// e.g. `cpu vs reference`, `cpu vs spirv`.
    pub label: String,
    /// The measured agreement.
    pub agreement: Agreement,
    /// Tolerance applied.
    pub tol: f64,
    /// Within tolerance.
    pub pass: bool,
}

/// Result of one case.
pub struct CaseReport {
    /// Case file name.
    pub name: String,
    /// Number of queries.
    pub queries: usize,
    /// Comparisons.
    pub rows: Vec<Row>,
    /// Backends that failed to run, with their error.
    pub errors: Vec<(String, String)>,
}

/// Runs one case on every backend; compares each with the reference and each pair.
pub fn run_case(case: &Case, backends: &[Box<dyn TableBackend>]) -> CaseReport {
    let mut outputs: Vec<(String, Vec<f64>)> = Vec::new();
    let mut errors = Vec::new();
    for b in backends {
        match b.evaluate_case(&case.spec) {
            Ok(v) => outputs.push((b.name(), v.into_iter().map(f64::from).collect())),
            Err(e) => errors.push((b.name(), e.to_string())),
        }
    }
    let mut rows = Vec::new();
    let mut push = |label: String, a: &[f64], b: &[f64]| {
        let ag = agreement(a, b);
        let pass = ag.max_rel <= case.rel_tol && ag.max_floor <= case.rel_tol;
        rows.push(Row {
            label,
            agreement: ag,
            tol: case.rel_tol,
            pass,
        });
    };
    if let Some(exp) = &case.expected {
        for (n, v) in &outputs {
            push(format!("{n} vs reference"), v, exp);
        }
    }
    for i in 0..outputs.len() {
        for j in i + 1..outputs.len() {
            push(
                format!("{} vs {}", outputs[i].0, outputs[j].0),
                &outputs[i].1,
                &outputs[j].1,
            );
        }
    }
    CaseReport {
        name: case.name.clone(),
        queries: case.spec.len(),
        rows,
        errors,
    }
}

/// Renders reports as a Markdown table.
pub fn markdown(reports: &[CaseReport]) -> String {
    let mut s = String::from(
        "| case | queries | comparison | max abs | max rel (≥1e-6·max) | below floor (÷max) | ULPs 0/1/2-4/5-16/17-256/>256 | tol | ok |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        for row in &r.rows {
            let a = &row.agreement;
            let u = a.ulps;
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {}/{}/{}/{}/{}/{} | {} | {} |\n",
                r.name,
                r.queries,
                row.label,
                g(a.max_abs, 3),
                g(a.max_rel, 3),
                g(a.max_floor, 3),
                u[0],
                u[1],
                u[2],
                u[3],
                u[4],
                u[5],
                g(row.tol, 2),
                if row.pass { "yes" } else { "**NO**" }
            );
        }
        for (b, e) in &r.errors {
            s += &format!(
                "| {} | {} | {b} | — | — | — | — | — | **failed: {e}** |\n",
                r.name, r.queries
            );
        }
    }
    s
}

/// Renders reports as JSON.
pub fn to_json(reports: &[CaseReport]) -> Value {
    Value::Array(
        reports
            .iter()
            .map(|r| {
                json!({
                    "case": r.name,
                    "queries": r.queries,
                    "comparisons": r.rows.iter().map(|row| json!({
                        "comparison": row.label,
                        "max_abs": row.agreement.max_abs,
                        "max_rel": row.agreement.max_rel,
                        "max_below_floor": row.agreement.max_floor,
                        "ulp_histogram": {"0": row.agreement.ulps[0], "1": row.agreement.ulps[1],
                            "2-4": row.agreement.ulps[2], "5-16": row.agreement.ulps[3],
                            "17-256": row.agreement.ulps[4], ">256": row.agreement.ulps[5]},
                        "tol": row.tol,
                        "pass": row.pass,
                    })).collect::<Vec<_>>(),
                    "errors": r.errors.iter().map(|(b, e)| json!({"backend": b, "error": e})).collect::<Vec<_>>(),
                })
            })
            .collect(),
    )
}
