//! Reading a model file: TOML into a checked [`ModelFile`], every problem one error naming the
//! key.

use super::expr::{parse, Expr, FUNCTIONS};
use super::parameters::{initial_ranges, number, parameters};
use super::system::MAX_VARIABLES;
use super::{DerivedDef, ModelFile, ModelFileError};
use std::path::Path;
use toml::{Table, Value};

const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "encoder",
    "parameters",
    "state",
    "observed",
    "initial",
    "derived",
];
/// The encoders a file may ask for.
pub const ENCODERS: &[&str] = &["small", "paper", "linear", "keypoints"];

/// Reads and checks the model file at `path`.
pub fn load(path: &Path) -> Result<ModelFile, ModelFileError> {
    if let Err(e) = crate::input::check_kind(path) {
        return Err(ModelFileError {
            file: path.to_path_buf(),
            key: "(file)".into(),
            problem: e,
        });
    }
    let text = std::fs::read_to_string(path).map_err(|e| ModelFileError {
        file: path.to_path_buf(),
        key: "file".into(),
        problem: format!("cannot be read ({e})"),
    })?;
    parse_file(path, &text)
}

fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next().is_some_and(|f| f.is_alphabetic() || f == '_')
        && c.all(|x| x.is_alphanumeric() || x == '_')
}

