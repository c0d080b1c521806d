//! The objective of a chain with yielding links: the same residuals as the
//! linear chain's (`case`), the output simulated by
//! [`bumpsim_core::chain::Chain`] with its history, and their exact
//! Jacobian in the log parameters by dual numbers through that history
//! ([`jacobian`]). `LogParameters` also serves the barrier objective
//! ([`super::barrier`]), whose Jacobian is exact the same way (the car
//! run into the wall on dual numbers, [`jacobian::fill`]).

use super::{Layout, LinkIdentError};
use crate::case::LoadCase;
use bumpsim_core::chain::{Chain, Drive, Frame};
use bumpsim_estimate::lm::LeastSquares;
use nalgebra::DMatrix;
use std::sync::Mutex;

#[path = "jacobian.rs"]
pub mod jacobian;

/// The frame of a case: forward (a moving car into a barrier) when its
/// force on m1 is mostly negative, rearward (a pendulum) otherwise.
pub fn frame(case: &LoadCase) -> Frame {
    let (lo, hi) = case
        .force
        .iter()
        .fold((0.0_f64, 0.0_f64), |(l, h), f| (l.min(*f), h.max(*f)));
    if -lo > hi {
        Frame::Forward
    } else {
        Frame::Rearward
    }
}

/// A case's drive: its force on m1 in its frame.
pub fn drive(case: &LoadCase) -> Drive<'_> {
    Drive::Force {
        force: &case.force,
        step: case.step,
        initial_velocity: case.initial_velocity,
        frame: frame(case),
    }
}

/// The simulated displacement of a case's output mass, m.
pub fn simulate(case: &LoadCase, chain: &Chain) -> Result<Vec<f64>, LinkIdentError> {
    let response = chain
        .run(&drive(case))
        .map_err(|source| LinkIdentError::Chain {
            case: case.name.clone(),
            source,
        })?;
    let out = case
        .output_dof
        .checked_sub(1)
        .and_then(|i| response.displacement.get(i));
    out.cloned().ok_or_else(|| LinkIdentError::Output {
        case: case.name.clone(),
        output: case.output_dof,
        dof: chain.dof(),
    })
}

/// The residuals of every case, in their domains and weights, from the
/// SI parameters `theta`; None when the chain cannot run.
fn residuals(cases: &[LoadCase], layout: &Layout, theta: &[f64], r: &mut [f64]) -> bool {
    let Ok(chain) = layout.chain(theta) else {
        return false;
    };
    let mut at = 0;
    for case in cases {
        let Ok(y) = simulate(case, &chain) else {
            return false;
        };
        let domain = case.compare.domain;
        let weight = case.compare.weight();
        for k in case.first_compared()..=case.window.1 {
            r[at] =
                weight * (domain.at(&y, k, case.step) - domain.at(&case.measured, k, case.step));
            at += 1;
        }
    }
    r.iter().all(|v| v.is_finite())
}

/// The free log parameters `p = ln θ` of a parameter vector with some
/// entries fixed, and the one evaluation of the residuals both links
/// objectives share: the SI parameters filled into a buffer allocated
/// once.
#[derive(Debug)]
pub(crate) struct LogParameters {
    /// The fixed SI values (free entries: 1, overwritten).
    fixed: Vec<f64>,
    free: Vec<usize>,
    /// The SI parameters.
    scratch: Mutex<Vec<f64>>,
}

impl Clone for LogParameters {
    fn clone(&self) -> Self {
        let guard = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        LogParameters {
            fixed: self.fixed.clone(),
            free: self.free.clone(),
            scratch: Mutex::new(guard.clone()),
        }
    }
}

impl LogParameters {
    /// `count` parameters, `fixed[i]` a fixed SI value, `residuals` rows.
    pub(crate) fn new(count: usize, fixed: &[Option<f64>], _residuals: usize) -> LogParameters {
        let held = |i: usize| fixed.get(i).copied().flatten();
        LogParameters {
            fixed: (0..count).map(|i| held(i).unwrap_or(1.0)).collect(),
            free: (0..count).filter(|&i| held(i).is_none()).collect(),
            scratch: Mutex::new(vec![0.0; count]),
        }
    }

    /// Indices of the free parameters.
    pub(crate) fn free(&self) -> &[usize] {
        &self.free
    }

    /// The SI parameters of the free log parameters `p` into `theta`.
    fn fill(&self, p: &[f64], theta: &mut [f64]) {
        theta.copy_from_slice(&self.fixed);
        for (&i, v) in self.free.iter().zip(p) {
            theta[i] = v.exp();
        }
    }

    /// The SI parameters of the free log parameters `p`.
    pub(crate) fn theta(&self, p: &[f64]) -> Vec<f64> {
        let mut theta = vec![0.0; self.fixed.len()];
        self.fill(p, &mut theta);
        theta
    }

    /// `residuals(θ, r)` at `p`, θ filled into the buffer allocated once.
    pub(crate) fn residuals(
        &self,
        p: &[f64],
        r: &mut [f64],
        residuals: &dyn Fn(&[f64], &mut [f64]) -> bool,
    ) -> bool {
        let mut theta = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        self.fill(p, &mut theta);
        residuals(&theta, r)
    }
}

/// The objective over the free log parameters.
pub struct LinkObjective<'a> {
    cases: &'a [LoadCase],
    layout: Layout,
    parameters: LogParameters,
    count: usize,
}

impl<'a> LinkObjective<'a> {
    /// The objective of `cases` for `layout`; `fixed[i]` holds a fixed SI value.
    pub fn new(cases: &'a [LoadCase], layout: Layout, fixed: &[Option<f64>]) -> LinkObjective<'a> {
        let count = cases.iter().map(LoadCase::residual_len).sum();
        LinkObjective {
            cases,
            layout,
            parameters: LogParameters::new(layout.count(), fixed, count),
            count,
        }
    }

    /// The SI parameters of the free log parameters `p`.
    pub fn theta(&self, p: &[f64]) -> Vec<f64> {
        self.parameters.theta(p)
    }

    /// The layout.
    pub fn layout(&self) -> Layout {
        self.layout
    }

    /// Indices of the free parameters.
    pub fn free(&self) -> &[usize] {
        self.parameters.free()
    }
}

impl LeastSquares for LinkObjective<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.parameters.free().len()
    }

    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let residuals =
            |theta: &[f64], r: &mut [f64]| residuals(self.cases, &self.layout, theta, r);
        if !self.parameters.residuals(p, r, &residuals) {
            return false;
        }
        let Some(j) = jacobian else {
            return true;
        };
        let theta = self.parameters.theta(p);
        jacobian::exact(self.cases, self.layout, &theta, self.free(), j)
    }
}
