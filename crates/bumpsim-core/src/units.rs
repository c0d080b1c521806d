//! Physical units: parsing the unit text of input files into SI factors, and
//! formatting SI values for people.
//!
//! Every quantity inside bumpsim is an `f64` in SI (kg, m, s, N, N/m, N·s/m, J).
//! Readers convert with [`Unit::to_si`]: `si = factor * value`. All units used
//! in crash testing are pure scale factors (no offsets), so a single factor is
//! exact. The standard gravity of `g` is 9.80665 m/s² (SAE J211-1, ISO 6487).
//!
//! Unit text is matched after a light normalisation: surrounding blanks,
//! inner spaces and the product signs `·`, `*`, `⋅` are removed, `**` and `²`
//! become `^`-powers. So `N·s/m`, `N*s/m`, `N s/m` and `Ns/m` are the same
//! unit, and `m/s**2` equals `m/s^2`. Matching is case-sensitive (`mm` is not
//! `Mm`); each unit's spellings are listed explicitly in one table, so an
//! unknown or ambiguous text is an error, never a guess.
//!
//! ```
//! use bumpsim_core::units::{Dimension, Unit};
//! let u = Unit::parse("N/mm").unwrap();
//! assert_eq!(u.dimension, Dimension::Stiffness);
//! assert_eq!(u.to_si(4.0), 4000.0);
//! assert!(Unit::parse("furlong").is_err());
//! ```

use std::fmt;

/// Standard gravity in m/s² (SAE J211-1 and ISO 6487).
pub const STANDARD_GRAVITY: f64 = 9.806_65;

/// The physical dimension of a quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dimension {
    /// A pure number (`-` or `1`).
    Dimensionless,
    /// Time, SI unit s.
    Time,
    /// Length or displacement, SI unit m.
    Length,
    /// Velocity, SI unit m/s.
    Velocity,
    /// Acceleration, SI unit m/s².
    Acceleration,
    /// Force, SI unit N.
    Force,
    /// Mass, SI unit kg.
    Mass,
    /// Spring stiffness, SI unit N/m.
    Stiffness,
    /// Viscous damping coefficient, SI unit N·s/m.
    Damping,
    /// Energy or work, SI unit J.
    Energy,
    /// Frequency, SI unit Hz.
    Frequency,
    /// Moment (torque), SI unit N·m; distinct from [`Dimension::Energy`]
    /// although both are N·m (ISO/TS 13499 dimension `MO`).
    Moment,
    /// Angle, SI unit rad (ISO/TS 13499 `AN`).
    Angle,
    /// Angular velocity, SI unit rad/s (ISO/TS 13499 `AV`).
    AngularVelocity,
    /// Angular acceleration, SI unit rad/s² (ISO/TS 13499 `AA`).
    AngularAcceleration,
}

