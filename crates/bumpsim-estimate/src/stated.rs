//! A study's `[priors]` table and its application to a model's default
//! priors ([`crate::prior`], issue 44 item 3): the one reading of the 1-D
//! and the planar studies.
//!
//! Each key is a prior's name (`total_mass`, `m2`, `body.yaw_inertia`,
//! `"left.springs[0]"`; dotted keys may be written as TOML's nested
//! tables), each value `"none"` (no prior) or `{ value = …, spread = … }`
//! (either may be left to the default). A value is SI, or text with a unit
//! where the model names the prior's dimension (`"1239 kg"`, `"900 N/mm"`);
//! a spread is the standard deviation of ln θ, a positive number (0.2 ≈
//! ±20 %). [`apply`] overrides a default's centre or spread, removes it,
//! or adds a prior on any other estimated parameter (spread 0.1 unless
//! given), and refuses a name the model does not estimate.
//!
//! ```
//! use bumpsim_estimate::prior::Prior;
//! use bumpsim_estimate::stated::{apply, settings};
//! let table: toml::Table = toml::from_str("m2 = { value = 250, spread = 0.2 }\ntotal_mass = \"none\"").unwrap();
//! let stated = settings(&table, &|_| None).unwrap();
//! let defaults = vec![Prior::sum("total_mass", vec![0, 1], 1450.0, 0.01).unwrap()];
//! let names = ["m1".to_string(), "m2".to_string()];
//! let priors = apply(defaults, &stated, &names, &["total_mass"]).unwrap();
//! assert_eq!(priors.len(), 1);
//! assert_eq!((priors[0].name.as_str(), priors[0].centre, priors[0].terms.clone()), ("m2", 250.0, vec![1]));
//! ```

use crate::prior::Prior;
use bumpsim_core::units::{Dimension, parse_quantity};

/// A study's setting of one prior: `removed`, or its centre and spread
/// (either left to the default).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PriorSetting {
    /// The prior's name (`total_mass`, `body.yaw_inertia`, a parameter's).
    pub name: String,
    /// `"none"`: no prior on it.
    pub removed: bool,
    /// Its centre, SI.
    pub value: Option<f64>,
    /// Its spread, the standard deviation of ln θ.
    pub spread: Option<f64>,
}

/// The spread of a prior a study adds without one.
pub const ADDED_SPREAD: f64 = 0.1;

/// A `[priors]` entry that cannot be read or applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("[priors] {key}: {message}")]
pub struct PriorsError {
    /// The key (`body.yaw_inertia`, `m2`).
    pub key: String,
    /// What is wrong.
    pub message: String,
}

/// The settings of a `[priors]` table; `dimension` names the dimension of
/// a prior's value by its name (text with a unit is read in it).
pub fn settings(
    table: &toml::Table,
    dimension: &dyn Fn(&str) -> Option<Dimension>,
) -> Result<Vec<PriorSetting>, PriorsError> {
    let mut out = Vec::new();
    flatten("", table, dimension, &mut out)?;
    Ok(out)
}

fn flatten(
    prefix: &str,
    table: &toml::Table,
    dimension: &dyn Fn(&str) -> Option<Dimension>,
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
                out.push(entry(name, t, dimension)?)
            }
            // `m2 = {}` set nothing and was passed over without a word
            toml::Value::Table(t) if t.is_empty() => {
                return Err(PriorsError {
                    key: name,
                    message: "an empty table: give { value = ..., spread = ... } (either may be left out) or \"none\"".into(),
                });
            }
            toml::Value::Table(t) => flatten(&name, t, dimension, out)?,
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

