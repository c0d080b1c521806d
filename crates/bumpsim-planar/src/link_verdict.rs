//! Which links the planar data want (issue 46, item 3): the car with
//! linear side members or with nonlinear ones (progressive, yielding:
//! [`crate::identify::LinkLaws`]), each identified from the same cases, compared as
//! the 1-D DOF table compares model orders (`bumpsim_ident::choice`).
//!
//! **Held out.** Each of the study's `validate = true` cases is scored by
//! what it can judge:
//! - a case with a striker is run **forward** by each identified car alone
//!   ([`crate::forward`]: the car, its bumper and the striker, no measured
//!   force), scored by the mean fit (%) of its channels: force,
//!   x-acceleration and yaw rate. This is the prediction the side members'
//!   law decides: how hard the car pushes back at a crush the training
//!   tests did not reach;
//! - a case without one (or whose forward run fails for either car) is
//!   **replayed** ([`crate::identify::predict`]), scored by the mean of its x and yaw
//!   fits. The measured forces drive the replay, so the side members'
//!   stiffness moves it little: it can tell a wrong mass or yaw inertia,
//!   hardly a wrong link law.
//!
//! **BIC** on the training residuals:
//! `BIC = n_eff ln(F/n) + q ln n_eff` (Schwarz 1978;
//! [`bumpsim_estimate::effective::bic`]), F the data objective and q the
//! free parameters, with the n residuals' effective number `n_eff = n/τ`,
//! τ the integrated autocorrelation time of the nonlinear car's residuals
//! (Sokal's window, [`bumpsim_estimate::effective`], the estimator the 1-D
//! DOF table uses; the larger model's residuals are the closer to the
//! noise, and one τ serves both so that they compare). The AR(1) inflation
//! `(1 + ρ)/(1 − ρ)` is not used here: displacement residuals have
//! ρ ≈ 0.9995, which counts two effective residuals of thousands and makes
//! the penalty `q ln n_eff` vanish.
//!
//! **The rule** ("prefer the simpler model" unless a criterion tells them
//! apart):
//! 1. held-out cases present and the two cars' mean held-out scores apart
//!    by more than [`HELD_OUT_MARGIN`]: the better predicting car (a
//!    prediction is what the training fit cannot test);
//! 2. else the BICs apart by more than [`INDISTINCT`] (Kass & Raftery
//!    1995: a difference below 2 is "not worth more than a bare mention"):
//!    the lower;
//! 3. else the linear links.
//!
//! The reasons (fits, objectives, parameters, τ, BIC, every held-out case's
//! scores, the criterion that decided) are printed whatever the verdict.

use crate::car::{PlanarCar, PlanarError};
use crate::forward::forward;
use crate::identify::{PlanarCase, PlanarIdentification, predict};
use bumpsim_estimate::effective::{Effective, bic};

/// Mean held-out scores closer than this (percentage points of fit) do not
/// tell the cars apart: run-to-run differences of a forward prediction
/// (the onset alignment's sample, the search's optimum) are of this order.
pub const HELD_OUT_MARGIN: f64 = 1.0;

/// BICs closer than this do not tell the cars apart (Kass & Raftery 1995,
/// as the 1-D DOF table's `INDISTINCT`).
pub const INDISTINCT: f64 = 2.0;

/// The criterion that decided a verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Criterion {
    /// The held-out cases' scores.
    HeldOut,
    /// The BIC on the training residuals.
    Bic,
    /// Neither told the cars apart: the simpler (linear) links.
    Simpler,
}

impl Criterion {
    /// Its name as the reasons print it.
    pub fn label(self) -> &'static str {
        match self {
            Criterion::HeldOut => "the held-out tests",
            Criterion::Bic => "the BIC",
            Criterion::Simpler => "neither criterion (the simpler links)",
        }
    }
}

/// How a held-out case was scored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Judged {
    /// Run forward from its striker: mean of the channels' fits.
    Forward,
    /// Replayed under its measured forces: mean of the x and yaw fits.
    Replay,
}

