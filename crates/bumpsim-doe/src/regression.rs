//! Multiple linear regression in coded units (spec §7).
//!
//! `y = X β + e` with columns for the intercept, main effects, optional
//! two-factor interactions and squares. Solved through the SVD
//! `X = U S Vᵀ` (rank-revealing): `β = V S⁻¹ Uᵀ y`, `(XᵀX)⁻¹ = V S⁻² Vᵀ`, hat
//! diagonal `h_ii = ‖U_i‖²`. With n runs, p terms, `σ² = SS_res / (n − p)`:
//! standard errors `σ sqrt((XᵀX)⁻¹_jj)`, t = β/SE, two-sided p from Student t,
//! 95 % intervals `β ± t₀.₉₇₅ SE`; `R² = 1 − SS_res/SS_tot`,
//! `R²_adj = 1 − (SS_res/(n−p)) / (SS_tot/(n−1))`; PRESS `= Σ (e_i/(1 − h_ii))²`,
//! `Q² = 1 − PRESS/SS_tot`. A saturated model (n = p, or any h_ii = 1) has no
//! Q²: it is reported as undefined with the reason. ANOVA splits the
//! residual into lack of fit and pure error when runs are replicated.
//! These equal statsmodels' OLS and its influence measures (tested).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor, StudentsT};

/// Why a regression cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RegressionError {
    /// Fewer runs than terms, or rank deficiency.
    #[error("regression: {0}")]
    Design(String),
    /// A standard error that is not a finite number ≥ 0 whose square is finite.
    #[error(
        "standard error {value} in data row {row}: expected a finite number ≥ 0 whose square (a variance) is a finite number"
    )]
    StandardError {
        /// 1-based data row.
        row: usize,
        /// The value.
        value: f64,
    },
    /// A zero standard error beside positive ones.
    #[error(
        "standard error 0 in data row {row} beside {value} in data row {positive}: a zero would be an exact identification with infinite weight; give every run a positive standard error, or every run 0 (unweighted)"
    )]
    ZeroStandardError {
        /// 1-based row of the zero.
        row: usize,
        /// 1-based row of a positive one.
        positive: usize,
        /// Its value.
        value: f64,
    },
    /// REML's Fisher scoring did not settle.
    #[error("τ² (REML) did not converge in {iterations} iterations")]
    NotConverged {
        /// Iterations taken.
        iterations: usize,
    },
}

/// A model term over coded factors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Term {
    /// The constant.
    Intercept,
    /// Factor i.
    Main(usize),
    /// Factors i and j multiplied.
    Interaction(usize, usize),
    /// Factor i squared.
    Square(usize),
}

impl Term {
    /// Its value at coded levels `z`.
    pub fn value(self, z: &[f64]) -> f64 {
        match self {
            Term::Intercept => 1.0,
            Term::Main(i) => z[i],
            Term::Interaction(i, j) => z[i] * z[j],
            Term::Square(i) => z[i] * z[i],
        }
    }

    /// Its name: `intercept`, `A`, `A*B`, `A^2`.
    pub fn name(self, factors: &[String]) -> String {
        match self {
            Term::Intercept => "intercept".into(),
            Term::Main(i) => factors[i].clone(),
            Term::Interaction(i, j) => format!("{}*{}", factors[i], factors[j]),
            Term::Square(i) => format!("{}^2", factors[i]),
        }
    }

    /// Parses a name written by [`Term::name`].
    pub fn parse(name: &str, factors: &[String]) -> Option<Term> {
        let index = |n: &str| factors.iter().position(|f| f == n.trim());
        if name == "intercept" {
            return Some(Term::Intercept);
        }
        if let Some(base) = name.strip_suffix("^2") {
            return index(base).map(Term::Square);
        }
        match name.split_once('*') {
            Some((a, b)) => Some(Term::Interaction(index(a)?, index(b)?)),
            None => index(name).map(Term::Main),
        }
    }
}

/// The terms of a model in k factors.
pub fn terms(k: usize, interactions: bool, squares: bool) -> Vec<Term> {
    let mut t = vec![Term::Intercept];
    t.extend((0..k).map(Term::Main));
    if interactions {
        t.extend((0..k).flat_map(|i| (i + 1..k).map(move |j| Term::Interaction(i, j))));
    }
    if squares {
        t.extend((0..k).map(Term::Square));
    }
    t
}

/// Lack of fit against pure error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LackOfFit {
    /// Lack-of-fit sum of squares and degrees of freedom.
    pub ss_lack_of_fit: f64,
    /// Degrees of freedom of the lack of fit.
    pub df_lack_of_fit: usize,
    /// Pure-error sum of squares (within replicates).
    pub ss_pure_error: f64,
    /// Degrees of freedom of the pure error.
    pub df_pure_error: usize,
    /// F = (SS_lof/df_lof) / (SS_pe/df_pe).
    pub f: f64,
    /// p value of F.
    pub p: f64,
}