fn entry(
    name: String,
    table: &toml::Table,
    dimension: &dyn Fn(&str) -> Option<Dimension>,
) -> Result<PriorSetting, PriorsError> {
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
            "value" => (crate::prior::CENTRE_RANGE, "SI, the search's range"),
            _ => (
                crate::prior::SPREAD_RANGE,
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

/// `defaults` with `stated` applied (see the module): `names` are the
/// estimated parameters' (a prior on one of them has its index as its
/// term; an empty name takes no prior), `extra` the names of defaults on several (`total_mass`). An
/// error names the key that is unknown, has no value to take or is not
/// a usable prior.
pub fn apply(
    defaults: Vec<Prior>,
    stated: &[PriorSetting],
    names: &[String],
    extra: &[&str],
) -> Result<Vec<Prior>, PriorsError> {
    let index = |name: &str| names.iter().position(|n| n == name);
    let mut out = defaults;
    for setting in stated {
        let error = |message: String| PriorsError {
            key: setting.name.clone(),
            message,
        };
        let named = !setting.name.is_empty() && index(&setting.name).is_some();
        if !extra.contains(&setting.name.as_str()) && !named {
            let known: Vec<&str> = extra
                .iter()
                .copied()
                .chain(names.iter().map(String::as_str))
                .filter(|n| !n.is_empty())
                .collect();
            return Err(error(format!(
                "no such estimated parameter; known: {}",
                known.join(", ")
            )));
        }
        let at = out.iter().position(|p| p.name == setting.name);
        if setting.removed {
            if let Some(at) = at {
                out.remove(at);
            }
            continue;
        }
        let base = at.map(|k| out[k].clone());
        let Some(value) = setting.value.or(base.as_ref().map(|p| p.centre)) else {
            return Err(error("needs a value (no default prior on it)".into()));
        };
        let spread = setting
            .spread
            .or(base.as_ref().map(|p| p.spread))
            .unwrap_or(ADDED_SPREAD);
        let terms = match (&base, index(&setting.name)) {
            (Some(p), _) => p.terms.clone(),
            (None, Some(i)) => vec![i],
            (None, None) => return Err(error("needs a value (no default prior on it)".into())),
        };
        let less = base.as_ref().map(|p| p.less.clone()).unwrap_or_default();
        let prior = Prior::sum(setting.name.clone(), terms, value, spread)
            .map_err(|e| error(e.to_string()))?
            .from_source("the study's [priors]");
        let prior = Prior { less, ..prior };
        match at {
            Some(at) => out[at] = prior,
            None => out.push(prior),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<PriorSetting>, PriorsError> {
        let dimension = |name: &str| match name.starts_with('m') || name == "total_mass" {
            true => Some(Dimension::Mass),
            false => None,
        };
        settings(&toml::from_str(text).unwrap(), &dimension)
    }

    #[test]
    fn dotted_keys_units_and_none_are_read() {
        let s = read(
            "body.yaw_inertia = { value = 2300, spread = 0.2 }\nk1 = \"none\"\ntotal_mass = { value = \"1.239 t\" }",
        )
        .unwrap();
        let by = |n: &str| s.iter().find(|p| p.name == n).unwrap().clone();
        assert_eq!(by("body.yaw_inertia").value, Some(2300.0));
        assert!(by("k1").removed);
        assert!((by("total_mass").value.unwrap() - 1239.0).abs() < 1e-9);
    }

    #[test]
    fn hostile_entries_name_their_key() {
        for (text, key) in [
            ("m1 = { value = nan }", "m1"),
            ("m1 = { spread = -0.1 }", "m1"),
            ("m1 = { spread = 0.0 }", "m1"),
            ("m1 = { value = \"fast\" }", "m1"),
            ("k1 = { value = \"2300 kg\" }", "k1"),
            ("m1 = { centre = 3 }", "m1"),
            ("m1 = 3", "m1"),
            ("m1 = \"some\"", "m1"),
            ("m1 = {}", "m1"),
            ("[body.yaw_inertia]", "body.yaw_inertia"),
        ] {
            let e = read(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("[priors] {key}")), "{text}: {e}");
        }
    }

    #[test]
    fn a_study_overrides_removes_adds_and_unknown_names_are_refused() {
        let names: Vec<String> = ["m1", "m2", "k1"].map(String::from).to_vec();
        let defaults = vec![
            Prior::sum("total_mass", vec![0, 1], 1000.0, 0.01).unwrap(),
            Prior::single("m1", 0, 10.0, 1.0).unwrap(),
        ];
        let setting = |name: &str, removed, value, spread| PriorSetting {
            name: name.into(),
            removed,
            value,
            spread,
        };
        let out = apply(
            defaults.clone(),
            &[
                setting("m1", false, None, Some(0.3)),
                setting("total_mass", true, None, None),
                setting("k1", false, Some(5e5), None),
            ],
            &names,
            &["total_mass"],
        )
        .unwrap();
        assert_eq!(out.len(), 2);
        assert_eq!((out[0].centre, out[0].spread), (10.0, 0.3));
        assert_eq!(
            (out[1].terms.clone(), out[1].spread),
            (vec![2], ADDED_SPREAD)
        );
        let refused = |s: PriorSetting| {
            apply(defaults.clone(), &[s], &names, &["total_mass"])
                .unwrap_err()
                .to_string()
        };
        let e = refused(setting("m9", false, Some(1.0), None));
        assert!(
            e.starts_with("[priors] m9") && e.contains("known: total_mass, m1"),
            "{e}"
        );
        let e = refused(setting("k1", false, None, Some(0.2)));
        assert!(e.contains("needs a value"), "{e}");
        let e = refused(setting("m1", false, Some(f64::NAN), None));
        assert!(e.contains("centre"), "{e}");
    }
}
