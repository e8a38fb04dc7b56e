//! `scratchwave table` streams: a `{"grid"}` of queries gives exactly the values of the same
//! queries listed (in the documented order), across chunk boundaries; a grid's bad entries
//! are rejected with the field path, exit code 2 and nothing on stdout; a spec too large to
//! read in memory is refused before it is read.

use std::io::Write;
use std::process::{Command, Output};

fn run(tag: &str, spec: &str) -> Output {
    let dir = std::env::temp_dir().join(format!("scratchwave-stream-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{tag}.json"));
    std::fs::File::create(&path)
        .unwrap()
        .write_all(spec.as_bytes())
        .unwrap();
    Command::new(env!("CARGO_BIN_EXE_scratchwave"))
        .args(["table", path.to_str().unwrap()])
        .output()
        .unwrap()
}

const HEAD: &str = r#""model": "velinov", "sigma_um": 10, "material": {"F": 0.8},
  "scratches": [{"p0": [-60, -5], "p1": [60, 5], "width": 2, "depth": 0.3},
                {"p0": [-20, -40], "p1": [10, 50], "width": 1, "depth": 0.2, "profile": "triangle"}]"#;

#[test]
fn grid_equals_the_listed_queries_in_order() {
    let wi = [[0.0, 0.0, 1.0], [0.3, 0.1, 0.9]];
    let wo: Vec<[f64; 3]> = (0..7)
        .map(|k| [0.02 * f64::from(k) - 0.06, 0.01, 1.0])
        .collect();
    let lambda = [450.0, 550.0, 650.0];
    let x = [[0.0, 0.0], [5.0, -3.0]];
    let j = |v: &dyn std::fmt::Debug| format!("{v:?}");
    let grid = format!(
        r#"{{{HEAD}, "queries": {{"grid": {{"wi": {}, "wo": {}, "lambda_nm": {}, "x": {}}}}}}}"#,
        j(&wi),
        j(&wo),
        j(&lambda),
        j(&x)
    );
    let mut listed = Vec::new();
    for a in &wi {
        for b in &wo {
            for l in &lambda {
                for p in &x {
                    listed.push(format!(
                        r#"{{"wi": {}, "wo": {}, "lambda_nm": {l}, "x": {}}}"#,
                        j(a),
                        j(b),
                        j(p)
                    ));
                }
            }
        }
    }
    let list = format!(r#"{{{HEAD}, "queries": [{}]}}"#, listed.join(", "));
    let (g, l) = (run("grid", &grid), run("list", &list));
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));
    assert!(l.status.success(), "{}", String::from_utf8_lossy(&l.stderr));
    assert_eq!(g.stdout.iter().filter(|&&b| b == b'\n').count(), 84);
    assert_eq!(g.stdout, l.stdout);
    // Not all equal: the order matters for the comparison to mean anything.
    let lines: Vec<&[u8]> = g.stdout.split(|&b| b == b'\n').collect();
    assert!(lines.windows(2).any(|w| w[0] != w[1]));
}

