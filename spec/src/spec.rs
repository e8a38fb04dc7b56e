//! Table and footprint specs (JSON) → kernel records. The formats are documented in the
//! README; every rejection names the field.

use crate::error::SpecError;
use crate::json::{self, Obj};
use crate::range;
use scratchwave_host::{FootprintBatch, TableBatch};
use scratchwave_kernel::conductor::Conductor;
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::layers::LayerForm;
use scratchwave_kernel::ghs::{self, DiffColor, GhsParams, Layer};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_kernel::table::{Model, TableParams, TableQuery};
use scratchwave_kernel::units::UNIT_TOLERANCE;
use serde_json::Value;

/// Default coherence σ (µm): δc = 6σ = 60 µm (Werner §4.1).
pub const DEFAULT_SIGMA_UM: f32 = 10.0;

/// Largest number of queries [`table_spec`] expands a `{"grid"}` into (2²², 320 MiB of
/// [`TableQuery`] records); larger grids are for [`table_stream`], which `scratchwave table`
/// uses.
pub const MAX_EXPANDED_QUERIES: u64 = 1 << 22;

/// Largest number of queries of a `{"grid"}` (2⁴⁰; streamed, so this bounds time, not memory).
pub const MAX_GRID_QUERIES: u64 = 1 << 40;

/// `"queries": {"grid": {"wi": [...], "wo": [...], "lambda_nm": [...], "x": [...]}}`: every
/// combination of the listed values, `wi` outermost, then `wo`, `lambda_nm`, and `x`
/// innermost (`x` optional for model `ghs`); each with the spec's material. Queries are made
/// on demand ([`QueryGrid::fill`]), so a grid of 10⁷ queries costs no memory until a chunk of
/// it is evaluated.
#[derive(Clone, Debug, PartialEq)]
pub struct QueryGrid {
    /// Incident directions (unit).
    pub wi: Vec<[f32; 3]>,
    /// Outgoing directions (unit).
    pub wo: Vec<[f32; 3]>,
    /// Wavelengths (nm).
    pub lambda_nm: Vec<f32>,
    /// Shading points (µm).
    pub x: Vec<[f32; 2]>,
    /// The material of every query.
    pub material: Material,
}

impl QueryGrid {
    /// Number of queries (the product of the list lengths; at most [`MAX_GRID_QUERIES`]).
    pub fn len(&self) -> u64 {
        [
            self.wi.len(),
            self.wo.len(),
            self.lambda_nm.len(),
            self.x.len(),
        ]
        .iter()
        .fold(1u64, |a, &n| a.saturating_mul(n as u64))
    }

    /// Whether the grid has no query (never, for a grid read by [`table_stream`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Query `i` (`i < len()`), in the order documented on [`QueryGrid`].
    pub fn query(&self, i: u64) -> TableQuery {
        let n = |v: usize| v as u64;
        let ix = (i % n(self.x.len())) as usize;
        let i = i / n(self.x.len());
        let il = (i % n(self.lambda_nm.len())) as usize;
        let i = i / n(self.lambda_nm.len());
        let io = (i % n(self.wo.len())) as usize;
        let ii = (i / n(self.wo.len())) as usize;
        TableQuery {
            wi: self.wi[ii],
            lambda_nm: self.lambda_nm[il],
            wo: self.wo[io],
            x: self.x[ix],
            material: self.material,
            ..TableQuery::default()
        }
    }

    /// Replaces `out` with queries `start..min(start + n, len())`.
    pub fn fill(&self, start: u64, n: usize, out: &mut Vec<TableQuery>) {
        out.clear();
        let end = self.len().min(start.saturating_add(n as u64));
        out.extend((start..end).map(|i| self.query(i)));
    }
}

/// A table spec as `scratchwave table` streams it: the batch (model, options, scratches,
/// materials) and its queries, listed in `batch.queries` or, for a `{"grid"}`, in `grid`
/// (then `batch.queries` is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct TableStream {
    /// Everything but a grid's queries.
    pub batch: TableBatch,
    /// The grid, if the spec gives one.
    pub grid: Option<QueryGrid>,
}

impl TableStream {
    /// Number of queries.
    pub fn len(&self) -> u64 {
        self.grid
            .as_ref()
            .map_or(self.batch.queries.len() as u64, QueryGrid::len)
    }

