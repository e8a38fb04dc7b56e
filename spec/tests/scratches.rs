//! Scratch sources: inline scratches, JSON and CSV files, seeded patterns, and the exact
//! field path of every rejection.

use scratchwave_host::pattern::{
    Count, Distribution, MAX_SEGMENTS, Orientation, ProfileChoice, ScratchPattern, Shape,
};
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_spec::SpecError;
use scratchwave_spec::scratches::scratch_sources;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

fn read(v: Value) -> Result<Vec<Scratch>, SpecError> {
    scratch_sources(&v, "scratches", &data())
}

/// The two scratches of `walls.csv` and `walls.json`.
fn walls() -> Vec<Scratch> {
    vec![
        Scratch::from_endpoints([0.0, 0.0], [100.0, 0.0], 2.0, 0.5, Profile::Rect),
        Scratch::from_endpoints([-10.5, 20.0], [30.0, 40.25], 1.5, 0.25, Profile::Triangle),
    ]
}

/// The error's field and message.
fn err(v: Value) -> (String, String) {
    match read(v) {
        Err(SpecError::Field { field, msg }) => (field, msg),
        other => panic!("expected a field error, got {other:?}"),
    }
}

/// Asserts that `v` is rejected at `field` with a message containing `msg`.
fn rejects(v: Value, field: &str, msg: &str) {
    let (f, m) = err(v);
    assert_eq!(f, field, "message: {m}");
    assert!(m.contains(msg), "{f}: {m:?} lacks {msg:?}");
}

/// A valid `generate` object to modify.
fn gen_base() -> Value {
    json!({
        "seed": 42,
        "count": 50,
        "region": {"min": [0, 0], "max": [1000, 500]},
        "shape": {"type": "straight", "length": {"uniform": [10, 300]}},
        "width": {"uniform": [0.8, 6]},
        "depth": 0.5
    })
}

/// `gen_base()` with `key` set to `value` (or removed when `value` is null), as a source list.
fn gen_with(key: &str, value: Value) -> Value {
    let mut g = gen_base();
    if value.is_null() {
        g.as_object_mut().unwrap().remove(key);
    } else {
        g[key] = value;
    }
    json!([{"generate": g}])
}

fn pattern_base() -> ScratchPattern {
    ScratchPattern {
        min: [0.0, 0.0],
        max: [1000.0, 500.0],
        count: Count::Exact(50),
        shape: Shape::Straight {
            length: Distribution::Uniform {
                lo: 10.0,
                hi: 300.0,
            },
        },
        orientation: Orientation::Random,
        width: Distribution::Uniform { lo: 0.8, hi: 6.0 },
        depth: Distribution::Constant(0.5),
        profile: ProfileChoice::Only(Profile::Rect),
        chord_tol_um: 0.1,
        max_segments: MAX_SEGMENTS,
    }
}

#[test]
fn inline_scratches_read_as_in_a_table_spec() {
    let s = read(json!([
        {"p0": [0, 0], "p1": [100, 0], "width": 2, "depth": 0.5},
        {"p0": [-10.5, 20], "p1": [30, 40.25], "width": 1.5, "depth": 0.25, "profile": "triangle"}
    ]))
    .unwrap();
    assert_eq!(s, walls());
    assert_eq!(read(json!([])).unwrap(), vec![]);
}

#[test]
fn json_and_csv_files_are_read_relative_to_the_base_dir() {
    assert_eq!(read(json!([{"file": "walls.json"}])).unwrap(), walls());
    assert_eq!(read(json!([{"file": "walls.csv"}])).unwrap(), walls());
}

