//! Regression on responses with known standard errors: identified
//! parameters (k1, c1, m2, ...) of DOE points, each with the
//! identification's standard error (issue 39, item 4).
//!
//! The model is the mixed-effects meta-regression
//! `y_i = x_iβ + ε_i + δ_i`, `δ_i ~ N(0, s_i²)` with `s_i` known (the
//! identification's standard error of run i), `ε_i ~ N(0, τ²)` unknown
//! (run-to-run scatter and model error). With `v_i = τ² + s_i²`,
//! `W = diag(1/v_i)` and `P = W − WX(XᵀWX)⁻¹XᵀW`:
//!
//! - τ² by restricted maximum likelihood (REML), maximising
//!   `ℓ_R(τ²) = −½[Σ ln v_i + ln det(XᵀWX) + eᵀWe]` (e the WLS residuals)
//!   by Fisher scoring, `τ² ← τ² + (eᵀW²e − tr P) / tr(P²)`, steps that lower
//!   `ℓ_R` halved, τ² truncated at 0 (Viechtbauer 2005, J. Educ. Behav.
//!   Stat. 30:261–293; the default of metafor, Viechtbauer 2010, J. Stat.
//!   Softw. 36(3), from which the scoring step is taken). REML rather than
//!   the DerSimonian–Laird moments: DL weights by 1/s_i² and cannot take
//!   s_i = 0, REML is less biased for few runs (Viechtbauer 2005; Langan et
//!   al. 2019, Res. Synth. Methods 10:83), and with every s_i = 0 it is
//!   exactly the OLS variance `SS_res/(n − p)`;
//! - weighted least squares with `w_i = 1/(τ̂² + s_i²)`: `β̂ = (XᵀWX)⁻¹XᵀWy`,
//!   covariance `(XᵀWX)⁻¹` with scale 1 (the weights are absolute inverse
//!   variances: no residual mean square multiplies it), intervals
//!   `β̂ ± t_{n−p} SE` (metafor's `test = "t"`).
//!
//! Consequences, each tested: with every `s_i = 0` this is [`fit`] exactly
//! (τ̂² = σ̂², `(XᵀWX)⁻¹ = σ̂²(XᵀX)⁻¹`, same t); when every `s_i ≥ σ̂` of the
//! OLS fit, `(XᵀWX)⁻¹ ≥ s_min²(XᵀX)⁻¹ ≥ σ̂²(XᵀX)⁻¹`, so each interval is at
//! least the OLS one: the identification's uncertainty is included. An
//! intercept-only model is the random-effects mean of a meta-analysis. A
//! saturated model (n = p) leaves no residual to tell τ² from the s_i: it
//! gets its coefficients without intervals and the reason, as OLS does.
//! Standard errors must be finite, ≥ 0, with a finite square, and all zero
//! or all positive (a zero beside positive ones would be an exact
//! identification with infinite weight). The residual heterogeneity
//! `Q_E = Σ e_i²/s_i²` of the fit weighted by 1/s_i² is χ²(n − p) when
//! τ² = 0 (Cochran's Q of meta-regression), given with its p value.
//!
//! ```
//! use bumpsim_doe::regression::terms;
//! use bumpsim_doe::weighted::fit_weighted;
//! let z: Vec<Vec<f64>> = [-1.0, -1.0, 0.0, 1.0, 1.0].iter().map(|v| vec![*v]).collect();
//! let y = [1.1, 0.8, 2.1, 3.2, 2.9];
//! let names = vec!["A".to_string()];
//! let ols = fit_weighted(&z, &y, &[0.0; 5], &terms(1, false, false), &names).unwrap();
//! let big = fit_weighted(&z, &y, &[1.0; 5], &terms(1, false, false), &names).unwrap();
//! let [lo, hi] = ols.fit.ci95[1].unwrap();
//! let [wlo, whi] = big.fit.ci95[1].unwrap();
//! assert!(wlo < lo && whi > hi); // the identification's uncertainty widens the interval
//! assert_eq!(big.weighting.tau2, Some(0.0)); // the scatter is within the SEs
//! ```