#[test]
fn grid_longer_than_a_chunk_streams_every_value() {
    // 2 × 600 × 1 × 300 = 360 000 queries > one chunk (2^18 = 262 144); only wo varies
    // the value along the middle axis, so the first and last lines of each x run must match
    // a listed evaluation of the same two queries.
    let wo: Vec<String> = (0..600)
        .map(|k| format!("[{}, 0, 1]", -0.3 + 0.001 * f64::from(k)))
        .collect();
    let x: Vec<String> = (0..300)
        .map(|k| format!("[{}, 0]", f64::from(k) * 0.5))
        .collect();
    let grid = format!(
        r#"{{{HEAD}, "queries": {{"grid": {{"wi": [[0, 0, 1], [0.1, 0, 1]], "wo": [{}], "lambda_nm": [500], "x": [{}]}}}}}}"#,
        wo.join(", "),
        x.join(", ")
    );
    let g = run("big", &grid);
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));
    let lines: Vec<&str> = std::str::from_utf8(&g.stdout).unwrap().lines().collect();
    assert_eq!(lines.len(), 360_000);
    // The very last query, and the one right after the chunk boundary.
    let at = |i: usize| {
        let (ii, rest) = (i / 180_000, i % 180_000);
        let (io, ix) = (rest / 300, rest % 300);
        let wi = if ii == 0 { "[0, 0, 1]" } else { "[0.1, 0, 1]" };
        format!(
            r#"{{"wi": {wi}, "wo": {}, "lambda_nm": 500, "x": {}}}"#,
            wo[io], x[ix]
        )
    };
    let idx = [0usize, 262_143, 262_144, 359_999];
    let list = format!(
        r#"{{{HEAD}, "queries": [{}]}}"#,
        idx.iter().map(|&i| at(i)).collect::<Vec<_>>().join(", ")
    );
    let l = run("big-list", &list);
    let want: Vec<&str> = std::str::from_utf8(&l.stdout).unwrap().lines().collect();
    for (k, &i) in idx.iter().enumerate() {
        assert_eq!(lines[i], want[k], "query {i}");
    }
}

#[test]
fn bad_grid_entries_name_the_field() {
    let cases = [
        (
            r#"{"wi": [[0, 0, 1]], "wo": [[0, 0, 1], [0, 0, 0]], "lambda_nm": [500], "x": [[0, 0]]}"#,
            "queries.grid.wo[1]",
        ),
        (
            r#"{"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "lambda_nm": [500, -1], "x": [[0, 0]]}"#,
            "queries.grid.lambda_nm[1]",
        ),
        (
            r#"{"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "lambda_nm": [500], "x": [[0, 1e39]]}"#,
            "queries.grid.x[0]",
        ),
        (
            r#"{"wi": [], "wo": [[0, 0, 1]], "lambda_nm": [500], "x": [[0, 0]]}"#,
            "queries.grid.wi",
        ),
        (
            r#"{"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "lambda_nm": [500]}"#,
            "queries.grid.x",
        ),
        (
            r#"{"wi": [[0, 0, 1]], "wo": [[0, 0, 1]], "lambda_nm": [500], "x": [[0, 0]], "y": 1}"#,
            "queries.grid.y",
        ),
    ];
    for (i, (g, field)) in cases.iter().enumerate() {
        let out = run(
            &format!("bad{i}"),
            &format!(r#"{{{HEAD}, "queries": {{"grid": {g}}}}}"#),
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{g} → {err}");
        assert!(out.stdout.is_empty(), "{g}");
        assert!(err.contains(field), "{err:?} does not name {field:?}");
    }
}

#[test]
fn grid_over_the_query_limit_is_refused() {
    // 2^11 · 2^11 · 2^10 · 2^9 = 2^41 > MAX_GRID_QUERIES (2^40): refused before any output.
    let list = |n: usize, item: &str| vec![item; n].join(", ");
    let spec = format!(
        r#"{{{HEAD}, "queries": {{"grid": {{"wi": [{}], "wo": [{}], "lambda_nm": [{}], "x": [{}]}}}}}}"#,
        list(2048, "[0, 0, 1]"),
        list(2048, "[0, 0, 1]"),
        list(1024, "500"),
        list(512, "[0, 0]")
    );
    let out = run("huge", &spec);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("queries.grid") && err.contains("MAX_GRID_QUERIES"),
        "{err}"
    );
}

#[test]
fn spec_too_large_for_memory_is_refused_before_reading() {
    // A sparse file: its size alone exceeds the limit (at most 8 GiB / 24 bytes per byte).
    let dir = std::env::temp_dir().join(format!("scratchwave-stream-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("sparse.json");
    std::fs::File::create(&path)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_scratchwave"))
        .args(["table", path.to_str().unwrap()])
        .output()
        .unwrap();
    std::fs::remove_file(&path).unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    assert!(err.contains("memory limit"), "{err}");
}
