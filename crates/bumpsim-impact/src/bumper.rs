//! Bumper force–compression characteristics (paper A, spec §5).
//!
//! Loading follows either the three-part curve of paper A — a ramp of slope
//! `s` up to the plateau `F_max` — or a tabulated curve (linear between
//! points, constant after the last). From the largest compression reached,
//! `d_max` with force `F_peak`, the bumper unloads elastically along the line
//! of slope `s_u`: `F = max(0, F_peak − s_u (d_max − d))`, and reloads along
//! the same line until it meets the loading curve again. There is no
//! tension. The permanent (remaining) compression is `d_max − F_peak / s_u`.
//!
//! Sign convention: compression `d` ≥ 0 shortens the bumper; the force
//! `F` ≥ 0 pushes the two sides apart. SI: m, N, N/m.
//!
//! ```
//! use bumpsim_impact::bumper::{Bumper, BumperState};
//! let b = Bumper::three_part(2e6, 60e3, 8e6).unwrap();
//! let mut s = BumperState::default();
//! assert!((b.force(0.01, &mut s) - 20e3).abs() < 1e-9);   // on the ramp
//! assert!((b.force(0.05, &mut s) - 60e3).abs() < 1e-9);   // on the plateau
//! assert!((b.force(0.045, &mut s) - 20e3).abs() < 1e-6);  // unloading at s_u
//! assert!((b.remaining(&s) - 0.0425).abs() < 1e-12);
//! ```

use serde::Deserialize;
use std::path::Path;

/// Why a bumper is not valid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BumperError {
    /// A parameter is out of range.
    #[error("bumper {name} = {value:?}: {expected}")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is allowed.
        expected: String,
    },
    /// The file cannot be read.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

/// The loading part of a characteristic.
#[derive(Debug, Clone, PartialEq)]
pub enum Loading {
    /// Ramp of slope `ramp` (N/m) up to the plateau `plateau` (N).
    ThreePart {
        /// Ramp slope s, N/m.
        ramp: f64,
        /// Plateau F_max, N.
        plateau: f64,
    },
    /// Tabulated (compression m, force N), from (0, 0), compression increasing.
    Table {
        /// Compressions, m.
        compression: Vec<f64>,
        /// Forces, N.
        force: Vec<f64>,
    },
}

/// A bumper characteristic: loading curve and unloading slope.
#[derive(Debug, Clone, PartialEq)]
pub struct Bumper {
    loading: Loading,
    unloading: f64,
}

/// The history a bumper remembers: largest compression and its force.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct BumperState {
    /// Largest compression reached, m.
    pub max_compression: f64,
    /// Force at the largest compression, N.
    pub peak_force: f64,
}

fn positive(name: &'static str, value: f64) -> Result<f64, BumperError> {
    match value.is_finite() && value > 0.0 {
        true => Ok(value),
        false => Err(BumperError::Parameter {
            name,
            value,
            expected: "must be a positive finite number".into(),
        }),
    }
}

impl Bumper {
    /// Paper A's three-part characteristic. The unloading slope must be at
    /// least the ramp slope: a shallower line would run below the ramp and
    /// the bumper would unload with more force than it loaded.
    pub fn three_part(ramp: f64, plateau: f64, unloading: f64) -> Result<Bumper, BumperError> {
        let ramp = positive("ramp (N/m)", ramp)?;
        let plateau = positive("plateau (N)", plateau)?;
        let unloading = positive("unloading (N/m)", unloading)?;
        if unloading < ramp {
            let expected =
                format!("the unloading slope must be at least the ramp slope {ramp} N/m");
            return Err(BumperError::Parameter {
                name: "unloading (N/m)",
                value: unloading,
                expected,
            });
        }
        Ok(Bumper {
            loading: Loading::ThreePart { ramp, plateau },
            unloading,
        })
    }

