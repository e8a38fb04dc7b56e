//! Shared helpers for the GHS sampling tests: a small RNG and a Mitsuba/pbrt-style χ² test
//! over (θ, φ) bins of the hemisphere.
#![allow(dead_code)]

use glam::Vec3;

/// PCG32 (O'Neill), enough for test sample streams.
pub struct Pcg(u64);

impl Pcg {
    pub fn new(seed: u64) -> Pcg {
        let mut p = Pcg(seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407));
        p.next_u32();
        p
    }
    pub fn next_u32(&mut self) -> u32 {
        let old = self.0;
        self.0 = old
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let xs = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xs.rotate_right(rot)
    }
    /// Uniform in [0, 1).
    pub fn f(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

/// Regularized upper incomplete gamma in f64 (series / Lentz continued fraction).
pub fn gamma_q64(a: f64, x: f64) -> f64 {
    fn lgamma(x: f64) -> f64 {
        // Lanczos g = 7
        const C: [f64; 9] = [
            0.999_999_999_999_809_9,
            676.5203681218851,
            -1259.1392167224028,
            771.323_428_777_653_1,
            -176.615_029_162_140_6,
            12.507343278686905,
            -0.13857109526572012,
            9.984_369_578_019_572e-6,
            1.5056327351493116e-7,
        ];
        let x = x - 1.0;
        let mut s = C[0];
        for (i, c) in C.iter().enumerate().skip(1) {
            s += c / (x + i as f64);
        }
        let t = x + 7.5;
        0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + s.ln()
    }
    if x <= 0.0 {
        return 1.0;
    }
    let pre = (a * x.ln() - x - lgamma(a)).exp();
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del < sum * 1e-15 {
                break;
            }
        }
        1.0 - pre * sum
    } else {
        let mut b = x + 1.0 - a;
        let mut c = 1e300;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < 1e-300 {
                d = 1e-300;
            }
            c = b + an / c;
            if c.abs() < 1e-300 {
                c = 1e-300;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        pre * h
    }
}

pub const NT: usize = 40;
pub const NP: usize = 80;
const SUB: usize = 6;

fn bin_of(w: Vec3) -> Option<usize> {
    if !(w.z > 0.0) {
        return None;
    }
    let th = w.z.min(1.0).acos();
    let mut ph = w.y.atan2(w.x);
    if ph < 0.0 {
        ph += std::f32::consts::TAU;
    }
    let i = ((th / std::f32::consts::FRAC_PI_2) * NT as f32) as usize;
    let j = ((ph / std::f32::consts::TAU) * NP as f32) as usize;
    Some(i.min(NT - 1) * NP + j.min(NP - 1))
}

/// Expected bin probabilities from a solid-angle pdf (midpoint rule on SUB×SUB sub-cells).
pub fn expected(pdf: &dyn Fn(Vec3) -> f64) -> Vec<f64> {
    let mut e = vec![0.0; NT * NP];
    let dth = std::f64::consts::FRAC_PI_2 / (NT * SUB) as f64;
    let dph = std::f64::consts::TAU / (NP * SUB) as f64;
    for it in 0..NT * SUB {
        let th = (it as f64 + 0.5) * dth;
        for ip in 0..NP * SUB {
            let ph = (ip as f64 + 0.5) * dph;
            let w = Vec3::new(
                (th.sin() * ph.cos()) as f32,
                (th.sin() * ph.sin()) as f32,
                th.cos() as f32,
            );
            e[(it / SUB) * NP + ip / SUB] += pdf(w) * th.sin() * dth * dph;
        }
    }
    e
}

/// χ² goodness-of-fit of `n` samples (None = rejected, its own bin) against the pdf.
/// Bins with expected count < 5 are pooled. Returns the p-value.
pub fn chi2(
    name: &str,
    n: usize,
    mut sampler: impl FnMut(&mut Pcg) -> Option<Vec3>,
    pdf: &dyn Fn(Vec3) -> f64,
) -> f64 {
    let mut obs = vec![0.0f64; NT * NP + 1];
    let mut rng = Pcg::new(0x5eed ^ n as u64 ^ name.len() as u64);
    for _ in 0..n {
        match sampler(&mut rng).and_then(bin_of) {
            Some(b) => obs[b] += 1.0,
            None => obs[NT * NP] += 1.0,
        }
    }
    let mut exp: Vec<f64> = expected(pdf).iter().map(|p| p * n as f64).collect();
    let total: f64 = exp.iter().sum();
    exp.push((n as f64 - total).max(0.0));
    // pool low bins
    let mut idx: Vec<usize> = (0..exp.len()).collect();
    idx.sort_by(|&a, &b| exp[a].partial_cmp(&exp[b]).unwrap());
    let (mut pool_e, mut pool_o) = (0.0, 0.0);
    let mut stat = 0.0;
    let mut dof = 0usize;
    for &i in &idx {
        if exp[i] < 5.0 {
            pool_e += exp[i];
            pool_o += obs[i];
            if obs[i] > 0.0 && exp[i] == 0.0 {
                // samples where the pdf says none can land
                println!(
                    "{name}: bin {i} has {} samples with zero expectation",
                    obs[i]
                );
            }
        } else {
            stat += (obs[i] - exp[i]).powi(2) / exp[i];
            dof += 1;
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    let dof = dof.saturating_sub(1).max(1);
    let pval = gamma_q64(dof as f64 / 2.0, stat / 2.0);
    println!(
        "{name}: χ² = {stat:.1}, dof = {dof}, p = {pval:.4}, integral of pdf = {total_frac:.5}",
        total_frac = total / n as f64
    );
    pval
}

/// Šidák-corrected per-test significance for `m` tests at family level 1 %.
pub fn sidak(m: usize) -> f64 {
    1.0 - (1.0f64 - 0.01).powf(1.0 / m as f64)
}
