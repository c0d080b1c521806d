//! The objective by core's modal form ([`ModalForm`]) where it is precise
//! enough (issue 19), else by the state-space recursion.
//!
//! Per point, in this order:
//!
//! 1. the residuals, and for the normal equations `JᵀJ` and `Jᵀr`, by the
//!    modal form, all in one pass per case;
//! 2. when the modal form refuses its *output* (a far mass that barely
//!    moves, a stiff chain: its estimated error exceeds
//!    [`bumpsim_core::modal::OUTPUT_PRECISION`]) but not its Jacobian: the
//!    residuals by the state-space recursion and the normal equations by
//!    the modal form for those residuals ([`ModalForm::jacobian`]);
//! 3. otherwise the state-space recursion with its sensitivities.
//!
//! The last point's modal forms (made with the sensitivities) are kept,
//! and, where the modal form refused its residuals, the state-space ones:
//! LM evaluates a trial point's residuals, then, when it accepts the step,
//! the normal equations at the same point, which reuse both (going to
//! step 2 at once, without simulating again, after a refusal). All three steps give the same function and derivatives to
//! the precision core states; which one ran depends on the point only, so
//! a run is the same on any number of threads.

use super::{Objective, accumulate};
use bumpsim_core::modal::{ModalError, ModalForm};
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// The modal forms of the last point an objective evaluated.
#[derive(Default)]
pub(super) struct Cache {
    /// The point (free log parameters).
    point: Vec<f64>,
    /// Its forms, or why there are none (None: the model cannot be
    /// evaluated).
    forms: Option<Result<Arc<Forms>, Refusal>>,
    /// The state-space residuals at the point where the modal form refused
    /// its own (empty otherwise; the buffer is kept across points).
    refused: Vec<f64>,
}

/// Why the modal form gave no result at a point.
#[derive(Clone, Copy)]
enum Refusal {
    /// Its output (residuals) would not be precise enough; its Jacobian may be.
    Output,
    /// Anything else (close eigenvalues, an imprecise Jacobian, ...).
    Other,
}

impl From<ModalError> for Refusal {
    fn from(error: ModalError) -> Refusal {
        match error.output_imprecise() {
            true => Refusal::Output,
            false => Refusal::Other,
        }
    }
}