use crate::regression::{Anova, Fit, RegressionError, Term, fit};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};

/// Iterations of the Fisher scoring before it gives up.
pub const MAX_ITERATIONS: usize = 500;

/// Residual heterogeneity: Cochran's Q of the fit weighted by 1/s_i².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Heterogeneity {
    /// `Q_E = Σ e_i²/s_i²`.
    pub q: f64,
    /// Its degrees of freedom, n − p.
    pub df: usize,
    /// P(χ²(df) ≥ Q_E): small when the runs scatter more than their SEs say.
    pub p: f64,
}

/// How the runs were weighted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Weighting {
    /// τ² (response unit²): REML, or σ̂² of OLS when every SE is zero;
    /// `None` when not estimable (a saturated model).
    pub tau2: Option<f64>,
    /// `REML`, or `OLS` when every standard error is zero.
    pub method: String,
    /// The standard errors s_i (response unit).
    pub standard_errors: Vec<f64>,
    /// The weights 1/(τ² + s_i²) (1/unit²).
    pub weights: Vec<f64>,
    /// Fisher-scoring iterations.
    pub iterations: usize,
    /// Residual heterogeneity (every s_i > 0 and n > p).
    pub heterogeneity: Option<Heterogeneity>,
    /// The OLS standard errors of the same terms, for comparison.
    pub ols_std_errors: Vec<Option<f64>>,
    /// What a reader must know (τ² at 0, not estimable).
    pub notes: Vec<String>,
}

impl Weighting {
    /// Each run's share of the total weight, smallest and largest.
    pub fn share_range(&self) -> [f64; 2] {
        let total: f64 = self.weights.iter().sum();
        let share = |w: f64| w / total;
        let lo = self.weights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self.weights.iter().copied().fold(0.0, f64::max);
        [share(lo), share(hi)]
    }
}

/// A weighted fit: the [`Fit`] (its `xtx_inverse` is the coefficients'
/// covariance `(XᵀWX)⁻¹` in unit², its R² and Q² weighted, its ANOVA sums
/// weighted and divided by the mean weight, its residual SD `None`: τ is
/// in the weighting) and how the runs were weighted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WeightedFit {
    /// The fit.
    pub fit: Fit,
    /// The weighting.
    pub weighting: Weighting,
}

