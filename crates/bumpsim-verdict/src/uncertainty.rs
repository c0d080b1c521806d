//! The car's uncertainty for the probability of passing (issue 39, item
//! 4; [`crate::probability`]).
//!
//! The car's parameters are log-normal around the car file's values:
//! `ln θᵢ = ln θ̂ᵢ + σᵢ zᵢ`, `z ~ N(0, R)`, with `σᵢ` the standard
//! deviation of `ln θᵢ` and `R` their correlation. Two sources:
//!
//! - a planar identification's JSON (`bumpsim identify --json` on a
//!   planar study): `σᵢ = SEᵢ/θ̂ᵢ`, its delta-method standard error over
//!   its estimate (the estimation layer's `Cov(ln θ) = σ² (JᵀJ)⁻¹`, AR(1)
//!   inflated; [`bumpsim_estimate::uncertainty`]), and `R` its correlation
//!   of the log parameters. The spreads are applied to the car file's
//!   values (the identified car's, usually). Parameters without a standard
//!   error (fixed, at a bound, not determined) and the lines of action are
//!   left out, and said;
//! - a TOML file of relative standard deviations, independent:
//!   `[uncertainty]` then `"body.mass" = 0.02`, one key per parameter.
//!
//! Names as in the car file and the identification: `body.mass`,
//! `body.yaw_inertia`, `left.masses[0]` (`dampers`, `springs`; `right`
//! alike), `tyres.mu_lateral`, `tyres.cornering_stiffness` (both axles),
//! and `bumper.force` (every segment's force scaled alike).
//!
//! A draw is `z = L u`, `L` the Cholesky factor of `R` and `u` standard
//! normal from the stream of the seed and the draw's index
//! ([`bumpsim_estimate::search::Draws`]), so any thread count gives the
//! same draws.

use crate::error::{VerdictError, require};
use bumpsim_estimate::posterior::gaussian;
use bumpsim_estimate::propagate::Probability;
use bumpsim_estimate::search::Draws;
use bumpsim_planar::PlanarCar;
use serde::Serialize;
use std::path::Path;

/// The car's uncertain parameters: log-normal, correlated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uncertainty {
    /// Where it comes from (the file).
    pub source: String,
    /// The parameters, by their car-file names.
    pub names: Vec<String>,
    /// Standard deviation of each parameter's logarithm, 1.
    pub log_sd: Vec<f64>,
    /// Their correlation (identity when independent).
    pub correlation: Vec<Vec<f64>>,
    /// Parameters of the source not propagated, and why.
    pub left_out: Vec<String>,
}

/// What a propagation ran and gave.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Propagation {
    /// The uncertainty propagated.
    pub uncertainty: Uncertainty,
    /// Draws asked for.
    pub samples: usize,
    /// The seed.
    pub seed: u64,
    /// Draws whose car or run failed.
    pub failed: usize,
    /// The probability that every test passes.
    pub passing: Probability,
}

/// Where a parameter lives in the planar car.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Part {
    Mass,
    YawInertia,
    Chain {
        left: bool,
        kind: usize,
        index: usize,
    },
    MuLateral,
    Cornering,
    BumperForce,
}

/// The part a name denotes (`None`: not a car parameter).
pub(crate) fn part(name: &str) -> Option<Part> {
    let fixed = [
        ("body.mass", Part::Mass),
        ("body.yaw_inertia", Part::YawInertia),
        ("tyres.mu_lateral", Part::MuLateral),
        ("tyres.cornering_stiffness", Part::Cornering),
        ("bumper.force", Part::BumperForce),
    ];
    if let Some((_, p)) = fixed.iter().find(|(n, _)| *n == name) {
        return Some(*p);
    }
    let (side, rest) = name.split_once('.')?;
    let left = match side {
        "left" => true,
        "right" => false,
        _ => return None,
    };
    let (what, index) = rest.strip_suffix(']')?.split_once('[')?;
    let kind = ["masses", "dampers", "springs"]
        .iter()
        .position(|k| *k == what)?;
    Some(Part::Chain {
        left,
        kind,
        index: index.parse().ok()?,
    })
}

