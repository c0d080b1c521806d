//! The least-squares problem of a planar identification, in `p = ln θ`:
//! each case replayed ([`crate::drive`]) with the car of `θ`, the residuals
//! the modelled minus the measured sensor displacements over each case's
//! window (sensors interleaved), and their Jacobian by forward differences
//! (step 1e-6 in ln θ, columns in parallel): the replay has no sensitivity
//! recursion, and its steps are fixed per template car, so the objective
//! does not jump where a trial car's own step would change.

use super::{PlanarCase, Unknowns};
use crate::car::PlanarError;
use crate::drive::{sensor_readings, substeps};
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::uncertainty::Series;
use nalgebra::DMatrix;
use rayon::prelude::*;
use std::sync::Mutex;

/// The least-squares problem over all cases.
#[derive(Debug)]
pub(crate) struct Objective<'a> {
    cases: &'a [PlanarCase],
    unknowns: &'a Unknowns,
    count: usize,
    /// Integration steps per sample of each case.
    substeps: Vec<usize>,
    /// The last point evaluated without its Jacobian and its residuals: LM
    /// asks for the Jacobian at a trial point it has just evaluated.
    last: Mutex<Option<(Vec<f64>, Vec<f64>)>>,
}

/// A clone starts with no remembered point (one per solver run).
impl Clone for Objective<'_> {
    fn clone(&self) -> Self {
        Objective {
            cases: self.cases,
            unknowns: self.unknowns,
            count: self.count,
            substeps: self.substeps.clone(),
            last: Mutex::new(None),
        }
    }
}

impl<'a> Objective<'a> {
    /// The problem, each case replayed with the step of the template at a
    /// safety factor of 0.05: a 40-fold margin to the stability limit for
    /// trial cars stiffer or lighter than the start.
    pub fn new(
        cases: &'a [PlanarCase],
        unknowns: &'a Unknowns,
    ) -> Result<Objective<'a>, PlanarError> {
        let count = cases
            .iter()
            .map(|c| c.measured.len() * (c.window.1 - c.window.0 + 1))
            .sum();
        let substeps = cases
            .iter()
            .map(|c| substeps(unknowns.template(), c.drive.step, 0.05))
            .collect::<Result<_, _>>()?;
        Ok(Objective {
            cases,
            unknowns,
            count,
            substeps,
            last: Mutex::new(None),
        })
    }

    /// What it estimates.
    pub fn unknowns(&self) -> &'a Unknowns {
        self.unknowns
    }

    /// The residual series: per case and sensor, interleaved by sensor.
    pub fn series(&self) -> Vec<Series> {
        let mut out = Vec::new();
        let mut at = 0;
        for case in self.cases {
            let (n, sensors) = (case.window.1 - case.window.0 + 1, case.measured.len());
            out.extend((0..sensors).map(|side| Series {
                start: at + side,
                len: n,
                stride: sensors,
            }));
            at += sensors * n;
        }
        out
    }

    /// Each case's sensor readings up to its window's end with the car of `p`.
    fn replays(&self, p: &[f64]) -> Option<Vec<Vec<Vec<f64>>>> {
        let theta = self.unknowns.theta(p);
        let car = self.unknowns.car(&theta).ok()?;
        self.cases
            .iter()
            .zip(&self.substeps)
            .enumerate()
            .map(|(i, (c, &n))| {
                let located = self.unknowns.case(&theta, i, c);
                let drive = &located.as_ref().unwrap_or(c).drive;
                sensor_readings(&car, drive, n, c.window.1 + 1).ok()
            })
            .collect()
    }

    fn residuals(&self, p: &[f64], r: &mut [f64]) -> bool {
        let Some(replays) = self.replays(p) else {
            return false;
        };
        let mut at = 0;
        for (case, replay) in self.cases.iter().zip(&replays) {
            for k in case.window.0..=case.window.1 {
                for (model, measured) in replay.iter().zip(&case.measured) {
                    r[at] = model[k] - measured[k];
                    at += 1;
                }
            }
        }
        r.iter().all(|v| v.is_finite())
    }
}

impl LeastSquares for Objective<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.unknowns.names().len()
    }

    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        let remembered = match (&*last, jacobian.is_some()) {
            (Some((q, residuals)), true) if q.as_slice() == p => {
                r.copy_from_slice(residuals);
                true
            }
            _ => false,
        };
        if !remembered && !self.residuals(p, r) {
            return false;
        }
        let Some(jac) = jacobian else {
            *last = Some((p.to_vec(), r.to_vec()));
            return true;
        };
        drop(last);
        const H: f64 = 1e-6;
        let columns: Vec<Option<Vec<f64>>> = (0..p.len())
            .into_par_iter()
            .map(|j| {
                let mut shifted = p.to_vec();
                shifted[j] += H;
                let mut column = vec![0.0; r.len()];
                self.residuals(&shifted, &mut column).then(|| {
                    column
                        .iter()
                        .zip(r.iter())
                        .map(|(a, b)| (a - b) / H)
                        .collect()
                })
            })
            .collect();
        for (j, column) in columns.into_iter().enumerate() {
            let Some(column) = column else {
                return false;
            };
            jac.column_mut(j).copy_from_slice(&column);
        }
        true
    }
}
