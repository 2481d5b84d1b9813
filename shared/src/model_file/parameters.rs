//! The numeric tables of a model file: `[parameters]` (each a start, optional bounds
//! (`positive`, `min`, `max`; the start strictly inside) and a unit) and `[initial]` (the ranges
//! `gen` draws initial states from).

use super::{ModelFile, ModelFileError, Parameter};
use crate::cli::num;
use toml::{Table, Value};

/// A TOML number (integer or float) as f64.
pub(super) fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(x) => Some(*x),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

const PARAMETER_KEYS: &[&str] = &["start", "positive", "min", "max", "unit"];

/// The parameters of `table`, in the file's order; `err` makes an error about a key and
/// `reserved` refuses names that are not names or are taken.
pub(super) fn parameters(
    table: &Table,
    err: &dyn Fn(&str, String) -> ModelFileError,
    reserved: &dyn Fn(&str, &str) -> Result<(), ModelFileError>,
) -> Result<Vec<Parameter>, ModelFileError> {
    let mut parameters = Vec::new();
    for (pname, v) in table.clone() {
        let key = format!("parameters.{pname}");
        reserved(&key, &pname)?;
        let Value::Table(spec) = v else {
            return Err(err(
                &key,
                "must be a table such as { start = 1.0, positive = true }".into(),
            ));
        };
        if let Some(k) = spec.keys().find(|k| !PARAMETER_KEYS.contains(&k.as_str())) {
            return Err(err(
                &format!("{key}.{k}"),
                format!("unknown key (known: {})", PARAMETER_KEYS.join(", ")),
            ));
        }
        let bound = |k: &str| -> Result<Option<f64>, ModelFileError> {
            spec.get(k)
                .map(|v| {
                    number(v)
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| err(&format!("{key}.{k}"), "must be a finite number".into()))
                })
                .transpose()
        };
        let start = bound("start")?.ok_or_else(|| {
            err(
                &format!("{key}.start"),
                "is missing (the initial value)".into(),
            )
        })?;
        let positive = match spec.get("positive") {
            None => false,
            Some(Value::Boolean(b)) => *b,
            Some(_) => {
                return Err(err(
                    &format!("{key}.positive"),
                    "must be true or false".into(),
                ))
            }
        };
        let (mut min, max) = (bound("min")?, bound("max")?);
        if positive {
            min = Some(min.map_or(0.0, |m| m.max(0.0)));
        }
        if let (Some(lo), Some(hi)) = (min, max) {
            if lo >= hi {
                return Err(err(
                    &key,
                    format!("min {} must be below max {}", num(lo), num(hi)),
                ));
            }
        }
        if min.is_some_and(|lo| start <= lo) || max.is_some_and(|hi| start >= hi) {
            return Err(err(
                &format!("{key}.start"),
                format!(
                    "{} must lie strictly inside the bounds ({}, {}) (a bounded parameter is learned through a map that reaches its bounds only in the limit)",
                    num(start),
                    min.map_or("-inf".into(), num),
                    max.map_or("inf".into(), num)
                ),
            ));
        }
        let unit = match spec.get("unit") {
            None => None,
            Some(Value::String(s)) => Some(s.clone()),
            Some(_) => return Err(err(&format!("{key}.unit"), "must be a string".into())),
        };
        parameters.push(Parameter {
            name: pname,
            start,
            min,
            max,
            unit,
        });
    }
    Ok(parameters)
}

/// The `[initial]` table: a range [min, max] for each state variable it names, `None` for the
/// others, in the order of `file`'s states.
pub(super) fn initial_ranges(
    file: &ModelFile,
    table: &Table,
) -> Result<Vec<Option<(f64, f64)>>, ModelFileError> {
    let mut initial = vec![None; file.states.len()];
    for (s, v) in table {
        let key = format!("initial.{s}");
        let i = file.states.iter().position(|x| x == s).ok_or_else(|| {
            file.error(
                &key,
                format!(
                    "'{s}' is not a state variable (they are: {})",
                    file.states.join(", ")
                ),
            )
        })?;
        let range: Vec<f64> = v
            .as_array()
            .map(|a| a.iter().filter_map(number).collect())
            .unwrap_or_default();
        match range[..] {
            [lo, hi] if lo.is_finite() && hi.is_finite() && lo <= hi => initial[i] = Some((lo, hi)),
            [lo, hi] if lo > hi => {
                return Err(file.error(&key, format!("min {} > max {}", num(lo), num(hi))))
            }
            _ => return Err(file.error(&key, "must be a range [min, max] of two finite numbers")),
        }
    }
    Ok(initial)
}
