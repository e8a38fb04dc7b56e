//! The safe batch core: a material with its scratch lookup, and `eval`, `pdf` and `sample`
//! over flat arrays of queries (`docs/bindings.md`). Each query is one call of the kernel's
//! `bsdf::eval`, `bsdf::pdf` or `bsdf::sample` (`docs/bsdf.md`), so a batch is bit-identical
//! to those calls in any order and on any number of threads.

use crate::error::Error;
use rayon::prelude::*;
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::bsdf::{self, BsdfMaterial, Lookup, ShadingPoint, Wavelengths};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::glam::{Vec2, Vec3};
use scratchwave_kernel::render::shading::SceneModel;
use scratchwave_kernel::scratch::{MAX_SPECTRAL, Profile, Scratch};
use scratchwave_spec::{SpecError, json, material, scratches};
use std::path::Path;

/// Queries per parallel work item.
const CHUNK: usize = 1024;

/// One work item of [`Bsdf::sample`]: its first query and its rows of `wi`, weight and pdf.
type SampleRows<'a> = (usize, &'a mut [f32], &'a mut [f32], &'a mut [f32]);

/// A set of scratch segments in scratch space (µm).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScratchSet {
    scratches: Vec<Scratch>,
}

impl ScratchSet {
    /// A JSON array of scratch sources, as a scene material's `"scratches"`: inline
    /// `{"p0", "p1", "width", "depth", "profile"}` scratches, `{"file"}` (JSON or CSV,
    /// relative to `base_dir`, default the working directory) and `{"generate"}` patterns
    /// (`docs/scratches.md`).
    pub fn from_json(text: &str, base_dir: Option<&Path>) -> Result<ScratchSet, Error> {
        let v = json::parse(text, "scratches")?;
        let dir = base_dir.unwrap_or(Path::new("."));
        Ok(ScratchSet {
            scratches: scratches::scratch_sources(&v, "scratches", dir)?,
        })
    }

    /// Rows `[x0, y0, x1, y1, width, depth]` (µm) with one profile each (`triangle[i]`:
    /// triangular, else rectangular). Errors name the row and column (`segments[3].width`).
    pub fn from_rows(rows: &[[f64; 6]], triangle: &[bool]) -> Result<ScratchSet, Error> {
        if triangle.len() != rows.len() {
            return Err(Error::arg(format!(
                "triangle: expected {} values (one per row), got {}",
                rows.len(),
                triangle.len()
            )));
        }
        let scratches = rows
            .iter()
            .zip(triangle)
            .enumerate()
            .map(|(i, (r, t))| {
                let profile = if *t { Profile::Triangle } else { Profile::Rect };
                scratches::scratch_from_row(*r, profile, &format!("segments[{i}]."))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ScratchSet { scratches })
    }

    /// The segments.
    pub fn scratches(&self) -> &[Scratch] {
        &self.scratches
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.scratches.len()
    }

    /// No segments.
    pub fn is_empty(&self) -> bool {
        self.scratches.is_empty()
    }
}

/// A material ready to shade: the kernel's [`BsdfMaterial`] and the lookup over its
/// scratches.
#[derive(Clone, Debug)]
pub struct Bsdf {
    material: BsdfMaterial,
    lookup: ScratchLookup,
}

/// One batch of queries as flat arrays (the layout of the C `SwQueries`). Directions are in
/// the local shading frame (`z` the normal, `x` the tangent, the first axis of scratch
/// space), both pointing away from the surface: `wo` towards the viewer, `wi` towards the
/// light. Their count `n = wo.len() / 3` is the batch size.
#[derive(Clone, Copy, Debug, Default)]
pub struct Queries<'a> {
    /// `3n` values.
    pub wo: &'a [f32],
    /// `3n` values; `eval` and `pdf` need it, `sample` ignores it.
    pub wi: Option<&'a [f32]>,
    /// `2n` scratch-space positions (µm); `None`: the origin.
    pub x_um: Option<&'a [f32]>,
    /// `3n` pixel footprints `(a1, a2, angle)`: semi-axes (µm) and the angle of `a1` against
    /// the tangent (radians); `None`: no footprint. Only the Velinov model averages over it.
    /// Semi-axes in `[1e-6, 1e9]` µm, the angle finite (checked, as by the spec reader).
    pub footprint: Option<&'a [f32]>,
    /// Wavelengths (nm): `lambda_count` values shared by every query, or `lambda_count` per
    /// query; `None`: 700, 520, 440 nm (Werner §5's RGB).
    pub lambda_nm: Option<&'a [f32]>,
    /// Wavelengths per query, 1 to 4 (ignored when `lambda_nm` is `None`).
    pub lambda_count: usize,
}

