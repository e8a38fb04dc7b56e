//! # scratchwave-spirv-shader
//!
//! The rust-gpu compute entry points of scratchwave. Each `#[spirv(compute)]` function is a
//! thin wrapper: it reads its invocation's element from a storage buffer, calls a plain
//! function — a kernel function, or a small dispatcher here that the CPU calls too — and
//! writes the result. No formula lives in this crate.
//!
//! Buffer conventions shared with the host (`scratchwave-spirv`'s `dispatch`):
//! descriptor set 0, read-only inputs at bindings `0..k` in the order the host passes them,
//! the output at binding `k`; one invocation per output element, workgroups of
//! [`WORKGROUP_SIZE`] along x. The host splits large jobs into chunks and binds each
//! chunk's sub-range, so `out.len()` is the chunk length and `id.x` indexes the chunk.
//!
//! The crate also compiles for the host (it is a workspace member), where the entry points
//! are ordinary functions and [`probe`] serves as the CPU reference.
#![no_std]

pub mod bsdf_probe;
pub mod lobe_probe;
pub mod probe;

use bytemuck::{Pod, Zeroable};
use scratchwave_kernel::bsdf::{BsdfMaterial, Lookup};
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::footprint::{self, Ellipse};
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::lights::{LightParams, LightQuery, light_integral};
use scratchwave_kernel::ray::Triangle;
use scratchwave_kernel::render::area::SceneLight;
use scratchwave_kernel::render::radiance::{
    self, FrameParams, MaterialScratches, PixelValue, SceneGeometry, SharedScratches,
    TriangleHierarchy,
};
use scratchwave_kernel::render::shading::ShadeMaterial;
use scratchwave_kernel::render::surface::{Surface, TriangleUv};
use scratchwave_kernel::scratch::{Scratch, ScratchBvh};
use scratchwave_kernel::table::{self, Model, TableParams, TableQuery};
use spirv_std::glam::UVec3;
use spirv_std::spirv;

/// Invocations per workgroup of every entry point (the `threads(64)` below).
pub const WORKGROUP_SIZE: u32 = 64;

/// Element-wise evaluation of one kernel math function (see [`probe::MathFunction`]).
#[spirv(compute(threads(64)))]
pub fn math_probe(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[probe::ProbeParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] args: &[[f32; 2]],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] out: &mut [[f32; 2]],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = probe::evaluate(params[0].function, args[i]);
    }
}

/// [`table::evaluate`] with the model fixed to `model` (a `#[repr(u32)]` GPU enum, so it
/// needs no Int8 capability): one BRDF value per query.
///
/// The host uploads the CPU backend's lookup: BVH `nodes` and the scratches in slot order,
/// and the kernel traverses them exactly as on the CPU ([`ScratchBvh`], a cursor-driven
/// stackless walk with no closures capturing references, which rust-gpu cannot store).
#[inline]
fn table_entry(
    model: Model,
    id: UVec3,
    params: &[TableParams],
    nodes: &[BvhNode],
    scratches: &[Scratch],
    queries: &[TableQuery],
    out: &mut [f32],
) {
    let i = id.x as usize;
    if i < out.len() {
        let params = TableParams {
            model: model as u32,
            ..params[0]
        };
        out[i] = table::evaluate(&params, &queries[i], &ScratchBvh::new(nodes, scratches));
    }
}

/// BRDF table, Werner Eq. 15 (coherent base and scratches).
#[spirv(compute(threads(64)))]
pub fn table_werner(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[TableParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] queries: &[TableQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] out: &mut [f32],
) {
    table_entry(Model::Werner, id, params, nodes, scratches, queries, out);
}

/// BRDF table, Werner §5 (coherent scratches only, for blending with a base BRDF).
#[spirv(compute(threads(64)))]
pub fn table_werner_blended(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[TableParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] queries: &[TableQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] out: &mut [f32],
) {
    table_entry(
        Model::WernerBlended,
        id,
        params,
        nodes,
        scratches,
        queries,
        out,
    );
}

/// BRDF table, Velinov Eq. 7 (incoherent sum of single-scratch responses).
#[spirv(compute(threads(64)))]
pub fn table_velinov(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[TableParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] queries: &[TableQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] out: &mut [f32],
) {
    table_entry(Model::Velinov, id, params, nodes, scratches, queries, out);
}

/// GHS table (Holzschuch & Pacanowski): [`table::evaluate_ghs_with_g1_table`], reading the
/// Smith G1 table from a buffer (the host uploads [`G1Table::FLAT`]).
#[spirv(compute(threads(64)))]
pub fn table_ghs(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[GhsParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] g1: &[f32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] queries: &[TableQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] out: &mut [f32],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = table::evaluate_ghs_with_g1_table(&params[0], G1Table::from_flat(g1), &queries[i]);
    }
}

/// Area light (Velinov §3.4): [`light_integral`], `∫ f_r cos θi dωi` over each query's
/// sphere or polygon light, summed over the scratches near the shading point (the same BVH
/// buffers as the table entry points).
#[spirv(compute(threads(64)))]
pub fn light(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[LightParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] queries: &[LightQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] out: &mut [f32],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = light_integral(&params[0], &queries[i], &ScratchBvh::new(nodes, scratches));
    }
}

/// Parameters of the footprint entry points.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FootprintParams {
    /// Coherence σ (µm).
    pub sigma_um: f32,
    /// Explicit padding.
    pub pad: [f32; 3],
}