/// The names a car's parameters go by.
fn known(car: &PlanarCar) -> String {
    let mut names = vec!["body.mass".to_string(), "body.yaw_inertia".into()];
    for (side, chain) in [("left", car.left()), ("right", car.right())] {
        for what in ["masses", "dampers", "springs"] {
            names.extend((0..chain.masses.len()).map(|i| format!("{side}.{what}[{i}]")));
        }
    }
    names.extend(
        [
            "tyres.mu_lateral",
            "tyres.cornering_stiffness",
            "bumper.force",
        ]
        .map(String::from),
    );
    names.join(", ")
}

/// `car` with each part's value multiplied by its factor; `None` when the
/// result is not a valid car.
pub(crate) fn scaled(car: &PlanarCar, parts: &[Part], factors: &[f64]) -> Option<PlanarCar> {
    let (mut body, mut tyres, mut beam) = (*car.body(), *car.tyres(), car.beam().clone());
    let (mut left, mut right) = (car.left().clone(), car.right().clone());
    for (part, &f) in parts.iter().zip(factors) {
        match *part {
            Part::Mass => body.mass *= f,
            Part::YawInertia => body.yaw_inertia *= f,
            Part::Chain {
                left: l,
                kind,
                index,
            } => {
                let chain = if l { &mut left } else { &mut right };
                let values = [&mut chain.masses, &mut chain.dampers, &mut chain.springs];
                *values.into_iter().nth(kind)?.get_mut(index)? *= f;
            }
            Part::MuLateral => {
                tyres.front.mu_lateral *= f;
                tyres.rear.mu_lateral *= f;
            }
            Part::Cornering => {
                tyres.front.cornering_stiffness *= f;
                tyres.rear.cornering_stiffness *= f;
            }
            Part::BumperForce => {
                let segments = beam.segments.iter();
                let scaled = segments.map(|s| bumpsim_planar::car::scaled(s, f).ok());
                beam.segments = scaled.collect::<Option<Vec<_>>>()?;
            }
        }
    }
    let name = car.name().map(str::to_string);
    PlanarCar::new(body, left, right, beam, tyres)
        .ok()
        .map(|c| c.with_name(name))
}

impl Uncertainty {
    /// Independent log-normal parameters: (car-file name, standard
    /// deviation of its logarithm, in (0, 3]).
    ///
    /// ```
    /// use bumpsim_verdict::probability::Uncertainty;
    /// let u = Uncertainty::independent("spreads", vec![("body.mass".into(), 0.02)]).unwrap();
    /// assert_eq!(u.correlation, vec![vec![1.0]]);
    /// assert!(Uncertainty::independent("spreads", vec![("body.mass".into(), f64::NAN)]).is_err());
    /// ```
    pub fn independent(
        source: &str,
        spreads: Vec<(String, f64)>,
    ) -> Result<Uncertainty, VerdictError> {
        let n = spreads.len();
        let correlation = (0..n)
            .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
            .collect();
        let (names, log_sd) = spreads.into_iter().unzip();
        Uncertainty::new(source, names, log_sd, correlation, vec![])
    }

    fn new(
        source: &str,
        names: Vec<String>,
        log_sd: Vec<f64>,
        correlation: Vec<Vec<f64>>,
        left_out: Vec<String>,
    ) -> Result<Uncertainty, VerdictError> {
        let expected = "the standard deviation of the parameter's logarithm (about its relative standard deviation), in (0, 3]: a larger spread is not determined well enough to propagate";
        for (name, &s) in names.iter().zip(&log_sd) {
            require(name, s, "1", expected, s > 0.0 && s <= 3.0)?;
            if part(name).is_none() {
                return Err(VerdictError::File {
                    path: source.into(),
                    message: format!(
                        "'{name}' is not a parameter of the car: body.mass, body.yaw_inertia, left.springs[0], ..., tyres.mu_lateral, tyres.cornering_stiffness, bumper.force"
                    ),
                });
            }
        }
        if names.is_empty() {
            return Err(VerdictError::File {
                path: source.into(),
                message: "no parameter to propagate: give at least one with its spread".into(),
            });
        }
        let u = Uncertainty {
            source: source.into(),
            names,
            log_sd,
            correlation,
            left_out,
        };
        u.cholesky()?;
        Ok(u)
    }

