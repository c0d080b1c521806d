//! A speed in an input file (TOML): a number in m/s or text with a unit
//! (`speed = 2.2` or `speed = "8 km/h"`), the one rule of the 1-D series'
//! heads, the planar series' tests and the planar study's cases.
//!
//! Either way the speed must be finite: the text is read by
//! [`bumpsim_core::units::parse_quantity`], which refuses `"nan"`, and a
//! TOML `nan` or `inf` is refused with the same message. The sign is the
//! caller's to check (a case's car may stand still, a pendulum must move).
//!
//! ```
//! use bumpsim_io::speed::speed_value;
//! assert_eq!(speed_value(&toml::Value::Float(2.5)).unwrap(), 2.5);
//! assert!((speed_value(&toml::Value::String("36 km/h".into())).unwrap() - 10.0).abs() < 1e-12);
//! assert!(speed_value(&toml::Value::Float(f64::NAN)).is_err());
//! ```

use bumpsim_core::units::{Dimension, QuantityError, parse_quantity};

/// Why a TOML value is not a speed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpeedError {
    /// Text that is not a finite speed with an optional unit (or a
    /// non-finite number).
    #[error(transparent)]
    Quantity(#[from] QuantityError),
    /// Neither a number nor text (a table, a list, a date, ...).
    #[error("speed {found}: expected m/s or text such as \"6 km/h\"")]
    Type {
        /// The value as TOML writes it.
        found: String,
    },
}

/// A speed, m/s: a TOML number in m/s, or text with a unit (`"6 km/h"`).
pub fn speed_value(value: &toml::Value) -> Result<f64, SpeedError> {
    let number = match value {
        toml::Value::Float(v) => *v,
        toml::Value::Integer(v) => *v as f64,
        toml::Value::String(s) => return Ok(parse_quantity(s, Dimension::Velocity)?),
        other => {
            return Err(SpeedError::Type {
                found: other.to_string(),
            });
        }
    };
    match number.is_finite() {
        true => Ok(number),
        false => Err(QuantityError::NotANumber(value.to_string()).into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use toml::Value;

    /// The cases of the two readers this one replaces (the 1-D series'
    /// heads and the planar study's cases), and the finiteness both missed
    /// for numbers.
    #[test]
    fn numbers_text_with_units_and_refusals() {
        assert_eq!(speed_value(&Value::Float(4.4)), Ok(4.4));
        assert_eq!(speed_value(&Value::Integer(8)), Ok(8.0));
        assert_eq!(speed_value(&Value::Integer(0)), Ok(0.0));
        assert_eq!(speed_value(&Value::Float(-2.0)), Ok(-2.0));
        let kmh = speed_value(&Value::String("8 km/h".into())).unwrap();
        assert!((kmh - 8.0 / 3.6).abs() < 1e-12);
        assert_eq!(speed_value(&Value::String("2.5".into())), Ok(2.5));
        let err = speed_value(&Value::String("8 kN".into())).unwrap_err();
        assert!(err.to_string().contains("expected a velocity"), "{err}");
        let err = speed_value(&Value::String("fast".into())).unwrap_err();
        assert!(
            err.to_string().contains("'fast' is not a finite number"),
            "{err}"
        );
        let err = speed_value(&Value::Boolean(true)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "speed true: expected m/s or text such as \"6 km/h\""
        );
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let err = speed_value(&Value::Float(v)).unwrap_err();
            assert!(matches!(err, SpeedError::Quantity(_)), "{v}: {err}");
            assert!(err.to_string().contains("is not a finite number"), "{err}");
        }
    }
}