    /// A tabulated loading curve: compressions increasing from 0 (m), forces
    /// ≥ 0 starting at 0 (N); the unloading slope must be at least the
    /// steepest secant from the origin.
    pub fn table(
        compression: Vec<f64>,
        force: Vec<f64>,
        unloading: f64,
    ) -> Result<Bumper, BumperError> {
        let unloading = positive("unloading (N/m)", unloading)?;
        let bad = |name, value, expected: &str| {
            Err(BumperError::Parameter {
                name,
                value,
                expected: expected.into(),
            })
        };
        if compression.len() != force.len() || compression.len() < 2 {
            return bad(
                "curve points",
                compression.len() as f64,
                "at least 2 (compression, force) pairs of equal length",
            );
        }
        if compression[0] != 0.0 || force[0] != 0.0 {
            return bad(
                "first curve point",
                compression[0],
                "the curve starts at (0 m, 0 N)",
            );
        }
        if let Some(w) = compression
            .windows(2)
            .find(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        {
            return bad("curve compression (m)", w[1], "compressions must increase");
        }
        if let Some(&f) = force.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
            return bad(
                "curve force (N)",
                f,
                "forces must be finite and not negative",
            );
        }
        let secant = compression
            .iter()
            .zip(&force)
            .skip(1)
            .map(|(d, f)| f / d)
            .fold(0.0, f64::max);
        if unloading < secant {
            return bad(
                "unloading (N/m)",
                unloading,
                &format!("must be at least the steepest secant of the curve, {secant} N/m"),
            );
        }
        Ok(Bumper {
            loading: Loading::Table { compression, force },
            unloading,
        })
    }

    /// The loading curve.
    pub fn loading(&self) -> &Loading {
        &self.loading
    }

    /// The loading curve as (compression m, force N) points from (0, 0): a
    /// table as given; the three-part curve as its knee and a plateau point
    /// at ten times the knee's compression (solvers hold the last value or
    /// extend the last, flat segment beyond it).
    pub fn loading_points(&self) -> Vec<(f64, f64)> {
        match &self.loading {
            Loading::ThreePart { ramp, plateau } => {
                let knee = plateau / ramp;
                vec![(0.0, 0.0), (knee, *plateau), (10.0 * knee, *plateau)]
            }
            Loading::Table { compression, force } => compression
                .iter()
                .copied()
                .zip(force.iter().copied())
                .collect(),
        }
    }

    /// The unloading slope s_u, N/m.
    pub fn unloading_slope(&self) -> f64 {
        self.unloading
    }

    /// Force on the loading curve at compression `d` ≥ 0, N.
    pub fn loading_force(&self, d: f64) -> f64 {
        match &self.loading {
            Loading::ThreePart { ramp, plateau } => (ramp * d).min(*plateau),
            Loading::Table { compression, force } => {
                let i = compression.partition_point(|&c| c <= d);
                match i {
                    0 => 0.0,
                    i if i == compression.len() => force[i - 1],
                    i => {
                        force[i - 1]
                            + (force[i] - force[i - 1]) * (d - compression[i - 1])
                                / (compression[i] - compression[i - 1])
                    }
                }
            }
        }
    }

    /// Area under the loading curve from 0 to `d`, J.
    pub fn loading_energy(&self, d: f64) -> f64 {
        match &self.loading {
            Loading::ThreePart { ramp, plateau } => {
                let knee = plateau / ramp;
                if d <= knee {
                    0.5 * ramp * d * d
                } else {
                    0.5 * plateau * knee + plateau * (d - knee)
                }
            }
            Loading::Table { compression, .. } => {
                let mut points: Vec<f64> = compression.iter().copied().filter(|&c| c < d).collect();
                points.push(d.max(0.0));
                points
                    .windows(2)
                    .map(|w| {
                        0.5 * (w[1] - w[0]) * (self.loading_force(w[0]) + self.loading_force(w[1]))
                    })
                    .sum()
            }
        }
    }

    /// The force at compression `d`, updating the remembered history.
    pub fn force(&self, d: f64, state: &mut BumperState) -> f64 {
        if d >= state.max_compression {
            state.max_compression = d;
            state.peak_force = self.loading_force(d);
            return state.peak_force;
        }
        (state.peak_force - self.unloading * (state.max_compression - d)).max(0.0)
    }

    /// The permanent compression after unloading, m.
    pub fn remaining(&self, state: &BumperState) -> f64 {
        (state.max_compression - state.peak_force / self.unloading).max(0.0)
    }