impl Queries<'_> {
    /// Number of queries.
    pub fn len(&self) -> usize {
        self.wo.len() / 3
    }

    /// No queries.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Wavelengths per query.
    pub fn wavelengths_per_query(&self) -> usize {
        match self.lambda_nm {
            None => 3,
            Some(_) => self.lambda_count,
        }
    }

    /// Checks every array's length; names the first one that is wrong.
    fn check(&self, need_wi: bool) -> Result<(), Error> {
        let n = self.len();
        let len = |name: &str, got: usize, per: usize| {
            if got == per * n {
                Ok(())
            } else {
                Err(Error::arg(format!(
                    "{name}: expected {per} values per query ({} for {n} queries), got {got}",
                    per * n
                )))
            }
        };
        if !self.wo.len().is_multiple_of(3) {
            return Err(Error::arg(format!(
                "wo: expected 3 values per query, got {} in all",
                self.wo.len()
            )));
        }
        match (self.wi, need_wi) {
            (Some(wi), _) if need_wi => len("wi", wi.len(), 3)?,
            (None, true) => return Err(Error::arg("wi: required by eval and pdf")),
            _ => {}
        }
        if let Some(x) = self.x_um {
            len("x_um", x.len(), 2)?;
        }
        if let Some(f) = self.footprint {
            len("footprint", f.len(), 3)?;
            check_footprints(f)?;
        }
        if let Some(l) = self.lambda_nm {
            let k = self.lambda_count;
            if !(1..=MAX_SPECTRAL).contains(&k) {
                return Err(Error::arg(format!(
                    "lambda_count: expected 1 to {MAX_SPECTRAL}, got {k}"
                )));
            }
            if l.len() != k && l.len() != k * n {
                return Err(Error::arg(format!(
                    "lambda_nm: expected {k} values (shared) or {} ({k} per query), got {}",
                    k * n,
                    l.len()
                )));
            }
            let lambda = scratchwave_spec::range::LAMBDA_NM;
            if let Some(bad) = l.iter().position(|x| !lambda.contains_f32(*x)) {
                return Err(Error::arg(format!(
                    "lambda_nm[{bad}]: must be in {}, got {}",
                    lambda.text, l[bad]
                )));
            }
        }
        Ok(())
    }

    fn vec3(a: &[f32], i: usize) -> Vec3 {
        Vec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2])
    }

    fn wo(&self, i: usize) -> Vec3 {
        Self::vec3(self.wo, i)
    }

    fn wi(&self, i: usize) -> Vec3 {
        self.wi.map_or(Vec3::ZERO, |a| Self::vec3(a, i))
    }

    fn point(&self, i: usize) -> ShadingPoint {
        let x = self.x_um.map_or([0.0; 2], |a| [a[2 * i], a[2 * i + 1]]);
        match self.footprint {
            Some(f) => ShadingPoint::with_footprint(
                x,
                Ellipse {
                    center: x,
                    angle_rad: f[3 * i + 2],
                    a1: f[3 * i],
                    a2: f[3 * i + 1],
                    pad: [0.0; 3],
                },
            ),
            None => ShadingPoint::at(x),
        }
    }

    fn wavelengths(&self, i: usize) -> Wavelengths {
        let Some(l) = self.lambda_nm else {
            return Wavelengths::rgb();
        };
        let k = self.lambda_count;
        let first = if l.len() == k { 0 } else { i * k };
        let mut w = Wavelengths::single(l[first]);
        for j in 0..k {
            w.nm[j] = l[first + j];
            w.pdf[j] = 1.0;
        }
        w.count = k as u32;
        w
    }
}

