//! bumpsim-estimate: the one estimation layer under every bumpsim model
//! (the 1-D chain of `bumpsim-ident`, the planar car of `bumpsim-planar`).
//!
//! A model hands the layer its residuals and their Jacobian in log
//! parameters through [`lm::LeastSquares`], its parameters' names and
//! units ([`uncertainty::Parameter`]), and, for the reduced-model advice,
//! its links ([`reduce::Reducible`]). It gets back:
//!
//! - [`lm`]: bounded Levenberg–Marquardt (Madsen, Nielsen & Tingleff 2004);
//! - [`bounds`]: bounds and fixed values of the parameters;
//! - [`search`], [`polish`], [`multistart`]: the staged multi-start search
//!   (explore, refine around the best, polish the best few) and the tally
//!   of what became of every start, with its warnings;
//! - [`uncertainty`]: standard errors, 95 % intervals, correlations, rank
//!   and determination flags, the weakest direction, and the variance
//!   inflation of AR(1) residuals;
//! - [`domain`]: the domain a series is compared in (displacement,
//!   velocity, acceleration; issue 44);
//! - [`fit`]: the fit % of paper B and the negative-fit warning;
//! - [`document`]: the prediction document every model's front end writes;
//! - [`reduce`]: the simpler model the data cannot tell apart, with the
//!   F-test;
//! - [`observer`]: progress without a required closure;
//! - [`text`]: the parameter table and the start statistics every model prints;
//! - [`effective`]: the effective sample size of correlated series;
//! - [`sampler`], [`posterior`]: the affine-invariant ensemble sampler and
//!   the posterior of any least-squares model (issue 39);
//! - [`sobol`]: Sobol' indices with bootstrap intervals (issue 39);
//! - [`propagate`]: draws through a model: distributions, prediction bands
//!   and probabilities of passing (issue 39);
//! - [`band`]: linearised predictive bands of histories from the
//!   parameters' covariance, their coverage and width (issue 44);
//! - [`prior`]: stated Gaussian priors on log parameters, added to any
//!   problem as residuals, each reported with how far the data moved it;
//!   [`tied`]: parameters tied together (a symmetric stage of a search)
//!   (issue 44); [`stated`]: a study's `[priors]` table applied to a
//!   model's default priors (the 1-D and planar studies');
//! - [`information`]: a priored estimate's intervals with the data at the
//!   noise the error model counts and each prior at its stated spread;
//! - [`walk`]: the covariance when each residual series is a random walk
//!   (integrated noise; issue 44);
//! - [`difference`]: the one forward-difference Jacobian, for residuals
//!   without exact sensitivities;
//! - [`binomial`]: exact bounds of a probability from its draws, one-sided
//!   when none fails (issue 45).
//!
//! Parameters are estimated as `p = ln θ`: masses, dampers and springs
//! spanning seven decades become comparable and stay positive.
//!
//! ```
//! use bumpsim_estimate::prelude::*;
//! use nalgebra::DMatrix;
//! /// y = a e^{−b t}: residuals in p = (ln a, ln b)
//! struct Decay { t: Vec<f64>, y: Vec<f64> }
//! impl LeastSquares for Decay {
//!     fn residual_count(&self) -> usize { self.t.len() }
//!     fn parameter_count(&self) -> usize { 2 }
//!     fn evaluate(&self, p: &[f64], r: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
//!         let (a, b) = (p[0].exp(), p[1].exp());
//!         for (k, &t) in self.t.iter().enumerate() {
//!             r[k] = a * (-b * t).exp() - self.y[k];
//!         }
//!         if let Some(j) = jac {
//!             for (k, &t) in self.t.iter().enumerate() {
//!                 j[(k, 0)] = a * (-b * t).exp();
//!                 j[(k, 1)] = -a * b * t * (-b * t).exp();
//!             }
//!         }
//!         true
//!     }
//! }
//! let t: Vec<f64> = (0..50).map(|k| k as f64 * 0.1).collect();
//! let y = t.iter().map(|t| 3.0 * (-0.7 * t).exp()).collect();
//! let problem = Decay { t, y };
//! let (lower, upper) = (vec![-10.0; 2], vec![10.0; 2]);
//! let search = Search {
//!     starts: 8, seed: 1, solver: LmSettings::default(),
//!     lower: &lower, upper: &upper, range: (&lower, &upper),
//! };
//! let explored = (0..8).map(|k| Draws::new(1, k).around(&[0.0, 0.0], 10.0)).collect();
//! let found = multistart::search(&|| &problem, explored, &search, &Silent).unwrap();
//! let best = found.best();
//! assert!((best.parameters[0].exp() - 3.0).abs() < 1e-6);
//! assert!((best.parameters[1].exp() - 0.7).abs() < 1e-6);
//! assert!(found.starts.reached_best >= 2);
//! ```

pub mod band;
pub mod binomial;
pub mod bounds;
pub mod difference;
pub mod document;
pub mod domain;
pub mod effective;
pub mod fit;
pub mod information;
pub mod lm;
pub mod multistart;
pub mod observer;
pub mod polish;
pub mod posterior;
pub mod prior;
pub mod propagate;
pub mod reduce;
pub mod sampler;
pub mod search;
pub mod sobol;
pub mod stated;
pub mod text;
pub mod tied;
pub mod trust;
pub mod uncertainty;
pub mod walk;

/// Every warning of an estimate, in the one order every model prints:
/// the uncertainty's (bounds, rank, weak directions) and the determination
/// statement, the starts' (failed starts, a best found by one exploring
/// start, a best run at the iteration limit), then `fits` (negative fits,
/// [`fit::negative_fit`]).
pub fn warnings(
    uncertainty: &uncertainty::Uncertainty,
    starts: &multistart::Starts,
    best: &lm::Outcome,
    fits: impl IntoIterator<Item = String>,
) -> Vec<String> {
    let mut out = uncertainty::warnings(uncertainty);
    out.extend(multistart::warnings(starts, best));
    out.extend(fits);
    out
}

/// The types most estimations need.
pub mod prelude {
    pub use crate::bounds::Bounds;
    pub use crate::lm::{LeastSquares, Outcome, Settings as LmSettings, Stop};
    pub use crate::multistart::{self, Search, Searched, Starts};
    pub use crate::observer::{Observer, Silent};
    pub use crate::reduce::{Reducible, Reduction};
    pub use crate::search::Draws;
    pub use crate::uncertainty::{Correlation, Parameter, Series as ResidualSeries, Uncertainty};
}
