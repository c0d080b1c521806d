//! The model order a DOF table recommends when the residuals are
//! correlated (issue 39), and the rule that decided.
//!
//! Displacements integrated from accelerations carry drift: their
//! residuals are strongly autocorrelated, and an information criterion
//! that counts every sample as independent overfits (the bundled example's
//! BIC over n = 3363 samples chose 4 of its 3 masses). Every criterion here
//! counts the effective sample size instead, `n_eff = n/τ`
//! ([`bumpsim_estimate::effective`], spectral: τ the integrated
//! autocorrelation time of the largest model's residuals, the one closest
//! to the noise; one τ for every row so that the rows compare):
//!
//! - `AIC = n_eff ln(F/n) + 2q`, `BIC = n_eff ln(F/n) + q ln n_eff`
//!   (q estimated parameters; F the objective resolved as the table's own
//!   AIC and BIC resolve it);
//! - the extra-sum-of-squares F-test of each order against the next smaller
//!   one, `F = ((F_r − F)/Δq) / (F/(n_eff − q))` against
//!   `F(Δq, n_eff − q)` (Seber & Wild 1989, sec. 5.3), none when fewer
//!   effective samples than parameters remain;
//! - leave-one-load-case-out cross-validation ([`crate::crossval`]) when
//!   the sweep ran it.
//!
//! **The rule.** The orders whose BIC is within [`INDISTINCT`] of the
//! lowest cannot be told apart by it (Kass & Raftery 1995: a difference
//! below 2 is "not worth more than a bare mention"). One such order: the
//! BIC decides. Several: cross-validation decides among them (the lowest
//! error of the left-out cases) when every one of them has it; else the
//! F-test (from the smallest, the next order is taken while its improvement
//! is significant at [`SIGNIFICANCE`]); else the smallest.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_ident::{LoadCase, Settings, dofs::table, choice::choose};
//! let truth = MsdModel::new(vec![30.0, 900.0], vec![3e3], vec![6e5]).unwrap();
//! let case = |name: &str, peak: f64, phase: f64| {
//!     let force = (0..300).map(|k| peak * (k as f64 * 5e-4 * 50.0).sin().max(0.0)).collect();
//!     let mut c = LoadCase { name: name.into(), start: 0.0, step: 5e-4, force,
//!         measured: vec![], output_dof: 1, initial_velocity: 0.0, window: (0, 299),
//!         compare: Default::default() };
//!     c.measured = c.simulate(&truth).unwrap();
//!     // a slow drift on the measurement, as double integration leaves
//!     for (k, x) in c.measured.iter_mut().enumerate() {
//!         *x += 1e-4 * (k as f64 * 0.01 + phase).sin() + 1e-5 * (k as f64 * 1.7).sin();
//!     }
//!     c
//! };
//! let cases = vec![case("flat", 2e4, 0.0), case("pole", 3e4, 2.0)];
//! let rows: Vec<_> = table(&[1, 2, 3], &|dof| (cases.clone(), Settings::new(dof, 4)))
//!     .into_iter().map(Result::unwrap).collect();
//! let choice = choose(&rows).unwrap();
//! assert_eq!(choice.dof, 2, "{:?}: {}", choice.rule, choice.reason);
//! ```

use crate::result::Identification;
use bumpsim_core::units::format_number;
use bumpsim_estimate::effective::Effective;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

/// Orders whose BIC is within this of the lowest cannot be told apart.
pub const INDISTINCT: f64 = 2.0;

/// A larger order is taken by the F-test when its p-value is below this.
pub const SIGNIFICANCE: f64 = 0.05;

/// One order's criteria with the effective sample size.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Number of masses.
    pub dof: usize,
    /// Estimated parameters q.
    pub parameters: usize,
    /// Residuals n.
    pub samples: usize,
    /// `F` resolved as the table's AIC and BIC resolve it, m².
    pub objective: f64,
    /// `n_eff ln(F/n) + 2q`.
    pub aic: f64,
    /// `n_eff ln(F/n) + q ln n_eff`.
    pub bic: f64,
    /// The F-test's p-value against the next smaller order of the table.
    pub p_value: Option<f64>,
    /// The leave-one-load-case-out error, m².
    pub cross_validation: Option<f64>,
}

/// Which rule decided the recommendation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rule {
    /// The lowest BIC with the effective sample size, by more than
    /// [`INDISTINCT`].
    Bic,
    /// Cross-validation among the orders the BIC cannot tell apart.
    CrossValidation,
    /// The F-test among them (no cross-validation).
    FTest,
    /// The smallest of them (neither).
    Smallest,
}

