//! Which links the data want (issue 46, item 3): the linear chain or the
//! chain with yielding links, compared as the DOF table compares sizes.
//!
//! Both are fitted to the same residuals, n of them, with q_lin and q_nl
//! free parameters and objectives F_lin ≥ F_nl (the yielding chain holds
//! the linear one as r → 1). The criterion is the Bayesian information
//! criterion on the **effective** number of residuals n_eff (correlated
//! residuals carry fewer independent values, [`bumpsim_estimate::effective`]):
//! `BIC = n_eff ln(F/n) + q ln n_eff` (Schwarz 1978). The yielding links
//! are preferred when their BIC is lower; the reasons (fits, objectives,
//! parameters, BIC) are printed whatever the verdict.
//!
//! A car identified into the barrier ([`super::into_wall`]) fits another
//! objective (the wall force and the output, scaled, with a prior):
//! [`compare_outputs`] compares it on the linear chain's own residuals,
//! those of its output run into the wall (`r_k = w (y_k − ŷ_k)` in the
//! case's domain over its window, w its weight), counting all its free
//! parameters, the front's and paths' too.

use super::{LinkIdentError, LinkIdentification};
use crate::case::LoadCase;
use crate::result::Identification;

/// The comparison and its reasons.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Whether the yielding links are preferred.
    pub yielding: bool,
    /// BIC of the linear and the yielding chain.
    pub bic: [f64; 2],
    /// The reasons, one line each.
    pub reasons: Vec<String>,
}

/// BIC on `n` residuals of which `effective` are independent.
fn bic(objective: f64, n: usize, effective: f64, q: usize) -> f64 {
    bumpsim_estimate::effective::bic(objective, n, effective, q)
}

/// Compares a linear identification with a yielding one of the same cases.
pub fn compare(linear: &Identification, yielding: &LinkIdentification) -> Verdict {
    let fits: Vec<f64> = yielding.fits.iter().map(|f| f.1).collect();
    let q = yielding.uncertainty.fixed.iter().filter(|f| !**f).count();
    let effective = linear.effective_samples.effective;
    weighed(linear, &fits, yielding.objective, q, effective)
}

/// Compares a linear identification with a car identified into the
/// barrier, on the linear chain's residuals of `cases` (the module's).
pub fn compare_outputs(
    linear: &Identification,
    yielding: &LinkIdentification,
    cases: &[LoadCase],
) -> Result<Verdict, LinkIdentError> {
    let mut residuals: Vec<Vec<f64>> = Vec::with_capacity(cases.len());
    for case in cases {
        let run = yielding.forward(case.initial_velocity, case.step, case.window.1 + 1)?;
        let y = run
            .displacement
            .get(case.output_dof.wrapping_sub(1))
            .ok_or_else(|| LinkIdentError::Output {
                case: case.name.clone(),
                output: case.output_dof,
                dof: yielding.layout.dof,
            })?;
        let (domain, w, h) = (case.compare.domain, case.compare.weight(), case.step);
        let series =
            (case.first_compared()..=case.window.1).map(|k| match case.compare.is_thesis() {
                true => y[k] - case.measured[k],
                false => w * (domain.at(y, k, h) - domain.at(&case.measured, k, h)),
            });
        residuals.push(series.collect());
    }
    let objective: f64 = residuals.iter().flatten().map(|r| r * r).sum();
    let views: Vec<&[f64]> = residuals.iter().map(Vec::as_slice).collect();
    let method = linear.effective_samples.method;
    let effective = bumpsim_estimate::effective::of_series(&views, method, false).effective;
    let fits: Vec<f64> = yielding.fits.iter().map(|f| f.1).collect();
    let q = yielding.uncertainty.fixed.iter().filter(|f| !**f).count();
    Ok(weighed(linear, &fits, objective, q, effective))
}

/// The comparison of `linear` with a yielding chain of fits `fits` %,
/// objective `objective` on the linear chain's residuals and `q_yielding`
/// free parameters, `effective` of the residuals independent.
fn weighed(
    linear: &Identification,
    yielding_fits: &[f64],
    objective: f64,
    q_yielding: usize,
    effective: f64,
) -> Verdict {
    let n = linear.residuals;
    let effective = effective.clamp(2.0, n as f64);
    let q_linear = linear.uncertainty.fixed.iter().filter(|f| !**f).count();
    let bic = [
        bic(linear.objective, n, effective, q_linear),
        bic(objective, n, effective, q_yielding),
    ];
    let fit = |fits: &[f64]| {
        fits.iter()
            .map(|f| format!("{f:.2} %"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let linear_fits: Vec<f64> = linear.cases.iter().map(|c| c.fit_percent).collect();
    let prefer = bic[1] < bic[0];
    let reasons = vec![
        format!(
            "fit: linear {} , yielding {}",
            fit(&linear_fits),
            fit(yielding_fits)
        ),
        format!(
            "objective: linear {:.4e}, yielding {:.4e} ({:.1} % lower)",
            linear.objective,
            objective,
            100.0 * (1.0 - objective / linear.objective)
        ),
        format!(
            "free parameters: linear {q_linear}, yielding {q_yielding}; {effective:.0} effective of {n} residuals"
        ),
        format!(
            "BIC: linear {:.1}, yielding {:.1}: {}",
            bic[0],
            bic[1],
            if prefer {
                "the data want yielding links"
            } else {
                "the data do not need yielding links"
            }
        ),
    ];
    Verdict {
        yielding: prefer,
        bic,
        reasons,
    }
}