/// Checks each footprint `(a1, a2, angle)` as the footprint spec reader does: semi-axes in
/// [`range::ELLIPSE_AXIS_UM`](scratchwave_spec::range::ELLIPSE_AXIS_UM), a finite angle.
/// Names the first bad value by its index in the flat array, its query and its column.
fn check_footprints(f: &[f32]) -> Result<(), Error> {
    let axis = scratchwave_spec::range::ELLIPSE_AXIS_UM;
    for (k, &v) in f.iter().enumerate() {
        let (query, column) = (k / 3, ["a1", "a2", "angle"][k % 3]);
        let why = if k % 3 == 2 {
            (!v.is_finite()).then(|| "must be finite".to_string())
        } else {
            (!axis.contains_f32(v)).then(|| format!("must be in {}", axis.text))
        };
        if let Some(why) = why {
            return Err(Error::arg(format!(
                "footprint[{k}] (query {query}, {column}): {why}, got {v}"
            )));
        }
    }
    Ok(())
}

/// Runs `f(first_query, chunk_of_out_rows)` over `out` in parallel chunks of [`CHUNK`]
/// queries, `per` outputs per query.
fn par_rows(out: &mut [f32], per: usize, f: impl Fn(usize, &mut [f32]) + Sync) {
    out.par_chunks_mut(CHUNK * per.max(1))
        .enumerate()
        .for_each(|(c, rows)| f(c * CHUNK, rows));
}

fn check_out(name: &str, got: usize, want: usize) -> Result<(), Error> {
    if got == want {
        Ok(())
    } else {
        Err(Error::arg(format!(
            "{name}: expected {want} values, got {got}"
        )))
    }
}

impl Bsdf {
    /// A material as the scene file writes it (`docs/render.md`, "materials"): `{"model":
    /// "werner" | "werner_blended" | "velinov" | "ghs", "sigma_um", "material", "options",
    /// "scratches", "base"}`. Scratch files are resolved against `base_dir` (default: the
    /// working directory). `scratches`, when given, are the material's scratches; the JSON
    /// must then have none of its own.
    pub fn from_json(
        text: &str,
        base_dir: Option<&Path>,
        scratches: Option<&ScratchSet>,
    ) -> Result<Bsdf, Error> {
        let v = json::parse(text, "material")?;
        let dir = base_dir.unwrap_or(Path::new("."));
        let mut spec = material::scene_material(&v, "material", dir, usize::MAX)?;
        if SceneModel::from_u32(spec.shade.model) == SceneModel::Auto {
            return Err(Error::Input(SpecError::field(
                "material.model",
                "\"auto\" chooses per hit and light inside the renderer; a BSDF evaluated \
                 at single directions takes \"werner\", \"werner_blended\", \"velinov\" or \"ghs\"",
            )));
        }
        if let Some(s) = scratches {
            if v.get("scratches").is_some() {
                return Err(Error::arg(
                    "scratches: given both in the material JSON and as a scratch set",
                ));
            }
            spec.scratches = s.scratches.clone();
        }
        Ok(Bsdf::new(
            BsdfMaterial::from_shade(&spec.shade),
            &spec.scratches,
        ))
    }

    /// A kernel material record with these scratches (µm).
    pub fn new(material: BsdfMaterial, scratches: &[Scratch]) -> Bsdf {
        Bsdf {
            lookup: ScratchLookup::new(scratches, material.sigma_um),
            material,
        }
    }