#[test]
fn generated_patterns_match_the_host_generator() {
    let s = read(json!([{"generate": gen_base()}])).unwrap();
    let want = pattern_base().generate(&mut SplitMix64::new(42)).unwrap();
    assert_eq!(s.len(), 50);
    assert_eq!(s, want);

    // Arcs in degrees, brushed, alternate profiles, density, tolerance.
    let g = json!({
        "seed": 7,
        "density_per_mm2": 100,
        "region": {"min": [-500, -500], "max": [500, 500]},
        "shape": {"type": "arc", "radius": {"log_uniform": [50, 5000]}, "sweep_deg": 90},
        "orientation": {"type": "brushed", "angle_deg": 30, "spread_deg": 5},
        "width": 2,
        "depth": {"uniform": [0.1, 0.3]},
        "profile": "alternate",
        "chord_tol_um": 0.05
    });
    let s = read(json!([{"generate": g}])).unwrap();
    let p = ScratchPattern {
        min: [-500.0, -500.0],
        max: [500.0, 500.0],
        count: Count::PerMm2(100.0),
        shape: Shape::Arc {
            radius: Distribution::LogUniform {
                lo: 50.0,
                hi: 5000.0,
            },
            sweep_rad: Distribution::Constant(90f64.to_radians()),
        },
        orientation: Orientation::Brushed {
            angle_rad: 30f64.to_radians(),
            spread_rad: 5f64.to_radians(),
        },
        width: Distribution::Constant(2.0),
        depth: Distribution::Uniform { lo: 0.1, hi: 0.3 },
        profile: ProfileChoice::Alternate,
        chord_tol_um: 0.05,
        max_segments: MAX_SEGMENTS,
    };
    let want = p.generate(&mut SplitMix64::new(7)).unwrap();
    assert!(want.len() > 200, "100 arcs of several chords each");
    assert_eq!(s, want);

    // Walks about a circular polish centre.
    let g = json!({
        "seed": 3,
        "count": 20,
        "region": {"min": [0, 0], "max": [100, 100]},
        "shape": {"type": "walk", "length": 50, "step_um": 2.5, "turn_sd_deg": 10},
        "orientation": {"type": "circular", "center": [50, 50]},
        "width": 1,
        "depth": 1,
        "profile": "triangle"
    });
    let s = read(json!([{"generate": g}])).unwrap();
    let p = ScratchPattern {
        min: [0.0, 0.0],
        max: [100.0, 100.0],
        count: Count::Exact(20),
        shape: Shape::Walk {
            length: Distribution::Constant(50.0),
            step_um: 2.5,
            turn_sd_rad: 10f64.to_radians(),
        },
        orientation: Orientation::Circular {
            center_um: [50.0, 50.0],
        },
        width: Distribution::Constant(1.0),
        depth: Distribution::Constant(1.0),
        profile: ProfileChoice::Only(Profile::Triangle),
        chord_tol_um: 0.1,
        max_segments: MAX_SEGMENTS,
    };
    assert_eq!(s.len(), 20 * 20);
    assert_eq!(s, p.generate(&mut SplitMix64::new(3)).unwrap());
}

#[test]
fn sources_are_concatenated_in_order() {
    let s = read(json!([
        {"file": "walls.csv"},
        {"p0": [1, 2], "p1": [3, 4], "width": 1, "depth": 0.1},
        {"generate": gen_base()},
        {"file": "walls.json"}
    ]))
    .unwrap();
    let mut want = walls();
    want.push(Scratch::from_endpoints(
        [1.0, 2.0],
        [3.0, 4.0],
        1.0,
        0.1,
        Profile::Rect,
    ));
    want.extend(pattern_base().generate(&mut SplitMix64::new(42)).unwrap());
    want.extend(walls());
    assert_eq!(s, want);
}

#[test]
fn files_written_at_run_time_are_read() {
    let dir = std::env::temp_dir().join(format!(
        "scratchwave-spec-scratches-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("run.csv"),
        "x0,y0,x1,y1,width,depth,profile\r\n1e3,0,2e3,0,3,0,rect\r\n",
    )
    .unwrap();
    let s = scratch_sources(&json!([{"file": "run.csv"}]), "m.scratches", &dir);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        s.unwrap(),
        vec![Scratch::from_endpoints(
            [1000.0, 0.0],
            [2000.0, 0.0],
            3.0,
            0.0,
            Profile::Rect
        )]
    );
}

