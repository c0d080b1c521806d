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
}