/// Fits `y` with standard errors `se` on `terms` of coded runs `z`.
pub fn fit_weighted(
    z: &[Vec<f64>],
    y: &[f64],
    se: &[f64],
    terms: &[Term],
    factors: &[String],
) -> Result<WeightedFit, RegressionError> {
    check(se, y.len())?;
    let ols = fit(z, y, terms, factors)?;
    if se.iter().all(|s| *s == 0.0) {
        return Ok(unweighted(ols, se));
    }
    let x = DMatrix::from_fn(z.len(), terms.len(), |r, c| terms[c].value(&z[r]));
    let (n, p) = x.shape();
    let rms = (ols.residuals.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt();
    let scale = se.iter().copied().fold(rms, f64::max);
    let scaled = Scaled {
        x,
        y: y.iter().map(|v| v / scale).collect(),
        s2: se.iter().map(|s| (s / scale).powi(2)).collect(),
    };
    let (tau2, state, iterations) = match n > p {
        true => scaled.reml(ols.residual_sd.unwrap_or(0.0) / scale)?,
        false => (0.0, scaled.evaluate(0.0).ok_or_else(|| span(se))?, 0),
    };
    let mut out = scaled.finish(&state, scale, ols, se)?;
    out.weighting.iterations = iterations;
    out.weighting.heterogeneity = scaled.heterogeneity(n - p);
    if n > p {
        out.weighting.tau2 = Some(tau2 * scale * scale);
        if tau2 == 0.0 {
            out.weighting.notes.push(
                "τ² = 0: the runs scatter no more than their standard errors say (REML at its bound)"
                    .into(),
            );
        }
    } else {
        out.weighting.notes.push(format!(
            "τ² not estimable: the model is saturated ({n} runs for {p} terms), no residual tells run-to-run scatter from the identification's; no intervals"
        ));
    }
    Ok(out)
}

/// Refuses standard errors that are not finite, negative, with a square
/// beyond the largest number, or zero beside positive ones.
fn check(se: &[f64], n: usize) -> Result<(), RegressionError> {
    if se.len() != n {
        return Err(RegressionError::Design(format!(
            "{} standard errors for {n} runs: give one per run",
            se.len()
        )));
    }
    if let Some(row) = se.iter().position(|s| !(*s >= 0.0 && (s * s).is_finite())) {
        return Err(RegressionError::StandardError {
            row: row + 1,
            value: se[row],
        });
    }
    let zero = se.iter().position(|s| *s == 0.0);
    let positive = se.iter().position(|s| *s > 0.0);
    if let (Some(zero), Some(positive)) = (zero, positive) {
        return Err(RegressionError::ZeroStandardError {
            row: zero + 1,
            positive: positive + 1,
            value: se[positive],
        });
    }
    Ok(())
}

fn span(se: &[f64]) -> RegressionError {
    let lo = se.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = se.iter().copied().fold(0.0, f64::max);
    RegressionError::Design(format!(
        "standard errors from {lo:e} to {hi:e}: they span too many orders of magnitude to weight the runs by"
    ))
}

/// Every s_i = 0: the OLS fit, τ² = σ̂².
fn unweighted(ols: Fit, se: &[f64]) -> WeightedFit {
    let tau2 = ols.residual_sd.map(|s| s * s);
    let weight = tau2.map_or(1.0, |t| 1.0 / t);
    WeightedFit {
        weighting: Weighting {
            tau2,
            method: "OLS".into(),
            standard_errors: se.to_vec(),
            weights: vec![weight; se.len()],
            iterations: 0,
            heterogeneity: None,
            ols_std_errors: ols.std_errors.clone(),
            notes: vec!["every standard error is 0: ordinary least squares, τ² = σ̂²".into()],
        },
        fit: ols,
    }
}

/// The problem in units of `scale` (the largest s_i or the OLS residuals'
/// RMS), so that squares neither overflow nor underflow.
struct Scaled {
    x: DMatrix<f64>,
    y: Vec<f64>,
    s2: Vec<f64>,
}

/// The WLS solution at one τ², with what REML needs.
struct State {
    weights: Vec<f64>,
    beta: DVector<f64>,
    covariance: DMatrix<f64>,
    leverage: Vec<f64>,
    residuals: Vec<f64>,
    /// `ℓ_R`.
    likelihood: f64,
    /// `(eᵀW²e − tr P) / tr(P²)`: the Fisher-scoring step.
    step: f64,
}

impl Scaled {
    /// WLS at `tau2`; `None` when a weight or the solution is not finite.
    fn evaluate(&self, tau2: f64) -> Option<State> {
        let (n, p) = self.x.shape();
        let weights: Vec<f64> = self.s2.iter().map(|s2| 1.0 / (tau2 + s2)).collect();
        let root = DVector::from_iterator(n, weights.iter().map(|w| w.sqrt()));
        let xw = DMatrix::from_fn(n, p, |r, c| root[r] * self.x[(r, c)]);
        let svd = xw.svd(true, true);
        let (u, v_t, s) = (svd.u?, svd.v_t?, svd.singular_values);
        if s.min() <= 1e-13 * s.max() || !s.iter().all(|v| v.is_finite()) {
            return None;
        }
        let yw = DVector::from_iterator(n, (0..n).map(|r| root[r] * self.y[r]));
        let uty = u.transpose() * yw;
        let beta = v_t.transpose() * DVector::from_iterator(p, (0..p).map(|k| uty[k] / s[k]));
        let covariance = DMatrix::from_fn(p, p, |a, b| {
            (0..p)
                .map(|k| v_t[(k, a)] * v_t[(k, b)] / (s[k] * s[k]))
                .sum()
        });
        let fitted = &self.x * &beta;
        let residuals: Vec<f64> = (0..n).map(|r| self.y[r] - fitted[r]).collect();
        let leverage: Vec<f64> = (0..n).map(|r| u.row(r).norm_squared()).collect();
        let sum = |f: &dyn Fn(usize) -> f64| (0..n).map(f).sum::<f64>();
        let trace_p = sum(&|i| weights[i] * (1.0 - leverage[i]));
        let ewwe = sum(&|i| (weights[i] * residuals[i]).powi(2));
        let m = DMatrix::from_fn(p, p, |a, b| sum(&|i| weights[i] * u[(i, a)] * u[(i, b)]));
        let trace_pp =
            sum(&|i| weights[i] * weights[i] * (1.0 - 2.0 * leverage[i])) + m.norm_squared();
        let likelihood = -0.5
            * (sum(&|i| (tau2 + self.s2[i]).ln())
                + s.iter().map(|v| 2.0 * v.ln()).sum::<f64>()
                + sum(&|i| weights[i] * residuals[i] * residuals[i]));
        let step = (ewwe - trace_p) / trace_pp;
        let finite = likelihood.is_finite() && beta.iter().all(|b| b.is_finite());
        finite.then_some(State {
            weights,
            beta,
            covariance,
            leverage,
            residuals,
            likelihood,
            step: if step.is_finite() { step } else { 0.0 },
        })
    }

    /// τ² by REML from the OLS residual SD `sigma` (scaled): τ², the state
    /// there and the iterations taken.
    fn reml(&self, sigma: f64) -> Result<(f64, State, usize), RegressionError> {
        let mean_s2 = self.s2.iter().sum::<f64>() / self.s2.len() as f64;
        let mut tau2 = (sigma * sigma - mean_s2).max(0.0);
        let fail = || RegressionError::Design("the weighted fit is not a finite number".into());
        let mut state = self.evaluate(tau2).ok_or_else(fail)?;
        for iteration in 1..=MAX_ITERATIONS {
            let (next, moved) = self.line_search(tau2, &state);
            let done = (next - tau2).abs() <= 1e-12 * (tau2 + mean_s2);
            tau2 = next;
            state = moved;
            if done {
                return Ok((tau2, state, iteration));
            }
        }
        Err(RegressionError::NotConverged {
            iterations: MAX_ITERATIONS,
        })
    }

    /// The scoring step from `tau2`, halved until `ℓ_R` does not drop.
    fn line_search(&self, tau2: f64, state: &State) -> (f64, State) {
        let mut step = state.step;
        for _ in 0..60 {
            let next = (tau2 + step).max(0.0);
            if let Some(s) = self.evaluate(next)
                && s.likelihood >= state.likelihood - 1e-14 * state.likelihood.abs()
            {
                return (next, s);
            }
            step *= 0.5;
        }
        (tau2, self.evaluate(tau2).expect("evaluated before"))
    }

    /// Cochran's Q of the fit weighted by 1/s_i² (τ² = 0).
    fn heterogeneity(&self, df: usize) -> Option<Heterogeneity> {
        let state = (df > 0).then(|| self.evaluate(0.0)).flatten()?;
        let q: f64 = (0..self.y.len())
            .map(|i| state.weights[i] * state.residuals[i].powi(2))
            .sum();
        let chi = ChiSquared::new(df as f64).ok()?;
        Some(Heterogeneity {
            q,
            df,
            p: 1.0 - chi.cdf(q),
        })
    }

    /// The fit in the response's units from the scaled state.
    fn finish(
        &self,
        state: &State,
        scale: f64,
        ols: Fit,
        se: &[f64],
    ) -> Result<WeightedFit, RegressionError> {
        let (n, p) = self.x.shape();
        let df = n - p;
        let covariance = &state.covariance * (scale * scale);
        if !covariance.iter().all(|v| v.is_finite()) {
            return Err(span(se));
        }
        let w = &state.weights;
        let total: f64 = w.iter().sum();
        let mean = (0..n).map(|i| w[i] * self.y[i]).sum::<f64>() / total;
        let ss_tot: f64 = (0..n).map(|i| w[i] * (self.y[i] - mean).powi(2)).sum();
        let ss_res: f64 = (0..n).map(|i| w[i] * state.residuals[i].powi(2)).sum();
        let r2 = 1.0 - ss_res / ss_tot;
        let mut out = Fit {
            terms: ols.terms.clone(),
            coefficients: state.beta.iter().map(|b| b * scale).collect(),
            std_errors: vec![None; p],
            t: vec![None; p],
            p: vec![None; p],
            ci95: vec![None; p],
            r2,
            r2_adjusted: (df > 0).then(|| 1.0 - (1.0 - r2) * (n - 1) as f64 / df as f64),
            q2: None,
            press: None,
            q2_note: None,
            residual_sd: None,
            dof_residual: df,
            fitted: (&self.x * &state.beta).iter().map(|v| v * scale).collect(),
            residuals: state.residuals.iter().map(|e| e * scale).collect(),
            leverage: state.leverage.clone(),
            xtx_inverse: (0..p)
                .map(|a| (0..p).map(|b| covariance[(a, b)]).collect())
                .collect(),
            anova: weighted_anova(&ols.anova, ss_tot, ss_res, total / n as f64, scale),
        };
        intervals(&mut out, df);
        out.q2 = weighted_q2(state, ss_tot, df, &mut out.q2_note);
        let weights = w.iter().map(|w| w / (scale * scale)).collect();
        Ok(WeightedFit {
            weighting: Weighting {
                tau2: None,
                method: "REML".into(),
                standard_errors: se.to_vec(),
                weights,
                iterations: 0,
                heterogeneity: None,
                ols_std_errors: ols.std_errors,
                notes: Vec::new(),
            },
            fit: out,
        })
    }
}

/// Standard errors from the covariance, t, p and 95 % intervals on `df`.
fn intervals(out: &mut Fit, df: usize) {
    let Some(dist) = (df > 0)
        .then(|| StudentsT::new(0.0, 1.0, df as f64).ok())
        .flatten()
    else {
        return;
    };
    let q = dist.inverse_cdf(0.975);
    for j in 0..out.terms.len() {
        let (b, se) = (out.coefficients[j], out.xtx_inverse[j][j].sqrt());
        let t = b / se;
        out.std_errors[j] = Some(se);
        out.t[j] = Some(t);
        out.p[j] = t.is_finite().then(|| 2.0 * (1.0 - dist.cdf(t.abs())));
        out.ci95[j] = Some([b - q * se, b + q * se]);
    }
}

/// Q² = 1 − PRESS_w/SS_tot,w with PRESS_w = Σ w_i (e_i/(1 − h_ii))².
fn weighted_q2(state: &State, ss_tot: f64, df: usize, note: &mut Option<String>) -> Option<f64> {
    if df == 0 || state.leverage.iter().any(|h| *h > 1.0 - 1e-9) {
        *note = Some("Q² undefined: a run has leverage 1 (saturated model)".into());
        return None;
    }
    let press: f64 = (0..state.weights.len())
        .map(|i| state.weights[i] * (state.residuals[i] / (1.0 - state.leverage[i])).powi(2))
        .sum();
    Some(1.0 - press / ss_tot)
}

/// The ANOVA of the weighted fit: weighted sums over the mean weight
/// (unit², equal to OLS's when the weights are equal), F weighted, no lack
/// of fit (pure error is not defined between differently weighted runs).
fn weighted_anova(ols: &Anova, ss_tot: f64, ss_res: f64, mean_weight: f64, scale: f64) -> Anova {
    let unit = scale * scale / mean_weight;
    let (df_reg, df) = (ols.df_regression, ols.df_residual);
    let f =
        (df > 0 && df_reg > 0).then(|| ((ss_tot - ss_res) / df_reg as f64) / (ss_res / df as f64));
    let p = f.and_then(|f| {
        let d = statrs::distribution::FisherSnedecor::new(df_reg as f64, df as f64).ok()?;
        (!f.is_nan()).then(|| 1.0 - d.cdf(f))
    });
    Anova {
        ss_regression: (ss_tot - ss_res) * unit,
        df_regression: df_reg,
        ss_residual: ss_res * unit,
        df_residual: df,
        f,
        p,
        lack_of_fit: None,
    }
}