    /// Whether there is no query.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Reads a table spec from a JSON value, with every query in `queries` (a grid is expanded:
/// at most [`MAX_EXPANDED_QUERIES`], else an error naming `queries.grid` and the limit).
pub fn table_spec(v: &Value) -> Result<TableBatch, SpecError> {
    let TableStream { mut batch, grid } = table_stream(v)?;
    if let Some(g) = grid {
        let n = g.len();
        if n > MAX_EXPANDED_QUERIES {
            return Err(SpecError::field(
                "queries.grid",
                format!(
                    "{n} queries, more than the {MAX_EXPANDED_QUERIES} (MAX_EXPANDED_QUERIES) \
                     this reader expands; `scratchwave table` streams grids of any size"
                ),
            ));
        }
        g.fill(0, n as usize, &mut batch.queries);
    }
    Ok(batch)
}

/// Reads a table spec from a JSON value; a `{"grid"}` of queries stays a [`QueryGrid`].
pub fn table_stream(v: &Value) -> Result<TableStream, SpecError> {
    let top = Obj::new(
        v,
        "",
        &[
            "model",
            "material",
            "sigma_um",
            "scratches",
            "options",
            "queries",
        ],
    )?;
    let model_name = top.choice("model", &["werner", "werner_blended", "velinov", "ghs"])?;
    if model_name == "ghs" {
        return ghs_table_spec(&top);
    }
    let model = match model_name {
        "werner_blended" => Model::WernerBlended,
        "velinov" => Model::Velinov,
        _ => Model::Werner,
    };
    let material = match top.get("material") {
        Some(m) => material(m, "material")?,
        None => Material::constant(1.0),
    };
    let sigma_um = sigma(&top)?;
    let scratches = scratches(&top)?;
    let mut params = TableParams {
        model: model as u32,
        sigma_um,
        ..TableParams::default()
    };
    if let Some(o) = top.get("options") {
        options(o, &top.path_of("options"), model, &mut params)?;
    }
    let (queries, grid) = queries(&top, true, Some(material))?;
    Ok(TableStream {
        batch: TableBatch {
            params,
            scratches,
            queries,
            default_material: material,
            ghs: None,
        },
        grid,
    })
}

/// Model options `{"eta", "depth_term", "base", "window", "crossings"}` at `path` into
/// `params` (`eta` and `base` only for model `velinov`); an option left out keeps the value
/// `params` has.
/// `window`: `"frozen"` (Werner's coherence window at each groove's centre line, the
/// default) or `"exact"` (integrated across the groove; `kernel::scratch::window`).
/// `crossings`: `"summed"` (Werner Eq. 9: an overlap is cut by both grooves, the default)
/// or `"deepest"` (cut once by the deeper groove; `kernel::scratch::crossing`; for
/// `velinov` each groove's intensity from the part of the surface it cuts).
pub fn options(
    v: &Value,
    path: &str,
    model: Model,
    params: &mut TableParams,
) -> Result<(), SpecError> {
    let o = Obj::new(
        v,
        path,
        &["eta", "depth_term", "base", "window", "crossings"],
    )?;
    let velinov_only = |key: &str| -> Result<(), SpecError> {
        if o.get(key).is_some() && model != Model::Velinov {
            return Err(SpecError::field(
                o.path_of(key),
                "only meaningful for model \"velinov\"",
            ));
        }
        Ok(())
    };
    velinov_only("eta")?;
    velinov_only("base")?;
    // Each option overrides `params` only when given, so a caller's defaults stand.
    if let Some(c) = o.opt_choice("eta", &["finite", "infinite"])? {
        params.eta = u32::from(c == "infinite");
    }
    if let Some(c) = o.opt_choice("depth_term", &["small_angle", "exact"])? {
        params.depth_term = u32::from(c == "exact");
    }
    if let Some(c) = o.opt_choice("base", &["none", "gaussian"])? {
        params.base_gaussian = u32::from(c == "gaussian");
    }
    if let Some(c) = o.opt_choice("window", &["frozen", "exact"])? {
        params.window = u32::from(c == "exact");
    }
    if let Some(c) = o.opt_choice("crossings", &["summed", "deepest"])? {
        params.crossings = u32::from(c == "deepest");
    }
    Ok(())
}

/// The queries of a table: a list, or a `{"grid"}`; `x` is required when `need_x`, a
/// per-query material is allowed when `material` is the spec's default.
fn queries(
    top: &Obj,
    need_x: bool,
    material: Option<Material>,
) -> Result<(Vec<TableQuery>, Option<QueryGrid>), SpecError> {
    if top.get("queries").is_some_and(Value::is_object) {
        let g = grid(top, need_x, material)?;
        return Ok((Vec::new(), Some(g)));
    }
    Ok((query_list(top, need_x, material)?, None))
}

/// `queries.grid`: four lists (see [`QueryGrid`]), each entry checked like the field of a
/// listed query.
fn grid(top: &Obj, need_x: bool, material: Option<Material>) -> Result<QueryGrid, SpecError> {
    let q = Obj::new(top.req("queries")?, "queries", &["grid"])?;
    let g = Obj::new(
        q.req("grid")?,
        "queries.grid",
        &["wi", "wo", "lambda_nm", "x"],
    )?;
    let list = |key: &str| -> Result<&Vec<Value>, SpecError> {
        let a = g.arr(key)?;
        if a.is_empty() {
            return Err(SpecError::field(g.path_of(key), "must not be empty"));
        }
        Ok(a)
    };
    let dirs = |key: &str| -> Result<Vec<[f32; 3]>, SpecError> {
        list(key)?
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let one = serde_json::json!({ "d": d });
                let path = format!("{}[{i}]", g.path_of(key));
                direction(&Obj::new(&one, "", &["d"])?, "d").map_err(|e| rename(e, &path))
            })
            .collect()
    };
    let wi = dirs("wi")?;
    let wo = dirs("wo")?;
    let lambda_nm = list("lambda_nm")?
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let path = format!("{}[{i}]", g.path_of("lambda_nm"));
            range::LAMBDA_NM.check(json::number(l, &path)?, &path)
        })
        .collect::<Result<Vec<f32>, SpecError>>()?;
    let x = if need_x || g.get("x").is_some() {
        list("x")?
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let path = format!("{}[{i}]", g.path_of("x"));
                let p = json::numbers::<2>(p, &path)?;
                Ok([json::to_f32(p[0], &path)?, json::to_f32(p[1], &path)?])
            })
            .collect::<Result<Vec<[f32; 2]>, SpecError>>()?
    } else {
        vec![[0.0; 2]]
    };
    let grid = QueryGrid {
        wi,
        wo,
        lambda_nm,
        x,
        material: material.unwrap_or_default(),
    };
    let n = [
        grid.wi.len(),
        grid.wo.len(),
        grid.lambda_nm.len(),
        grid.x.len(),
    ]
    .iter()
    .map(|&n| n as f64)
    .product::<f64>();
    if n > MAX_GRID_QUERIES as f64 {
        return Err(SpecError::field(
            "queries.grid",
            format!("{n:e} queries, more than the limit of {MAX_GRID_QUERIES} (MAX_GRID_QUERIES)"),
        ));
    }
    Ok(grid)
}