/// The recommendation of a DOF table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Choice {
    /// The recommended number of masses.
    pub dof: usize,
    /// The rule that decided.
    pub rule: Rule,
    /// The orders the BIC cannot tell apart (the recommended among them).
    pub indistinct: Vec<usize>,
    /// The effective sample size of the largest order's residuals.
    pub effective: Effective,
    /// Every order's criteria, by number of masses.
    pub rows: Vec<Row>,
    /// Why the rule decided, in words.
    pub reason: String,
    /// The recommended model's parameters the data do not determine (at a
    /// bound, no interval, or one wider than a factor 1000): a
    /// recommendation never hides them.
    pub undetermined: Vec<String>,
}

/// The recommendation over `results` (see the module); `None` when no
/// result has a finite objective.
pub fn choose(results: &[Identification]) -> Option<Choice> {
    let mut usable: Vec<&Identification> = results
        .iter()
        .filter(|r| r.objective.is_finite() && r.aic.is_finite())
        .collect();
    usable.sort_by_key(|r| r.dof);
    let effective = usable.last()?.effective_samples;
    let mut rows: Vec<Row> = usable.iter().map(|r| row(r, effective.time)).collect();
    for j in 1..rows.len() {
        rows[j].p_value = f_test(&rows[j - 1], &rows[j], effective.time);
    }
    let lowest = rows.iter().map(|r| r.bic).fold(f64::INFINITY, f64::min);
    let tied: Vec<&Row> = rows
        .iter()
        .filter(|r| r.bic < lowest + INDISTINCT)
        .collect();
    let (dof, rule) = decide(&tied, effective.time);
    let indistinct: Vec<usize> = tied.iter().map(|r| r.dof).collect();
    let reason = detail(rule, &indistinct, &effective);
    let undetermined = usable
        .iter()
        .find(|r| r.dof == dof)
        .map(|r| undetermined(&r.uncertainty))
        .unwrap_or_default();
    Some(Choice {
        dof,
        rule,
        indistinct,
        effective,
        rows,
        reason,
        undetermined,
    })
}

/// The names of the parameters the data do not determine.
fn undetermined(u: &bumpsim_estimate::uncertainty::Uncertainty) -> Vec<String> {
    u.names
        .iter()
        .zip(&u.determined)
        .filter(|(_, d)| **d == Some(false))
        .map(|(n, _)| n.clone())
        .collect()
}

/// The criteria of one result with variance inflation `time` (τ).
fn row(r: &Identification, time: f64) -> Row {
    let q = r.uncertainty.fixed.iter().filter(|f| !**f).count();
    let n = r.residuals;
    // the resolved ln(F/n) of the table's own criteria: AIC = n ln(F/n) + 2q
    let ln_term = (r.aic - 2.0 * q as f64) / n as f64;
    let n_eff = (n as f64 / time).max(1.0);
    Row {
        dof: r.dof,
        parameters: q,
        samples: n,
        objective: n as f64 * ln_term.exp(),
        aic: n_eff * ln_term + 2.0 * q as f64,
        bic: n_eff * ln_term + q as f64 * n_eff.ln(),
        p_value: None,
        cross_validation: r.cross_validation.as_ref().map(|c| c.error),
    }
}

/// The p-value of `full` against `reduced` with `n/time` effective
/// samples; `None` when the full order has no more parameters or no
/// effective degrees of freedom are left.
pub fn f_test(reduced: &Row, full: &Row, time: f64) -> Option<f64> {
    let extra = full.parameters.checked_sub(reduced.parameters)?;
    let freedom = full.samples as f64 / time - full.parameters as f64;
    if extra == 0 || freedom < 1.0 {
        return None;
    }
    let gain = (reduced.objective - full.objective).max(0.0) / extra as f64;
    let statistic = gain / (full.objective / freedom);
    let distribution = FisherSnedecor::new(extra as f64, freedom).ok()?;
    Some(distribution.sf(statistic))
}

/// The order and the rule among `tied` (by number of masses).
fn decide(tied: &[&Row], time: f64) -> (usize, Rule) {
    if let [one] = tied {
        return (one.dof, Rule::Bic);
    }
    let errors: Option<Vec<f64>> = tied.iter().map(|r| r.cross_validation).collect();
    if let Some(errors) = errors {
        let best = (0..tied.len())
            .min_by(|&a, &b| errors[a].total_cmp(&errors[b]))
            .unwrap_or(0);
        return (tied[best].dof, Rule::CrossValidation);
    }
    let mut chosen = tied[0];
    let mut tested = false;
    for &next in &tied[1..] {
        let p = f_test(chosen, next, time);
        tested |= p.is_some();
        if p.is_some_and(|p| p < SIGNIFICANCE) {
            chosen = next;
        }
    }
    match tested {
        true => (chosen.dof, Rule::FTest),
        false => (tied[0].dof, Rule::Smallest),
    }
}

