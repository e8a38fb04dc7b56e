//! `--backend spirv` for scenes: the scene prepared and flattened on the CPU
//! (`scratchwave_render::per_pixel::FlatScene`), every pixel rendered by the
//! `render_pixels` compute shader (`Gpu::render_scene`), the image read back.

use scratchwave_render::per_pixel::{FlatScene, image_from_pixels, image_stats};
use scratchwave_render::{Rendered, Scene, prepare};
use scratchwave_spirv::{Gpu, SceneInput};
use std::time::Instant;

/// Renders `scene` on `gpu`; `progress(done, total)` counts pixels.
pub fn render_spirv(
    gpu: &Gpu,
    scene: &Scene,
    progress: &dyn Fn(usize, usize),
) -> Result<Rendered, String> {
    let t0 = Instant::now();
    let prep = prepare::prepare(scene);
    let flat = FlatScene::new(scene, &prep).map_err(|e| e.to_string())?;
    let build_seconds = t0.elapsed().as_secs_f64();
    let bvh = &flat.bvh;
    let input = SceneInput {
        frame: flat.frame,
        tri_nodes: bvh.nodes(),
        tri_slots: bvh.triangles(),
        prim_ids: bvh.prim_ids(),
        geometry: prep.geometry(),
        materials: &prep.materials,
        lights: &prep.lights,
        scratches: flat.scratches.view(),
    };
    let out = gpu
        .render_scene(&input, progress)
        .map_err(|e| format!("spirv: {e}"))?;
    let cam = flat.frame.camera;
    let mut stats = image_stats(&flat.frame, &out.output);
    // Upload, paced dispatches and readback; the pipeline's compilation is not frame time.
    stats.seconds = out.timings.total().as_secs_f64();
    Ok(Rendered {
        image: image_from_pixels(cam.width_px, cam.height_px, &out.output),
        stats,
        build_seconds,
    })
}