impl Objective<'_> {
    /// The residuals at the free log parameters `p`; false when the model
    /// cannot be evaluated.
    pub(super) fn residuals(&self, p: &[f64], residuals: &mut [f64]) -> bool {
        if !self.is_thesis() {
            return self.simulate(p, residuals, false, &mut |_, _, _| {});
        }
        match self.modal_residuals(p, residuals) {
            Ok(ok) => ok,
            Err(refusal) => {
                let ok = self.simulate(p, residuals, false, &mut |_, _, _| {});
                let mut cache = self.modal.lock().unwrap_or_else(|e| e.into_inner());
                if matches!(refusal, Refusal::Output) && ok && cache.point == p {
                    cache.refused.clear();
                    cache.refused.extend_from_slice(residuals);
                }
                ok
            }
        }
    }

    /// The residuals and the full-parameter normal equations at `p` into
    /// `sums` (`JᵀJ`) and `g` (`Jᵀr`), zero on entry; false when the model
    /// cannot be evaluated.
    pub(super) fn normal_equations(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        sums: &mut DMatrix<f64>,
        g: &mut DVector<f64>,
    ) -> bool {
        if !self.is_thesis() {
            return self.simulate(p, residuals, true, &mut |_, rows, r| {
                accumulate(rows, r, sums, g);
            });
        }
        let known = self.refused_residuals(p, residuals);
        let jacobian_only = known
            || match self.modal_normal(p, residuals, sums, g) {
                Ok(ok) => return ok,
                Err(Refusal::Output) => true,
                Err(Refusal::Other) => false,
            };
        if jacobian_only {
            sums.fill(0.0);
            g.fill(0.0);
            if !known && !self.simulate(p, residuals, false, &mut |_, _, _| {}) {
                return false;
            }
            if self.modal_jacobian(p, residuals, sums, g) {
                return true;
            }
        }
        sums.fill(0.0);
        g.fill(0.0);
        self.simulate(p, residuals, true, &mut |_, rows, r| {
            accumulate(rows, r, sums, g);
        })
    }

    /// The modal forms (with sensitivities) of each distinct output mass at
    /// `p`, and each case's: the last point's again, or made and kept (None
    /// when the model cannot be evaluated).
    fn forms(&self, p: &[f64]) -> Option<Result<Arc<Forms>, Refusal>> {
        let mut cache = self.modal.lock().unwrap_or_else(|e| e.into_inner());
        if cache.point != p {
            cache.point.clear();
            cache.point.extend_from_slice(p);
            cache.forms = self.make_forms(p);
            cache.refused.clear();
        }
        cache.forms.clone()
    }

    /// Copies the state-space residuals kept for `p` (where the modal form
    /// refused its own) into `residuals`; false when there are none.
    fn refused_residuals(&self, p: &[f64], residuals: &mut [f64]) -> bool {
        let cache = self.modal.lock().unwrap_or_else(|e| e.into_inner());
        let known = cache.point == p && cache.refused.len() == residuals.len();
        if known {
            residuals.copy_from_slice(&cache.refused);
        }
        known
    }

    /// [`Objective::forms`] made anew.
    fn make_forms(&self, p: &[f64]) -> Option<Result<Arc<Forms>, Refusal>> {
        let model = self.model(p)?;
        let mut outputs: Vec<usize> = Vec::new();
        let mut forms = Forms {
            forms: Vec::new(),
            of_case: Vec::with_capacity(self.cases.len()),
        };
        for case in self.cases {
            let index = match outputs.iter().position(|&o| o == case.output_dof) {
                Some(index) => index,
                None => match ModalForm::new(&model, case.output_dof - 1, true) {
                    Ok(form) => {
                        outputs.push(case.output_dof);
                        forms.forms.push(form);
                        outputs.len() - 1
                    }
                    Err(error) => return Some(Err(error.into())),
                },
            };
            forms.of_case.push(index);
        }
        Some(Ok(Arc::new(forms)))
    }

    /// Step 1 without the normal equations: the residuals by the modal form.
    fn modal_residuals(&self, p: &[f64], residuals: &mut [f64]) -> Result<bool, Refusal> {
        let Some(forms) = self.forms(p) else {
            return Ok(false);
        };
        let forms = forms?;
        let mut buffers = self.buffers.lock().unwrap_or_else(|e| e.into_inner());
        let y = &mut buffers.y;
        let mut row = 0;
        for (case, form) in forms.zip(self.cases) {
            let (first, last) = case.window;
            let next = row + last + 1 - first;
            form.simulate(
                case.step,
                case.initial_velocity,
                &case.force[..=last],
                &mut y[..=last],
            )?;
            let simulated = y[first..=last].iter().zip(&case.measured[first..=last]);
            for (r, (x, m)) in residuals[row..next].iter_mut().zip(simulated) {
                *r = x - m;
            }
            row = next;
        }
        Ok(residuals.iter().all(|r| r.is_finite()))
    }

    /// Step 1: residuals and normal equations by the modal form.
    fn modal_normal(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        sums: &mut DMatrix<f64>,
        g: &mut DVector<f64>,
    ) -> Result<bool, Refusal> {
        let Some(forms) = self.forms(p) else {
            return Ok(false);
        };
        let forms = forms?;
        let mut row = 0;
        for (case, form) in forms.zip(self.cases) {
            let (first, last) = case.window;
            let next = row + last + 1 - first;
            let (force, measured) = (&case.force[..=last], &case.measured[first..=last]);
            let out = &mut residuals[row..next];
            let (jtj, gradient) = (sums.as_mut_slice(), g.as_mut_slice());
            form.normal(
                case.step,
                case.initial_velocity,
                force,
                measured,
                out,
                jtj,
                gradient,
            )?;
            row = next;
        }
        Ok(residuals.iter().all(|r| r.is_finite()))
    }

    /// Step 2: the normal equations by the modal form for `residuals`
    /// computed elsewhere; false when refused.
    fn modal_jacobian(
        &self,
        p: &[f64],
        residuals: &[f64],
        sums: &mut DMatrix<f64>,
        g: &mut DVector<f64>,
    ) -> bool {
        let Some(Ok(forms)) = self.forms(p) else {
            return false;
        };
        let mut row = 0;
        for (case, form) in forms.zip(self.cases) {
            let (first, last) = case.window;
            let next = row + last + 1 - first;
            let (jtj, gradient) = (sums.as_mut_slice(), g.as_mut_slice());
            let window = &residuals[row..next];
            if form
                .jacobian(case.step, &case.force[..=last], window, jtj, gradient)
                .is_err()
            {
                return false;
            }
            row = next;
        }
        true
    }
}

/// The modal forms of a point: one per distinct output mass, and each
/// case's index into them.
struct Forms {
    forms: Vec<ModalForm>,
    of_case: Vec<usize>,
}

impl Forms {
    /// The form of case `i` with the case.
    fn zip<'c, C>(&self, cases: &'c [C]) -> impl Iterator<Item = (&'c C, &ModalForm)> {
        cases
            .iter()
            .zip(&self.of_case)
            .map(|(case, &index)| (case, &self.forms[index]))
    }
}