/// A field error of a value read under a stand-in path, moved to `path`.
fn rename(e: SpecError, path: &str) -> SpecError {
    match e {
        SpecError::Field { msg, .. } => SpecError::field(path, msg),
        other => other,
    }
}

/// A listed `queries` array.
fn query_list(
    top: &Obj,
    need_x: bool,
    material: Option<Material>,
) -> Result<Vec<TableQuery>, SpecError> {
    let mut out = Vec::new();
    for (i, q) in top.arr("queries")?.iter().enumerate() {
        let path = format!("queries[{i}]");
        let q = Obj::new(q, &path, &["wi", "wo", "lambda_nm", "x", "material"])?;
        let wi = direction(&q, "wi")?;
        let wo = direction(&q, "wo")?;
        let lambda_nm = range::LAMBDA_NM.check(q.num("lambda_nm")?, &q.path_of("lambda_nm"))?;
        let x = if need_x || q.get("x").is_some() {
            point(&q, "x")?
        } else {
            [0.0; 2]
        };
        let m = match (q.get("material"), material) {
            (Some(m), Some(_)) => self::material(m, &q.path_of("material"))?,
            (Some(_), None) => {
                return Err(SpecError::field(
                    q.path_of("material"),
                    "per-query materials are not supported by model \"ghs\"",
                ));
            }
            (None, m) => m.unwrap_or_default(),
        };
        out.push(TableQuery {
            wi,
            lambda_nm,
            wo,
            x,
            material: m,
            ..TableQuery::default()
        });
    }
    Ok(out)
}

