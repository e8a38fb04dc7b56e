//! Monte Carlo estimate of `∫_light f_r cos θi dωi`: what a renderer without the closed
//! form would do (light sampling, N samples), for the speed-vs-accuracy chart.
//!
//! Spheres: directions uniform in the cone (pdf `1/(2π(1 − cos α))`). Polygons: points
//! uniform on the planar polygon (fan about the vertex mean, triangles chosen by area;
//! pdf in solid angle `d²/(A |cos θ_l|)`, so each sample weighs `f_r cos θi A |cos θ_l| / d²`). Samples below the horizon contribute 0.

use scratchwave_host::rng::SplitMix64 as Rng;
use scratchwave_kernel::lights::{Cone, LightKind, LightParams, LightQuery};
use scratchwave_kernel::scratch::Scratch;

use crate::dvec::{basis, unit};
use crate::light_reference::scratch_brdf;
use glam::DVec3;

/// `N`-sample light-sampling estimate (0 for degenerate lights).
pub fn light_mc(
    params: &LightParams,
    q: &LightQuery,
    scratch: &Scratch,
    n: usize,
    rng: &mut Rng,
) -> f64 {
    let brdf = scratch_brdf(params, q, scratch);
    let f = |wi: DVec3| -> f64 {
        if wi[2] <= 0.0 {
            return 0.0;
        }
        brdf(wi) * wi[2]
    };
    let l = &q.light;
    let mut sum = 0.0;
    if LightKind::from_u32(l.kind) == LightKind::Polygon {
        let k = (l.count as usize).min(l.vertices.len());
        if k < 3 {
            return 0.0;
        }
        let v: Vec<DVec3> = l.vertices[..k]
            .iter()
            .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
            .collect();
        let c = v.iter().fold(DVec3::ZERO, |a, p| a + *p / k as f64);
        let tris: Vec<(DVec3, DVec3, f64)> = (0..k)
            .map(|m| {
                let (a, b) = (v[m], v[(m + 1) % k]);
                let n = (a - c).cross(b - c);
                (a, b, 0.5 * n.dot(n).sqrt())
            })
            .collect();
        let area: f64 = tris.iter().map(|t| t.2).sum();
        if !(area > 0.0) {
            return 0.0;
        }
        for _ in 0..n {
            let mut pick = rng.next_f64() * area;
            let mut tri = tris[k - 1];
            for t in &tris {
                if pick < t.2 {
                    tri = *t;
                    break;
                }
                pick -= t.2;
            }
            let (a, b, ta) = tri;
            if !(ta > 0.0) {
                continue;
            }
            let (mut x, mut y) = (rng.next_f64(), rng.next_f64());
            if x + y > 1.0 {
                (x, y) = (1.0 - x, 1.0 - y);
            }
            let p = c + x * (a - c) + y * (b - c);
            let d2 = p.dot(p);
            let wi = unit(p);
            let nrm = unit((a - c).cross(b - c));
            let cos_l = nrm.dot(wi).abs();
            if d2 > 0.0 {
                sum += f(wi) * cos_l / d2;
            }
        }
        sum * area / n as f64
    } else {
        let cen = DVec3::new(l.sphere[0] as f64, l.sphere[1] as f64, l.sphere[2] as f64);
        let r = l.sphere[3] as f64;
        let d = cen.dot(cen).sqrt();
        if !(r > 0.0 && d > 0.0) {
            return 0.0;
        }
        let alpha = match Cone::from_u32(l.cone) {
            Cone::Asin if d <= r => std::f64::consts::PI,
            Cone::Asin => (r / d).asin(),
            Cone::Atan => r.atan2(d),
        };
        let axis = unit(cen);
        let (e1, e2) = basis(axis);
        let cos_a = alpha.cos();
        let solid = std::f64::consts::TAU * (1.0 - cos_a);
        for _ in 0..n {
            let ct = 1.0 - rng.next_f64() * (1.0 - cos_a);
            let st = (1.0 - ct * ct).max(0.0).sqrt();
            let ph = std::f64::consts::TAU * rng.next_f64();
            let (sp, cp) = ph.sin_cos();
            let wi = ct * axis + st * (cp * e1 + sp * e2);
            sum += f(wi);
        }
        sum * solid / n as f64
    }
}