const _: () = assert!(core::mem::size_of::<FootprintParams>() == 16);

/// One footprint average per (scratch, ellipse) pair: `average(scratch, ellipse, σ)`.
#[inline]
fn footprint_entry(
    average: impl Fn(&Scratch, &Ellipse, f32) -> f32,
    id: UVec3,
    params: &[FootprintParams],
    scratches: &[Scratch],
    ellipses: &[Ellipse],
    out: &mut [f32],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = average(&scratches[i], &ellipses[i], params[0].sigma_um);
    }
}

/// [`footprint::eta_p_eq15`]: Velinov Eq. 15.
#[spirv(compute(threads(64)))]
pub fn footprint_eq15(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[FootprintParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] ellipses: &[Ellipse],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] out: &mut [f32],
) {
    footprint_entry(footprint::eta_p_eq15, id, params, scratches, ellipses, out);
}

/// [`footprint::eta_p_eq16`]: Velinov Eq. 16 with its π restored.
#[spirv(compute(threads(64)))]
pub fn footprint_eq16(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[FootprintParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] ellipses: &[Ellipse],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] out: &mut [f32],
) {
    footprint_entry(footprint::eta_p_eq16, id, params, scratches, ellipses, out);
}

/// [`footprint::eta_p_accurate`]: the accurate quadrature.
#[spirv(compute(threads(64)))]
pub fn footprint_accurate(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[FootprintParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] ellipses: &[Ellipse],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] out: &mut [f32],
) {
    footprint_entry(
        footprint::eta_p_accurate,
        id,
        params,
        scratches,
        ellipses,
        out,
    );
}

/// [`footprint::rho_p_eq18`]: Velinov Eq. 18 without its factor 2 (σ unused).
#[spirv(compute(threads(64)))]
pub fn footprint_rho_p(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[FootprintParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] ellipses: &[Ellipse],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] out: &mut [f32],
) {
    footprint_entry(
        |s, e, _| footprint::rho_p_eq18(s, e),
        id,
        params,
        scratches,
        ellipses,
        out,
    );
}

/// The BSDF interface (`scratchwave_kernel::bsdf`): `eval`, `pdf` and `sample` of one
/// material per query ([`bsdf_probe::evaluate`]), over the uploaded scratch BVH and the G1
/// table as a buffer.
#[spirv(compute(threads(64)))]
pub fn bsdf(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] material: &[BsdfMaterial],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] g1: &[f32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] queries: &[bsdf_probe::BsdfQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] out: &mut [bsdf_probe::BsdfResult],
) {
    let i = id.x as usize;
    if i < out.len() {
        let set = ScratchBvh::new(nodes, scratches);
        let lk = Lookup::with_g1_table(set, G1Table::from_flat(g1));
        out[i] = bsdf_probe::evaluate(&material[0], &lk, &queries[i]);
    }
}

/// The scratch models' sampling lobes ([`lobe_probe::evaluate`]): one `Lobe1`, disk-lobe or
/// vMF-ring density, mass or sample per query.
#[spirv(compute(threads(64)))]
pub fn lobe_probe(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] queries: &[lobe_probe::LobeQuery],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] out: &mut [[f32; 4]],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = lobe_probe::evaluate(&queries[i]);
    }
}

/// One pixel of a scene ([`radiance::pixel_radiance`]): its camera rays through the
/// triangle hierarchy (`tri_nodes`, slot-ordered `tri_slots` and `prim_ids`), the hit's
/// shapes (`triangles`, `uvs`, `prim_object`, `surfaces` by primitive id and object), the
/// materials with their scratch lookups in shared buffers (`scratch_materials`, BVH
/// `scratch_nodes` and `scratches`, grid `offsets` and `items`), the lights, and the G1
/// table. `pixels[i]` is the pixel's index `j·W + i` in the image.
#[spirv(compute(threads(64)))]
#[allow(clippy::too_many_arguments)]
pub fn render_pixels(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] frame: &[FrameParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] tri_nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] tri_slots: &[Triangle],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] prim_ids: &[u32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] triangles: &[Triangle],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] uvs: &[TriangleUv],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] prim_object: &[u32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] surfaces: &[Surface],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] materials: &[ShadeMaterial],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] lights: &[SceneLight],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)]
    scratch_materials: &[MaterialScratches],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] scratch_nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 12)] scratches: &[Scratch],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 13)] offsets: &[u32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 14)] items: &[u32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 15)] g1: &[f32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 16)] pixels: &[u32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 17)] out: &mut [PixelValue],
) {
    let k = id.x as usize;
    if k < out.len() && k < pixels.len() {
        let frame = frame[0];
        let w = frame.camera.width_px;
        let p = pixels[k];
        let (i, j) = if w > 0 { (p % w, p / w) } else { (0, 0) };
        let geo = SceneGeometry {
            triangles,
            uvs,
            prim_object,
            surfaces,
        };
        let lookups = SharedScratches {
            materials: scratch_materials,
            nodes: scratch_nodes,
            scratches,
            offsets,
            items,
            g1,
        };
        let tracer = TriangleHierarchy {
            nodes: tri_nodes,
            triangles: tri_slots,
            prim_ids,
        };
        out[k] = radiance::pixel_radiance(&frame, &geo, materials, lights, &lookups, &tracer, i, j);
    }
}