/// The ANOVA table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Anova {
    /// Regression sum of squares (about the mean) and its degrees of freedom.
    pub ss_regression: f64,
    /// Degrees of freedom of the regression.
    pub df_regression: usize,
    /// Residual sum of squares.
    pub ss_residual: f64,
    /// Degrees of freedom of the residual.
    pub df_residual: usize,
    /// F of the regression (when df_residual > 0).
    pub f: Option<f64>,
    /// Its p value.
    pub p: Option<f64>,
    /// Lack of fit vs pure error, when there are replicates.
    pub lack_of_fit: Option<LackOfFit>,
}

/// A fitted response.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fit {
    /// Term names.
    pub terms: Vec<String>,
    /// Coefficients in coded units.
    pub coefficients: Vec<f64>,
    /// Standard errors (`None` for a saturated model).
    pub std_errors: Vec<Option<f64>>,
    /// t statistics.
    pub t: Vec<Option<f64>>,
    /// Two-sided p values.
    pub p: Vec<Option<f64>>,
    /// 95 % confidence intervals.
    pub ci95: Vec<Option<[f64; 2]>>,
    /// R².
    pub r2: f64,
    /// Adjusted R² (`None` when n − p = 0).
    pub r2_adjusted: Option<f64>,
    /// Q² (`None` when undefined).
    pub q2: Option<f64>,
    /// PRESS (`None` when undefined).
    pub press: Option<f64>,
    /// Why Q² is undefined.
    pub q2_note: Option<String>,
    /// Residual standard deviation σ.
    pub residual_sd: Option<f64>,
    /// n − p.
    pub dof_residual: usize,
    /// Fitted values.
    pub fitted: Vec<f64>,
    /// Residuals.
    pub residuals: Vec<f64>,
    /// Leverages h_ii.
    pub leverage: Vec<f64>,
    /// (XᵀX)⁻¹ for prediction intervals.
    pub xtx_inverse: Vec<Vec<f64>>,
    /// ANOVA.
    pub anova: Anova,
}

/// Fits `y` on `terms` of coded runs `z`.
pub fn fit(
    z: &[Vec<f64>],
    y: &[f64],
    terms: &[Term],
    factors: &[String],
) -> Result<Fit, RegressionError> {
    let (n, p) = (z.len(), terms.len());
    if n < p || y.len() != n {
        return Err(RegressionError::Design(format!(
            "{n} runs for {p} terms: need at least as many runs as terms"
        )));
    }
    if let Some(v) = y.iter().chain(z.iter().flatten()).find(|v| !v.is_finite()) {
        return Err(RegressionError::Design(format!(
            "a value of {v}: every factor and response value must be finite"
        )));
    }
    let mean = y.iter().sum::<f64>() / n.max(1) as f64;
    if y.iter()
        .all(|v| (v - mean).abs() <= 1e-12 * mean.abs().max(f64::MIN_POSITIVE))
    {
        return Err(RegressionError::Design(format!(
            "the response is constant ({mean} in every run): nothing to fit, R² is undefined"
        )));
    }
    let x = DMatrix::from_fn(n, p, |r, c| terms[c].value(&z[r]));
    let svd = x.clone().svd(true, true);
    let (u, v_t) = (
        svd.u.as_ref().expect("computed"),
        svd.v_t.as_ref().expect("computed"),
    );
    let s = &svd.singular_values;
    let largest = s.max();
    if s.min() <= 1e-10 * largest {
        return Err(RegressionError::Design(
            "the design matrix is rank deficient: terms are aliased (confounded) in this design"
                .into(),
        ));
    }
    let yv = DVector::from_column_slice(y);
    let uty = u.transpose() * &yv;
    let beta = v_t.transpose() * DVector::from_iterator(p, (0..p).map(|i| uty[i] / s[i]));
    let inverse = DMatrix::from_fn(p, p, |a, b| {
        (0..p)
            .map(|k| v_t[(k, a)] * v_t[(k, b)] / (s[k] * s[k]))
            .sum()
    });
    let fitted: Vec<f64> = (&x * &beta).iter().copied().collect();
    let residuals: Vec<f64> = y.iter().zip(&fitted).map(|(a, b)| a - b).collect();
    let leverage: Vec<f64> = (0..n)
        .map(|r| (0..p).map(|c| u[(r, c)].powi(2)).sum())
        .collect();
    let mean = y.iter().sum::<f64>() / n as f64;
    let ss_tot: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    let ss_res: f64 = residuals.iter().map(|e| e * e).sum();
    if !(ss_tot.is_finite() && ss_res.is_finite()) {
        return Err(RegressionError::Design(format!(
            "the response varies too much for its sum of squares to be a number (values up to {:e}): rescale it (other units)",
            y.iter().map(|v| v.abs()).fold(0.0, f64::max)
        )));
    }
    let df = n - p;
    let sigma = (df > 0).then(|| (ss_res / df as f64).sqrt());
    let t_dist = (df > 0)
        .then(|| StudentsT::new(0.0, 1.0, df as f64).ok())
        .flatten();
    let quantile = t_dist.as_ref().map(|d| d.inverse_cdf(0.975));
    let mut out = Fit {
        terms: terms.iter().map(|t| t.name(factors)).collect(),
        coefficients: beta.iter().copied().collect(),
        std_errors: vec![None; p],
        t: vec![None; p],
        p: vec![None; p],
        ci95: vec![None; p],
        r2: 1.0 - ss_res / ss_tot,
        r2_adjusted: (df > 0).then(|| 1.0 - (ss_res / df as f64) / (ss_tot / (n - 1) as f64)),
        q2: None,
        press: None,
        q2_note: None,
        residual_sd: sigma,
        dof_residual: df,
        fitted,
        residuals: residuals.clone(),
        leverage: leverage.clone(),
        xtx_inverse: (0..p)
            .map(|a| (0..p).map(|b| inverse[(a, b)]).collect())
            .collect(),
        anova: anova(z, y, &residuals, ss_tot, ss_res, p, df),
    };
    if let (Some(sigma), Some(dist), Some(q)) = (sigma, t_dist, quantile) {
        for j in 0..p {
            let se = sigma * inverse[(j, j)].sqrt();
            let t = out.coefficients[j] / se;
            out.std_errors[j] = Some(se);
            out.t[j] = Some(t);
            out.p[j] = Some(2.0 * upper_tail(|x| dist.cdf(x), t.abs())).filter(|p| !p.is_nan());
            out.ci95[j] = Some([out.coefficients[j] - q * se, out.coefficients[j] + q * se]);
        }
    }
    match leverage.iter().position(|h| *h > 1.0 - 1e-9) {
        _ if df == 0 => {
            out.q2_note = Some(format!(
                "Q² undefined: the model is saturated ({n} runs for {p} terms), every residual is zero and no run can be left out"
            ))
        }
        Some(i) => {
            out.q2_note = Some(format!(
                "Q² undefined: run {} has leverage 1 (the model passes through it whatever its value)",
                i + 1
            ))
        }
        None => {
            let press: f64 = residuals
                .iter()
                .zip(&leverage)
                .map(|(e, h)| (e / (1.0 - h)).powi(2))
                .sum();
            out.press = Some(press);
            out.q2 = Some(1.0 - press / ss_tot);
        }
    }
    Ok(out)
}

