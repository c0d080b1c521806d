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

use super::LinkIdentification;
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
    let n = linear.residuals;
    let effective = linear.effective_samples.effective.clamp(2.0, n as f64);
    let q_linear = linear.uncertainty.fixed.iter().filter(|f| !**f).count();
    let q_yielding = yielding.uncertainty.fixed.iter().filter(|f| !**f).count();
    let bic = [
        bic(linear.objective, n, effective, q_linear),
        bic(yielding.objective, n, effective, q_yielding),
    ];
    let fit = |fits: &[f64]| {
        fits.iter()
            .map(|f| format!("{f:.2} %"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let linear_fits: Vec<f64> = linear.cases.iter().map(|c| c.fit_percent).collect();
    let yielding_fits: Vec<f64> = yielding.fits.iter().map(|f| f.1).collect();
    let prefer = bic[1] < bic[0];
    let reasons = vec![
        format!(
            "fit: linear {} , yielding {}",
            fit(&linear_fits),
            fit(&yielding_fits)
        ),
        format!(
            "objective: linear {:.4e}, yielding {:.4e} ({:.1} % lower)",
            linear.objective,
            yielding.objective,
            100.0 * (1.0 - yielding.objective / linear.objective)
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
