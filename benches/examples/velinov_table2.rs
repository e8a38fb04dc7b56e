//! Velinov et al. 2018, Table 2, reproduced on the CPU renderer: a curved scratched metal
//! object (`benches/scenes/velinov_table2.json`: a 20 mm sphere, 10 000 arc scratches split
//! into ~4·10^5 segments, the incoherent model) at 1280×720, lit by a 5 mm sphere light 1 m
//! away or by an 8-pointed star polygon light (ear-clipped into triangles, as Velinov's star
//! light), at zoom 0.5×/1×/2× (field of view), antialiasing off (`footprint: none`) and on
//! (`footprint: ellipse`, Velinov's camera-footprint integration), on 1 and 2 threads.
//!
//! Shadow rays are adaptive (`render.shadows: "adaptive"`, the default): 4 probe rays per
//! sphere light and 3 per star triangle, the other quadrature nodes only in penumbrae.
//! Velinov's renderer rasterises primary visibility and casts no shadow rays at all.
//!
//! `cargo run --release -p scratchwave-benches --example velinov_table2 [-- REPEATS [sphere|star]]`
//! (the optional second argument runs one light's rows only)
//!
//! Prints one Markdown table: ms/frame (tile loop, median of the repeats) per row and the
//! share of that time spent in ray queries (Embree closest-hit and occlusion calls, timed
//! around each call, so the share includes the timer's own cost of ~25 ns per call).

use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::ray::{Hit, Ray};
use scratchwave_render::{prepare, render, scene_file};
use serde_json::{Value, json};
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repeats: usize = std::env::args().nth(1).map_or(Ok(1), |s| s.parse())?;
    let only = std::env::args().nth(2);
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/velinov_table2.json");
    let base: Value = serde_json::from_str(&std::fs::read_to_string(&file)?)?;
    let fov0 = base["camera"]["fov_y_deg"].as_f64().unwrap_or(22.0);
    let sphere_light = base["lights"][0].clone();
    let c = sphere_light["center"]
        .as_array()
        .map(|a| [0, 1, 2].map(|i| a[i].as_f64().unwrap_or(0.0)))
        .unwrap_or([600.0, -500.0, 600.0]);
    let lights = [("sphere", sphere_light), ("star", star(c, 40.0))];
    println!(
        "| light | AA | zoom | threads | ms/frame | ray queries | Mrays/s | shading evaluations | segments |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (light_name, light) in &lights {
        if only.as_deref().is_some_and(|o| o != *light_name) {
            continue;
        }
        for aa in [false, true] {
            for zoom in [0.5f64, 1.0, 2.0] {
                let mut v = base.clone();
                let half = (fov0.to_radians() / 2.0).tan() / zoom;
                v["camera"]["fov_y_deg"] = json!((2.0 * half.atan()).to_degrees());
                v["lights"] = json!([light]);
                v["render"]["footprint"] = json!(if aa { "ellipse" } else { "none" });
                let scene = scene_file::scene_from_value(
                    &v,
                    "velinov_table2",
                    file.parent().unwrap_or(Path::new(".")),
                )?;
                let prep = prepare::prepare(&scene);
                let segments: usize = scene.materials.iter().map(|m| m.scratches.len()).sum();
                let device = scratchwave_embree::Device::new()?;
                let mut builder = scratchwave_embree::SceneBuilder::new(&device)?;
                let (vs, is) = prep.indexed();
                builder.add_triangle_mesh(&vs, &is)?;
                let embree = builder.commit()?;
                for threads in [1usize, 2] {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()?;
                    let mut runs = Vec::new();
                    for _ in 0..repeats.max(1) {
                        let timed = Timed {
                            inner: &embree,
                            nanos: AtomicU64::new(0),
                        };
                        let (_, stats) =
                            pool.install(|| render::render(&scene, &prep, &timed, &|_, _| {}));
                        let ray_s = timed.nanos.load(Ordering::Relaxed) as f64 * 1e-9;
                        runs.push((stats, ray_s));
                    }
                    runs.sort_by(|a, b| a.0.seconds.total_cmp(&b.0.seconds));
                    let (stats, ray_s) = runs[runs.len() / 2];
                    // Ray time is summed over threads; the frame time is wall time.
                    let share = ray_s / (stats.seconds * threads as f64);
                    println!(
                        "| {light_name} | {} | {zoom}× | {threads} | {:.0} | {:.0} % | {:.2} | {} | {segments} |",
                        if aa { "on" } else { "off" },
                        stats.seconds * 1e3,
                        100.0 * share,
                        stats.mrays_per_s(),
                        stats.shading_evaluations
                    );
                }
            }
        }
    }
    Ok(())
}
