//! Measured channels: a sampled signal with its identity.
//!
//! A crash-test channel is a [`UniformSeries`] in SI units plus what a test
//! engineer uses to find it again: the channel code (ISO/TS 13499 16-character
//! code, or the NHTSA `SENSOR-LOCATION-AXIS` triple), a human name, the
//! physical [`Dimension`], the unit the file was written in, and free-form
//! metadata (`key`, `value`) copied from the file header.
//!
//! Sign convention: values keep the sign of the file they came from; scaling
//! and sign changes are explicit processing steps (bumpsim-signal).
//!
//! An ISO/TS 13499 code follows the processing ([`Channel::filtered`],
//! [`Channel::with_dimension`], [`Channel::scaled`]): a CFC filter sets the
//! filter-class letter (CFC 1000 `A`, 600 `B`, 180 `C`, 60 `D`, 20 `L`, any
//! other cut-off `S` "special filter") and records `Channel frequency
//! class`; integration and derivation set the physical-dimension letters
//! (`AC` → `VE` → `DS`, `AA` → `AV` → `AN`, `AC` → `FO` for F = m a); the
//! standard has no letter for a reversed axis, so a sign change keeps the
//! direction letter and says so in `Comments`. Other codes (NHTSA, CSV
//! names) are left as they are.
//!
//! ```
//! use bumpsim_core::channel::Channel;
//! use bumpsim_core::series::UniformSeries;
//! use bumpsim_core::units::Dimension;
//! let series = UniformSeries::new(0.0, 1e-4, vec![0.0, 9.80665]).unwrap();
//! let accel = Channel::new("10SIMELE0000ACXP", "Sill left X", Dimension::Acceleration, series);
//! assert_eq!(accel.dimension.si_symbol(), "m/s^2");
//! ```

use crate::series::UniformSeries;
use crate::units::Dimension;
use std::fmt;

/// The fields of a 16-character ISO/TS 13499 channel code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChannelCode {
    /// Test object: `0`..`9` vehicles, `P` pendulum / impactor, `B` barrier, `D` dummy...
    pub test_object: char,
    /// Position (seat or side).
    pub position: char,
    /// Main location, 4 characters (`SIME` sill/side member, `HEAD`, `IMPA` impactor).
    pub main_location: String,
    /// Fine locations 1, 2 and 3, 2 characters each.
    pub fine_locations: [String; 3],
    /// Physical dimension, 2 characters (`AC`, `FO`, `DS`, `VE`).
    pub dimension: String,
    /// Direction (`X`, `Y`, `Z`, `R`, `0`).
    pub direction: char,
    /// Filter class (`A` CFC 1000, `B` 600, `C` 180, `D` 60, `P` prefiltered, `0`/`X` none).
    pub filter_class: char,
}

impl ChannelCode {
    /// Splits a 16-character code of ASCII letters and digits; `None` otherwise.
    pub fn parse(code: &str) -> Option<ChannelCode> {
        let c: Vec<char> = code.trim().chars().collect();
        if c.len() != 16 || !c.iter().all(|ch| ch.is_ascii_alphanumeric()) {
            return None;
        }
        let s = |a: usize, b: usize| c[a..b].iter().collect::<String>();
        Some(ChannelCode {
            test_object: c[0],
            position: c[1],
            main_location: s(2, 6),
            fine_locations: [s(6, 8), s(8, 10), s(10, 12)],
            dimension: s(12, 14),
            direction: c[14],
            filter_class: c[15],
        })
    }

    /// The CFC the filter-class letter stands for, if any.
    pub fn cfc(&self) -> Option<f64> {
        match self.filter_class.to_ascii_uppercase() {
            'A' | 'E' => Some(1000.0),
            'B' | 'F' => Some(600.0),
            'C' | 'G' => Some(180.0),
            'D' | 'H' => Some(60.0),
            'L' => Some(20.0),
            _ => None,
        }
    }

    /// The filter-class letter of a CFC: `A` 1000, `B` 600, `C` 180, `D` 60,
    /// `L` 20, `S` (special filter) for any other class.
    pub fn filter_letter(cfc: f64) -> char {
        [
            (1000.0, 'A'),
            (600.0, 'B'),
            (180.0, 'C'),
            (60.0, 'D'),
            (20.0, 'L'),
        ]
        .iter()
        .find(|(class, _)| (cfc - class).abs() < 1e-9)
        .map_or('S', |&(_, letter)| letter)
    }

    /// The ISO/TS 13499 physical-dimension letters of a dimension (`None`
    /// for stiffness and damping, which are no channel quantities).
    pub fn dimension_letters(dimension: Dimension) -> Option<&'static str> {
        Some(match dimension {
            Dimension::Dimensionless => "00",
            Dimension::Time => "TI",
            Dimension::Length => "DS",
            Dimension::Velocity => "VE",
            Dimension::Acceleration => "AC",
            Dimension::Force => "FO",
            Dimension::Mass => "MA",
            Dimension::Energy => "EN",
            Dimension::Frequency => "FR",
            Dimension::Moment => "MO",
            Dimension::Angle => "AN",
            Dimension::AngularVelocity => "AV",
            Dimension::AngularAcceleration => "AA",
            Dimension::Stiffness | Dimension::Damping => return None,
        })
    }
}