    /// Reads an uncertainty file: a planar identification's JSON (`{`
    /// first) or a TOML `[uncertainty]` table of relative standard
    /// deviations.
    pub fn read(path: &Path) -> Result<Uncertainty, VerdictError> {
        let source = path.display().to_string();
        let text = bumpsim_core::files::read_text(path).map_err(|e| {
            let message = e.to_string();
            let message = message
                .strip_prefix(&format!("{source}: "))
                .unwrap_or(&message);
            VerdictError::File {
                path: source.clone(),
                message: message.into(),
            }
        })?;
        Uncertainty::parse(&text, path)
    }

    /// [`Uncertainty::read`] of a file's text; `path` names it in messages.
    ///
    /// ```
    /// use bumpsim_verdict::probability::Uncertainty;
    /// let u = Uncertainty::parse("[uncertainty]\n\"left.springs[0]\" = 0.15\n", "u.toml".as_ref()).unwrap();
    /// assert_eq!((u.names[0].as_str(), u.log_sd[0]), ("left.springs[0]", 0.15));
    /// let e = Uncertainty::parse("[uncertainty]\n\"wheel.size\" = 0.1\n", "u.toml".as_ref()).unwrap_err();
    /// assert!(e.to_string().contains("wheel.size"));
    /// ```
    pub fn parse(text: &str, path: &Path) -> Result<Uncertainty, VerdictError> {
        let source = path.display().to_string();
        let error = |message: String| VerdictError::File {
            path: source.clone(),
            message,
        };
        match text.trim_start().starts_with('{') {
            true => {
                let doc: serde_json::Value = serde_json::from_str(text)
                    .map_err(|e| error(format!("not valid JSON: {e}")))?;
                identified(&doc, &source)
            }
            false => {
                let table: toml::Table = toml::from_str(text)
                    .map_err(|e| error(format!("not valid TOML: {}", e.message())))?;
                Uncertainty::independent(&source, spreads(&table).map_err(error)?)
            }
        }
    }

    /// The lower Cholesky factor of the correlation.
    pub(crate) fn cholesky(&self) -> Result<Vec<Vec<f64>>, VerdictError> {
        let r = &self.correlation;
        let n = self.names.len();
        let mut l = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in 0..=i {
                let s = r[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
                l[i][j] = match i == j {
                    true if s > 1e-12 => s.sqrt(),
                    true => {
                        return Err(VerdictError::Value {
                            key: format!("{}: correlation of {}", self.source, self.names[i]),
                            value: s,
                            unit: "1",
                            expected:
                                "a positive definite correlation of the parameters' logarithms"
                                    .into(),
                        });
                    }
                    false => s / l[j][j],
                };
            }
        }
        Ok(l)
    }

    /// The factors `exp(σ z)` of draw `index`.
    pub(crate) fn factors(&self, lower: &[Vec<f64>], seed: u64, index: u64) -> Vec<f64> {
        let mut draws = Draws::new(seed, index);
        let u: Vec<f64> = (0..self.names.len())
            .map(|_| gaussian(&mut draws))
            .collect();
        lower
            .iter()
            .zip(&self.log_sd)
            .map(|(row, s)| (s * row.iter().zip(&u).map(|(l, u)| l * u).sum::<f64>()).exp())
            .collect()
    }

    /// Checks that every parameter exists in `car`.
    pub(crate) fn check(&self, car: &PlanarCar) -> Result<(), VerdictError> {
        let parts: Vec<Part> = self.names.iter().filter_map(|n| part(n)).collect();
        for (name, p) in self.names.iter().zip(&parts) {
            if scaled(car, &[*p], &[1.0]).is_none() {
                return Err(VerdictError::Missing {
                    path: self.source.clone(),
                    key: name.clone(),
                    expected: format!("a parameter of the car: {}", known(car)),
                });
            }
        }
        Ok(())
    }
}

/// The relative spreads of a TOML `[uncertainty]` table.
fn spreads(table: &toml::Table) -> Result<Vec<(String, f64)>, String> {
    let entries = table
        .get("uncertainty")
        .and_then(toml::Value::as_table)
        .ok_or("expected an [uncertainty] table: \"body.mass\" = 0.02, one relative standard deviation per parameter (docs/verdict.md)")?;
    entries
        .iter()
        .map(|(k, v)| {
            let s = v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
            s.map(|s| (k.clone(), s))
                .ok_or_else(|| format!("uncertainty.\"{k}\" = {v}: expected a number, the parameter's relative standard deviation"))
        })
        .collect()
}

