//! Monte Carlo estimate of `∫_light f_r cos θi dωi`: what a renderer without the closed
//! form would do (light sampling, N samples), for the speed-vs-accuracy chart.
//!
//! Spheres: directions uniform in the cone (pdf `1/(2π(1 − cos α))`). Polygons: points
//! uniform on the planar polygon (fan about the vertex mean, triangles chosen by area;
//! pdf in solid angle `d²/(A |cos θ_l|)`, so each sample weighs `f_r cos θi A |cos θ_l| / d²`). Samples below the horizon contribute 0.

use crate::light_configs::Rng;
use scratchwave_kernel::lights::{Cone, LIGHT_POLYGON, LightParams, LightQuery};
use scratchwave_kernel::scratch::Scratch;

use crate::light_reference::scratch_brdf;
use crate::vec64::{V3, basis, cross, dot, norm, sub};

/// `N`-sample light-sampling estimate (0 for degenerate lights).
pub fn light_mc(
    params: &LightParams,
    q: &LightQuery,
    scratch: &Scratch,
    n: usize,
    rng: &mut Rng,
) -> f64 {
    let brdf = scratch_brdf(params, q, scratch);
    let f = |wi: V3| -> f64 {
        if wi[2] <= 0.0 {
            return 0.0;
        }
        brdf(wi) * wi[2]
    };
    let l = &q.light;
    let mut sum = 0.0;
    if l.kind == LIGHT_POLYGON {
        let k = (l.count as usize).min(l.vertices.len());
        if k < 3 {
            return 0.0;
        }
        let v: Vec<V3> = l.vertices[..k]
            .iter()
            .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64])
            .collect();
        let c = v.iter().fold([0.0; 3], |a, p| {
            [
                a[0] + p[0] / k as f64,
                a[1] + p[1] / k as f64,
                a[2] + p[2] / k as f64,
            ]
        });
        let tris: Vec<(V3, V3, f64)> = (0..k)
            .map(|m| {
                let (a, b) = (v[m], v[(m + 1) % k]);
                let n = cross(sub(a, c), sub(b, c));
                (a, b, 0.5 * dot(n, n).sqrt())
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
            let p = [
                c[0] + x * (a[0] - c[0]) + y * (b[0] - c[0]),
                c[1] + x * (a[1] - c[1]) + y * (b[1] - c[1]),
                c[2] + x * (a[2] - c[2]) + y * (b[2] - c[2]),
            ];
            let d2 = dot(p, p);
            let wi = norm(p);
            let nrm = norm(cross(sub(a, c), sub(b, c)));
            let cos_l = dot(nrm, wi).abs();
            if d2 > 0.0 {
                sum += f(wi) * cos_l / d2;
            }
        }
        sum * area / n as f64
    } else {
        let cen = [l.sphere[0] as f64, l.sphere[1] as f64, l.sphere[2] as f64];
        let r = l.sphere[3] as f64;
        let d = dot(cen, cen).sqrt();
        if !(r > 0.0 && d > 0.0) {
            return 0.0;
        }
        let alpha = match Cone::from_u32(l.cone) {
            Cone::Asin if d <= r => std::f64::consts::PI,
            Cone::Asin => (r / d).asin(),
            Cone::Atan => r.atan2(d),
        };
        let axis = norm(cen);
        let (e1, e2) = basis(axis);
        let cos_a = alpha.cos();
        let solid = std::f64::consts::TAU * (1.0 - cos_a);
        for _ in 0..n {
            let ct = 1.0 - rng.next_f64() * (1.0 - cos_a);
            let st = (1.0 - ct * ct).max(0.0).sqrt();
            let ph = std::f64::consts::TAU * rng.next_f64();
            let (sp, cp) = ph.sin_cos();
            let wi = [
                ct * axis[0] + st * (cp * e1[0] + sp * e2[0]),
                ct * axis[1] + st * (cp * e1[1] + sp * e2[1]),
                ct * axis[2] + st * (cp * e1[2] + sp * e2[2]),
            ];
            sum += f(wi);
        }
        sum * solid / n as f64
    }
}
