//! Velinov et al. 2018, Table 2, reproduced on the CPU renderer: a curved scratched metal
//! object (`benches/scenes/velinov_table2.json`: a 20 mm sphere, 10 000 arc scratches split
//! into ~4·10^5 segments, the incoherent model) at 1280×720, lit by a 5 mm sphere light 1 m
//! away or by an 8-pointed star polygon light (ear-clipped into triangles, as Velinov's star
//! light), at zoom 0.5×/1×/2× (field of view), antialiasing off (`footprint: none`) and on
//! (`footprint: ellipse`, Velinov's camera-footprint integration), on 1 and 2 threads.
//! Each thread count runs in a child process of this program on rayon's global pool
//! (`RAYON_NUM_THREADS` set to it), as `scratchwave render` runs; the 2-thread child also
//! times the 2× sphere grid frame in a separately built pool, which is slower here.
//!
//! Shadow rays are adaptive (`render.shadows: "adaptive"`, the default): 4 probe rays per
//! sphere light and 3 per star triangle, the other quadrature nodes only in penumbrae.
//! Velinov's renderer rasterises primary visibility and casts no shadow rays at all.
//!
//! `cargo run --release -p scratchwave-benches --example velinov_table2 [-- REPEATS [sphere|star]]`
//! (the optional second argument runs one light's rows only)
//!
//! Prints one Markdown table in Velinov's layout: per light and configuration (AA off with
//! the scratch grid, the analogue of Velinov's per-triangle arrays; AA off with the BVH
//! alone; AA on, whose footprint radii go to the BVH) and thread count, ms/frame (tile
//! loop, median of the repeats) at 0.5×/1×/2× and the share of the tile loop's thread time
//! spent in ray queries (Embree closest-hit and occlusion calls, timed around each batch),
//! beside the paper's GTX 970M numbers.

use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::ray::{Hit, Ray};
use scratchwave_render::{prepare, render, scene_file};
use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Ray queries that add the time spent in them to a counter.
struct Timed<'a, Q> {
    inner: &'a Q,
    nanos: AtomicU64,
}

impl<Q: RayQueries> RayQueries for Timed<'_, Q> {
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        let t = Instant::now();
        let h = self.inner.closest_hit(ray);
        self.nanos
            .fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
        h
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let t = Instant::now();
        let o = self.inner.occluded(ray);
        self.nanos
            .fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
        o
    }

    fn closest_hits(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherence: Coherence) {
        let t = Instant::now();
        self.inner.closest_hits(rays, hits, coherence);
        self.nanos
            .fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
    }

    fn occluded_many(&self, rays: &[Ray], out: &mut [bool], coherence: Coherence) {
        let t = Instant::now();
        self.inner.occluded_many(rays, out, coherence);
        self.nanos
            .fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
    }
}

/// An 8-pointed star (16 vertices, inner radius 0.4 of the outer) centred at `c`, facing
/// the origin.
fn star(c: [f64; 3], outer: f64) -> Value {
    let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let n = [-c[0] / len, -c[1] / len, -c[2] / len];
    let helper = if n[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let e1 = cross(n, helper);
    let l1 = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
    let e1 = [e1[0] / l1, e1[1] / l1, e1[2] / l1];
    let e2 = cross(n, e1);
    let vertices: Vec<Value> = (0..16)
        .map(|k| {
            let r = if k % 2 == 0 { outer } else { 0.4 * outer };
            let (s, co) = (std::f64::consts::TAU * k as f64 / 16.0).sin_cos();
            json!([
                c[0] + r * (co * e1[0] + s * e2[0]),
                c[1] + r * (co * e1[1] + s * e2[1]),
                c[2] + r * (co * e1[2] + s * e2[2])
            ])
        })
        .collect();
    json!({"type": "polygon", "vertices": vertices, "radiance": 40.0})
}

/// The environment variable that makes this program a child that measures every cell on
/// rayon's global pool (sized by `RAYON_NUM_THREADS`, which the parent sets to the same
/// count) and prints one `cell` line per cell.
const CHILD: &str = "SCRATCHWAVE_TABLE2_THREADS";

/// The configurations of Velinov's Table 2: AA off with the scratch grid (our analogue of
/// his per-triangle arrays), AA off with the BVH alone, AA on (footprint radii exceed the
/// grid's and go to the BVH). Name, `render.footprint`, `render.scratch_lookup`.
const CONFIGS: [(&str, &str, &str); 3] = [
    ("off, grid", "none", "grid"),
    ("off, BVH", "none", "bvh"),
    ("on, BVH", "ellipse", "grid"),
];

const ZOOMS: [f64; 3] = [0.5, 1.0, 2.0];

const THREADS: [usize; 2] = [1, 2];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repeats: usize = std::env::args().nth(1).map_or(Ok(1), |s| s.parse())?;
    let only = std::env::args().nth(2);
    match std::env::var(CHILD) {
        Ok(threads) => measure(repeats.max(1), only.as_deref(), threads.parse()?),
        Err(_) => table(),
    }
}

