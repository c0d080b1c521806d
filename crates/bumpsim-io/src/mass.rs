//! The test sheet's mass in an input file (TOML): a number in kg or text
//! with a unit (`mass = 1719` or `mass = "1719 kg"`), finite and positive;
//! the one rule of the planar and the 1-D studies' `[model] mass`.
//!
//! ```
//! use bumpsim_io::mass::sheet_mass;
//! assert_eq!(sheet_mass(&toml::Value::Integer(1719)), Some(1719.0));
//! assert_eq!(sheet_mass(&toml::Value::String("1.5 t".into())), Some(1500.0));
//! assert_eq!(sheet_mass(&toml::Value::Float(-3.0)), None);
//! ```

use bumpsim_core::units::{Dimension, parse_quantity};

/// What a refusal of [`sheet_mass`] says is expected.
pub const EXPECTED: &str = "expected a positive mass in kg or text such as \"1350 kg\"";

/// The mass, kg, of a TOML number (kg) or text with a unit; `None` for
/// anything not a finite positive mass (say so with [`EXPECTED`]).
pub fn sheet_mass(value: &toml::Value) -> Option<f64> {
    let mass = match value {
        toml::Value::Float(v) => *v,
        toml::Value::Integer(v) => *v as f64,
        toml::Value::String(s) => parse_quantity(s, Dimension::Mass).ok()?,
        _ => return None,
    };
    (mass.is_finite() && mass > 0.0).then_some(mass)
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
        ] {
            assert_eq!(sheet_mass(&bad), None, "{bad}");
        }
    }
}