impl Dimension {
    /// The SI unit symbol as bumpsim writes it in file headers (ASCII, and
    /// accepted back by [`Unit::parse`]).
    pub fn si_symbol(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "-",
            Dimension::Time => "s",
            Dimension::Length => "m",
            Dimension::Velocity => "m/s",
            Dimension::Acceleration => "m/s^2",
            Dimension::Force => "N",
            Dimension::Mass => "kg",
            Dimension::Stiffness => "N/m",
            Dimension::Damping => "Ns/m",
            Dimension::Energy => "J",
            Dimension::Frequency => "Hz",
            Dimension::Moment => "Nm",
            Dimension::Angle => "rad",
            Dimension::AngularVelocity => "rad/s",
            Dimension::AngularAcceleration => "rad/s^2",
        }
    }

    /// A lower-case name for messages (`"force"`, `"time"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "dimensionless",
            Dimension::Time => "time",
            Dimension::Length => "length",
            Dimension::Velocity => "velocity",
            Dimension::Acceleration => "acceleration",
            Dimension::Force => "force",
            Dimension::Mass => "mass",
            Dimension::Stiffness => "stiffness",
            Dimension::Damping => "damping",
            Dimension::Energy => "energy",
            Dimension::Frequency => "frequency",
            Dimension::Moment => "moment",
            Dimension::Angle => "angle",
            Dimension::AngularVelocity => "angular velocity",
            Dimension::AngularAcceleration => "angular acceleration",
        }
    }

    /// The unit bumpsim uses to show this dimension to people: the unit a
    /// bumper engineer reads (mm, kN, ms, N/mm, Ns/mm, g), not always SI.
    pub fn display_unit(self) -> Unit {
        let symbol = match self {
            Dimension::Time => "ms",
            Dimension::Length => "mm",
            Dimension::Force => "kN",
            Dimension::Stiffness => "N/mm",
            Dimension::Damping => "Ns/mm",
            Dimension::Acceleration => "g",
            Dimension::Angle => "deg",
            Dimension::AngularVelocity => "deg/s",
            other => other.si_symbol(),
        };
        Unit::parse(symbol).unwrap_or(Unit::si(self))
    }
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A unit: its canonical symbol, dimension and factor to SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// Canonical symbol, e.g. `"kN"`.
    pub symbol: &'static str,
    /// What the unit measures.
    pub dimension: Dimension,
    /// SI value = `factor` × value in this unit.
    pub factor: f64,
}

/// A unit text that is not in bumpsim's table.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("unknown unit '{text}' (known units: {known})")]
pub struct UnitError {
    /// The text as given.
    pub text: String,
    /// The known spellings, for the message.
    pub known: String,
}

/// One row of the unit table: spellings (after normalisation), dimension, factor.
type UnitRow = (&'static [&'static str], Dimension, f64);

/// The unit table. The first spelling is the canonical symbol. Besides the
/// SI spellings it lists what the peers write: pyisomme (astropy's
/// `m / s2`, `N m`, `rad / s2`, which normalise to `m/s2`, `Nm`, `rad/s2`)
/// and NHTSA's upper-case unit codes (`G'S`, `NWT`, `NWM`, `MM`, `DEG`,
/// `DPS`, `SEC`, ...; NHTSA Test Reference Guide, "Units" code table).
const UNITS: &[UnitRow] = &[
    (&["-", "1", "NA", "NON"], Dimension::Dimensionless, 1.0),
    (&["s", "SEC"], Dimension::Time, 1.0),
    (&["ms", "MSC", "MSEC"], Dimension::Time, 1e-3),
    (&["us", "µs", "μs"], Dimension::Time, 1e-6),
    (&["m", "MET"], Dimension::Length, 1.0),
    (&["mm", "MM", "MMS"], Dimension::Length, 1e-3),
    (&["cm", "CM"], Dimension::Length, 1e-2),
    (&["m/s", "MPS"], Dimension::Velocity, 1.0),
    (&["mm/s"], Dimension::Velocity, 1e-3),
    (&["mm/ms"], Dimension::Velocity, 1.0),
    (&["km/h", "kph", "KPH"], Dimension::Velocity, 1.0 / 3.6),
    (&["mph", "MPH"], Dimension::Velocity, 0.447_04),
    (
        &["m/s^2", "m/s2", "m/(s^2)", "m/(ss)"],
        Dimension::Acceleration,
        1.0,
    ),
    (&["mm/s^2", "mm/s2"], Dimension::Acceleration, 1e-3),
    (
        &["g", "G", "g0", "G'S", "GS", "g's"],
        Dimension::Acceleration,
        STANDARD_GRAVITY,
    ),
    (&["N", "NWT"], Dimension::Force, 1.0),
    (&["daN"], Dimension::Force, 10.0),
    (&["kN", "KN", "KNW"], Dimension::Force, 1e3),
    (&["MN"], Dimension::Force, 1e6),
    (&["kg", "KG", "KGM"], Dimension::Mass, 1.0),
    (&["t", "tonne"], Dimension::Mass, 1e3),
    (&["N/m"], Dimension::Stiffness, 1.0),
    (&["N/mm", "kN/m"], Dimension::Stiffness, 1e3),
    (&["kN/mm", "MN/m"], Dimension::Stiffness, 1e6),
    (&["Ns/m"], Dimension::Damping, 1.0),
    (&["Ns/mm", "kNs/m"], Dimension::Damping, 1e3),
    (&["kNs/mm"], Dimension::Damping, 1e6),
    (&["J"], Dimension::Energy, 1.0),
    (&["mJ"], Dimension::Energy, 1e-3),
    (&["kJ"], Dimension::Energy, 1e3),
    (&["Nm", "NWM"], Dimension::Moment, 1.0),
    (&["Nmm"], Dimension::Moment, 1e-3),
    (&["kNm"], Dimension::Moment, 1e3),
    (&["rad", "RAD"], Dimension::Angle, 1.0),
    (
        &["deg", "°", "DEG"],
        Dimension::Angle,
        std::f64::consts::PI / 180.0,
    ),
    (&["rad/s", "RPS", "RDS"], Dimension::AngularVelocity, 1.0),
    (
        &["deg/s", "°/s", "DPS"],
        Dimension::AngularVelocity,
        std::f64::consts::PI / 180.0,
    ),
    (
        &["rad/s^2", "rad/s2", "rad/(s^2)", "rad/(ss)", "RS2"],
        Dimension::AngularAcceleration,
        1.0,
    ),
    (
        &["deg/s^2", "deg/s2", "°/s^2", "°/s2", "DS2"],
        Dimension::AngularAcceleration,
        std::f64::consts::PI / 180.0,
    ),
    (&["Hz", "HZ"], Dimension::Frequency, 1.0),
    (&["kHz"], Dimension::Frequency, 1e3),
];