impl fmt::Display for ChannelCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [f1, f2, f3] = &self.fine_locations;
        write!(
            f,
            "{}{}{}{f1}{f2}{f3}{}{}{}",
            self.test_object,
            self.position,
            self.main_location,
            self.dimension,
            self.direction,
            self.filter_class
        )
    }
}

/// A sampled channel in SI units with its code, name and metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Channel code (ISO-MME code, NHTSA triple, or CSV column name).
    pub code: String,
    /// Human-readable name.
    pub name: String,
    /// Physical dimension; values are in its SI unit.
    pub dimension: Dimension,
    /// The samples, SI.
    pub series: UniformSeries,
    /// The unit as written in the source file (for reports; values are SI).
    pub source_unit: String,
    /// Header fields copied from the source, in file order.
    pub metadata: Vec<(String, String)>,
}

impl Channel {
    /// A channel without metadata whose source unit is the SI unit.
    pub fn new(code: &str, name: &str, dimension: Dimension, series: UniformSeries) -> Channel {
        Channel {
            code: code.to_string(),
            name: name.to_string(),
            dimension,
            series,
            source_unit: dimension.si_symbol().to_string(),
            metadata: Vec::new(),
        }
    }

    /// The value of a metadata key (first occurrence), if present.
    pub fn meta(&self, key: &str) -> Option<&str> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// Sets a metadata key (replacing its first occurrence, or appending).
    pub fn set_meta(&mut self, key: &str, value: &str) {
        match self.metadata.iter_mut().find(|(k, _)| k == key) {
            Some(entry) => entry.1 = value.to_string(),
            None => self.metadata.push((key.to_string(), value.to_string())),
        }
    }

    /// Records a CFC filter of class `cfc`: the ISO code's filter-class
    /// letter and the `Channel frequency class` field.
    pub fn filtered(mut self, cfc: f64) -> Channel {
        if let Some(mut code) = ChannelCode::parse(&self.code) {
            code.filter_class = ChannelCode::filter_letter(cfc);
            self.code = code.to_string();
        }
        self.set_meta("Channel frequency class", &format!("{cfc}"));
        self
    }

    /// Records a change of physical dimension (integration, derivation,
    /// F = m a): the dimension, the SI source unit and the ISO code's
    /// dimension letters.
    pub fn with_dimension(mut self, dimension: Dimension) -> Channel {
        let letters = ChannelCode::dimension_letters(dimension);
        if let (Some(mut code), Some(letters)) = (ChannelCode::parse(&self.code), letters) {
            code.dimension = letters.to_string();
            self.code = code.to_string();
        }
        self.dimension = dimension;
        self.source_unit = dimension.si_symbol().to_string();
        self
    }

    /// Records a scaling by `factor`; a negative factor reverses the sign
    /// relative to the reference system, which ISO/TS 13499 codes cannot
    /// express, so it is written to `Comments`.
    pub fn scaled(mut self, factor: f64) -> Channel {
        if factor < 0.0 {
            let note = format!("sign reversed: scaled by {factor}");
            let comments = match self.meta("Comments") {
                Some(old) if !old.is_empty() && !old.eq_ignore_ascii_case("NOVALUE") => {
                    format!("{old}; {note}")
                }
                _ => note,
            };
            self.set_meta("Comments", &comments);
        }
        self
    }

    /// A copy with other values on the same identity (used by processing steps).
    pub fn with_series(&self, series: UniformSeries) -> Channel {
        Channel {
            series,
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_identity_when_values_change() {
        let s = UniformSeries::new(0.0, 1.0, vec![1.0, 2.0]).unwrap();
        let mut c = Channel::new("A", "a", Dimension::Force, s);
        c.metadata.push(("Unit".into(), "kN".into()));
        let d = c.with_series(UniformSeries::new(0.0, 1.0, vec![3.0]).unwrap());
        assert_eq!(d.code, "A");
        assert_eq!(d.meta("Unit"), Some("kN"));
        assert_eq!(d.meta("none"), None);
        assert_eq!(d.series.len(), 1);
    }

    #[test]
    fn iso_codes_follow_the_processing() {
        let s = UniformSeries::new(0.0, 1.0, vec![1.0, 2.0]).unwrap();
        let c = Channel::new("10SIMELE0000ACXP", "a", Dimension::Acceleration, s);
        let f = c.filtered(180.0);
        assert_eq!(f.code, "10SIMELE0000ACXC");
        assert_eq!(f.meta("Channel frequency class"), Some("180"));
        let v = f.with_dimension(Dimension::Velocity);
        assert_eq!(v.code, "10SIMELE0000VEXC");
        let d = v
            .with_dimension(Dimension::Length)
            .filtered(33.0)
            .scaled(-1.0);
        assert_eq!(d.code, "10SIMELE0000DSXS");
        assert!(d.meta("Comments").unwrap().contains("sign reversed"));
        let nhtsa = Channel::new(
            "1-AC-FLLR-XG",
            "x",
            Dimension::Acceleration,
            d.series.clone(),
        );
        assert_eq!(nhtsa.filtered(60.0).code, "1-AC-FLLR-XG");
        let code = ChannelCode::parse("10SIMELE0000ACXD").unwrap();
        assert_eq!(
            (code.main_location.as_str(), code.cfc()),
            ("SIME", Some(60.0))
        );
        assert!(ChannelCode::parse("1-AC-FLLR-XG-R-1").is_none());
    }
}