    /// The kernel record.
    pub fn material(&self) -> &BsdfMaterial {
        &self.material
    }

    /// Number of scratch segments.
    pub fn scratch_count(&self) -> usize {
        self.lookup.scratches().len()
    }

    /// The BRDF (1/sr, without the cosine) of every query: `out` holds
    /// `wavelengths_per_query()` values per query, query-major.
    pub fn eval(&self, q: &Queries<'_>, out: &mut [f32]) -> Result<(), Error> {
        q.check(true)?;
        let k = q.wavelengths_per_query();
        check_out("out", out.len(), q.len() * k)?;
        let set = self.lookup.set();
        let lk = Lookup::new(&set);
        par_rows(out, k, |first, rows| {
            for (r, row) in rows.chunks_mut(k).enumerate() {
                let i = first + r;
                let wl = q.wavelengths(i);
                let f = bsdf::eval(&self.material, &q.point(i), q.wi(i), q.wo(i), &wl, &lk);
                row.copy_from_slice(&f.v[..k]);
            }
        });
        Ok(())
    }

    /// The solid-angle pdf with which [`Bsdf::sample`] draws `wi` given `wo`: one value per
    /// query.
    pub fn pdf(&self, q: &Queries<'_>, out: &mut [f32]) -> Result<(), Error> {
        q.check(true)?;
        check_out("out", out.len(), q.len())?;
        let set = self.lookup.set();
        let lk = Lookup::new(&set);
        par_rows(out, 1, |first, rows| {
            for (r, v) in rows.iter_mut().enumerate() {
                let i = first + r;
                let wl = q.wavelengths(i);
                *v = bsdf::pdf(&self.material, &q.point(i), q.wo(i), q.wi(i), &wl, &lk);
            }
        });
        Ok(())
    }

    /// Draws `wi` given `wo` for every query from three uniform numbers per query (`u`:
    /// the component choice, then the warp's two). Writes `wi` (3 per query), the weight
    /// `f·cosθi/pdf` (`wavelengths_per_query()` per query) and the pdf (1 per query); where
    /// nothing can be drawn (below the horizon, no component) all three are 0.
    pub fn sample(
        &self,
        q: &Queries<'_>,
        u: &[f32],
        wi_out: &mut [f32],
        weight_out: &mut [f32],
        pdf_out: &mut [f32],
    ) -> Result<(), Error> {
        q.check(false)?;
        let n = q.len();
        let k = q.wavelengths_per_query();
        check_out("u", u.len(), 3 * n)?;
        check_out("wi_out", wi_out.len(), 3 * n)?;
        check_out("weight_out", weight_out.len(), k * n)?;
        check_out("pdf_out", pdf_out.len(), n)?;
        let set = self.lookup.set();
        let lk = Lookup::new(&set);
        let rows: Vec<SampleRows<'_>> = wi_out
            .chunks_mut(3 * CHUNK)
            .zip(weight_out.chunks_mut(k * CHUNK))
            .zip(pdf_out.chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, ((a, b), p))| (c * CHUNK, a, b, p))
            .collect();
        rows.into_par_iter().for_each(|(first, wi, weight, pdf)| {
            for (r, p) in pdf.iter_mut().enumerate() {
                let i = first + r;
                let wl = q.wavelengths(i);
                let uu = &u[3 * i..3 * i + 3];
                let s = bsdf::sample(
                    &self.material,
                    &q.point(i),
                    q.wo(i),
                    &wl,
                    uu[0],
                    Vec2::new(uu[1], uu[2]),
                    &lk,
                );
                let (d, w, pd) = match s {
                    Some(s) => (s.wi.to_array(), s.weight.v, s.pdf),
                    None => ([0.0; 3], [0.0; MAX_SPECTRAL], 0.0),
                };
                wi[3 * r..3 * r + 3].copy_from_slice(&d);
                weight[k * r..k * r + k].copy_from_slice(&w[..k]);
                *p = pd;
            }
        });
        Ok(())
    }
}