/// Spellings whose blanks carry meaning: astropy (hence pyisomme) writes the
/// product N·m as `m N`, which without its blank would read as millinewton.
const SPACED: &[(&str, &str)] = &[
    ("m N", "Nm"),
    ("N m", "Nm"),
    ("mm N", "Nmm"),
    ("N mm", "Nmm"),
    ("kN m", "kNm"),
    ("m kN", "kNm"),
];

/// Removes blanks and product signs and writes powers as `^n`.
fn normalise(text: &str) -> String {
    text.trim()
        .replace("**", "^")
        .replace('²', "^2")
        .chars()
        .filter(|c| !matches!(c, ' ' | '\t' | '·' | '*' | '⋅' | '.'))
        .collect()
}

impl Unit {
    /// Parses a unit text such as `kN`, `N·s/m`, `m/s**2` or `km/h`.
    pub fn parse(text: &str) -> Result<Unit, UnitError> {
        let spaced = text.split_whitespace().collect::<Vec<_>>().join(" ");
        let key = SPACED
            .iter()
            .find(|(written, _)| *written == spaced)
            .map_or_else(|| normalise(text), |(_, symbol)| symbol.to_string());
        UNITS
            .iter()
            .find(|(names, _, _)| names.contains(&key.as_str()))
            .map(|&(names, dimension, factor)| Unit {
                symbol: names[0],
                dimension,
                factor,
            })
            .ok_or_else(|| UnitError {
                text: text.to_string(),
                known: UNITS
                    .iter()
                    .map(|(names, _, _)| names[0])
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// The SI unit of a dimension.
    pub fn si(dimension: Dimension) -> Unit {
        Unit {
            symbol: dimension.si_symbol(),
            dimension,
            factor: 1.0,
        }
    }

    /// Converts a value in this unit to SI.
    pub fn to_si(&self, value: f64) -> f64 {
        value * self.factor
    }

    /// Converts an SI value to this unit.
    pub fn from_si(&self, value: f64) -> f64 {
        value / self.factor
    }
}

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol)
    }
}

