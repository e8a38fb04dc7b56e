//! Renders are bitwise reproducible across thread counts (tiles are independent, sub-pixel
//! positions depend only on the pixel index and sample number).

use scratchwave_render::{Backend, render_scene, scene_file};
use std::path::Path;

#[test]
fn same_image_on_one_and_three_threads() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../conformance/scenes");
    let mut scene = scene_file::read_scene(&root.join("werner_closeup.json")).unwrap();
    scene.settings.spp = 3;
    let on = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| {
                render_scene(&scene, Backend::Cpu, &|_, _| {})
                    .unwrap()
                    .image
            })
    };
    let a = on(1);
    let b = on(3);
    assert!(a.rgb.iter().any(|p| p[0] > 0.0));
    let bits = |i: &scratchwave_render::Image| -> Vec<u32> {
        i.rgb.iter().flat_map(|p| p.map(f32::to_bits)).collect()
    };
    assert_eq!(bits(&a), bits(&b));
}
