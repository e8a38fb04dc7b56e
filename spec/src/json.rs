//! A strict reader over `serde_json::Value` that knows each value's path, so every error
//! names the field (`queries[2].wi`), unknown fields are rejected, and numbers must be finite.

use crate::error::SpecError;
use serde_json::{Map, Value};

/// A JSON object being read, with its path.
pub struct Obj<'a> {
    path: String,
    map: &'a Map<String, Value>,
}

/// Joins a parent path and a key.
fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

impl<'a> Obj<'a> {
    /// Reads `v` as an object at `path`, allowing only the keys in `allowed`.
    pub fn new(v: &'a Value, path: &str, allowed: &[&str]) -> Result<Obj<'a>, SpecError> {
        let map = v
            .as_object()
            .ok_or_else(|| SpecError::field(display(path), "expected a JSON object"))?;
        for k in map.keys() {
            if !allowed.contains(&k.as_str()) {
                return Err(SpecError::field(
                    join(path, k),
                    format!("unknown field (allowed: {})", allowed.join(", ")),
                ));
            }
        }
        Ok(Obj {
            path: path.to_string(),
            map,
        })
    }

    /// The path of field `key`.
    pub fn path_of(&self, key: &str) -> String {
        join(&self.path, key)
    }

    /// The raw value of an optional field.
    pub fn get(&self, key: &str) -> Option<&'a Value> {
        self.map.get(key)
    }

    /// The raw value of a required field.
    pub fn req(&self, key: &str) -> Result<&'a Value, SpecError> {
        self.map
            .get(key)
            .ok_or_else(|| SpecError::field(self.path_of(key), "missing required field"))
    }

    /// A required finite number.
    pub fn num(&self, key: &str) -> Result<f64, SpecError> {
        number(self.req(key)?, &self.path_of(key))
    }

    /// A required whole number in `0..=max` (seeds, counts).
    pub fn integer(&self, key: &str, max: f64) -> Result<u64, SpecError> {
        let n = self.num(key)?;
        if n >= 0.0 && n <= max && n.fract() == 0.0 {
            Ok(n as u64)
        } else {
            Err(SpecError::field(
                self.path_of(key),
                format!("must be an integer in 0..={max}"),
            ))
        }
    }

    /// An optional finite number.
    pub fn opt_num(&self, key: &str) -> Result<Option<f64>, SpecError> {
        self.get(key)
            .map(|v| number(v, &self.path_of(key)))
            .transpose()
    }

    /// A required array of exactly `N` finite numbers.
    pub fn vec<const N: usize>(&self, key: &str) -> Result<[f64; N], SpecError> {
        numbers::<N>(self.req(key)?, &self.path_of(key))
    }

    /// A required array.
    pub fn arr(&self, key: &str) -> Result<&'a Vec<Value>, SpecError> {
        self.req(key)?
            .as_array()
            .ok_or_else(|| SpecError::field(self.path_of(key), "expected an array"))
    }

    /// An optional string that must be one of `choices`.
    pub fn opt_choice(&self, key: &str, choices: &[&str]) -> Result<Option<&'a str>, SpecError> {
        let Some(v) = self.get(key) else {
            return Ok(None);
        };
        let s = v
            .as_str()
            .ok_or_else(|| SpecError::field(self.path_of(key), "expected a string"))?;
        if choices.contains(&s) {
            Ok(Some(s))
        } else {
            Err(SpecError::field(
                self.path_of(key),
                format!(
                    "unknown value {s:?} (expected one of: {})",
                    choices.join(", ")
                ),
            ))
        }
    }

    /// A required string that must be one of `choices`.
    pub fn choice(&self, key: &str, choices: &[&str]) -> Result<&'a str, SpecError> {
        self.req(key)?;
        Ok(self.opt_choice(key, choices)?.unwrap_or_default())
    }
}

fn display(path: &str) -> String {
    if path.is_empty() {
        "(top level)".into()
    } else {
        path.into()
    }
}

/// A finite JSON number.
pub fn number(v: &Value, path: &str) -> Result<f64, SpecError> {
    let x = v
        .as_f64()
        .ok_or_else(|| SpecError::field(path, "expected a number"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(SpecError::field(path, "must be finite"))
    }
}

/// An array of exactly `N` finite numbers.
pub fn numbers<const N: usize>(v: &Value, path: &str) -> Result<[f64; N], SpecError> {
    let a = v
        .as_array()
        .filter(|a| a.len() == N)
        .ok_or_else(|| SpecError::field(path, format!("expected an array of {N} numbers")))?;
    let mut out = [0.0; N];
    for (i, x) in a.iter().enumerate() {
        out[i] = number(x, &format!("{path}[{i}]"))?;
    }
    Ok(out)
}

/// Checks `x > 0` (or `x ≥ 0` when `allow_zero`) and that it fits an `f32`.
pub fn positive(x: f64, path: &str, allow_zero: bool) -> Result<f32, SpecError> {
    let ok = if allow_zero { x >= 0.0 } else { x > 0.0 };
    if !ok {
        let what = if allow_zero {
            "must be >= 0"
        } else {
            "must be > 0"
        };
        return Err(SpecError::field(path, format!("{what}, got {x}")));
    }
    to_f32(x, path)
}

/// Converts to `f32`, rejecting values that overflow it.
pub fn to_f32(x: f64, path: &str) -> Result<f32, SpecError> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(SpecError::field(path, format!("{x} does not fit in f32")))
    }
}

/// Parses a whole document, naming the file in errors.
pub fn parse(text: &str, file: &str) -> Result<Value, SpecError> {
    serde_json::from_str(text).map_err(|e| SpecError::Json {
        path: file.into(),
        msg: e.to_string(),
    })
}