/// Why asked units cannot be used for a table's columns.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum UnitChoice {
    /// A unit whose dimension no column has.
    #[error("{0}: no column measures {dimension}", dimension = .0.dimension)]
    NoColumn(Unit),
    /// Two units of one dimension (the second was ignored).
    #[error("{second}: {first} was asked for {dimension} already", dimension = .first.dimension)]
    Twice {
        /// The first asked.
        first: Unit,
        /// The second, of the same dimension.
        second: Unit,
    },
}

/// The unit of each column of a table: the one of `asked` that measures
/// the column's dimension, else its SI unit. Every asked unit must apply to
/// some column (time included), and at most one to each dimension.
///
/// ```
/// use bumpsim_core::units::{choose_units, Dimension, Unit};
/// let (ms, kn, n) = (Unit::parse("ms").unwrap(), Unit::parse("kN").unwrap(), Unit::parse("N").unwrap());
/// let chosen = choose_units(&[ms], &[Dimension::Time, Dimension::Force]).unwrap();
/// assert_eq!((chosen[0].symbol, chosen[1].symbol), ("ms", "N"));
/// assert!(choose_units(&[ms], &[Dimension::Force]).is_err());
/// assert!(choose_units(&[kn, n], &[Dimension::Force]).is_err());
/// ```
pub fn choose_units(asked: &[Unit], dimensions: &[Dimension]) -> Result<Vec<Unit>, UnitChoice> {
    if let Some(unused) = asked.iter().find(|u| !dimensions.contains(&u.dimension)) {
        return Err(UnitChoice::NoColumn(*unused));
    }
    for (k, second) in asked.iter().enumerate() {
        if let Some(first) = asked[..k].iter().find(|u| u.dimension == second.dimension) {
            return Err(UnitChoice::Twice {
                first: *first,
                second: *second,
            });
        }
    }
    Ok(dimensions
        .iter()
        .map(|&d| {
            asked
                .iter()
                .copied()
                .find(|u| u.dimension == d)
                .unwrap_or(Unit::si(d))
        })
        .collect())
}

/// A value as an error shows it: plain (`0`, `-5`, `2.2`), or in exponent
/// form where plain would print hundreds of digits (`1e308`, `1e-300`).
///
/// ```
/// use bumpsim_core::units::short;
/// assert_eq!(short(2.5), "2.5");
/// assert_eq!(short(1e-300), "1e-300");
/// assert_eq!(short(-1e308), "-1e308");
/// ```
pub fn short(value: f64) -> String {
    let plain = value == 0.0 || (1e-4..1e15).contains(&value.abs()) || !value.is_finite();
    match plain {
        true => format!("{value}"),
        false => format!("{value:?}"),
    }
}

/// Formats a number with `digits` significant digits: plain notation between
/// 1e-3 and 1e6, scientific outside; trailing zeros are kept so that columns
/// of numbers read alike.
pub fn format_number(value: f64, digits: usize) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    if value == 0.0 {
        return "0".to_string();
    }
    let digits = digits.max(1);
    let exponent = value.abs().log10().floor() as i32;
    if (-3..6).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.prec$e}", prec = digits - 1)
    }
}

/// Formats an SI value in the display unit of its dimension with four
/// significant digits, e.g. `Dimension::Force, 40_000.0` → `"40.00 kN"`.
///
/// ```
/// use bumpsim_core::units::{format_quantity, Dimension};
/// assert_eq!(format_quantity(0.1234, Dimension::Length), "123.4 mm");
/// assert_eq!(format_quantity(5.0e5, Dimension::Stiffness), "500.0 N/mm");
/// // a time below a picosecond is the rounding of a sum of steps
/// assert_eq!(format_quantity(-6.939e-18, Dimension::Time), "0 ms");
/// ```
pub fn format_quantity(value_si: f64, dimension: Dimension) -> String {
    let noise = dimension == Dimension::Time && value_si.abs() < TIME_NOISE;
    format_in(if noise { 0.0 } else { value_si }, dimension.display_unit())
}