/// One held-out case's scores.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOutScore {
    /// The case.
    pub case: String,
    /// How it was scored.
    pub judged: Judged,
    /// The linear and the nonlinear car's score, % of fit.
    pub scores: [f64; 2],
    /// Each car's channels as printed (`force 81.94 %, …`).
    pub detail: [String; 2],
}

/// The comparison and its reasons.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkVerdict {
    /// Whether the nonlinear links are preferred.
    pub nonlinear: bool,
    /// The criterion that decided.
    pub criterion: Criterion,
    /// BIC of the linear and the nonlinear car.
    pub bic: [f64; 2],
    /// The effective number of residuals the BIC counts.
    pub effective: Effective,
    /// Mean held-out score (%) of the linear and the nonlinear car; `None`
    /// without held-out cases.
    pub held_out: Option<[f64; 2]>,
    /// Every held-out case's scores.
    pub cases: Vec<HeldOutScore>,
    /// The reasons, one line each.
    pub reasons: Vec<String>,
}

/// The free parameters of an identification.
fn free(result: &PlanarIdentification) -> usize {
    result.uncertainty.fixed.iter().filter(|f| !**f).count()
}

/// `car`'s forward channels on `case`: (mean fit %, printed), `None` when
/// the case has no striker or the run fails.
fn ahead(car: &PlanarCar, case: &PlanarCase) -> Option<(f64, String)> {
    case.striker.as_ref()?;
    let run = forward(car, case).ok()?;
    let fits: Vec<f64> = run.channels.iter().map(|c| c.fit_percent).collect();
    let mean = fits.iter().sum::<f64>() / fits.len().max(1) as f64;
    let text = run
        .channels
        .iter()
        .map(|c| format!("{} {:.2} %", c.name, c.fit_percent))
        .collect::<Vec<_>>()
        .join(", ");
    (!fits.is_empty() && mean.is_finite()).then_some((mean, text))
}

/// `car`'s replay of `case`: (mean of x and yaw fits %, printed).
fn replayed(car: &PlanarCar, case: &PlanarCase) -> Result<(f64, String), PlanarError> {
    let fit = predict(car, case)?.fit;
    Ok((
        0.5 * (fit.fit_x + fit.fit_yaw),
        format!("x {:.2} %, yaw {:.2} %", fit.fit_x, fit.fit_yaw),
    ))
}

/// One held-out case scored by the two cars (see the module).
fn scored(cars: [&PlanarCar; 2], case: &PlanarCase) -> Result<HeldOutScore, PlanarError> {
    let (judged, [l, n]) = match (ahead(cars[0], case), ahead(cars[1], case)) {
        (Some(l), Some(n)) => (Judged::Forward, [l, n]),
        _ => (
            Judged::Replay,
            [replayed(cars[0], case)?, replayed(cars[1], case)?],
        ),
    };
    Ok(HeldOutScore {
        case: case.name.clone(),
        judged,
        scores: [l.0, n.0],
        detail: [l.1, n.1],
    })
}

/// The decision from the mean held-out scores (linear, nonlinear) and the
/// BICs (linear, nonlinear): the rule of the module.
pub fn decide(held_out: Option<[f64; 2]>, bic: [f64; 2]) -> (bool, Criterion) {
    if let Some([l, n]) = held_out.filter(|[l, n]| (n - l).abs() > HELD_OUT_MARGIN) {
        return (n > l, Criterion::HeldOut);
    }
    match (bic[0] - bic[1]).abs() > INDISTINCT {
        true => (bic[1] < bic[0], Criterion::Bic),
        false => (false, Criterion::Simpler),
    }
}

fn fits(result: &PlanarIdentification) -> String {
    result
        .fits
        .iter()
        .map(|f| format!("{} x {:.2} % yaw {:.2} %", f.name, f.fit_x, f.fit_yaw))
        .collect::<Vec<_>>()
        .join(", ")
}

fn word(nonlinear: bool) -> &'static str {
    match nonlinear {
        true => "nonlinear",
        false => "linear",
    }
}