/// Model `ghs` (Holzschuch & Pacanowski): the material carries the surface statistics; there
/// are no scratches, σ or options.
fn ghs_table_spec(top: &Obj) -> Result<TableStream, SpecError> {
    for key in ["sigma_um", "options"] {
        if top.get(key).is_some() {
            return Err(SpecError::field(
                top.path_of(key),
                "not used by model \"ghs\"",
            ));
        }
    }
    if let Some(s) = top.get("scratches")
        && s.as_array().is_none_or(|a| !a.is_empty())
    {
        return Err(SpecError::field(
            top.path_of("scratches"),
            "model \"ghs\" takes no scratches",
        ));
    }
    let ghs = ghs_material(top.req("material")?, &top.path_of("material"))?;
    let (queries, grid) = queries(top, false, None)?;
    Ok(TableStream {
        batch: TableBatch {
            params: TableParams {
                model: GHS_MODEL_ID,
                ..TableParams::default()
            },
            scratches: Vec::new(),
            queries,
            default_material: Material::default(),
            ghs: Some(ghs),
        },
        grid,
    })
}

/// `TableParams::model` value recorded for GHS tables (the evaluation goes through
/// [`TableBatch::ghs`]; the id only keeps reports unambiguous).
pub const GHS_MODEL_ID: u32 = 3;

/// A GHS material: `{"sigma_s_um", "beta", "p", "b_um", "c", "ior": [n, k] | "gold" | …,
/// "diff_color"?, "layer"?}` with the ranges the kernel documents.
pub fn ghs_material(v: &Value, path: &str) -> Result<GhsParams, SpecError> {
    let m = Obj::new(
        v,
        path,
        &[
            "sigma_s_um",
            "beta",
            "p",
            "b_um",
            "c",
            "ior",
            "diff_color",
            "layer",
        ],
    )?;
    let range = |key: &str, lo: f64, hi: f64, lo_open: bool| -> Result<f32, SpecError> {
        let x = m.num(key)?;
        let ok = if lo_open { x > lo } else { x >= lo } && x <= hi;
        if ok {
            json::to_f32(x, &m.path_of(key))
        } else {
            let l = if lo_open { "(" } else { "[" };
            Err(SpecError::field(
                m.path_of(key),
                format!("must be in {l}{lo}, {hi}], got {x}"),
            ))
        }
    };
    let sigma_s_um = range("sigma_s_um", 0.0, 1.0e3, false)?;
    let beta = range("beta", 0.0, f64::from(ghs::limits::BETA_MAX), true)?;
    let p = range("p", 0.1, 4.0, false)?;
    let b_um = range("b_um", 0.0, 1.0e6, true)?;
    let c = range("c", 1.0, f64::from(ghs::limits::C_MAX), true)?;
    let (n, k, metal) = ior(&m)?;
    let mut params = GhsParams::new(sigma_s_um, beta, p, b_um, c, n, k);
    params.conductor = metal as u32;
    params.diff_color = match m.opt_choice("diff_color", &["Q/2", "Q", "F", "none"])? {
        Some("Q") => DiffColor::Q as u32,
        Some("F") => DiffColor::Fresnel as u32,
        Some("none") => DiffColor::None as u32,
        _ => DiffColor::HalfQ as u32,
    };
    if let Some(l) = m.get("layer") {
        let lp = m.path_of("layer");
        let l = Obj::new(l, &lp, &["type", "rho_d", "albedo", "form"])?;
        let (layer, key) = match l.choice("type", &["none", "plastic", "subsurface"])? {
            "plastic" => (Layer::Plastic, Some("rho_d")),
            "subsurface" => (Layer::Subsurface, Some("albedo")),
            _ => (Layer::None, None),
        };
        for other in ["rho_d", "albedo", "form"] {
            if l.get(other).is_some() && key.is_none_or(|k| k != other && other != "form") {
                return Err(SpecError::field(
                    l.path_of(other),
                    "not used by this layer type",
                ));
            }
        }
        let albedo = match key {
            Some(k) => {
                let x = l.num(k)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(SpecError::field(
                        l.path_of(k),
                        format!("must be in [0, 1], got {x}"),
                    ));
                }
                x as f32
            }
            None => 0.0,
        };
        let form = match l.opt_choice("form", &["published", "energy-conserving"])? {
            Some("energy-conserving") => LayerForm::EnergyConserving,
            _ => LayerForm::Published,
        };
        params = params.with_layer(layer, form, albedo);
    }
    Ok(params)
}

