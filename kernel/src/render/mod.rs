//! Rendering formulas: everything a renderer computes per pixel and per hit, defined once
//! here so the CPU renderer (`scratchwave-render`) and a SPIR-V renderer call the same
//! functions on the same flat `Pod` records.
//!
//! | file | what |
//! |---|---|
//! | `camera` | orthographic/perspective primary rays and their ray differentials |
//! | `footprint` | the pixel footprint ellipse from ray differentials; Velinov averaged over it |
//! | `surface` | hit position, shading frame and scratch-space position of an object |
//! | `shading` | the BRDF of a scene material and the contribution of each light kind |
//! | `model_choice` | `"model": "auto"`: coherent or incoherent per hit and light, within a tolerance |
//! | `area` | deterministic quadrature nodes over sphere and triangle lights |
//! | `radiance` | the light loop of a hit and the value of a pixel (first shadow rays, probes' consensus, wavelength groups) |
//! | `spectrum` | wavelengths of a spectrum mode, CIE 1931 2° observer, XYZ → linear sRGB |
//! | `pixel` | deterministic sub-pixel positions (rank-1 lattice, hashed rotation per pixel) |

pub mod area;
pub mod camera;
pub mod footprint;
pub mod model_choice;
pub mod pixel;
pub mod radiance;
pub mod shading;
pub mod spectrum;
pub mod surface;
