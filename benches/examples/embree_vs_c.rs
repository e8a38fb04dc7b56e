//! Embree through the Rust wrapper (`scratchwave-embree`) against a C program calling the
//! same library on the same rays (`backend-embree/bench-c/embree_rays.c`, compiled here with
//! the system `cc`), and against the portable kernel BVH (`scratchwave_host::TriangleBvh`):
//!
//!     cargo run --release -p scratchwave-benches --example embree_vs_c
//!         [-- --triangles 1000000 --camera 256 --random 65536 --seconds 1.2 --rounds 12
//!             --config threads=1 --only sphere,camera,rtcIntersect16]
//!
//! Meshes: a closed UV sphere and a triangle soup of `--triangles` each. Rays: `--camera`²
//! camera rays in 4 × 4 tiles (coherent), `--random` random rays (incoherent), and the camera
//! rays turned around (`miss`: they leave the scene's bounding box at once, so Embree does
//! almost nothing and what remains is the cost of a call, the wrapper's included). Paths:
//! `rtcIntersect1` (single rays), `rtcIntersect8`/`16` (packets of consecutive rays, with the
//! coherence hint of the ray set), `rtcOccluded1`. Everything is single-threaded (Embree
//! device `--config`, the same for Rust and C, so both build the same BVH).
//!
//! Each row runs the Rust wrapper and the C program in `--rounds` interleaved rounds (the
//! order alternating) of `--seconds / --rounds` each, so load from other processes hits both
//! alike. Passes trace blocks of 4096 consecutive rays, each timed in CPU time of the tracing
//! thread (`CLOCK_THREAD_CPUTIME_ID`: waiting for a core on a shared machine does not count);
//! rays/s is the ray count over the sum of each block's fastest time (the same estimator on
//! both sides: what a pass takes when nothing else interrupts it). Rust ÷ C is the median
//! (with quartiles) of the per-round ratios: each round's Rust and C runs are back to back, so
//! a load that changes over seconds cancels in the pair. Every row also checks that
//! Rust and C produced bit-identical hits (checksum over ids, `t`, `u`, `v`, normals); a
//! mismatch makes the exit status 1. The portable BVH has no packets: its column is single
//! rays (`closest_hit`, or `occluded` in the occlusion rows), timed the same way.
//! `--only` (comma-separated: `sphere`, `soup`, `camera`, `random`, `miss`, Embree calls)
//! restricts the meshes, ray sets or calls it names.

use scratchwave_embree::c_reference::{
    Budget, CProgram, Measurement, QueryPath, compile, run_rust, thread_cpu_seconds, time_passes,
    write_workload,
};
use scratchwave_embree::{Device, SceneBuilder};
use scratchwave_host::{Coherence, RayQueries, TriangleBvh};
use scratchwave_kernel::ray::{Hit, Ray};
use scratchwave_testkit::fixtures::{camera_rays, random_rays, sphere_with, triangle_soup};
use scratchwave_testkit::heightfield::quantile;
use std::hint::black_box;
use std::path::PathBuf;
use std::process::ExitCode;

/// Rays per timed block (see `Budget::block`).
const BLOCK: usize = 4096;

struct Options {
    triangles: usize,
    camera: usize,
    random: usize,
    seconds: f64,
    rounds: u32,
    config: String,
    /// Names selecting rows (`sphere`, `soup`, `camera`, `random`, `miss`, `rtcIntersect1`,
    /// …): a mesh, ray set or call runs if it is named, or if nothing of its kind is.
    only: Vec<String>,
}

fn options() -> Result<Options, String> {
    let mut o = Options {
        triangles: 1_000_000,
        camera: 256,
        random: 65_536,
        seconds: 1.2,
        rounds: 12,
        config: "threads=1".into(),
        only: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        let bad = |e: &dyn std::fmt::Display| format!("{flag} {value}: {e}");
        match flag.as_str() {
            "--triangles" => o.triangles = value.parse().map_err(|e| bad(&e))?,
            "--camera" => o.camera = value.parse().map_err(|e| bad(&e))?,
            "--random" => o.random = value.parse().map_err(|e| bad(&e))?,
            "--seconds" => o.seconds = value.parse().map_err(|e| bad(&e))?,
            "--rounds" => o.rounds = value.parse().map_err(|e| bad(&e))?,
            "--config" => o.config = value,
            "--only" => o.only = value.split(',').map(str::to_owned).collect(),
            _ => return Err(format!("unknown option {flag}")),
        }
    }
    if o.camera == 0 || !o.camera.is_multiple_of(4) {
        return Err("--camera must be a positive multiple of 4".into());
    }
    if o.rounds == 0 || o.seconds.is_nan() || o.seconds < 0.0 {
        return Err("--rounds must be positive and --seconds non-negative".into());
    }
    Ok(o)
}

