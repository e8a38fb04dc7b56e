//! Importance sampling: pure warps (random numbers are inputs) with matching pdfs and,
//! where the warp is invertible, inverses (for tests and for MIS bookkeeping).

pub mod ghs;
pub mod warp;

use glam::Vec3;

/// One sampled direction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// The sampled outgoing direction (local frame, `z > 0`).
    pub wo: Vec3,
    /// Its solid-angle pdf (the full mixture pdf, as returned by the model's `pdf`).
    pub pdf: f32,
    /// The BRDF value at `wo` (without the cosine).
    pub value: f32,
    /// `value · cosθo / pdf`.
    pub weight: f32,
    /// Which lobe produced it (model specific; GHS: 0 micro-facet, 1 diffraction, 2 diffuse).
    pub lobe: u32,
}