/// Times below this (s) print as 0: records are sampled every nanosecond
/// or slower (the readers' limit), so a smaller time is the rounding error
/// of a sum of steps (`-6.939e-15 ms` was printed for a time zero).
pub const TIME_NOISE: f64 = 1e-12;

/// Formats an SI value in a chosen unit with four significant digits.
pub fn format_in(value_si: f64, unit: Unit) -> String {
    format!(
        "{} {}",
        format_number(unit.from_si(value_si), 4),
        unit.symbol
    )
}

/// A time `t` (s) of a record sampled every `step` (s), in ms rounded to
/// the sample: as many decimals as the step needs (a 1/30 ms step gives
/// two), so that a contact starting one sample in reads `0.03 ms`, not
/// `0.03333 ms`, and the rounding error of a sum of steps (`-6.939e-15 ms`)
/// reads `0 ms`. Without a usable step, [`format_quantity`].
///
/// ```
/// use bumpsim_core::units::format_time_at;
/// assert_eq!(format_time_at(1.0 / 30_000.0, 1.0 / 30_000.0), "0.03 ms");
/// assert_eq!(format_time_at(-6.939e-18, 1e-4), "0.0 ms");
/// assert_eq!(format_time_at(0.2424, 1e-5), "242.40 ms");
/// ```
pub fn format_time_at(t: f64, step: f64) -> String {
    let step_ms = step * 1e3;
    if !(step_ms.is_finite() && step_ms > 0.0 && t.is_finite()) {
        return format_quantity(t, Dimension::Time);
    }
    let decimals = (-step_ms.log10()).ceil().clamp(0.0, 9.0) as usize;
    let ms = match (t * 1e3).abs() < 0.5 * step_ms {
        true => 0.0,
        false => t * 1e3,
    };
    format!("{ms:.decimals$} ms")
}

/// Splits a label `name [unit]` (a table's column header, a campaign's
/// derived quantity `expression [unit]`) into its name and unit, both
/// trimmed; the unit is the text in the last brackets, which must end the
/// label. `None` when there is no such unit or no name before it.
///
/// ```
/// use bumpsim_core::units::split_unit;
/// assert_eq!(split_unit(" force [kN] "), Some(("force", "kN")));
/// assert_eq!(split_unit("2 * t_rail [m]"), Some(("2 * t_rail", "m")));
/// assert_eq!(split_unit("force"), None);
/// ```
pub fn split_unit(label: &str) -> Option<(&str, &str)> {
    let label = label.trim();
    let open = label.rfind('[')?;
    let unit = label[open + 1..].strip_suffix(']')?;
    let name = label[..open].trim();
    (!name.is_empty()).then_some((name, unit.trim()))
}

/// Parses a quantity written as a number with an optional unit, such as
/// `"1.67"`, `"6 km/h"` or `"6km/h"`. A bare number is taken in SI. The unit
/// must measure `expected`.
///
/// ```
/// use bumpsim_core::units::{parse_quantity, Dimension};
/// let v = parse_quantity("36 km/h", Dimension::Velocity).unwrap();
/// assert!((v - 10.0).abs() < 1e-12);
/// assert!(parse_quantity("36 kN", Dimension::Velocity).is_err());
/// ```
pub fn parse_quantity(text: &str, expected: Dimension) -> Result<f64, QuantityError> {
    let text = text.trim();
    let split = text
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || "+-.eE".contains(c)) || is_unit_start(text, i))
        .map_or(text.len(), |(i, _)| i);
    let (number, unit_text) = text.split_at(split);
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| QuantityError::NotANumber(text.to_string()))?;
    if !value.is_finite() {
        return Err(QuantityError::NotANumber(text.to_string()));
    }
    if unit_text.trim().is_empty() {
        return Ok(value);
    }
    let unit = Unit::parse(unit_text)?;
    if unit.dimension != expected {
        return Err(QuantityError::WrongDimension {
            text: text.to_string(),
            expected,
            found: unit.dimension,
        });
    }
    Ok(unit.to_si(value))
}