fn si(x: f64) -> String {
    if x >= 1e6 {
        format!("{:.3} M", x / 1e6)
    } else {
        format!("{:.1} K", x / 1e3)
    }
}

fn first_line_of(path: &str, key: &str) -> String {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .map(|l| l.split(':').nth(1).unwrap_or(l).trim().to_owned())
        })
        .unwrap_or_else(|| "unknown".into())
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

struct Row {
    mesh: &'static str,
    rays: &'static str,
    path: QueryPath,
    rust: Measurement,
    c: Measurement,
    /// Rust ÷ C rays/s of each round (the two sides ran back to back).
    paired: Vec<f64>,
    portable: f64,
    same: bool,
}

/// `median [lower quartile, upper quartile]` of the paired Rust ÷ C ratios.
fn paired_summary(paired: &[f64]) -> String {
    // Linear interpolation between order statistics (testkit's definition).
    format!(
        "{:.3} [{:.3}, {:.3}]",
        quantile(paired, 0.5),
        quantile(paired, 0.25),
        quantile(paired, 0.75)
    )
}

fn main() -> ExitCode {
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => {
            eprintln!("error: Rust and C disagree on some hits (see the table)");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<bool, String> {
    let o = options()?;
    let exe_dir = std::env::current_exe()
        .map_err(|e| e.to_string())?
        .parent()
        .map(|p| p.join("embree-c"))
        .unwrap_or_else(|| PathBuf::from("embree-c"));
    let c_exe = compile(&exe_dir).map_err(|e| e.to_string())?;
    let device = Device::with_config(&o.config).map_err(|e| e.to_string())?;
    println!(
        "Embree {} ({}), device config {:?}; CPU {}; {} cores; load average {}",
        device.version(),
        scratchwave_embree::ffi::library_path().display(),
        o.config,
        first_line_of("/proc/cpuinfo", "model name"),
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        load_average()
    );
    println!(
        "native packets: 8 {}, 16 {}; C program {}",
        device.native_packet(8),
        device.native_packet(16),
        c_exe.display()
    );

    let ray_sets: [(&'static str, Vec<Ray>, Coherence); 3] = [
        (
            "camera",
            camera_rays(o.camera, o.camera, 0.4),
            Coherence::Coherent,
        ),
        ("random", random_rays(o.random, 1), Coherence::Incoherent),
        (
            "miss",
            camera_rays(o.camera, o.camera, 0.4)
                .into_iter()
                .map(|r| Ray::new(r.origin, [r.dir[0], r.dir[1], -r.dir[2]]))
                .collect(),
            Coherence::Coherent,
        ),
    ];
    let sets: Vec<&[Ray]> = ray_sets.iter().map(|(_, r, _)| r.as_slice()).collect();
    let slice = Budget {
        min_seconds: o.seconds / f64::from(o.rounds),
        // At least 2 passes per round: 24 samples of every block even for the slowest rows.
        min_passes: 2,
        block: BLOCK,
    };
    let whole = Budget {
        min_seconds: o.seconds,
        ..slice
    };

    let mut rows = Vec::new();
    let named = |name: &str| o.only.iter().any(|w| w == name);
    let wanted = |name: &str, kind: &[&str]| named(name) || !kind.iter().any(|k| named(k));
    let calls = QueryPath::ALL.map(QueryPath::embree_function);
    for (mesh_key, mesh_name, soup) in [("sphere", "UV sphere", false), ("soup", "soup", true)] {
        if !wanted(mesh_key, &["sphere", "soup"]) {
            continue;
        }
        let mesh = if soup {
            triangle_soup(o.triangles, 5)
        } else {
            sphere_with(o.triangles)
        };
        let workload = exe_dir.join("workload.bin");
        write_workload(&workload, &mesh.vertices, &mesh.indices, &sets)
            .map_err(|e| e.to_string())?;
        let mut c = CProgram::start(&c_exe, &o.config, &workload).map_err(|e| e.to_string())?;
        let start = thread_cpu_seconds();
        let mut builder = SceneBuilder::new(&device).map_err(|e| e.to_string())?;
        builder
            .add_triangle_mesh(&mesh.vertices, &mesh.indices)
            .map_err(|e| e.to_string())?;
        let scene = builder.commit().map_err(|e| e.to_string())?;
        let rust_build = thread_cpu_seconds() - start;
        let start = thread_cpu_seconds();
        let portable =
            TriangleBvh::new(&mesh.vertices, &mesh.indices).map_err(|e| e.to_string())?;
        println!(
            "\n{mesh_name}: {} triangles; build (CPU time): Embree from Rust {rust_build:.2} s, from C {:.2} s (incl. reading), portable BVH {:.2} s",
            mesh.indices.len(),
            c.build_seconds(),
            thread_cpu_seconds() - start
        );

        for (set, (rays_name, rays, coherence)) in ray_sets.iter().enumerate() {
            if !wanted(rays_name, &["camera", "random", "miss"]) {
                continue;
            }
            let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
            let (_, best, _) = time_passes(whole, rays.len(), |r| {
                portable.closest_hits(black_box(&rays[r.clone()]), &mut hits[r], *coherence)
            });
            let portable_closest = rays.len() as f64 / best;
            let mut occluded = vec![false; rays.len()];
            let (_, best, _) = time_passes(whole, rays.len(), |r| {
                for (ray, out) in black_box(&rays[r.clone()]).iter().zip(&mut occluded[r]) {
                    *out = portable.occluded(ray);
                }
            });
            let portable_occluded = rays.len() as f64 / best;

            for path in QueryPath::ALL {
                if !wanted(path.embree_function(), &calls) {
                    continue;
                }
                let mut rust: Option<Measurement> = None;
                let mut from_c: Option<Measurement> = None;
                let mut same = true;
                let mut paired = Vec::new();
                for round in 0..o.rounds {
                    let run_rust_once = || run_rust(&scene, rays, path, *coherence, slice);
                    let (r, m) = if round % 2 == 0 {
                        let r = run_rust_once();
                        (r, c.run(set, path, *coherence, slice))
                    } else {
                        let m = c.run(set, path, *coherence, slice);
                        (run_rust_once(), m)
                    };
                    let m = m.map_err(|e| e.to_string())?;
                    same &= r.checksum == m.checksum && r.hits == m.hits;
                    same &= rust.is_none_or(|prev| prev.checksum == r.checksum);
                    paired.push(r.rays_per_second() / m.rays_per_second());
                    rust = Some(rust.map_or(r, |prev| prev.merge(r)));
                    from_c = Some(from_c.map_or(m, |prev| prev.merge(m)));
                }
                let (Some(rust), Some(from_c)) = (rust, from_c) else {
                    return Err("no rounds".into());
                };
                println!(
                    "  {rays_name:6} {:14} Rust {:>10}/s ({} passes)  C {:>10}/s ({} passes)  Rust/C {}  hits {} of {}  {}",
                    path.embree_function(),
                    si(rust.rays_per_second()),
                    rust.passes,
                    si(from_c.rays_per_second()),
                    from_c.passes,
                    paired_summary(&paired),
                    rust.hits,
                    rust.rays,
                    if same { "same hits" } else { "HITS DIFFER" }
                );
                rows.push(Row {
                    mesh: mesh_name,
                    rays: rays_name,
                    path,
                    rust,
                    c: from_c,
                    paired,
                    portable: if path == QueryPath::Occluded1 {
                        portable_occluded
                    } else {
                        portable_closest
                    },
                    same,
                });
            }
        }
    }

    println!(
        "\nload average at the end: {}\n\n\
         | mesh | rays | Embree call | Rust wrapper rays/s | C rays/s | Rust ÷ C, paired rounds: median [quartiles] | portable BVH rays/s | Rust ÷ portable | hits identical |\n\
         |---|---|---|---|---|---|---|---|---|",
        load_average()
    );
    for r in &rows {
        let rust = r.rust.rays_per_second();
        println!(
            "| {} | {} | `{}` | {} | {} | {} | {} | {:.1}× | {} |",
            r.mesh,
            r.rays,
            r.path.embree_function(),
            si(rust),
            si(r.c.rays_per_second()),
            paired_summary(&r.paired),
            si(r.portable),
            rust / r.portable,
            if r.same { "yes" } else { "NO" }
        );
    }
    Ok(rows.iter().all(|r| r.same))
}