#[test]
fn list_and_inline_errors_name_the_field() {
    rejects(
        json!({"file": "walls.csv"}),
        "scratches",
        "expected an array",
    );
    rejects(json!([3]), "scratches[0]", "expected a JSON object");
    rejects(
        json!([{"p0": [0, 0], "p1": [1, 0], "width": -1, "depth": 0}]),
        "scratches[0].width",
        "must be >= 0",
    );
    rejects(
        json!([{"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0, "colour": 1}]),
        "scratches[0].colour",
        "unknown field",
    );
    rejects(
        json!([{"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0}, {"p0": [0, 0], "width": 1, "depth": 0}]),
        "scratches[1].p1",
        "missing required field",
    );
    rejects(
        json!([{"file": "walls.csv", "scale": 2}]),
        "scratches[0].scale",
        "unknown field",
    );
    rejects(
        json!([{"generate": gen_base(), "file": "walls.csv"}]),
        "scratches[0].generate",
        "unknown field",
    );
}

#[test]
fn file_errors_name_the_file_and_line_or_index() {
    let cases = [
        (
            "bad_depth.csv",
            "bad_depth.csv:4: depth: must be >= 0, got -0.5",
        ),
        (
            "bad_width.json",
            "bad_width.json: [1].width: must be >= 0, got -1",
        ),
        (
            "bad_header.csv",
            "bad_header.csv:1: expected the header \"x0,y0,x1,y1,width,depth,profile\"",
        ),
        (
            "bad_profile.csv",
            "bad_profile.csv:2: profile: unknown value \"round\"",
        ),
        ("missing.csv", "missing.csv: cannot read: "),
        ("walls.txt", "walls.txt: expected a .json or .csv file"),
        ("walls.csv", ""),
    ];
    for (file, msg) in cases {
        let v = json!([{"file": "walls.json"}, {"file": file}]);
        if msg.is_empty() {
            assert_eq!(read(v).unwrap().len(), 4);
            continue;
        }
        let (f, m) = err(v);
        assert_eq!(f, "scratches[1].file");
        assert!(m.starts_with(msg), "{m:?} does not start with {msg:?}");
    }
    let e = read(json!([{"file": "bad_depth.csv"}])).unwrap_err();
    assert_eq!(
        e.to_string(),
        "scratches[0].file: bad_depth.csv:4: depth: must be >= 0, got -0.5"
    );
    rejects(
        json!([{"file": 3}]),
        "scratches[0].file",
        "expected a file name",
    );
}

#[test]
fn csv_rows_are_checked_column_by_column() {
    let dir = std::env::temp_dir().join(format!(
        "scratchwave-spec-csv-rows-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let rows = [
        ("0,0,1,1,1,1", "x.csv:2: (line): expected 7 columns, got 6"),
        (
            "0,zero,1,1,1,1,rect",
            "x.csv:2: y0: expected a number, got \"zero\"",
        ),
        ("0,0,NaN,1,1,1,rect", "x.csv:2: x1: must be finite"),
        (
            "0,0,1,1e39,1,1,rect",
            "x.csv:2: y1: 1000000000000000000000000000000000000000 does not fit in f32",
        ),
        ("0,0,1,1,-2,1,rect", "x.csv:2: width: must be >= 0, got -2"),
    ];
    let mut got = Vec::new();
    for (row, _) in rows {
        std::fs::write(
            dir.join("x.csv"),
            format!("x0,y0,x1,y1,width,depth,profile\n{row}\n"),
        )
        .unwrap();
        got.push(scratch_sources(&json!([{"file": "x.csv"}]), "s", &dir));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    for ((_, msg), g) in rows.iter().zip(got) {
        assert_eq!(g, Err(SpecError::field("s[0].file", *msg)));
    }
}

#[test]
fn generate_errors_name_the_field() {
    let g = "scratches[0].generate";
    rejects(
        gen_with("colour", json!(1)),
        &format!("{g}.colour"),
        "unknown field",
    );
    rejects(
        gen_with("seed", json!(1.5)),
        &format!("{g}.seed"),
        "integer",
    );
    rejects(
        gen_with("seed", Value::Null),
        &format!("{g}.seed"),
        "missing",
    );
    rejects(
        gen_with("count", Value::Null),
        g,
        "needs \"count\" or \"density_per_mm2\"",
    );
    rejects(gen_with("density_per_mm2", json!(3)), g, "not both");
    rejects(
        gen_with("count", json!(-1)),
        &format!("{g}.count"),
        "integer",
    );
    let mut v = gen_with("count", Value::Null);
    v[0]["generate"]["density_per_mm2"] = json!(-2);
    rejects(v, &format!("{g}.density_per_mm2"), "must be >= 0");
    rejects(
        gen_with("region", json!({"min": [0, 0], "max": [-1, 5]})),
        &format!("{g}.region.max"),
        "must be >= min",
    );
    rejects(
        gen_with("region", json!({"min": [0, 0], "max": [1e8, 5]})),
        &format!("{g}.region"),
        "within",
    );
    rejects(
        gen_with("region", json!({"min": [0, 0]})),
        &format!("{g}.region.max"),
        "missing",
    );
    rejects(
        gen_with("width", json!({"uniform": [6, 0.8]})),
        &format!("{g}.width"),
        "lo <= hi",
    );
    rejects(gen_with("depth", json!(-1)), &format!("{g}.depth"), ">= 0");
    rejects(
        gen_with("width", json!({"normal": [1, 2]})),
        &format!("{g}.width.normal"),
        "unknown field",
    );
    rejects(
        gen_with("width", json!({"uniform": [1, 2], "log_uniform": [1, 2]})),
        &format!("{g}.width"),
        "expected a number",
    );
    rejects(
        gen_with("width", json!({"uniform": [1]})),
        &format!("{g}.width.uniform"),
        "array of 2 numbers",
    );
    rejects(
        gen_with("width", json!("wide")),
        &format!("{g}.width"),
        "JSON object",
    );
    rejects(
        gen_with(
            "shape",
            json!({"type": "straight", "length": {"log_uniform": [0, 5]}}),
        ),
        &format!("{g}.shape.length"),
        "lo > 0",
    );
    rejects(
        gen_with("shape", json!({"type": "spiral"})),
        &format!("{g}.shape.type"),
        "unknown value",
    );
    rejects(
        gen_with(
            "shape",
            json!({"type": "straight", "length": 5, "radius": 3}),
        ),
        &format!("{g}.shape.radius"),
        "unknown field",
    );
    rejects(
        gen_with(
            "shape",
            json!({"type": "arc", "radius": 0, "sweep_deg": 30}),
        ),
        &format!("{g}.shape.radius"),
        "> 0",
    );
    rejects(
        gen_with(
            "shape",
            json!({"type": "arc", "radius": 10, "sweep_deg": 400}),
        ),
        &format!("{g}.shape.sweep_deg"),
        "<= 360",
    );
    rejects(
        gen_with(
            "shape",
            json!({"type": "walk", "length": 10, "step_um": 0, "turn_sd_deg": 1}),
        ),
        &format!("{g}.shape.step_um"),
        "must be in (0",
    );
    rejects(
        gen_with("shape", json!({"type": "walk", "length": 10, "step_um": 1})),
        &format!("{g}.shape.turn_sd_deg"),
        "missing",
    );
    rejects(
        gen_with(
            "orientation",
            json!({"type": "brushed", "angle_deg": 0, "spread_deg": -1}),
        ),
        &format!("{g}.orientation.spread_deg"),
        "must be in [0",
    );
    rejects(
        gen_with("orientation", json!({"type": "random", "angle_deg": 0})),
        &format!("{g}.orientation.angle_deg"),
        "unknown field",
    );
    rejects(
        gen_with("orientation", json!({"type": "circular", "center": [1]})),
        &format!("{g}.orientation.center"),
        "array of 2 numbers",
    );
    rejects(
        gen_with("profile", json!("round")),
        &format!("{g}.profile"),
        "unknown value",
    );
    rejects(
        gen_with("chord_tol_um", json!(0)),
        &format!("{g}.chord_tol_um"),
        "> 0",
    );
}

#[test]
fn patterns_beyond_the_limit_are_rejected_with_the_estimate() {
    let (f, m) = err(gen_with("count", json!(1e12)));
    assert_eq!(f, "scratches[0].generate");
    assert_eq!(
        m,
        format!(
            "the pattern could produce up to 1.0000e12 segments, more than the limit of {MAX_SEGMENTS}"
        )
    );
    // Full circles of 1 m radius at 1 nm: 70249 chords each.
    let mut v = gen_with(
        "shape",
        json!({"type": "arc", "radius": 1e6, "sweep_deg": 360}),
    );
    v[0]["generate"]["chord_tol_um"] = json!(0.001);
    v[0]["generate"]["count"] = json!(1000);
    let (f, m) = err(v);
    assert_eq!(f, "scratches[0].generate");
    assert!(m.contains("up to 7.0249e7 segments"), "{m}");
    // The limit is shared: what earlier sources produced is no longer available.
    let mut v = gen_with("count", json!(MAX_SEGMENTS));
    v.as_array_mut().unwrap().insert(
        0,
        json!({"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0}),
    );
    let (f, m) = err(v);
    assert_eq!(f, "scratches[1].generate");
    assert!(m.contains(&format!("limit of {}", MAX_SEGMENTS - 1)), "{m}");
}

#[test]
fn every_json_example_in_the_docs_is_a_valid_source() {
    let doc =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/scratches.md"))
            .unwrap();
    let blocks: Vec<&str> = doc
        .split("```json\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap())
        .collect();
    assert_eq!(blocks.len(), 3);
    for b in blocks {
        let v: Value = serde_json::from_str(b).unwrap();
        let s = read(json!([v])).unwrap_or_else(|e| panic!("{b}: {e}"));
        assert!(!s.is_empty());
    }
}

#[test]
fn a_caller_budget_limits_every_source_kind() {
    use scratchwave_spec::scratches::scratch_sources_with_limit;
    let pattern = json!([{"generate": {
        "seed": 1, "count": 10, "region": {"min": [0, 0], "max": [10, 10]},
        "shape": {"type": "straight", "length": 5}, "width": 1, "depth": 0.1
    }}]);
    let n = |v: &Value, limit| scratch_sources_with_limit(v, "scratches", &data(), limit);
    assert_eq!(n(&pattern, 10).map(|s| s.len()), Ok(10));
    let e = n(&pattern, 9).unwrap_err();
    assert!(
        matches!(&e, SpecError::Field { field, msg }
            if field == "scratches[0].generate" && msg.contains("limit of 9")),
        "{e}"
    );
    // A file after an inline scratch: 1 + 2 segments against a budget of 2.
    let file = json!([
        {"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0.1},
        {"file": "walls.csv"}
    ]);
    assert_eq!(n(&file, 3).map(|s| s.len()), Ok(3));
    let e = n(&file, 2).unwrap_err();
    assert!(
        matches!(&e, SpecError::Field { field, msg }
            if field == "scratches[1].file" && msg.contains("1 left of the limit of 2")),
        "{e}"
    );
    // Inline scratches: the third one is over a budget of 2.
    let inline = json!([
        {"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0.1},
        {"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0.1},
        {"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0.1}
    ]);
    let e = n(&inline, 2).unwrap_err();
    assert!(
        matches!(&e, SpecError::Field { field, .. } if field == "scratches[2]"),
        "{e}"
    );
    // The documented limit is the largest budget: a larger one is clamped to it.
    assert_eq!(n(&pattern, usize::MAX).map(|s| s.len()), Ok(10));
}

/// Regression (fuzz target `scratch_sources`): end points within the f32 range but more
/// than 2·f32::MAX apart gave a scratch with an infinite half length, which reflects
/// nothing; such segments are now rejected, inline and in files.
#[test]
fn segments_longer_than_the_f32_range_are_rejected() {
    // Minimized fuzz input: [{"p0":[-3e38,-3e38],"p1":[3e38,3e38],"width":1,"depth":1}]
    rejects(
        json!([{"p0": [-3e38, -3e38], "p1": [3e38, 3e38], "width": 1, "depth": 1}]),
        "scratches[0].p1",
        "segment too long: 8.485",
    );
    rejects(
        json!([{"file": "too_long.csv"}]),
        "scratches[0].file",
        "too_long.csv:3: x1: segment too long",
    );
    // The longest segment that still fits: half length f32::MAX-ish, finite.
    let s = read(json!([{"p0": [-3e38, 0], "p1": [3e38, 0], "width": 1, "depth": 1}])).unwrap();
    assert_eq!(s[0].half_len, 3e38);
}