/// One row of the table: ms/frame and ray-query share (%) per zoom, in zoom order.
#[derive(Default)]
struct Row {
    ms: Vec<String>,
    share: Vec<String>,
}

/// Runs one child per thread count, on the global pool as `scratchwave render` runs, and
/// prints the table from their `cell` lines.
fn table() -> Result<(), Box<dyn std::error::Error>> {
    // (light, configuration, threads) → row.
    let mut rows: BTreeMap<(String, String, usize), Row> = BTreeMap::new();
    let mut notes = Vec::new();
    for threads in THREADS {
        let out = std::process::Command::new(std::env::current_exe()?)
            .args(std::env::args().skip(1))
            .env(CHILD, threads.to_string())
            .env("RAYON_NUM_THREADS", threads.to_string())
            .stderr(std::process::Stdio::inherit())
            .output()?;
        if !out.status.success() {
            return Err(format!("the {threads}-thread run failed ({})", out.status).into());
        }
        for line in String::from_utf8(out.stdout)?.lines() {
            // cell <light>|<config>|<ms>|<share %>, zooms in order
            if let Some(rest) = line.strip_prefix("cell ") {
                let f: Vec<&str> = rest.split('|').collect();
                if f.len() != 4 {
                    return Err(format!("unexpected child line: {line}").into());
                }
                let row = rows
                    .entry((f[0].to_string(), f[1].to_string(), threads))
                    .or_default();
                row.ms.push(f[2].to_string());
                row.share.push(f[3].to_string());
            } else {
                notes.push(line.to_string());
            }
        }
    }
    // Velinov's Table 2 (GTX 970M, ms), zoom 0.5×, 1×, 2×.
    let paper = |light: &str, config: &str| match (light, config) {
        ("sphere", "off, grid") => "3.9 / 4.7 / 8.8",
        ("sphere", "off, BVH") => "4.5 / 6.3 / 12.8",
        ("sphere", "on, BVH") => "27.3 / 31.7 / 36.3",
        ("star", "off, grid") => "12.5 / 21.1 / 43.4",
        ("star", "off, BVH") => "13.9 / 26.5 / 60.6",
        _ => "48.5 / 60.3 / 94.1",
    };
    println!(
        "| light | AA, lookup | threads | 0.5× | 1× | 2× | ray queries | GTX 970M (Velinov) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for light in ["sphere", "star"] {
        for (config, _, _) in CONFIGS {
            for threads in THREADS {
                let Some(r) = rows.get(&(light.to_string(), config.to_string(), threads)) else {
                    continue;
                };
                println!(
                    "| {light} | {config} | {threads} | {} | {} % | {} |",
                    r.ms.join(" | "),
                    r.share.join(" / "),
                    paper(light, config)
                );
            }
        }
    }
    println!();
    for n in notes {
        println!("{n}");
    }
    Ok(())
}