    /// The bumper with its force scaled by `factor` at every compression
    /// (and its unloading slope with it).
    ///
    /// ```
    /// let b = bumpsim_impact::Bumper::three_part(1e6, 5e4, 2e6)?.scaled(1.1)?;
    /// assert!((b.loading_force(1.0) - 5.5e4).abs() < 1e-6);
    /// # Ok::<(), bumpsim_impact::BumperError>(())
    /// ```
    pub fn scaled(&self, factor: f64) -> Result<Bumper, BumperError> {
        let unloading = self.unloading * factor;
        match &self.loading {
            Loading::ThreePart { ramp, plateau } => {
                Bumper::three_part(ramp * factor, plateau * factor, unloading)
            }
            Loading::Table { compression, force } => {
                let force = force.iter().map(|f| f * factor).collect();
                Bumper::table(compression.clone(), force, unloading)
            }
        }
    }

    /// The steepest slope of the characteristic, N/m (for the time step).
    pub fn stiffest(&self) -> f64 {
        let loading = match &self.loading {
            Loading::ThreePart { ramp, .. } => *ramp,
            Loading::Table { compression, force } => compression
                .windows(2)
                .zip(force.windows(2))
                .map(|(c, f)| ((f[1] - f[0]) / (c[1] - c[0])).abs())
                .fold(0.0, f64::max),
        };
        loading.max(self.unloading)
    }

    /// Reads a bumper TOML file: `ramp` (N/m), `plateau` (N), `unloading`
    /// (N/m); or `unloading` and `curve = [[d, F], ...]` (m, N).
    pub fn read(path: &Path) -> Result<Bumper, BumperError> {
        let error = |message: String| BumperError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| error(format!("cannot read: {e}")))?;
        let file: BumperFile =
            toml::from_str(&text).map_err(|e| error(bumpsim_io::toml_message(&text, &e)))?;
        let result = match (file.ramp, file.plateau, file.curve) {
            (Some(ramp), Some(plateau), None) => Bumper::three_part(ramp, plateau, file.unloading),
            (None, None, Some(curve)) => {
                let (d, f) = curve.iter().map(|p| (p[0], p[1])).unzip();
                Bumper::table(d, f, file.unloading)
            }
            _ => {
                return Err(error(
                    "give either `ramp` and `plateau`, or `curve` (with `unloading` in both cases)"
                        .into(),
                ));
            }
        };
        result.map_err(|e| error(e.to_string()))
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BumperFile {
    ramp: Option<f64>,
    plateau: Option<f64>,
    unloading: f64,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional_list")]
    curve: Option<Vec<[f64; 2]>>,
    #[allow(dead_code)]
    name: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_parameters_are_refused() {
        assert!(Bumper::three_part(-1.0, 1e4, 1e6).is_err());
        assert!(Bumper::three_part(1e6, 0.0, 1e6).is_err());
        let err = Bumper::three_part(2e6, 1e4, 1e6).unwrap_err().to_string();
        assert!(err.contains("at least the ramp slope"), "{err}");
        assert!(Bumper::table(vec![0.0, 0.01], vec![0.0, 1e4], 1e5).is_err());
        assert!(Bumper::table(vec![0.0, 0.01, 0.01], vec![0.0, 1e4, 2e4], 1e7).is_err());
    }

    #[test]
    fn table_interpolates_and_integrates() {
        let b = Bumper::table(vec![0.0, 0.02, 0.05], vec![0.0, 4e4, 5e4], 5e6).unwrap();
        assert!((b.loading_force(0.01) - 2e4).abs() < 1e-9);
        assert!((b.loading_force(0.1) - 5e4).abs() < 1e-9);
        assert!((b.loading_energy(0.05) - (400.0 + 1350.0)).abs() < 1e-9);
        let three = Bumper::three_part(2e6, 4e4, 5e6).unwrap();
        assert!((three.loading_energy(0.03) - (400.0 + 400.0)).abs() < 1e-9);
        let mut s = BumperState::default();
        three.force(0.03, &mut s);
        assert_eq!(three.force(-0.01, &mut s), 0.0);
        assert!(
            (three.force(0.03, &mut s) - 4e4).abs() < 1e-9,
            "reloads along the unloading line"
        );
    }
}
