//! The objective by core's modal form ([`ModalForm`]) where it is precise
//! enough (issue 19), else by the state-space recursion, in every domain
//! (issue 44).
//!
//! **Every domain by the displacement's modal form.** The chain is linear
//! and time-invariant, and its zoh samples are `y[k] = v0 k h + Σ_(j<k)
//! g[k − j] f[j]` (h the step, g the pulse response). A backward
//! difference of y is therefore the response to the same difference of
//! the force (taken as zero before the first sample) plus that of the
//! rigid motion: `(y[k] − y[k−1]) / h = v0 + (g ∗ Δf / h)[k]` for k ≥ 1 and
//! `Δ²y[k] / h² = (g ∗ Δ²f / h²)[k]` for k ≥ 2, exactly, and so are their
//! sensitivities. A case's weight w (1 / noise) multiplies the force alike.
//! So each case is handed to the modal form as an [`Input`]: the force
//! `w Δ^q f / h^q` (q the domain's order), the measured values
//! `w (Δ^q x̂ / h^q − v0 [q = 1])` and the initial velocity `w v0` (q = 0)
//! or 0; the form's residuals, `JᵀJ` and `Jᵀr` are then the weighted
//! domain's, as [`bumpsim_estimate::domain::Domain`] defines them (the
//! state-space path differences the simulated displacement instead: the
//! same numbers to rounding, tested to 1e-9).
//!
//! Per point, in this order:
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

