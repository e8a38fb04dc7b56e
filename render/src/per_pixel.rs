//! The one-invocation-per-pixel form of the renderer, as a GPU runs it: every pixel is
//! the kernel's [`pixel_radiance`] over the scene's flattened records, its scratch lookups
//! in shared buffers ([`SharedScratchData`]) and the kernel's own triangle hierarchy.
//! [`render_per_pixel`] runs it on the CPU (rayon over rows), so the GPU's program and
//! buffers are checked against the tile loop without a GPU; a GPU backend takes the same
//! records from [`FlatScene`].

use crate::prepare::Prepared;
use crate::render::{Image, RenderStats, frame_params};
use crate::scene::Scene;
use rayon::prelude::*;
use scratchwave_host::{SharedScratchData, SharedScratchesError, TriangleBvh};
use scratchwave_kernel::render::radiance::{
    FrameParams, PixelValue, TriangleHierarchy, pixel_radiance,
};
use std::time::Instant;

/// A prepared scene flattened for a per-pixel renderer: the frame record, the kernel
/// triangle hierarchy and every material's scratch lookup in shared buffers.
pub struct FlatScene<'p> {
    /// The preparation (geometry, materials, lights).
    pub prep: &'p Prepared,
    /// Camera, samples, footprint, shadows, spectrum.
    pub frame: FrameParams,
    /// The triangle hierarchy.
    pub bvh: TriangleBvh,
    /// The scratch lookups.
    pub scratches: SharedScratchData,
}

impl<'p> FlatScene<'p> {
    /// Flattens `prep` (of `scene`).
    pub fn new(scene: &Scene, prep: &'p Prepared) -> Result<FlatScene<'p>, SharedScratchesError> {
        Ok(FlatScene {
            prep,
            frame: frame_params(scene, prep),
            bvh: prep.cpu_bvh(),
            scratches: SharedScratchData::new(&prep.lookups, &prep.grids)?,
        })
    }

    /// The kernel's view of the triangle hierarchy.
    pub fn tracer(&self) -> TriangleHierarchy<'_> {
        TriangleHierarchy {
            nodes: self.bvh.nodes(),
            triangles: self.bvh.triangles(),
            prim_ids: self.bvh.prim_ids(),
        }
    }
}

/// Renders `flat` pixel by pixel on the CPU with [`pixel_radiance`].
pub fn render_per_pixel(flat: &FlatScene<'_>) -> (Image, RenderStats) {
    let cam = flat.frame.camera;
    let (w, h) = (cam.width_px, cam.height_px);
    let start = Instant::now();
    let geo = flat.prep.geometry();
    let lookups = flat.scratches.view();
    let tracer = flat.tracer();
    let rows: Vec<Vec<PixelValue>> = (0..h)
        .into_par_iter()
        .map(|j| {
            (0..w)
                .map(|i| {
                    pixel_radiance(
                        &flat.frame,
                        &geo,
                        &flat.prep.materials,
                        &flat.prep.lights,
                        &lookups,
                        &tracer,
                        i,
                        j,
                    )
                })
                .collect()
        })
        .collect();
    let values: Vec<PixelValue> = rows.into_iter().flatten().collect();
    let mut stats = image_stats(&flat.frame, &values);
    stats.seconds = start.elapsed().as_secs_f64();
    (image_from_pixels(w, h, &values), stats)
}

/// The image of per-pixel values (row-major from the top-left).
pub fn image_from_pixels(width: u32, height: u32, values: &[PixelValue]) -> Image {
    Image {
        width,
        height,
        rgb: values.iter().map(|v| v.rgb).collect(),
        model_choice: if values
            .iter()
            .any(|v| v.auto_coherent + v.auto_incoherent > 0)
        {
            values
                .iter()
                .map(|v| [v.auto_coherent, v.auto_incoherent])
                .collect()
        } else {
            Vec::new()
        },
    }
}

/// The counts of per-pixel values (`seconds` left 0).
pub fn image_stats(frame: &FrameParams, values: &[PixelValue]) -> RenderStats {
    let cam = &frame.camera;
    RenderStats {
        primary_rays: u64::from(cam.width_px) * u64::from(cam.height_px) * u64::from(frame.spp),
        shadow_rays: values.iter().map(|v| u64::from(v.shadow_rays)).sum(),
        shading_evaluations: values.iter().map(|v| u64::from(v.shading)).sum(),
        seconds: 0.0,
        auto_coherent: values.iter().map(|v| u64::from(v.auto_coherent)).sum(),
        auto_incoherent: values.iter().map(|v| u64::from(v.auto_incoherent)).sum(),
    }
}
