//! One request to carry a car's uncertainty through its run (issue 39,
//! item 4), as every front end makes it (`bumpsim impact|planar
//! --uncertainty`, Python's `impact`/`planar_impact(uncertainty=...)`):
//! read the uncertainty file ([`crate::uncertainty`]), check the draws, the
//! level and the Sobol' base samples against the car before anything runs,
//! then [`crate::prediction::predict`] (medians, intervals, pointwise bands)
//! and, when asked, [`crate::prediction::sensitivity`] (Saltelli's
//! first-order and total indices). The front ends only name their own
//! options in the errors and print or return what comes back.

use crate::prediction::{
    self, Outputs, Prediction, Sampling, Sensitivity, SensitivityError, SobolSettings,
};
use crate::uncertainty::{Model, Uncertainty, UncertaintyError};
use std::path::Path;

/// The defaults of the draws, the seed and the Sobol' base samples (the
/// CLI's `--samples`, `--seed`, `--sobol-base`; Python's keywords).
pub const DEFAULT_SAMPLES: usize = 1000;
/// See [`DEFAULT_SAMPLES`].
pub const DEFAULT_SEED: u64 = 1;
/// See [`DEFAULT_SAMPLES`].
pub const DEFAULT_SOBOL_BASE: usize = 256;

/// Why a propagation cannot be set up or run; each variant says which
/// option is at fault, so a front end can name its flag or argument.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PropagationError {
    /// The draws or the level (`key` of the error: `samples`, `level`).
    #[error(transparent)]
    Sampling(UncertaintyError),
    /// The uncertainty file: unreadable, or not the car's parameters.
    #[error(transparent)]
    File(UncertaintyError),
    /// The Sobol' base samples, or too many parameters for them.
    #[error(transparent)]
    Sobol(UncertaintyError),
    /// The prediction or the indices failed.
    #[error(transparent)]
    Run(#[from] SensitivityError),
}

/// A checked request: the uncertainty, the draws and the Sobol' settings.
#[derive(Debug, Clone)]
pub struct Propagation<M: Model> {
    uncertainty: Uncertainty<M>,
    sampling: Sampling,
    sobol: Option<SobolSettings>,
}

/// What a propagation gave.
#[derive(Debug, Clone)]
pub struct Propagated<M> {
    /// Spreads and bands.
    pub prediction: Prediction<M>,
    /// The Sobol' indices, when asked.
    pub sensitivity: Option<Sensitivity>,
}

impl<M: Model> Propagation<M> {
    /// Reads the uncertainty at `path` and checks it, `sampling` and the
    /// Sobol' base samples `sobol_base` (`None`: no indices) against `car`.
    ///
    /// ```
    /// use bumpsim_impact::impact::{Options, Scenario, simulate};
    /// use bumpsim_impact::prediction::Sampling;
    /// use bumpsim_impact::propagation::Propagation;
    /// use bumpsim_impact::uncertainty::{Chain, ChainCar};
    /// let car = ChainCar {
    ///     model: bumpsim_core::model::MsdModel::new(vec![1000.0], vec![], vec![])?,
    ///     bumper: bumpsim_impact::Bumper::three_part(1e6, 1e9, 1e6)?,
    /// };
    /// let path = std::env::temp_dir().join("bumpsim-propagation-doc.toml");
    /// std::fs::write(&path, "[uncertainty]\n\"bumper.force\" = 0.1\n")?;
    /// let sampling = Sampling { samples: 50, seed: 1, level: 0.9 };
    /// let request = Propagation::<Chain>::read(&path, sampling, None, &car)?;
    /// let run = |c: &ChainCar| simulate(&c.model, &c.bumper, Scenario::Barrier { speed: 2.0 }, &Options::default()).ok();
    /// let nominal = run(&car).unwrap();
    /// let out = request.run(&car, &nominal, &run)?;
    /// assert!(out.sensitivity.is_none() && out.prediction.outputs[0].spread.is_some());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn read(
        path: &Path,
        sampling: Sampling,
        sobol_base: Option<usize>,
        car: &M::Car,
    ) -> Result<Propagation<M>, PropagationError> {
        sampling.check().map_err(PropagationError::Sampling)?;
        let uncertainty = Uncertainty::<M>::read(path).map_err(PropagationError::File)?;
        uncertainty.check(car).map_err(PropagationError::File)?;
        let parameters = uncertainty.names.len();
        let sobol = sobol_base
            .map(|base| {
                prediction::check_base(base, parameters)?;
                Ok(SobolSettings::new(base, sampling.seed))
            })
            .transpose()
            .map_err(PropagationError::Sobol)?;
        Ok(Propagation {
            uncertainty,
            sampling,
            sobol,
        })
    }

    /// The prediction of `run` over the uncertainty and, when asked, the
    /// Sobol' indices; `nominal` is `run`'s result for `car`.
    pub fn run<R: Outputs>(
        &self,
        car: &M::Car,
        nominal: &R,
        run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
    ) -> Result<Propagated<M>, PropagationError> {
        let u = &self.uncertainty;
        let prediction = prediction::predict(car, nominal, u, &self.sampling, run)
            .map_err(SensitivityError::from)?;
        let sensitivity = (self.sobol.as_ref())
            .map(|settings| prediction::sensitivity(car, nominal, u, settings, run))
            .transpose()?;
        Ok(Propagated {
            prediction,
            sensitivity,
        })
    }
}