/// An `e`/`E` that starts a unit rather than an exponent (no digit or sign follows).
fn is_unit_start(text: &str, i: usize) -> bool {
    let bytes = text.as_bytes();
    matches!(bytes[i], b'e' | b'E')
        && !bytes
            .get(i + 1)
            .is_some_and(|b| b.is_ascii_digit() || *b == b'-' || *b == b'+')
}

/// A quantity text that could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuantityError {
    /// The number part is missing or not a finite number.
    #[error("'{0}' is not a finite number with an optional unit (e.g. 1.67 or 6 km/h)")]
    NotANumber(String),
    /// The unit is unknown.
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// The unit measures something else.
    #[error("'{text}' is a {found}, expected a {expected}")]
    WrongDimension {
        /// The text as given.
        text: String,
        /// What was expected.
        expected: Dimension,
        /// What the unit measures.
        found: Dimension,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn spellings_of_one_unit_agree() {
        for text in ["N·s/m", "N*s/m", "N s/m", "Ns/m", " N.s/m "] {
            let unit = Unit::parse(text).unwrap();
            assert_eq!(unit.dimension, Dimension::Damping, "{text}");
            assert_relative_eq!(unit.factor, 1.0);
        }
        assert_eq!(
            Unit::parse("m/s**2").unwrap().dimension,
            Dimension::Acceleration
        );
        assert_eq!(
            Unit::parse("m/s²").unwrap().dimension,
            Dimension::Acceleration
        );
    }

    /// Every spelling pyisomme (astropy) and NHTSA write, with what it means.
    #[test]
    fn peer_spellings_are_known() {
        use std::f64::consts::PI;
        let cases = [
            // pyisomme / astropy
            ("m / s2", Dimension::Acceleration, 1.0),
            ("m/s**2", Dimension::Acceleration, 1.0),
            ("m/(s*s)", Dimension::Acceleration, 1.0),
            ("g", Dimension::Acceleration, STANDARD_GRAVITY),
            ("m / s", Dimension::Velocity, 1.0),
            ("km / h", Dimension::Velocity, 1.0 / 3.6),
            ("m N", Dimension::Moment, 1.0),
            ("N m", Dimension::Moment, 1.0),
            ("Nm", Dimension::Moment, 1.0),
            ("N·m", Dimension::Moment, 1.0),
            ("rad / s", Dimension::AngularVelocity, 1.0),
            ("deg / s", Dimension::AngularVelocity, PI / 180.0),
            ("rad / s2", Dimension::AngularAcceleration, 1.0),
            ("rad/(s*s)", Dimension::AngularAcceleration, 1.0),
            ("deg", Dimension::Angle, PI / 180.0),
            ("°", Dimension::Angle, PI / 180.0),
            ("rad", Dimension::Angle, 1.0),
            ("1", Dimension::Dimensionless, 1.0),
            // NHTSA EV5 unit codes
            ("G'S", Dimension::Acceleration, STANDARD_GRAVITY),
            ("NWT", Dimension::Force, 1.0),
            ("NWM", Dimension::Moment, 1.0),
            ("KNW", Dimension::Force, 1e3),
            ("MM", Dimension::Length, 1e-3),
            ("MMS", Dimension::Length, 1e-3),
            ("DEG", Dimension::Angle, PI / 180.0),
            ("DPS", Dimension::AngularVelocity, PI / 180.0),
            ("MPS", Dimension::Velocity, 1.0),
            ("KPH", Dimension::Velocity, 1.0 / 3.6),
            ("SEC", Dimension::Time, 1.0),
            ("MSC", Dimension::Time, 1e-3),
        ];
        for (text, dimension, factor) in cases {
            let unit = Unit::parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_eq!(unit.dimension, dimension, "{text}");
            assert_relative_eq!(unit.factor, factor, max_relative = 1e-15);
        }
        assert_eq!(Unit::parse("J").unwrap().dimension, Dimension::Energy);
        assert_eq!(Unit::parse("mN").unwrap_err().text, "mN");
    }

    #[test]
    fn every_dimension_writes_a_symbol_it_reads_back() {
        use Dimension::*;
        for d in [
            Dimensionless,
            Time,
            Length,
            Velocity,
            Acceleration,
            Force,
            Mass,
            Stiffness,
            Damping,
            Energy,
            Frequency,
            Moment,
            Angle,
            AngularVelocity,
            AngularAcceleration,
        ] {
            let unit = Unit::parse(&d.si_symbol().replace('^', "**")).unwrap();
            assert_eq!((unit.dimension, unit.factor), (d, 1.0), "{d}");
            assert_eq!(d.display_unit().dimension, d);
        }
    }

    #[test]
    fn factors_convert_to_si() {
        let cases = [
            ("ms", 2.0, 2e-3),
            ("kN", 3.0, 3e3),
            ("mm", 5.0, 5e-3),
            ("km/h", 36.0, 10.0),
            ("g", 1.0, 9.80665),
            ("t", 1.5, 1500.0),
            ("N/mm", 4.0, 4e3),
            ("Ns/mm", 0.2, 200.0),
        ];
        for (text, value, si) in cases {
            assert_relative_eq!(
                Unit::parse(text).unwrap().to_si(value),
                si,
                max_relative = 1e-15
            );
        }
    }

    #[test]
    fn unknown_and_case_errors_are_reported() {
        let err = Unit::parse("Mm").unwrap_err();
        assert!(err.to_string().contains("unknown unit 'Mm'"), "{err}");
        assert!(Unit::parse("").is_err());
    }

    #[test]
    fn quantities_parse_with_and_without_unit() {
        assert_relative_eq!(parse_quantity("1.67", Dimension::Velocity).unwrap(), 1.67);
        assert_relative_eq!(
            parse_quantity("6km/h", Dimension::Velocity).unwrap(),
            6.0 / 3.6
        );
        assert_relative_eq!(
            parse_quantity("1e3 mm/s", Dimension::Velocity).unwrap(),
            1.0
        );
        assert!(parse_quantity("fast", Dimension::Velocity).is_err());
        assert!(parse_quantity("nan", Dimension::Velocity).is_err());
    }

    /// The cases of the two splitters this one replaces: the table's
    /// headers and the campaign's derived quantities.
    #[test]
    fn labels_split_into_name_and_unit() {
        assert_eq!(split_unit(" force [kN] "), Some(("force", "kN")));
        assert_eq!(split_unit("a [b] [N/mm]"), Some(("a [b]", "N/mm")));
        assert_eq!(
            split_unit("5.0e5 * m3 / 1670 [ N/m ]"),
            Some(("5.0e5 * m3 / 1670", "N/m"))
        );
        assert_eq!(split_unit("y * 2 [kg]  "), Some(("y * 2", "kg")));
        assert_eq!(split_unit("x []"), Some(("x", "")));
        assert_eq!(split_unit("force"), None);
        assert_eq!(split_unit("a + b"), None);
        assert_eq!(split_unit("[kN]"), None);
        assert_eq!(split_unit("  [kN]"), None);
        assert_eq!(split_unit("force [kN] x"), None);
        assert_eq!(split_unit("force kN]"), None);
    }

    #[test]
    fn numbers_format_with_significant_digits() {
        assert_eq!(format_number(123.456, 4), "123.5");
        assert_eq!(format_number(0.012345, 3), "0.0123");
        assert_eq!(format_number(1.5e7, 3), "1.50e7");
        assert_eq!(format_quantity(40_000.0, Dimension::Force), "40.00 kN");
        assert_eq!(format_quantity(9.80665, Dimension::Acceleration), "1.000 g");
    }
}