/// Reads a footprint spec from a JSON value.
pub fn footprint_spec(v: &Value) -> Result<FootprintBatch, SpecError> {
    let top = Obj::new(v, "", &["sigma_um", "scratches", "queries"])?;
    let sigma_um = sigma(&top)?;
    let scratches = scratches(&top)?;
    let mut queries = Vec::new();
    for (i, q) in top.arr("queries")?.iter().enumerate() {
        let path = format!("queries[{i}]");
        let q = Obj::new(q, &path, &["scratch", "ellipse"])?;
        let idx = q.num("scratch")?;
        let scratch = if idx >= 0.0 && idx.fract() == 0.0 && (idx as usize) < scratches.len() {
            scratches[idx as usize]
        } else {
            return Err(SpecError::field(
                q.path_of("scratch"),
                format!(
                    "must be an index into scratches (0..{}), got {idx}",
                    scratches.len()
                ),
            ));
        };
        let e = Obj::new(
            q.req("ellipse")?,
            &q.path_of("ellipse"),
            &["center", "angle_rad", "a1", "a2"],
        )?;
        let ellipse = Ellipse {
            center: point(&e, "center")?,
            angle_rad: json::to_f32(e.num("angle_rad")?, &e.path_of("angle_rad"))?,
            a1: range::ELLIPSE_AXIS_UM.check(e.num("a1")?, &e.path_of("a1"))?,
            a2: range::ELLIPSE_AXIS_UM.check(e.num("a2")?, &e.path_of("a2"))?,
            ..Ellipse::default()
        };
        queries.push((scratch, ellipse));
    }
    Ok(FootprintBatch { sigma_um, queries })
}

/// `sigma_um` of `top` (default [`DEFAULT_SIGMA_UM`]), in [`range::SIGMA_UM`].
pub fn sigma(top: &Obj) -> Result<f32, SpecError> {
    match top.opt_num("sigma_um")? {
        Some(s) => range::SIGMA_UM.check(s, &top.path_of("sigma_um")),
        None => Ok(DEFAULT_SIGMA_UM),
    }
}

fn scratches(top: &Obj) -> Result<Vec<Scratch>, SpecError> {
    scratch_list(top.req("scratches")?, &top.path_of("scratches"))
}

/// An inline scratch list `[{"p0", "p1", "width", "depth", "profile"?}, ...]` at `path`
/// (µm).
pub fn scratch_list(v: &Value, path: &str) -> Result<Vec<Scratch>, SpecError> {
    v.as_array()
        .ok_or_else(|| SpecError::field(path, "expected an array"))?
        .iter()
        .enumerate()
        .map(|(i, s)| scratch(s, &format!("{path}[{i}]")))
        .collect()
}

/// One inline scratch `{"p0": [x, y], "p1": [x, y], "width", "depth", "profile"?}` (µm;
/// width and depth ≥ 0; profile `"rect"` (default) or `"triangle"`) at `path`.
pub(crate) fn scratch(v: &Value, path: &str) -> Result<Scratch, SpecError> {
    let s = Obj::new(v, path, &["p0", "p1", "width", "depth", "profile"])?;
    let profile = match s.opt_choice("profile", &["rect", "triangle"])? {
        Some("triangle") => Profile::Triangle,
        _ => Profile::Rect,
    };
    let (p0, p1) = (point64(&s, "p0")?, point64(&s, "p1")?);
    let width = range::WIDTH_UM.check(s.num("width")?, &s.path_of("width"))?;
    let depth = range::DEPTH_UM.check(s.num("depth")?, &s.path_of("depth"))?;
    segment(p0, p1, width, depth, profile, &s.path_of("p1"))
}

/// `Scratch::from_endpoints`, rejecting (at field `path`) a segment whose half length is
/// beyond the f32 range: end points within f32 range can be up to 2√2 · 3.4e38 apart, and
/// an infinite half length would silently make the scratch reflect nothing (found by the
/// `scratch_sources` fuzz target's invariant check).
pub(crate) fn segment(
    p0: [f64; 2],
    p1: [f64; 2],
    width: f32,
    depth: f32,
    profile: Profile,
    path: &str,
) -> Result<Scratch, SpecError> {
    let s = Scratch::from_endpoints(p0, p1, width, depth, profile);
    if !s.half_len.is_finite() {
        let len = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
        return Err(SpecError::field(
            path,
            format!("segment too long: {len:e} µm, half of it is beyond the f32 range"),
        ));
    }
    Ok(s)
}