/// Compares a linear identification with a nonlinear one of the same
/// cases, on the held-out cases `held` where there are any (see the
/// module); an error when a held-out case cannot be replayed.
pub fn compare_links(
    linear: &PlanarIdentification,
    nonlinear: &PlanarIdentification,
    held: &[PlanarCase],
) -> Result<LinkVerdict, PlanarError> {
    let effective = nonlinear.effective;
    let n = effective.samples.max(1);
    let counted = effective.effective.clamp(1.0, n as f64);
    let (q_l, q_n) = (free(linear), free(nonlinear));
    let bics = [
        bic(linear.objective, n, counted, q_l),
        bic(nonlinear.objective, n, counted, q_n),
    ];
    let cases = held
        .iter()
        .map(|case| scored([&linear.car, &nonlinear.car], case))
        .collect::<Result<Vec<_>, _>>()?;
    let held_out = (!cases.is_empty()).then(|| {
        let mean = |i: usize| cases.iter().map(|c| c.scores[i]).sum::<f64>() / cases.len() as f64;
        [mean(0), mean(1)]
    });
    let (prefer, criterion) = decide(held_out, bics);
    let unit = linear.domain.squared_unit();
    let mut reasons = vec![
        format!("training fit: linear {}", fits(linear)),
        format!("training fit: nonlinear {}", fits(nonlinear)),
        format!(
            "objective: linear {:.4e} {unit}, nonlinear {:.4e} {unit} ({:.1} % lower)",
            linear.objective,
            nonlinear.objective,
            100.0 * (1.0 - nonlinear.objective / linear.objective)
        ),
        format!(
            "free parameters: linear {q_l}, nonlinear {q_n}; {counted:.1} effective of {n} residuals (integrated autocorrelation time τ = {:.1} samples{})",
            effective.time,
            match effective.reliable {
                true => "",
                false => ", a lower bound: the series are shorter than 5 τ",
            }
        ),
        format!(
            "BIC: linear {:.1}, nonlinear {:.1} (apart by {:.1}; {INDISTINCT} or less tells nothing)",
            bics[0],
            bics[1],
            (bics[0] - bics[1]).abs()
        ),
    ];
    for c in &cases {
        reasons.push(format!(
            "held out {} ({}): linear {:.2} % ({}), nonlinear {:.2} % ({})",
            c.case,
            match c.judged {
                Judged::Forward => "forward from its striker, mean of the channels",
                Judged::Replay => "replayed under its measured forces, mean of x and yaw",
            },
            c.scores[0],
            c.detail[0],
            c.scores[1],
            c.detail[1]
        ));
    }
    if let Some([l, nl]) = held_out {
        reasons.push(format!(
            "held out, mean over {} case(s): linear {l:.2} %, nonlinear {nl:.2} % (apart by {:.2} points; {HELD_OUT_MARGIN} or less tells nothing)",
            cases.len(),
            (nl - l).abs()
        ));
    }
    reasons.push(format!(
        "verdict: {} side members, decided by {}",
        word(prefer),
        criterion.label()
    ));
    Ok(LinkVerdict {
        nonlinear: prefer,
        criterion,
        bic: bics,
        effective,
        held_out,
        cases,
        reasons,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule on known answers: a clear held-out difference decides
    /// either way whatever the BIC; a held-out tie falls to the BIC; a BIC
    /// tie too to the linear links.
    #[test]
    fn the_rule_takes_the_first_criterion_that_tells_the_cars_apart() {
        let lower_nonlinear = [100.0, 80.0];
        let lower_linear = [80.0, 100.0];
        let tie = [100.0, 99.0];
        assert_eq!(
            decide(Some([72.0, 82.0]), lower_linear),
            (true, Criterion::HeldOut)
        );
        assert_eq!(
            decide(Some([82.0, 72.0]), lower_nonlinear),
            (false, Criterion::HeldOut)
        );
        assert_eq!(
            decide(Some([75.28, 75.18]), lower_nonlinear),
            (true, Criterion::Bic)
        );
        assert_eq!(decide(None, lower_linear), (false, Criterion::Bic));
        assert_eq!(decide(None, tie), (false, Criterion::Simpler));
        assert_eq!(decide(Some([90.0, 90.5]), tie), (false, Criterion::Simpler));
    }
}