impl Rule {
    /// Its name as the recommendation prints it.
    pub fn label(self) -> &'static str {
        match self {
            Rule::Bic => "lowest BIC",
            Rule::CrossValidation => "cross-validation",
            Rule::FTest => "F-test",
            Rule::Smallest => "the smallest",
        }
    }
}

/// Why `rule` decided among the orders `tied`, in words.
fn detail(rule: Rule, tied: &[usize], effective: &Effective) -> String {
    let samples = format!(
        "{} effective of {} samples, {}",
        format_number(effective.effective, 3),
        effective.samples,
        effective.method.label()
    );
    let list = tied
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ");
    let apart = format!("the BIC ({samples}) cannot tell {list} DOF apart");
    match rule {
        Rule::Bic => format!("counted with {samples}"),
        Rule::CrossValidation => {
            format!("{apart}; this one predicts the left-out load cases best")
        }
        Rule::FTest => format!("{apart}; the next larger is taken while significant"),
        Rule::Smallest => format!("{apart}, and no other rule can"),
    }
}

/// The DOF table's lines of the choice: every order's criteria with the
/// effective sample size, then the recommendation.
pub fn lines(choice: &Choice) -> String {
    let e = &choice.effective;
    let mut out = format!(
        "with correlated residuals: n_eff = {} of {} samples ({} τ = {}, lag-1 ρ = {})\n",
        format_number(e.effective, 4),
        e.samples,
        e.method.label(),
        format_number(e.time, 4),
        format_number(e.lag_one, 4)
    );
    out += &format!(
        "{:>4} {:>12} {:>12} {:>12} {:>16}\n",
        "DOF", "AIC n_eff", "BIC n_eff", "F-test p", "CV error m²"
    );
    for r in &choice.rows {
        let p = r.p_value.map_or("-".into(), |p| format_number(p, 3));
        let cv = r
            .cross_validation
            .map_or("-".into(), |c| format_number(c, 5));
        out += &format!(
            "{:>4} {:>12} {:>12} {p:>12} {cv:>16}\n",
            r.dof,
            format_number(r.aic, 6),
            format_number(r.bic, 6)
        );
    }
    out += &format!(
        "recommended: {} DOF ({}): {}\n",
        choice.dof,
        choice.rule.label(),
        choice.reason
    );
    let estimated = choice
        .rows
        .iter()
        .find(|r| r.dof == choice.dof)
        .map_or(0, |r| r.parameters);
    match choice.undetermined.len() {
        0 => {}
        n if n >= estimated => {
            out += &format!(
                "  but the data determine none of its parameters ({}; see that model's \
                 warnings): this model is not identified by these tests and none of its values \
                 is to be quoted; add load cases that excite them, fix some from other \
                 knowledge, or take a smaller model\n",
                choice.undetermined.join(", ")
            )
        }
        _ => {
            out += &format!(
                "  but the data do not determine its {} (see that model's warnings): its values \
                 are not to be quoted; add load cases that excite them, or fix them from other \
                 knowledge\n",
                choice.undetermined.join(", ")
            )
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_estimate::effective::Method;

    /// A recommendation of 2 DOF (3 parameters) with `undetermined` ones.
    fn choice(undetermined: &[&str]) -> Choice {
        let row = Row {
            dof: 2,
            parameters: 3,
            samples: 1000,
            objective: 1e-6,
            aic: -100.0,
            bic: -95.0,
            p_value: None,
            cross_validation: None,
        };
        Choice {
            dof: 2,
            rule: Rule::Bic,
            indistinct: vec![2],
            effective: Effective {
                method: Method::Spectral,
                samples: 1000,
                effective: 10.0,
                time: 100.0,
                lag_one: 0.99,
                window: 50,
                reliable: true,
            },
            rows: vec![row],
            reason: "counted with 10 effective samples".into(),
            undetermined: undetermined.iter().map(|s| s.to_string()).collect(),
        }
    }

    /// Issue 44: a recommended model never has undetermined parameters
    /// without saying so, and says so plainly when none is determined.
    #[test]
    fn the_recommendation_names_what_the_data_do_not_determine() {
        let text = lines(&choice(&[]));
        assert!(text.contains("recommended: 2 DOF"), "{text}");
        assert!(!text.contains("determine"), "{text}");
        let text = lines(&choice(&["k1"]));
        assert!(
            text.contains("but the data do not determine its k1"),
            "{text}"
        );
        let text = lines(&choice(&["m1", "c1", "k1"]));
        assert!(
            text.contains("but the data determine none of its parameters (m1, c1, k1;"),
            "{text}"
        );
    }
}
