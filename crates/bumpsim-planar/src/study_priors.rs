//! The `[priors]` table of a planar study ([`crate::identify::priors`]):
//! each key a prior's name (`total_mass`, `body.yaw_inertia`,
//! `"left.springs[0]"`; dotted keys may be written as TOML's nested
//! tables), each value `"none"` (no prior) or `{ value = …, spread = … }`
//! (either may be left to the default). A value is SI, or text with a unit
//! for a mass, spring or damper (`"1239 kg"`, `"900 N/mm"`); a spread is
//! the standard deviation of ln θ, a positive number (0.2 ≈ ±20 %).

use crate::identify::PriorSetting;
use bumpsim_core::units::{Dimension, parse_quantity};

/// A `[priors]` entry that cannot be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("[priors] {key}: {message}")]
pub struct PriorsError {
    /// The key (`body.yaw_inertia`).
    pub key: String,
    /// What is wrong.
    pub message: String,
}

/// The settings of a `[priors]` table.
pub fn settings(table: &toml::Table) -> Result<Vec<PriorSetting>, PriorsError> {
    let mut out = Vec::new();
    flatten("", table, &mut out)?;
    Ok(out)
}

fn flatten(
    prefix: &str,
    table: &toml::Table,
    out: &mut Vec<PriorSetting>,
) -> Result<(), PriorsError> {
    for (key, value) in table {
        let name = match prefix.is_empty() {
            true => key.clone(),
            false => format!("{prefix}.{key}"),
        };
        match value {
            toml::Value::String(word) if word.trim() == "none" => out.push(PriorSetting {
                name,
                removed: true,
                ..Default::default()
            }),
            toml::Value::Table(t) if t.contains_key("value") || t.contains_key("spread") => {
                out.push(entry(name, t)?)
            }
            toml::Value::Table(t) => flatten(&name, t, out)?,
            other => {
                return Err(PriorsError {
                    key: name,
                    message: format!(
                        "{other} is neither \"none\" nor {{ value = ..., spread = ... }}"
                    ),
                });
            }
        }
    }
    Ok(())
}

fn entry(name: String, table: &toml::Table) -> Result<PriorSetting, PriorsError> {
    let error = |message: String| PriorsError {
        key: name.clone(),
        message,
    };
    if let Some(k) = table.keys().find(|k| *k != "value" && *k != "spread") {
        return Err(error(format!(
            "unknown field '{k}': expected value, spread"
        )));
    }
    let number = |field: &str, v: &toml::Value| -> Result<f64, PriorsError> {
        let x = match v {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            toml::Value::String(text) => match dimension(&name) {
                Some(d) if field == "value" => parse_quantity(text, d)
                    .map_err(|e| error(format!("{field} = {text:?}: {e}")))?,
                _ => {
                    return Err(error(format!("{field} = {text:?}: a number expected (SI)")));
                }
            },
            other => return Err(error(format!("{field} = {other}: a number expected"))),
        };
        let (range, what) = match field {
            "value" => (
                bumpsim_estimate::prior::CENTRE_RANGE,
                "SI, the search's range",
            ),
            _ => (
                bumpsim_estimate::prior::SPREAD_RANGE,
                "sd of ln θ; \"none\" for no prior",
            ),
        };
        match (x.is_finite() && x > 0.0, range.contains(&x)) {
            (true, true) => Ok(x),
            (false, _) => Err(error(format!("{field} = {x}: must be finite and positive"))),
            (true, false) => Err(error(format!(
                "{field} = {}: must be from {:e} to {:e} ({what})",
                bumpsim_core::units::short(x),
                range.start(),
                range.end()
            ))),
        }
    };
    Ok(PriorSetting {
        value: table.get("value").map(|v| number("value", v)).transpose()?,
        spread: table
            .get("spread")
            .map(|v| number("spread", v))
            .transpose()?,
        name: name.clone(),
        removed: false,
    })
}

/// The dimension of a value given with a unit, by the prior's name.
fn dimension(name: &str) -> Option<Dimension> {
    if name == crate::identify::TOTAL_MASS || name == "body.mass" || name.contains(".masses[") {
        Some(Dimension::Mass)
    } else if name.contains(".springs[") {
        Some(Dimension::Stiffness)
    } else if name.contains(".dampers[") {
        Some(Dimension::Damping)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<PriorSetting>, PriorsError> {
        settings(&toml::from_str(text).unwrap())
    }

    #[test]
    fn dotted_keys_units_and_none_are_read() {
        let s = read(
            "body.yaw_inertia = { value = 2300, spread = 0.2 }\ntyres.mu_lateral = \"none\"\ntotal_mass = { value = \"1.239 t\" }\n\"left.springs[0]\" = { value = \"900 N/mm\", spread = 0.5 }",
        )
        .unwrap();
        let by = |n: &str| s.iter().find(|p| p.name == n).unwrap().clone();
        assert_eq!(by("body.yaw_inertia").value, Some(2300.0));
        assert!(by("tyres.mu_lateral").removed);
        assert!((by("total_mass").value.unwrap() - 1239.0).abs() < 1e-9);
        assert!((by("left.springs[0]").value.unwrap() - 9e5).abs() < 1e-6);
    }

    #[test]
    fn hostile_entries_name_their_key() {
        for (text, key) in [
            ("body.mass = { value = nan }", "body.mass"),
            ("body.mass = { spread = -0.1 }", "body.mass"),
            ("body.mass = { spread = 0.0 }", "body.mass"),
            ("body.mass = { value = \"fast\" }", "body.mass"),
            (
                "body.yaw_inertia = { value = \"2300 kg\" }",
                "body.yaw_inertia",
            ),
            ("body.mass = { centre = 3 }", "body.mass"),
            ("body.mass = 3", "body.mass"),
            ("body.mass = \"some\"", "body.mass"),
        ] {
            let e = read(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("[priors] {key}")), "{text}: {e}");
        }
    }
}