/// A point kept in f64 (scratch end points: see `Scratch::from_endpoints`), finite and
/// within f32 range.
pub(crate) fn point64(o: &Obj, key: &str) -> Result<[f64; 2], SpecError> {
    let p = o.vec::<2>(key)?;
    let path = o.path_of(key);
    json::to_f32(p[0], &format!("{path}[0]"))?;
    json::to_f32(p[1], &format!("{path}[1]"))?;
    Ok(p)
}

fn point(o: &Obj, key: &str) -> Result<[f32; 2], SpecError> {
    let p = o.vec::<2>(key)?;
    let path = o.path_of(key);
    Ok([
        json::to_f32(p[0], &format!("{path}[0]"))?,
        json::to_f32(p[1], &format!("{path}[1]"))?,
    ])
}

/// A direction, normalised in f64 unless it is already unit within the kernel's
/// `UNIT_TOLERANCE` (then used as given, so f32 inputs are not rounded twice); zero length is
/// an error (z ≤ 0 is allowed and evaluates to 0).
pub fn direction(o: &Obj, key: &str) -> Result<[f32; 3], SpecError> {
    let d = o.vec::<3>(key)?;
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if !(l2 > 0.0 && l2.is_finite()) {
        return Err(SpecError::field(
            o.path_of(key),
            "direction must have non-zero, finite length",
        ));
    }
    let s = if (l2 - 1.0).abs() <= f64::from(UNIT_TOLERANCE) {
        1.0
    } else {
        1.0 / l2.sqrt()
    };
    Ok([(d[0] * s) as f32, (d[1] * s) as f32, (d[2] * s) as f32])
}

/// The `"ior"` field of `m`: `[n, k]` (constant), or the name of a metal whose measured
/// spectral IOR the kernel interpolates at each wavelength (`kernel::conductor`: "gold",
/// "silver", "copper", "aluminium", "nickel"; then `n = k = 0` and the metal is returned).
fn ior(m: &Obj<'_>) -> Result<(f32, f32, Conductor), SpecError> {
    if m.get("ior").is_some_and(Value::is_string) {
        let name = m.choice("ior", &Conductor::NAMES)?;
        let code = Conductor::NAMES
            .iter()
            .position(|&n| n == name)
            .unwrap_or(0);
        return Ok((0.0, 0.0, Conductor::from_u32(code as u32 + 1)));
    }
    let [n, k] = m.vec::<2>("ior")?;
    let ior_path = m.path_of("ior");
    let n = json::positive(n, &format!("{ior_path}[0]"), false)?;
    let k = json::positive(k, &format!("{ior_path}[1]"), true)?;
    Ok((n, k, Conductor::None))
}

/// A reflectance `{"F"}` or `{"ior": [n, k] | "gold" | …, "fresnel_angle"?}` at `path`.
pub fn material(v: &Value, path: &str) -> Result<Material, SpecError> {
    let m = Obj::new(v, path, &["F", "ior", "fresnel_angle"])?;
    match (m.get("F"), m.get("ior")) {
        (Some(_), Some(_)) => Err(SpecError::field(
            path,
            "give either \"F\" or \"ior\", not both",
        )),
        (Some(_), None) => {
            if m.get("fresnel_angle").is_some() {
                return Err(SpecError::field(
                    m.path_of("fresnel_angle"),
                    "only meaningful with \"ior\"",
                ));
            }
            let f = m.num("F")?;
            if !(0.0..=1.0).contains(&f) {
                return Err(SpecError::field(
                    m.path_of("F"),
                    format!("must be in [0, 1], got {f}"),
                ));
            }
            Ok(Material::constant(f as f32))
        }
        (None, Some(_)) => {
            let (n, k, metal) = ior(&m)?;
            let angle = match m.opt_choice("fresnel_angle", &["theta_d", "theta_i", "normal"])? {
                Some("theta_i") => FresnelAngle::ThetaI,
                Some("normal") => FresnelAngle::Normal,
                _ => FresnelAngle::ThetaD,
            };
            let mut material = Material::ior(n, k, angle);
            material.conductor = metal as u32;
            Ok(material)
        }
        (None, None) => Err(SpecError::field(path, "needs \"F\" or \"ior\"")),
    }
}
