//! The C reference program (`bench-c/embree_rays.c`, compiled here with the system `cc`)
//! and the Rust wrapper trace the same rays to bit-identical hits: on a UV sphere and a
//! triangle soup, camera and random rays, for every query path (`rtcIntersect1/8/16`,
//! `rtcOccluded1`), the hit counts and the checksums over every hit's ids, `t`, `u`, `v`
//! and normal are equal. The embree_vs_c example times the same paths.

use scratchwave_embree::c_reference::{
    Budget, CProgram, CReferenceError, QueryPath, compile, run_rust, write_workload,
};
use scratchwave_embree::{Device, SceneBuilder};
use scratchwave_host::Coherence;
use scratchwave_kernel::ray::Ray;
use scratchwave_testkit::fixtures::{Mesh, camera_rays, random_rays, sphere_with, triangle_soup};
use std::path::PathBuf;

/// The device configuration both sides use (same build settings, so the same BVH).
const CONFIG: &str = "threads=1";

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_reference")
}

#[test]
fn c_program_and_wrapper_find_identical_hits() {
    let exe = match compile(&dir()) {
        Ok(exe) => exe,
        Err(e @ CReferenceError::NoCompiler { .. }) => {
            println!("skipped: {e}");
            return;
        }
        Err(e) => panic!("{e}"),
    };
    let device = Device::with_config(CONFIG).expect("Embree (run scripts/fetch-embree.sh)");
    let once = Budget {
        block: 1024,
        ..Budget::ONCE
    };
    let ray_sets: [(&str, Vec<Ray>, Coherence); 2] = [
        ("camera", camera_rays(64, 64, 0.4), Coherence::Coherent),
        ("random", random_rays(4099, 3), Coherence::Incoherent),
    ];
    let sets: Vec<&[Ray]> = ray_sets.iter().map(|(_, r, _)| r.as_slice()).collect();
    let meshes: [(&str, Mesh); 2] = [
        ("sphere", sphere_with(20_000)),
        ("soup", triangle_soup(20_000, 5)),
    ];
    for (mesh_name, mesh) in &meshes {
        let workload = dir().join(format!("{mesh_name}.bin"));
        write_workload(&workload, &mesh.vertices, &mesh.indices, &sets).expect("workload");
        let mut c = CProgram::start(&exe, CONFIG, &workload).expect("C program");
        assert_eq!(c.version(), device.version(), "same library");
        let mut builder = SceneBuilder::new(&device).expect("scene");
        builder
            .add_triangle_mesh(&mesh.vertices, &mesh.indices)
            .expect("mesh");
        let scene = builder.commit().expect("commit");
        for (set, (rays_name, rays, coherence)) in ray_sets.iter().enumerate() {
            for path in QueryPath::ALL {
                let what = format!("{mesh_name}/{rays_name}/{}", path.name());
                let from_c = c.run(set, path, *coherence, once).expect("C run");
                let from_rust = run_rust(&scene, rays, path, *coherence, once);
                assert_eq!(from_c.rays, rays.len(), "{what}");
                assert!(
                    from_c.hits > rays.len() as u64 / 10,
                    "{what}: too few hits ({}) to prove anything",
                    from_c.hits
                );
                assert_eq!(from_rust.hits, from_c.hits, "{what}: hit counts");
                assert_eq!(
                    from_rust.checksum, from_c.checksum,
                    "{what}: hit checksums differ"
                );
                println!(
                    "{what}: {} of {} rays hit, checksum {:016x} on both sides",
                    from_c.hits,
                    rays.len(),
                    from_c.checksum
                );
            }
        }
    }
}
