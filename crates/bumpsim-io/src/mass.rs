//! The test sheet's mass in an input file (TOML): a number in kg or text
//! with a unit (`mass = 1719` or `mass = "1719 kg"`), from 0.001 kg to 1000 t
//! ([`RANGE`]); the one rule of the planar and the 1-D studies' `[model]
//! mass`. A mass beyond it is no car's: `1e300` was taken, its prior then
//! dropped without a word (outside the search's range) and only a warning
//! said the sheet was 100 % off.
//!
//! ```
//! use bumpsim_io::mass::sheet_mass;
//! assert_eq!(sheet_mass(&toml::Value::Integer(1719)), Some(1719.0));
//! assert_eq!(sheet_mass(&toml::Value::String("1.5 t".into())), Some(1500.0));
//! assert_eq!(sheet_mass(&toml::Value::Float(-3.0)), None);
//! assert_eq!(sheet_mass(&toml::Value::Float(1e300)), None);
//! ```

use bumpsim_core::units::{Dimension, parse_quantity};

/// What a refusal of [`sheet_mass`] says is expected.
pub const EXPECTED: &str =
    "expected a positive mass in kg or text such as \"1350 kg\", from 0.001 to 1e6 kg";

/// The test sheet masses taken, kg: from a gram (a model's bumper part)
/// to a thousand tonnes (beyond any vehicle a bumper test weighs).
pub const RANGE: std::ops::RangeInclusive<f64> = 1e-3..=1e6;

/// The mass, kg, of a TOML number (kg) or text with a unit; `None` for
/// anything not a mass within [`RANGE`] (say so with [`EXPECTED`]).
pub fn sheet_mass(value: &toml::Value) -> Option<f64> {
    let mass = match value {
        toml::Value::Float(v) => *v,
        toml::Value::Integer(v) => *v as f64,
        toml::Value::String(s) => parse_quantity(s, Dimension::Mass).ok()?,
        _ => return None,
    };
    RANGE.contains(&mass).then_some(mass)
}

/// The value as a refusal quotes it: a number short (`1e300`, not its 301
/// digits), anything else as written.
pub fn quoted(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(v) => bumpsim_core::units::short(*v),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use toml::Value;

    #[test]
    fn numbers_and_text_in_kg_or_with_units_nothing_else() {
        assert_eq!(sheet_mass(&Value::Float(1265.5)), Some(1265.5));
        assert_eq!(sheet_mass(&Value::String("1265 kg".into())), Some(1265.0));
        for bad in [
            Value::Float(f64::NAN),
            Value::Float(f64::INFINITY),
            Value::Integer(0),
            Value::String("1265 N".into()),
            Value::String("heavy".into()),
            Value::Boolean(true),
            Value::Float(1e300),
            Value::String("1e300 kg".into()),
            Value::Float(1e7),
            Value::String("0.1e-3 kg".into()),
        ] {
            assert_eq!(sheet_mass(&bad), None, "{bad}");
        }
        assert_eq!(quoted(&Value::Float(1e300)), "1e300");
        assert_eq!(quoted(&Value::String("1 kg".into())), "\"1 kg\"");
    }
}