/// Parses `text` (the contents of `path`).
pub(super) fn parse_file(path: &Path, text: &str) -> Result<ModelFile, ModelFileError> {
    let err = |key: &str, problem: String| ModelFileError {
        file: path.to_path_buf(),
        key: key.to_string(),
        problem,
    };
    let table: Table = text.parse().map_err(|e: toml::de::Error| {
        let at = e
            .span()
            .map(|s| {
                let line = text[..s.start].matches('\n').count() + 1;
                let col = s.start - text[..s.start].rfind('\n').map_or(0, |i| i + 1) + 1;
                format!("line {line}, column {col}: ")
            })
            .unwrap_or_default();
        err("toml", format!("{at}{}", e.message()))
    })?;
    if let Some(k) = table.keys().find(|k| !TOP_KEYS.contains(&k.as_str())) {
        return Err(err(
            k,
            format!("unknown key (known: {})", TOP_KEYS.join(", ")),
        ));
    }
    let string = |key: &str, required: bool| -> Result<Option<String>, ModelFileError> {
        match table.get(key) {
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(_) => Err(err(key, "must be a string".into())),
            None if required => Err(err(key, "is missing".into())),
            None => Ok(None),
        }
    };
    let name = string("name", true)?.unwrap_or_default();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_alphanumeric() || "-_.".contains(c))
    {
        return Err(err(
            "name",
            format!(
                "'{name}' must be letters, digits, '-', '_' or '.' (it names the model in reports)"
            ),
        ));
    }
    let description = string("description", false)?.unwrap_or_default();
    let encoder = string("encoder", false)?;
    if let Some(e) = encoder.as_deref().filter(|e| !ENCODERS.contains(e)) {
        return Err(err(
            "encoder",
            format!("'{e}' is not one of {}", ENCODERS.join(", ")),
        ));
    }
    let section = |key: &str| -> Result<Table, ModelFileError> {
        match table.get(key) {
            Some(Value::Table(t)) => Ok(t.clone()),
            Some(_) => Err(err(key, "must be a table ([{key}])".replace("{key}", key))),
            None => Ok(Table::new()),
        }
    };
    let reserved = |key: &str, n: &str| -> Result<(), ModelFileError> {
        if !is_identifier(n) {
            return Err(err(
                key,
                format!("'{n}' is not a name (letters, digits, '_')"),
            ));
        }
        if n == "t" || n == "pi" || FUNCTIONS.iter().any(|(f, _)| *f == n) {
            return Err(err(
                key,
                format!("'{n}' is reserved (t, pi and the functions)"),
            ));
        }
        Ok(())
    };

    let parameters = parameters(&section("parameters")?, &err, &reserved)?;
    if parameters.is_empty() {
        return Err(err(
            "parameters",
            "none given: a model needs at least one learnable parameter".into(),
        ));
    }

    let state_table = section("state")?;
    let observed_table = section("observed")?;
    let initial_table = section("initial")?;
    let states: Vec<String> = state_table.keys().cloned().collect();
    if states.is_empty() {
        return Err(err(
            "state",
            "no equations: give d/dt of each state variable, e.g. x = \"v\"".into(),
        ));
    }
    for s in &states {
        reserved(&format!("state.{s}"), s)?;
        if let Some(p) = parameters.iter().find(|p| &p.name == s) {
            return Err(err(
                &format!("state.{s}"),
                format!("'{}' is a parameter too", p.name),
            ));
        }
    }
    let mut file = ModelFile {
        path: path.to_path_buf(),
        source: text.to_string(),
        name,
        description,
        encoder,
        parameters,
        states,
        equations: Vec::new(),
        equation_texts: Vec::new(),
        observed: Vec::new(),
        initial: Vec::new(),
        derived: Vec::new(),
        kl: Vec::new(),
    };
    // Names used as state variables elsewhere but without an equation.
    let mentioned: Vec<String> = initial_table
        .keys()
        .cloned()
        .chain(
            observed_table
                .get("latent")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
                .filter_map(|v| v.as_str().map(String::from)),
        )
        .collect();
    let expression = |file: &ModelFile,
                      key: &str,
                      v: &Value,
                      lookup: &dyn Fn(&str) -> Option<usize>|
     -> Result<Expr, ModelFileError> {
        let text = match v {
            Value::String(s) => s.clone(),
            v if number(v).is_some() => number(v).unwrap_or(0.0).to_string(),
            _ => return Err(file.error(key, "must be an expression in quotes, e.g. \"-k*x\"")),
        };
        if text.trim().is_empty() {
            return Err(file.error(key, "has no equation (an empty expression)"));
        }
        let e = parse(&text, lookup).map_err(|e| {
            let hint = e
                .message
                .strip_prefix("unknown name '")
                .and_then(|n| n.strip_suffix('\''))
                .map(|n| {
                    if file.states.iter().any(|s| s == n) {
                        format!(
                            " ('{n}' is a state variable, which {key} cannot read: kl reads the \
                             observed ones, derived values the parameters)"
                        )
                    } else if mentioned.iter().any(|m| m == n) {
                        format!(" ('{n}' is a state variable without an equation: add {n} = \"...\" under [state])")
                    } else {
                        String::new()
                    }
                })
                .unwrap_or_default();
            file.error(key, format!("column {}: {}{hint} in \"{text}\"", e.column, e.message))
        })?;
        Ok(e)
    };
    for (s, v) in &state_table {
        let e = expression(&file, &format!("state.{s}"), v, &|n| file.variable(n))?;
        file.equations.push(e);
        file.equation_texts
            .push(v.as_str().map_or_else(|| v.to_string(), String::from));
    }
    let (n, m) = (file.states.len(), file.parameters.len());
    if n + m + 1 > MAX_VARIABLES {
        return Err(file.error(
            "state",
            format!(
                "{n} state variables and {m} parameters: at most {} in all",
                MAX_VARIABLES - 1
            ),
        ));
    }
    for (j, p) in file.parameters.iter().enumerate() {
        if !file.equations.iter().any(|e| e.uses(n + j)) {
            return Err(file.error(
                format!("parameters.{}", p.name),
                "appears in no equation of [state]: remove it or use it",
            ));
        }
    }

    if let Some(k) = observed_table.keys().find(|k| *k != "latent" && *k != "kl") {
        return Err(file.error(format!("observed.{k}"), "unknown key (known: latent, kl)"));
    }
    let latent = observed_table.get("latent").ok_or_else(|| {
        file.error(
            "observed.latent",
            "is missing: the state variables the latent measures, e.g. latent = [\"x\"]",
        )
    })?;
    let names = latent.as_array().filter(|a| !a.is_empty()).ok_or_else(|| {
        file.error(
            "observed.latent",
            "must be a non-empty list of state variables",
        )
    })?;
    for v in names {
        let name = v
            .as_str()
            .ok_or_else(|| file.error("observed.latent", "must list names in quotes"))?;
        let i = file.states.iter().position(|s| s == name).ok_or_else(|| {
            file.error(
                "observed.latent",
                format!(
                    "'{name}' is not a state variable (they are: {})",
                    file.states.join(", ")
                ),
            )
        })?;
        if file.observed.contains(&i) {
            return Err(file.error("observed.latent", format!("'{name}' is listed twice")));
        }
        file.observed.push(i);
    }
    if let Some(kl) = observed_table.get("kl") {
        let items = kl.as_array().filter(|a| !a.is_empty()).ok_or_else(|| {
            file.error(
                "observed.kl",
                "must be a non-empty list of expressions of the observed variables",
            )
        })?;
        let observed_only = |name: &str| {
            file.observed
                .iter()
                .copied()
                .find(|&i| file.states[i] == name)
        };
        let mut kl = Vec::new();
        for item in items {
            let e = expression(&file, "observed.kl", item, &observed_only)?;
            if !file.observed.iter().any(|&i| e.uses(i)) {
                return Err(file.error(
                    "observed.kl",
                    "each expression must read an observed variable (a constant has no spread)",
                ));
            }
            kl.push(e);
        }
        file.kl = kl;
    }

    file.initial = initial_ranges(&file, &initial_table)?;

    for (d, v) in section("derived")? {
        let key = format!("derived.{d}");
        reserved(&key, &d)?;
        if file.variable(&d).is_some() {
            return Err(file.error(
                &key,
                format!("'{d}' is already a state variable or parameter"),
            ));
        }
        let (text, unit) = match &v {
            Value::Table(t) => {
                if let Some(k) = t.keys().find(|k| *k != "value" && *k != "unit") {
                    return Err(
                        file.error(format!("{key}.{k}"), "unknown key (known: value, unit)")
                    );
                }
                let value = t
                    .get("value")
                    .ok_or_else(|| file.error(format!("{key}.value"), "is missing"))?;
                (
                    value.clone(),
                    t.get("unit").and_then(Value::as_str).map(String::from),
                )
            }
            v => (v.clone(), None),
        };
        let params_only = |name: &str| {
            file.parameters
                .iter()
                .position(|p| p.name == name)
                .map(|j| n + j)
        };
        let expr = expression(&file, &key, &text, &params_only)?;
        file.derived.push(DerivedDef {
            name: d,
            expr,
            unit,
        });
    }

    Ok(file)
}