impl<M: Model> Propagated<M> {
    /// The lines printed after a result's summary: each output's
    /// distribution, then the indices.
    pub fn lines(&self) -> String {
        let indices = self.sensitivity.as_ref();
        prediction::lines(&self.prediction)
            + &indices.map_or(String::new(), prediction::sensitivity_lines)
    }

    /// `document` (a result's JSON object) with `prediction` and, when
    /// computed, `sensitivity` beside its fields, as `--json` writes it.
    pub fn insert_into(&self, document: &mut serde_json::Value) -> serde_json::Result<()> {
        if let Some(fields) = document.as_object_mut() {
            fields.insert("prediction".into(), serde_json::to_value(&self.prediction)?);
            if let Some(s) = &self.sensitivity {
                fields.insert("sensitivity".into(), serde_json::to_value(s)?);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::uncertainty::{Chain, ChainCar};

    fn car() -> ChainCar {
        ChainCar {
            model: bumpsim_core::model::MsdModel::new(vec![1000.0], vec![], vec![]).unwrap(),
            bumper: crate::Bumper::three_part(1e6, 1e9, 1e6).unwrap(),
        }
    }

    fn file(name: &str, text: &str) -> std::path::PathBuf {
        let path = std::env::temp_dir().join(format!("bumpsim-propagation-{name}.toml"));
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn each_refusal_names_its_option() {
        let good = file("good", "[uncertainty]\n\"bumper.force\" = 0.1\n");
        let sampling = Sampling {
            samples: 50,
            seed: 1,
            level: 0.9,
        };
        let read =
            |path: &Path, sampling, base| Propagation::<Chain>::read(path, sampling, base, &car());
        let few = Sampling {
            samples: 5,
            ..sampling
        };
        assert!(matches!(
            read(&good, few, None),
            Err(PropagationError::Sampling(_))
        ));
        let unknown = file("unknown", "[uncertainty]\n\"springs[3]\" = 0.1\n");
        assert!(matches!(
            read(&unknown, sampling, None),
            Err(PropagationError::File(_))
        ));
        assert!(matches!(
            read(&good, sampling, Some(3)),
            Err(PropagationError::Sobol(_))
        ));
        assert!(read(&good, sampling, Some(16)).is_ok());
    }

    #[test]
    fn the_document_gets_the_prediction_and_the_indices() {
        let path = file("run", "[uncertainty]\n\"bumper.force\" = 0.1\n");
        let sampling = Sampling {
            samples: 20,
            seed: 3,
            level: 0.9,
        };
        let car = car();
        let request = Propagation::<Chain>::read(&path, sampling, Some(16), &car).unwrap();
        let options = crate::impact::Options::default();
        let scenario = crate::Scenario::Barrier { speed: 2.0 };
        let run =
            |c: &ChainCar| crate::impact::simulate(&c.model, &c.bumper, scenario, &options).ok();
        let out = request.run(&car, &run(&car).unwrap(), &run).unwrap();
        let mut document = serde_json::json!({ "result": 1 });
        out.insert_into(&mut document).unwrap();
        assert_eq!(document["prediction"]["sampling"]["samples"], 20);
        assert!(document["sensitivity"].is_object() && out.lines().contains("Sobol"));
        // the elastic bumper leaves no compression: that output has no
        // indices, and says so (it aborted the whole table)
        let constant = &out.sensitivity.as_ref().unwrap().constant;
        assert_eq!(constant[0].name, "remaining compression");
        assert!(
            out.lines()
                .contains("the same at every point: 0 m (no index)")
        );
    }
}
