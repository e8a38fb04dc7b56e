//! One record in, one record out: the scratch models' sampling lobes
//! (`scratchwave_kernel::bsdf::lobe1d::Lobe1`, `bsdf::lobes::DiskLobe`, Werner §5's
//! von Mises–Fisher ring), so that their domain sweeps (issue #20) run on SPIR-V too. The
//! [`lobe_probe`](fn@crate::lobe_probe) entry point and the CPU reference run this same [`evaluate`].

use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::lobe1d::{LOBE1_MAX, Lobe1, Lobe1Kind};
use scratchwave_kernel::bsdf::lobes::{DiskLobe, vmf_ring_pdf, vmf_ring_sample};
use scratchwave_kernel::glam;

/// A [`Lobe1`] as plain data. GPU-visible: 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LobeRecord {
    /// A [`Lobe1Kind`] as `u32`.
    pub kind: u32,
    /// Number of components.
    pub count: u32,
    /// Centres μ, then a padding lane.
    pub mu: [f32; 4],
    /// Scales s, then a padding lane.
    pub scale: [f32; 4],
    /// Weights, then a padding lane.
    pub weight: [f32; 4],
    /// Explicit padding.
    pub pad: [u32; 2],
}

const _: () = assert!(core::mem::size_of::<LobeRecord>() == 64);

impl LobeRecord {
    /// The record of `l`.
    pub fn new(l: &Lobe1) -> LobeRecord {
        let mut r = LobeRecord {
            kind: l.kind as u32,
            count: l.count,
            ..LobeRecord::default()
        };
        let mut j = 0;
        while j < LOBE1_MAX {
            r.mu[j] = l.mu[j];
            r.scale[j] = l.scale[j];
            r.weight[j] = l.weight[j];
            j += 1;
        }
        r
    }

    /// The lobe it holds.
    pub fn lobe(&self) -> Lobe1 {
        Lobe1 {
            kind: Lobe1Kind::from_u32(self.kind),
            count: self.count,
            mu: [self.mu[0], self.mu[1], self.mu[2]],
            scale: [self.scale[0], self.scale[1], self.scale[2]],
            weight: [self.weight[0], self.weight[1], self.weight[2]],
        }
    }
}

scratchwave_kernel::gpu_enum! {
    /// What [`evaluate`] computes ([`LobeQuery::function`]).
    pub enum LobeFunction {
        /// `l1.mass(a, b)`, `args = [a, b, _, _]`.
        Lobe1Mass = 0,
        /// `l1.pdf(x, a, b)`, `args = [a, b, x, _]`.
        Lobe1Pdf = 1,
        /// `l1.sample(u, a, b)`, `args = [a, b, _, u]`.
        Lobe1Sample = 2,
        /// `DiskLobe { e1, l1, l2 }.pdf(wo, wi)`, `args = [e1.x, e1.y, _, _]`.
        DiskPdf = 3,
        /// `DiskLobe { e1, l1, l2 }.sample(wo, u)`, `args = [e1.x, e1.y, u.x, u.y]`.
        DiskSample = 4,
        /// `vmf_ring_pdf(t, κ, wo, wi)`, `args = [t.x, t.y, κ, _]`.
        VmfPdf = 5,
        /// `vmf_ring_sample(t, κ, wo, u_ring, u)`, `args = [t.x, t.y, κ, u_ring]`, `u = wi.xy`.
        VmfSample = 6,
    }
    fallback = Lobe1Mass;
}

/// One lobe query. GPU-visible: 192 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LobeQuery {
    /// A [`LobeFunction`] as `u32`.
    pub function: u32,
    /// Explicit padding.
    pub pad: [u32; 3],
    /// The one-dimensional lobe, or the disk lobe's first axis lobe.
    pub l1: LobeRecord,
    /// The disk lobe's second axis lobe.
    pub l2: LobeRecord,
    /// The arguments (see [`LobeFunction`]).
    pub args: [f32; 4],
    /// `wo` (`xyz`).
    pub wo: [f32; 4],
    /// `wi` (`xyz`), or the vMF sample's `u` (`xy`).
    pub wi: [f32; 4],
}

const _: () = assert!(core::mem::size_of::<LobeQuery>() == 192);

impl LobeQuery {
    /// A query of `function` with everything else zero.
    pub fn new(function: LobeFunction) -> LobeQuery {
        LobeQuery {
            function: function as u32,
            ..LobeQuery::default()
        }
    }
}

/// `[value, 0, 0, 1]` for a mass or density, `[x, 0, 0, 1]` for a `Lobe1` sample,
/// `[wi.x, wi.y, wi.z, 1]` for a direction; the last lane 0 when a sampler returned `None`.
pub fn evaluate(q: &LobeQuery) -> [f32; 4] {
    let [a0, a1, a2, a3] = q.args;
    let wo = Vec3::new(q.wo[0], q.wo[1], q.wo[2]);
    let wi = Vec3::new(q.wi[0], q.wi[1], q.wi[2]);
    let disk = DiskLobe {
        e1: Vec2::new(a0, a1),
        l1: q.l1.lobe(),
        l2: q.l2.lobe(),
    };
    match LobeFunction::from_u32(q.function) {
        LobeFunction::Lobe1Mass => value(disk.l1.mass(a0, a1)),
        LobeFunction::Lobe1Pdf => value(disk.l1.pdf(a2, a0, a1)),
        LobeFunction::Lobe1Sample => match disk.l1.sample(a3, a0, a1) {
            Some(x) => value(x),
            None => [0.0; 4],
        },
        LobeFunction::DiskPdf => value(disk.pdf(wo, wi)),
        LobeFunction::DiskSample => encode_direction(disk.sample(wo, Vec2::new(a2, a3))),
        LobeFunction::VmfPdf => value(vmf_ring_pdf(Vec2::new(a0, a1), a2, wo, wi)),
        LobeFunction::VmfSample => encode_direction(vmf_ring_sample(
            Vec2::new(a0, a1),
            a2,
            wo,
            a3,
            Vec2::new(wi.x, wi.y),
        )),
    }
}

/// A scalar result.
#[inline]
fn value(v: f32) -> [f32; 4] {
    [v, 0.0, 0.0, 1.0]
}

/// A sampled direction as a result record: `[x, y, z, 1]`, or zeros for `None`
/// ([`decode_direction`] reads it back).
#[inline]
fn encode_direction(d: Option<Vec3>) -> [f32; 4] {
    match d {
        Some(d) => [d.x, d.y, d.z, 1.0],
        None => [0.0; 4],
    }
}

/// The sampled direction of a result record written by the sampling functions (`None`
/// when its last lane is 0).
#[inline]
pub fn decode_direction(r: [f32; 4]) -> Option<Vec3> {
    if r[3] != 0.0 {
        Some(Vec3::new(r[0], r[1], r[2]))
    } else {
        None
    }
}