/// Measures every cell on the global pool of `threads` threads; prints `cell` lines, then
/// the segment count and, on two threads, the 2× sphere grid frame in a separately built
/// pool of the same size.
fn measure(
    repeats: usize,
    only: Option<&str>,
    threads: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    if rayon::current_num_threads() != threads {
        return Err(format!(
            "the global pool has {} threads, not {threads}",
            rayon::current_num_threads()
        )
        .into());
    }
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/velinov_table2.json");
    let base: Value = serde_json::from_str(&std::fs::read_to_string(&file)?)?;
    let fov0 = base["camera"]["fov_y_deg"].as_f64().unwrap_or(22.0);
    let sphere_light = base["lights"][0].clone();
    let c = sphere_light["center"]
        .as_array()
        .map(|a| [0, 1, 2].map(|i| a[i].as_f64().unwrap_or(0.0)))
        .unwrap_or([600.0, -500.0, 600.0]);
    let lights = [("sphere", sphere_light), ("star", star(c, 40.0))];
    let mut segments = 0;
    for (light_name, light) in &lights {
        if only.is_some_and(|o| o != *light_name) {
            continue;
        }
        for (config, footprint, lookup) in CONFIGS {
            for zoom in ZOOMS {
                let mut v = base.clone();
                let half = (fov0.to_radians() / 2.0).tan() / zoom;
                v["camera"]["fov_y_deg"] = json!((2.0 * half.atan()).to_degrees());
                v["lights"] = json!([light]);
                v["render"]["footprint"] = json!(footprint);
                v["render"]["scratch_lookup"] = json!(lookup);
                let scene = scene_file::scene_from_value(
                    &v,
                    "velinov_table2",
                    file.parent().unwrap_or(Path::new(".")),
                )?;
                let prep = prepare::prepare(&scene);
                segments = scene.materials.iter().map(|m| m.scratches.len()).sum();
                let device = scratchwave_embree::Device::new()?;
                let mut builder = scratchwave_embree::SceneBuilder::new(&device)?;
                let (vs, is) = prep.indexed();
                builder.add_triangle_mesh(&vs, &is)?;
                let embree = builder.commit()?;
                let frame = |run: &dyn Fn(&Timed<'_, _>) -> f64| {
                    let mut runs = Vec::new();
                    for _ in 0..repeats {
                        let timed = Timed {
                            inner: &embree,
                            nanos: AtomicU64::new(0),
                        };
                        let seconds = run(&timed);
                        let ray_s = timed.nanos.load(Ordering::Relaxed) as f64 * 1e-9;
                        runs.push((seconds, ray_s));
                    }
                    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
                    runs[runs.len() / 2]
                };
                let (seconds, ray_s) =
                    frame(&|q| render::render(&scene, &prep, q, &|_, _| {}).1.seconds);
                // Ray time is summed over threads; the frame time is wall time.
                println!(
                    "cell {light_name}|{config}|{:.0}|{:.0}",
                    seconds * 1e3,
                    100.0 * ray_s / (seconds * threads as f64)
                );
                if threads == 2 && *light_name == "sphere" && config == "off, grid" && zoom == 2.0 {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()?;
                    let (own, _) = frame(&|q| {
                        pool.install(|| render::render(&scene, &prep, q, &|_, _| {}))
                            .1
                            .seconds
                    });
                    println!(
                        "The sphere, off, grid frame at 2× takes {:.0} ms on the global pool of 2 threads and {:.0} ms in a separately built 2-thread pool entered with `ThreadPool::install`.",
                        seconds * 1e3,
                        own * 1e3
                    );
                }
            }
        }
    }
    if threads == 2 {
        println!(
            "{segments} segments; ms per frame (tile loop, median of {repeats}) on rayon's global pool (RAYON_NUM_THREADS = threads, as `scratchwave render` runs); ray queries: share of the tile loop's thread time in Embree calls at 0.5× / 1× / 2×."
        );
    }
    Ok(())
}