fn anova(
    z: &[Vec<f64>],
    y: &[f64],
    residuals: &[f64],
    ss_tot: f64,
    ss_res: f64,
    p: usize,
    df: usize,
) -> Anova {
    let regression_df = p.saturating_sub(1);
    let fdist = (df > 0 && regression_df > 0)
        .then(|| FisherSnedecor::new(regression_df as f64, df as f64).ok())
        .flatten();
    let f = fdist
        .as_ref()
        .map(|_| ((ss_tot - ss_res) / regression_df as f64) / (ss_res / df as f64));
    let mut groups: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for (row, &value) in z.iter().zip(y) {
        match groups
            .iter_mut()
            .find(|(r, _)| r.iter().zip(row).all(|(a, b)| (a - b).abs() < 1e-12))
        {
            Some(g) => g.1.push(value),
            None => groups.push((row.clone(), vec![value])),
        }
    }
    let df_pe: usize = groups.iter().map(|g| g.1.len() - 1).sum();
    let ss_pe: f64 = groups
        .iter()
        .map(|g| {
            let m = g.1.iter().sum::<f64>() / g.1.len() as f64;
            g.1.iter().map(|v| (v - m).powi(2)).sum::<f64>()
        })
        .sum();
    let _ = residuals;
    let lack_of_fit = (df_pe > 0 && df > df_pe).then(|| {
        let df_lof = df - df_pe;
        let ss_lof = ss_res - ss_pe;
        let f = (ss_lof / df_lof as f64) / (ss_pe / df_pe as f64);
        let p = FisherSnedecor::new(df_lof as f64, df_pe as f64)
            .map_or(f64::NAN, |d| upper_tail(|x| d.cdf(x), f));
        LackOfFit {
            ss_lack_of_fit: ss_lof,
            df_lack_of_fit: df_lof,
            ss_pure_error: ss_pe,
            df_pure_error: df_pe,
            f,
            p,
        }
    });
    Anova {
        ss_regression: ss_tot - ss_res,
        df_regression: regression_df,
        ss_residual: ss_res,
        df_residual: df,
        f,
        p: fdist.zip(f).map(|(d, f)| upper_tail(|x| d.cdf(x), f)),
        lack_of_fit,
    }
}

/// 1 − cdf(x), or NaN for a NaN statistic (0/0 of a perfect fit or of
/// identical replicates): statrs panics on NaN.
fn upper_tail(cdf: impl Fn(f64) -> f64, x: f64) -> f64 {
    if x.is_nan() { f64::NAN } else { 1.0 - cdf(x) }
}

/// Points of a normal probability plot: (normal quantile, sorted residual),
/// with Blom's plotting positions `(i − 3/8) / (n + 1/4)`.
pub fn normal_scores(residuals: &[f64]) -> Vec<(f64, f64)> {
    let mut sorted = residuals.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    let normal = statrs::distribution::Normal::new(0.0, 1.0).expect("standard normal");
    sorted
        .iter()
        .enumerate()
        .map(|(i, &r)| (normal.inverse_cdf((i as f64 + 1.0 - 0.375) / (n + 0.25)), r))
        .collect()
}