/// The uncertainty of a planar identification's JSON document.
fn identified(doc: &serde_json::Value, source: &str) -> Result<Uncertainty, VerdictError> {
    let error = |message| VerdictError::File {
        path: source.into(),
        message,
    };
    let result = doc.get("result").unwrap_or(doc);
    let (kept, left_out) = parameters(result).map_err(error)?;
    let r = correlation(result, &kept).map_err(error)?;
    let names = kept.iter().map(|(_, n, _)| n.to_string()).collect();
    let log_sd = kept.iter().map(|&(.., s)| s).collect();
    Uncertainty::new(source, names, log_sd, r, left_out)
}

/// A propagated parameter of an identification: its index, name and spread.
type Kept<'a> = (usize, &'a str, f64);

/// The parameters of an identification's result with a standard error,
/// and those left out with the reason.
fn parameters(result: &serde_json::Value) -> Result<(Vec<Kept<'_>>, Vec<String>), String> {
    let parameters = result.get("parameters").and_then(|p| p.as_array()).ok_or(
        "expected a planar identification's JSON (bumpsim identify --json on a planar study): no result.parameters",
    )?;
    let (mut kept, mut left_out) = (Vec::new(), Vec::new());
    for (i, p) in parameters.iter().enumerate() {
        let name = p.get("name").and_then(|n| n.as_str()).unwrap_or("?");
        let value = p.get("value").and_then(|v| v.as_f64());
        let se = p.get("standard_error").and_then(|v| v.as_f64());
        match (part(name), value, se) {
            (None, ..) => left_out.push(format!("{name}: not a car parameter")),
            (_, Some(v), Some(se)) if v > 0.0 && se > 0.0 => kept.push((i, name, se / v)),
            _ => left_out.push(format!(
                "{name}: no standard error (fixed, at a bound or not determined)"
            )),
        }
    }
    Ok((kept, left_out))
}

/// The correlation of the kept parameters' logarithms.
fn correlation(result: &serde_json::Value, kept: &[Kept]) -> Result<Vec<Vec<f64>>, String> {
    let matrix = result
        .get("uncertainty")
        .and_then(|u| u.get("correlation"))
        .and_then(|c| c.as_array())
        .ok_or("no result.uncertainty.correlation: expected a planar identification's JSON")?;
    let cell = |i: usize, j: usize| {
        let value = matrix.get(i).and_then(|r| r.as_array()?.get(j)?.as_f64());
        value.ok_or(format!(
            "result.uncertainty.correlation[{i}][{j}] is not a number"
        ))
    };
    kept.iter()
        .map(|&(i, ..)| kept.iter().map(|&(j, ..)| cell(i, j)).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Correlated draws have the correlation and spreads asked for, within
    /// their sampling error.
    #[test]
    fn draws_have_the_correlation_asked_for() {
        let mut u = Uncertainty::independent(
            "test",
            vec![("body.mass".into(), 0.1), ("bumper.force".into(), 0.2)],
        )
        .unwrap();
        u.correlation = vec![vec![1.0, 0.6], vec![0.6, 1.0]];
        let lower = u.cholesky().unwrap();
        let n = 20_000;
        let logs: Vec<Vec<f64>> = (0..n)
            .map(|i| u.factors(&lower, 7, i).iter().map(|f| f.ln()).collect())
            .collect();
        let sd = |k: usize| (logs.iter().map(|l| l[k] * l[k]).sum::<f64>() / n as f64).sqrt();
        let r = logs.iter().map(|l| l[0] * l[1]).sum::<f64>() / n as f64 / (sd(0) * sd(1));
        assert!((sd(0) - 0.1).abs() < 0.003 && (sd(1) - 0.2).abs() < 0.006);
        assert!((r - 0.6).abs() < 0.02, "{r}");
        u.correlation = vec![vec![1.0, 1.2], vec![1.2, 1.0]];
        assert!(u.cholesky().is_err(), "not positive definite");
    }

    #[test]
    fn names_denote_the_car_parts() {
        assert_eq!(
            part("right.dampers[1]"),
            Some(Part::Chain {
                left: false,
                kind: 1,
                index: 1
            })
        );
        for bad in [
            "left.springs",
            "middle.masses[0]",
            "left.masses[x]",
            "body.width",
        ] {
            assert_eq!(part(bad), None, "{bad}");
        }
    }
}
