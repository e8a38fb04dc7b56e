//! Werner et al. 2017, "Scratch iridescence": the coherent wave-optical SVBRDF of
//! line-segment scratches, and the pieces Velinov et al. 2018 reuse.
//!
//! | file | what |
//! |---|---|
//! | `record` | the `Pod` scratch record and its frame (tangent, bitangent, centre) |
//! | `profile` | mask and groove-profile Fourier transforms (Werner Eqs. 14, 26–31) |
//! | `spatial_phase` | η, finite (App. A) and infinite (Velinov Eq. 8) |
//! | `set` | "every scratch near x0": brute force or the flattened BVH |
//! | `response` | base response B (Eq. 16), scratch response S (Eq. 17), ρc |
//! | `window` | the coherence window across a groove: frozen (Werner) or exact (#21) |
//! | `crossing` | crossings cut once by the deeper groove (#21): the pair correction |
//! | `coherent_sum` | `S = Σ S_k` summed exactly on a grid, so `B − S` survives cancellation |

pub mod coherent_sum;
pub mod crossing;
pub mod grid;
pub mod profile;
pub mod record;
pub mod response;
pub mod set;
pub mod spatial_phase;
pub mod window;

pub use coherent_sum::CoherentSum;
pub use crossing::Crossings;
pub use grid::{GridHeader, ScratchGrid};
pub use profile::{DepthTerm, Profile};
pub use record::{Scratch, SegmentFrame};
#[cfg(not(target_arch = "spirv"))]
pub use response::{LaneUse, scratch_response_batch};
pub use response::{
    MAX_SPECTRAL, ResponseInputs, ScratchTerms, SpectralInputs, base_response, base_response_lanes,
    scratch_area_density, scratch_response_spectral, scratch_term, scratch_term_lanes,
};
pub use set::{NearCursor, ScratchBvh, ScratchSet, ScratchSlice};
pub use spatial_phase::{EtaMode, eta_finite, eta_infinite};
pub use window::Window;
