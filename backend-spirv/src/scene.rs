//! Scenes on the GPU: the kernel's per-pixel light loop
//! (`scratchwave_kernel::render::radiance::pixel_radiance`) in the `render_pixels` entry
//! point, over the scene's flattened records. The host uploads them once and reads the
//! image back; the pixels are dispatched in paced slices ([`Pace`](crate::Pace)).

use crate::dispatch::{Dispatched, Input};
use crate::error::Result;
use crate::gpu::Gpu;
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::ray::Triangle;
use scratchwave_kernel::render::area::SceneLight;
use scratchwave_kernel::render::radiance::{
    FrameParams, PixelValue, SceneGeometry, SharedScratches,
};
use scratchwave_kernel::render::shading::ShadeMaterial;

/// Everything a frame reads, flattened (see the `render_pixels` entry point).
#[derive(Clone, Copy, Debug)]
pub struct SceneInput<'a> {
    /// Camera, samples, footprint, shadows, spectrum.
    pub frame: FrameParams,
    /// The triangle hierarchy's nodes.
    pub tri_nodes: &'a [BvhNode],
    /// Its triangles in slot order.
    pub tri_slots: &'a [Triangle],
    /// The primitive id of each slot.
    pub prim_ids: &'a [u32],
    /// The shapes by primitive id and object.
    pub geometry: SceneGeometry<'a>,
    /// Materials.
    pub materials: &'a [ShadeMaterial],
    /// Lights.
    pub lights: &'a [SceneLight],
    /// Every material's scratch lookup and the G1 table.
    pub scratches: SharedScratches<'a>,
}

impl Gpu {
    /// Renders every pixel of `scene` (row-major from the top-left) in slices of the
    /// `Gpu`'s [`Pace`](crate::Pace); `progress(done, total)` after each slice.
    pub fn render_scene(
        &self,
        scene: &SceneInput<'_>,
        progress: &dyn Fn(usize, usize),
    ) -> Result<Dispatched<PixelValue>> {
        let cam = &scene.frame.camera;
        let n = cam.width_px as usize * cam.height_px as usize;
        let pixels: Vec<u32> = (0..n as u32).collect();
        let frame = FrameParams {
            light_count: scene.lights.len() as u32,
            ..scene.frame
        };
        let g = &scene.geometry;
        let s = &scene.scratches;
        let inputs = [
            Input::whole(std::slice::from_ref(&frame)),
            Input::whole(scene.tri_nodes),
            Input::whole(scene.tri_slots),
            Input::whole(scene.prim_ids),
            Input::whole(g.triangles),
            Input::whole(g.uvs),
            Input::whole(g.prim_object),
            Input::whole(g.surfaces),
            Input::whole(scene.materials),
            Input::whole(scene.lights),
            Input::whole(s.materials),
            Input::whole(s.nodes),
            Input::whole(s.scratches),
            Input::whole(s.offsets),
            Input::whole(s.items),
            Input::whole(s.g1),
            Input::per_item(&pixels),
        ];
        self.dispatch_with_progress("render_pixels", &inputs, n, progress)
    }
}