use super::{LoadCase, Objective, accumulate};
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
    /// The point of the last normal equations the modal form made, and its
    /// forms: `Jᵀv` there for another vector ([`Objective::modal_transposed`]).
    normal: Option<(Vec<f64>, Arc<Forms>)>,
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
        let known = self.refused_residuals(p, residuals);
        self.modal.lock().unwrap_or_else(|e| e.into_inner()).normal = None;
        let jacobian_only = known
            || match self.modal_normal(p, residuals, sums, g) {
                Ok(ok) => return ok && self.keep_normal(p),
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
                return self.keep_normal(p);
            }
        }
        sums.fill(0.0);
        g.fill(0.0);
        self.simulate(p, residuals, true, &mut |_, rows, r| {
            accumulate(rows, r, sums, g);
        })
    }

    /// Keeps the forms of `p`, whose normal equations the modal form made,
    /// for [`Objective::modal_transposed`]; true.
    fn keep_normal(&self, p: &[f64]) -> bool {
        let mut cache = self.modal.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(Ok(forms)) = cache.forms.as_ref().filter(|_| cache.point == p) {
            cache.normal = Some((p.to_vec(), Arc::clone(forms)));
        }
        true
    }

    /// `Jᵀv` (all parameters) at `p` for a vector `v` of the residuals'
    /// length into `product` (zero on entry), by the modal forms of the
    /// last normal equations, when they were made at `p` by the modal
    /// form; false otherwise (no Jacobian is made for it).
    pub(super) fn modal_transposed(&self, p: &[f64], v: &[f64], product: &mut [f64]) -> bool {
        let forms = {
            let cache = self.modal.lock().unwrap_or_else(|e| e.into_inner());
            match &cache.normal {
                Some((point, forms)) if point == p => Arc::clone(forms),
                _ => return false,
            }
        };
        let mut row = 0;
        for (input, form) in forms.zip(&self.inputs) {
            let next = row + input.measured.len();
            if form
                .transposed(input.step, &input.force, &v[row..next], product)
                .is_err()
            {
                return false;
            }
            row = next;
        }
        product.iter().all(|x| x.is_finite())
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
        for (input, form) in forms.zip(&self.inputs) {
            let (last, next) = (input.force.len() - 1, row + input.measured.len());
            let first = last + 1 - input.measured.len();
            form.simulate(
                input.step,
                input.initial_velocity,
                &input.force,
                &mut y[..=last],
            )?;
            let simulated = y[first..=last].iter().zip(&input.measured);
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
        for (input, form) in forms.zip(&self.inputs) {
            let next = row + input.measured.len();
            let out = &mut residuals[row..next];
            let (jtj, gradient) = (sums.as_mut_slice(), g.as_mut_slice());
            form.normal(
                input.step,
                input.initial_velocity,
                &input.force,
                &input.measured,
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
        for (input, form) in forms.zip(&self.inputs) {
            let next = row + input.measured.len();
            let (jtj, gradient) = (sums.as_mut_slice(), g.as_mut_slice());
            let window = &residuals[row..next];
            if form
                .jacobian(input.step, &input.force, window, jtj, gradient)
                .is_err()
            {
                return false;
            }
            row = next;
        }
        true
    }
}

/// A load case as the modal form takes it (see the module): the force,
/// measured values and initial velocity whose displacement residuals are
/// the case's residuals in its domain, weighted.
pub(super) struct Input {
    /// Sample interval, s.
    step: f64,
    /// The force up to the window's end, its domain's difference, weighted.
    force: Vec<f64>,
    /// The measured values compared (the window's samples that have a
    /// value in the domain), less the rigid motion's part, weighted.
    measured: Vec<f64>,
    /// The initial velocity the form simulates from.
    initial_velocity: f64,
}

impl Input {
    /// The input of `case`: for the thesis's objective its own force,
    /// window and initial velocity.
    pub(super) fn new(case: &LoadCase) -> Input {
        let (domain, w, h) = (case.compare.domain, case.compare.weight(), case.step);
        let (first, last, q) = (case.first_compared(), case.window.1, domain.order());
        if case.compare.is_thesis() {
            return Input {
                step: h,
                force: case.force[..=last].to_vec(),
                measured: case.measured[first..=last].to_vec(),
                initial_velocity: case.initial_velocity,
            };
        }
        // the force is zero before the first sample: q zeros in front
        let padded: Vec<f64> = std::iter::repeat_n(0.0, q)
            .chain(case.force[..=last].iter().copied())
            .collect();
        let rigid = if q == 1 { case.initial_velocity } else { 0.0 };
        Input {
            step: h,
            force: (0..=last)
                .map(|k| w * domain.at(&padded, k + q, h))
                .collect(),
            measured: (first..=last)
                .map(|k| w * (domain.at(&case.measured, k, h) - rigid))
                .collect(),
            initial_velocity: if q == 0 {
                w * case.initial_velocity
            } else {
                0.0
            },
        }
    }
}

/// The modal forms of a point: one per distinct output mass, and each
/// case's index into them.
struct Forms {
    forms: Vec<ModalForm>,
    of_case: Vec<usize>,
}

impl Forms {
    /// The form of case `i` with the case's input.
    fn zip<'c, C>(&self, cases: &'c [C]) -> impl Iterator<Item = (&'c C, &ModalForm)> {
        cases
            .iter()
            .zip(&self.of_case)
            .map(|(case, &index)| (case, &self.forms[index]))
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Comparison, Domain, LoadCase, Objective, accumulate};
    use bumpsim_core::model::MsdModel;
    use nalgebra::{DMatrix, DVector};

    const STEP: f64 = 2e-4;

    /// Two pendulum-like cases (a half-sine force from 2 ms on, the
    /// measurement a 3-DOF car's displacement with a little deterministic
    /// noise, from 1.5 m/s) compared in `domain`, weighted by `noise`, over
    /// a window that starts after the first samples.
    fn cases(domain: Domain, noise: Option<f64>) -> Vec<LoadCase> {
        let truth = MsdModel::new(
            vec![30.0, 250.0, 1170.0],
            vec![8e3, 2.5e4],
            vec![1.5e6, 6e5],
        )
        .unwrap();
        [(4.5e4, 0.06, 1.5), (2.5e4, 0.085, -0.4)]
            .iter()
            .enumerate()
            .map(|(l, &(peak, duration, v0))| {
                let force = (0..450)
                    .map(|k| {
                        let t = k as f64 * STEP - 2e-3;
                        let inside = (0.0..duration).contains(&t);
                        if inside {
                            peak * (std::f64::consts::PI * t / duration).sin()
                        } else {
                            0.0
                        }
                    })
                    .collect();
                let mut case = LoadCase {
                    name: format!("case {l}"),
                    start: 0.0,
                    step: STEP,
                    force,
                    measured: vec![0.0; 450],
                    output_dof: 1 + l,
                    initial_velocity: v0,
                    window: (3 + 5 * l, 420),
                    compare: Comparison::new(domain, noise),
                };
                case.measured = case
                    .simulate(&truth)
                    .unwrap()
                    .iter()
                    .enumerate()
                    .map(|(k, x)| x + 2e-5 * ((k * 7 + l) as f64).sin())
                    .collect();
                case
            })
            .collect()
    }

    /// Largest difference relative to `scale`.
    fn relative(a: &[f64], b: &[f64], scale: f64) -> f64 {
        let worst = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        worst / scale
    }

    /// In every domain, weighted or not, the modal form's residuals and
    /// normal equations (`Input`: the difference moved onto the force)
    /// equal the state-space recursion's, which differences the simulated
    /// displacement and its sensitivities, to 1e-9: residuals relative to
    /// the largest, `JᵀJ` to its largest entry, `Jᵀr` to `‖J‖ ‖r‖`.
    #[test]
    fn every_domain_by_the_modal_form_equals_the_state_space_one() {
        // a point off the truth, so that the residuals are not noise alone
        let p: Vec<f64> = [33.0f64, 230.0, 1200.0, 9e3, 2.2e4, 1.4e6, 6.5e5]
            .iter()
            .map(|v| v.ln())
            .collect();
        let compared = [
            (Domain::Displacement, None),
            (Domain::Displacement, Some(1e-4)),
            (Domain::Velocity, Some(3e-3)),
            (Domain::Velocity, None),
            (Domain::Acceleration, Some(0.7)),
        ];
        for (domain, noise) in compared {
            let cases = cases(domain, noise);
            let objective = Objective::new(&cases, 3, &[]);
            let m = objective.residuals;
            let (mut modal, mut state) = (vec![0.0; m], vec![0.0; m]);
            let (mut jtj, mut g) = (DMatrix::zeros(7, 7), DVector::zeros(7));
            let used = objective.modal_normal(&p, &mut modal, &mut jtj, &mut g);
            assert!(
                matches!(used, Ok(true)),
                "{domain:?}: the modal form refused"
            );
            let (mut jtj_state, mut g_state) = (DMatrix::zeros(7, 7), DVector::zeros(7));
            assert!(objective.simulate(&p, &mut state, true, &mut |_, rows, r| {
                accumulate(rows, r, &mut jtj_state, &mut g_state);
            }));
            let largest = |v: &[f64]| v.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
            let r_norm = state.iter().map(|r| r * r).sum::<f64>().sqrt();
            let scale = largest(jtj_state.as_slice());
            let errors = [
                relative(&modal, &state, largest(&state)),
                relative(jtj.as_slice(), jtj_state.as_slice(), scale),
                relative(g.as_slice(), g_state.as_slice(), scale.sqrt() * r_norm),
            ];
            assert!(
                errors.iter().all(|e| *e < 1e-9),
                "{domain:?} {noise:?}: {errors:?}"
            );
            // the trial steps' residuals too
            let mut trial = vec![0.0; m];
            assert!(matches!(
                objective.modal_residuals(&p, &mut trial),
                Ok(true)
            ));
            let error = relative(&trial, &state, largest(&state));
            assert!(error < 1e-9, "{domain:?} {noise:?}: residuals {error:.1e}");
        }
    }
}
