//! Which links the planar data want (issue 46, item 3): the car with
//! linear side members or with nonlinear ones (progressive, yielding:
//! [`super::LinkLaws`]), each identified from the same cases, compared as
//! the 1-D chain's links are (`bumpsim_ident::links::verdict`).
//!
//! - **BIC** on the training residuals ([`bumpsim_estimate::effective::bic`]):
//!   `BIC = n_eff ln(F/n) + q ln n_eff` with the n residuals' effective
//!   number `n_eff = n / ((1 + ρ)/(1 − ρ))` (the variance inflation of
//!   their lag-1 correlation ρ), F the data objective and q the free
//!   parameters;
//! - **held out**: the mean of the x and yaw fits (%) of the study's
//!   `validate = true` cases replayed by each car ([`super::predict`]).
//!
//! The held-out fits decide where the study has held-out cases (they test
//! what the training fit cannot: a prediction), the BIC otherwise; the
//! reasons (fits, objectives, parameters, BIC, held-out fits) are printed
//! whatever the verdict.

use super::{PlanarCase, PlanarIdentification, predict};
use crate::car::PlanarError;
use bumpsim_estimate::effective::bic;

/// The comparison and its reasons.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkVerdict {
    /// Whether the nonlinear links are preferred.
    pub nonlinear: bool,
    /// BIC of the linear and the nonlinear car.
    pub bic: [f64; 2],
    /// Mean held-out fit (x and yaw, %) of the linear and the nonlinear
    /// car; `None` without held-out cases.
    pub held_out: Option<[f64; 2]>,
    /// The reasons, one line each.
    pub reasons: Vec<String>,
}

/// The BIC of an identification and its free parameters.
fn criterion(result: &PlanarIdentification) -> (f64, usize, usize, f64) {
    let u = &result.uncertainty;
    let q = u.fixed.iter().filter(|f| !**f).count();
    let n = u.degrees_of_freedom + q;
    let effective = (n as f64 / result.inflation.max(1.0)).clamp(2.0, n.max(2) as f64);
    (bic(result.objective, n, effective, q), q, n, effective)
}

/// The mean held-out fit (x and yaw, %) of `result`'s car on `held`.
fn held_out(result: &PlanarIdentification, held: &[PlanarCase]) -> Result<f64, PlanarError> {
    let mut sum = 0.0;
    for case in held {
        let fit = predict(&result.car, case)?.fit;
        sum += 0.5 * (fit.fit_x + fit.fit_yaw);
    }
    Ok(sum / held.len() as f64)
}

fn fits(result: &PlanarIdentification) -> String {
    result
        .fits
        .iter()
        .map(|f| format!("{} x {:.2} % yaw {:.2} %", f.name, f.fit_x, f.fit_yaw))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Compares a linear identification with a nonlinear one of the same
/// cases, on the held-out cases `held` where there are any.
pub fn compare_links(
    linear: &PlanarIdentification,
    nonlinear: &PlanarIdentification,
    held: &[PlanarCase],
) -> Result<LinkVerdict, PlanarError> {
    let (bic_l, q_l, n, effective) = criterion(linear);
    let (bic_n, q_n, _, _) = criterion(nonlinear);
    let held_out = match held.is_empty() {
        true => None,
        false => Some([held_out(linear, held)?, held_out(nonlinear, held)?]),
    };
    let by_bic = bic_n < bic_l;
    let prefer = match held_out {
        Some([l, nl]) => nl > l,
        None => by_bic,
    };
    let mut reasons = vec![
        format!("training fit: linear {}", fits(linear)),
        format!("training fit: nonlinear {}", fits(nonlinear)),
        format!(
            "objective: linear {:.4e} m², nonlinear {:.4e} m² ({:.1} % lower)",
            linear.objective,
            nonlinear.objective,
            100.0 * (1.0 - nonlinear.objective / linear.objective)
        ),
        format!(
            "free parameters: linear {q_l}, nonlinear {q_n}; {effective:.0} effective of {n} residuals"
        ),
        format!(
            "BIC: linear {bic_l:.1}, nonlinear {bic_n:.1}: {}",
            match by_bic {
                true => "the training data want the nonlinear links",
                false => "the training data do not need the nonlinear links",
            }
        ),
    ];
    if let Some([l, nl]) = held_out {
        reasons.push(format!(
            "held-out fit (mean of x and yaw over {} case(s)): linear {l:.2} %, nonlinear {nl:.2} %: {}",
            held.len(),
            match prefer {
                true => "the held-out tests want the nonlinear links",
                false => "the held-out tests do not need the nonlinear links",
            }
        ));
    }
    reasons.push(format!(
        "verdict: {} side members",
        match prefer {
            true => "nonlinear",
            false => "linear",
        }
    ));
    Ok(LinkVerdict {
        nonlinear: prefer,
        bic: [bic_l, bic_n],
        held_out,
        reasons,
    })
}
