//! Renders are bitwise reproducible across thread counts on each ray backend (tiles are
//! independent, sub-pixel positions depend only on the pixel index and sample number). Tile
//! boundaries are covered by `region.rs`: regions of any size assemble into the whole image
//! bit for bit. (The two ray backends agree within the conformance tolerance, not bit for
//! bit: their hit points differ in the last bits.)

use scratchwave_render::{Backend, Image, render_scene, scene_file};
use std::path::Path;

fn bits(image: &Image) -> Vec<u32> {
    image.rgb.iter().flat_map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn same_image_on_1_2_and_8_threads_on_each_ray_backend() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../conformance/scenes");
    let mut scene = scene_file::read_scene(&root.join("werner_closeup.json")).unwrap();
    scene.settings.spp = 3;
    let on = |threads: usize, backend: Backend| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_scene(&scene, backend, &|_, _| {}).unwrap().image)
    };
    let mut backends = vec![Backend::Cpu];
    if scratchwave_embree::Device::new().is_ok() {
        backends.push(Backend::Embree);
    }
    for backend in backends {
        let reference = on(1, backend);
        assert!(
            reference.rgb.iter().any(|p| p[0] > 0.0),
            "{}",
            backend.name()
        );
        for threads in [2, 8] {
            assert_eq!(
                bits(&reference),
                bits(&on(threads, backend)),
                "{} on {threads} threads",
                backend.name()
            );
        }
    }
}
