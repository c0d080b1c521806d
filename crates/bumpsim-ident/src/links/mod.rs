//! Identification of a chain with yielding links (issue 46, item 2).
//!
//! The chain of [`bumpsim_core::chain`] with, between masses j and j+1, a
//! viscous damper c_j and a bilinear elasto-plastic link
//! ([`bumpsim_core::link::Curve::bilinear`]): elastic stiffness k_j, yield
//! force F_yj, hardening ratio r_j (`F = F_y + r k (δ − δ_y)` past yield)
//! and unloading slope `u_j k_j` (u ≥ 1; Kamal 1970's lumped crush
//! springs). The parameter vector ([`Layout`]) is
//!
//! ```text
//! θ = [m1..mn, c1..c(n−1), k1..k(n−1), Fy1.., r1.., u1..]   (kg, N·s/m, N/m, N, -, -)
//! ```
//!
//! searched as `p = ln θ` by the estimation layer's staged multi-start
//! bounded Levenberg–Marquardt ([`bumpsim_estimate::multistart`]) on the
//! same residuals as the linear chain's (each case's output displacement
//! in its domain and weight over its window), with the exact Jacobian by
//! dual numbers through the links' history ([`objective`]). Starts: the linear chain's estimate when
//! given (its masses, dampers and springs, a yield force at half the
//! largest force, r = 0.2, u = 5) and draws around it. The uncertainty is
//! the shared engine's ([`bumpsim_estimate::uncertainty`], spectral
//! inflation for correlated residuals); the plastic set of each link at
//! the end of each case carries a 95 % interval by the delta method on the
//! log-parameter covariance (`σ² = gᵀ Σ g`, g exact by dual numbers).
//!
//! A barrier test is better identified as the car ran into the barrier
//! ([`barrier`], [`into_wall`]): the chain behind a tabulated front crush
//! zone, driven by the wall, fitted to the wall force and the output
//! together with the test sheet's mass as a prior, optionally with a
//! second load path and a rebound link into the wall. Its forward run is
//! the identified car itself; the force-driven fit above leaves m1 and the
//! first link free (on NHTSA 10146 it throws m1 through its link).

pub mod barrier;
pub mod front;
pub mod into_wall;
pub mod objective;
mod report;
pub mod study;
pub mod verdict;
pub mod weighting;

use bumpsim_core::chain::{Chain, ChainError};
use bumpsim_core::link::{Curve, Link, LinkError, Unloading};
use bumpsim_core::model::{ModelError, MsdModel};
use bumpsim_core::units::Dimension;
use bumpsim_estimate::lm::{LeastSquares, Settings as LmSettings};
use bumpsim_estimate::multistart::{self, AllFailed, Search, Starts};
use bumpsim_estimate::observer::Observer;
use bumpsim_estimate::search::{Draws, exploring};
use bumpsim_estimate::uncertainty::{
    Correlation, Estimated, Parameter, Series, Uncertainty, uncertainty,
};
use nalgebra::DMatrix;
pub use objective::LinkObjective;
pub use report::text;

use crate::case::{CaseError, LoadCase};

/// Why a chain with yielding links cannot be identified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LinkIdentError {
    /// A load case is not usable.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A parameter vector is not a chain.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A link's parameters are not a link.
    #[error("link {link}: {source}")]
    Link {
        /// 1-based link.
        link: usize,
        /// Why.
        source: LinkError,
    },
    /// The chain cannot run a case.
    #[error("load case '{case}': {source}")]
    Chain {
        /// The case.
        case: String,
        /// Why.
        source: ChainError,
    },
    /// A case measures a mass the chain lacks.
    #[error("load case '{case}' measures mass {output}; the chain has {dof}")]
    Output {
        /// The case.
        case: String,
        /// Its output mass, 1-based.
        output: usize,
        /// The chain's masses.
        dof: usize,
    },
    /// A settings value is out of range.
    #[error("{0}")]
    Settings(String),
    /// Every start failed.
    #[error(transparent)]
    AllFailed(#[from] AllFailed),
}

/// The parameter layout of an n-mass chain with bilinear links.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of masses.
    pub dof: usize,
}

/// The six kinds of parameter, in layout order.
const KINDS: [(&str, Dimension); 6] = [
    ("m", Dimension::Mass),
    ("c", Dimension::Damping),
    ("k", Dimension::Stiffness),
    ("Fy", Dimension::Force),
    ("r", Dimension::Dimensionless),
    ("u", Dimension::Dimensionless),
];

/// Default search bounds (SI) per kind.
const BOUNDS: [(f64, f64); 6] = [
    (10.0, 1e5),
    (1.0, 1e7),
    (1e3, 1e8),
    (1e2, 1e7),
    (1e-3, 0.5),
    (1.0, 30.0),
];

impl Layout {
    /// Number of parameters: n masses, 5 per link.
    pub fn count(self) -> usize {
        self.dof + 5 * (self.dof - 1)
    }

    /// Kind (0..6) and 0-based index of parameter `i`.
    fn kind(self, i: usize) -> (usize, usize) {
        if i < self.dof {
            (0, i)
        } else {
            let rest = i - self.dof;
            (1 + rest / (self.dof - 1), rest % (self.dof - 1))
        }
    }

    /// The parameters' names (`m1`, `Fy2`, `u1`) and units.
    pub fn parameters(self) -> Vec<Parameter> {
        (0..self.count())
            .map(|i| {
                let (kind, j) = self.kind(i);
                let (letter, dimension) = KINDS[kind];
                let name = format!("{letter}{}", j + 1);
                match dimension {
                    Dimension::Dimensionless => Parameter::with_symbol(name, "-"),
                    d => Parameter::new(name, d),
                }
            })
            .collect()
    }

    /// The default bounds (SI) of every parameter.
    pub fn bounds(self) -> (Vec<f64>, Vec<f64>) {
        (0..self.count()).map(|i| BOUNDS[self.kind(i).0]).unzip()
    }

    /// The chain of the SI parameters `theta`.
    pub fn chain(self, theta: &[f64]) -> Result<Chain, LinkIdentError> {
        let (n, l) = (self.dof, self.dof - 1);
        if theta.len() != self.count() {
            return Err(LinkIdentError::Settings(format!(
                "{} parameters for {n} masses with yielding links: expected {}",
                theta.len(),
                self.count()
            )));
        }
        let part = |kind: usize| &theta[n + (kind - 1) * l..n + kind * l];
        let links = (0..l)
            .map(|j| {
                let (k, fy, r, u) = (part(2)[j], part(3)[j], part(4)[j], part(5)[j]);
                let curve = Curve::bilinear(k, fy, r.min(1.0));
                curve
                    .and_then(|c| Link::new(c, Unloading::Slope(u.max(1.0) * k)))
                    .map_err(|source| LinkIdentError::Link {
                        link: j + 1,
                        source,
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Chain::new(theta[..n].to_vec(), part(1).to_vec(), links)?)
    }

    /// A start from a linear chain: its masses, dampers and springs, the
    /// yield force `yield_force`, r = 0.2, u = 5.
    pub fn start_from(self, linear: &MsdModel, yield_force: f64) -> Vec<f64> {
        let l = self.dof - 1;
        [
            linear.masses(),
            linear.dampers(),
            linear.springs(),
            &vec![yield_force; l],
            &vec![0.2; l],
            &vec![5.0; l],
        ]
        .concat()
    }
}

/// How to identify.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkSettings {
    /// Masses.
    pub dof: usize,
    /// Starts of the multi-start search.
    pub starts: usize,
    /// Seed of the drawn starts.
    pub seed: u64,
    /// The first start (SI, layout order).
    pub start: Vec<f64>,
    /// Bounds (SI, layout order).
    pub lower: Vec<f64>,
    /// Upper bounds.
    pub upper: Vec<f64>,
    /// Fixed values (SI) of parameters held.
    pub fixed: Vec<Option<f64>>,
    /// Solver settings.
    pub solver: LmSettings,
}

impl LinkSettings {
    /// Default bounds, nothing fixed, `starts` starts from `start`.
    pub fn new(dof: usize, starts: usize, start: Vec<f64>) -> LinkSettings {
        let layout = Layout { dof };
        let (lower, upper) = layout.bounds();
        LinkSettings {
            dof,
            starts,
            seed: 1,
            start,
            lower,
            upper,
            fixed: vec![None; layout.count()],
            solver: LmSettings {
                max_iterations: 200,
                ftol: 1e-10,
                ..LmSettings::default()
            },
        }
    }

    fn check(&self) -> Result<Layout, LinkIdentError> {
        let layout = Layout { dof: self.dof };
        let p = layout.count();
        let bad = |what: String| Err(LinkIdentError::Settings(what));
        if self.dof < 2 {
            return bad(format!(
                "{} masses: a chain with links needs at least 2",
                self.dof
            ));
        }
        if [
            self.start.len(),
            self.lower.len(),
            self.upper.len(),
            self.fixed.len(),
        ] != [p; 4]
        {
            return bad(format!(
                "start, bounds and fixed need {p} values each ({} masses)",
                self.dof
            ));
        }
        if self.starts == 0 {
            return bad("starts = 0: at least one start".into());
        }
        let names = layout.parameters();
        for (i, name) in names.iter().enumerate() {
            let (lo, hi, s) = (self.lower[i], self.upper[i], self.start[i]);
            if !(lo > 0.0
                && lo <= hi
                && lo.is_finite()
                && hi.is_finite()
                && s.is_finite()
                && s > 0.0)
            {
                return bad(format!(
                    "{}: bounds [{lo}, {hi}] and start {s} must be positive, finite and ordered",
                    name.name
                ));
            }
        }
        Ok(layout)
    }
}

/// A link's plastic set at the end of a case, with its interval.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PlasticSet {
    /// The case.
    pub case: String,
    /// 1-based link.
    pub link: usize,
    /// δ_p, m.
    pub value: f64,
    /// Its 95 % interval, m (delta method), when the covariance exists.
    pub ci95: Option<[f64; 2]>,
}

/// Below this, m, a plastic set or its interval's half width is the
/// run's round-off (a link that never yields has δ_p = 0 and gradient 0,
/// which floating point gives as ±1e-17 m): 1 nm.
pub const SET_ROUND_OFF: f64 = 1e-9;

impl PlasticSet {
    /// The set `value` of `link` after `case` with its delta-method
    /// interval, read as a plastic set: round-off (below
    /// [`SET_ROUND_OFF`]) is zero, and the interval is clipped at zero (a
    /// set is never negative; the delta method's symmetric interval can
    /// reach below, and clipping it keeps every set it held).
    pub fn new(case: String, link: usize, value: f64, ci95: Option<[f64; 2]>) -> PlasticSet {
        let clean = |v: f64| {
            if v.abs() < SET_ROUND_OFF {
                0.0
            } else {
                v.max(0.0)
            }
        };
        let ci95 = ci95.map(|[lo, hi]| match (hi - lo) / 2.0 < SET_ROUND_OFF {
            true => [clean(value); 2],
            false => [clean(lo), clean(hi)],
        });
        PlasticSet {
            case,
            link,
            value: clean(value),
            ci95,
        }
    }
}

/// What the identification found.
#[derive(Debug, Clone)]
pub struct LinkIdentification {
    /// The chain's layout.
    pub layout: Layout,
    /// Every parameter's name and unit, in the order of `theta` (the
    /// chain's, then a barrier identification's front zone).
    pub parameters: Vec<Parameter>,
    /// The estimate, SI, in the order of `parameters`.
    pub theta: Vec<f64>,
    /// The chain it gives.
    pub chain: Chain,
    /// Each case's name and fit % of its output.
    pub fits: Vec<(String, f64)>,
    /// Each case's name and the fit % of its wall force (a barrier
    /// identification, [`into_wall`]; empty otherwise).
    pub force_fits: Vec<(String, f64)>,
    /// Each case's channel scales `[s_F N, s_y]` ([`barrier`]; empty when
    /// force-driven).
    pub scales: Vec<[f64; 2]>,
    /// The stated priors and where the data left them.
    pub moved: Vec<bumpsim_estimate::prior::Moved>,
    /// The objective Σ r².
    pub objective: f64,
    /// The shared engine's uncertainty.
    pub uncertainty: Uncertainty,
    /// Plastic sets at the end of each case (link 0: the front crush zone).
    pub plastic_sets: Vec<PlasticSet>,
    /// The front crush zone read off the first barrier case
    /// ([`front::front_link`]); None without a barrier case.
    pub front: Option<bumpsim_core::link::Link>,
    /// The second load path into the wall (the barrier identification's,
    /// [`barrier::BarrierLayout::path_knots`]); None otherwise. Plastic
    /// set number n (the chain's masses) is its.
    pub path: Option<bumpsim_core::chain::WallPath>,
    /// The rebound link into the wall (the barrier identification's,
    /// [`barrier::BarrierLayout::rebound`]); None otherwise. Its plastic
    /// set follows the second path's.
    pub rebound: Option<bumpsim_core::chain::WallPath>,
    /// What became of the starts.
    pub starts: Starts,
}

impl LinkIdentification {
    /// The identified car alone (the chain with its front link and second
    /// path) into a
    /// rigid wall at `speed` m/s, recorded every `step` s for `samples`.
    pub fn forward(
        &self,
        speed: f64,
        step: f64,
        samples: usize,
    ) -> Result<bumpsim_core::chain::ChainResponse, LinkIdentError> {
        let mut chain = match &self.front {
            Some(front) => self.chain.clone().with_front(front.clone()),
            None => self.chain.clone(),
        };
        if let Some(path) = &self.path {
            chain = chain.with_path(path.mass, path.gap, path.link.clone())?;
        }
        if let Some(rebound) = &self.rebound {
            chain = chain.with_rebound(rebound.mass, rebound.gap, rebound.link.clone())?;
        }
        let drive = bumpsim_core::chain::Drive::Barrier {
            speed,
            step,
            samples,
        };
        chain.run(&drive).map_err(|source| LinkIdentError::Chain {
            case: "forward".into(),
            source,
        })
    }
}

/// Identifies a chain with yielding links from `cases`.
pub fn identify(
    cases: &[LoadCase],
    settings: &LinkSettings,
    observer: &dyn Observer,
) -> Result<LinkIdentification, LinkIdentError> {
    let layout = settings.check()?;
    for case in cases {
        case.validate()?;
    }
    let objective = LinkObjective::new(cases, layout, &settings.fixed);
    let free = objective.free().to_vec();
    let log = |v: &[f64]| free.iter().map(|&i| v[i].ln()).collect::<Vec<f64>>();
    let (lower, upper) = (log(&settings.lower), log(&settings.upper));
    let points = start_points(
        &log(&settings.start),
        (&lower, &upper),
        settings.starts,
        settings.seed,
    );
    let search = Search {
        starts: settings.starts,
        seed: settings.seed,
        solver: settings.solver,
        lower: &lower,
        upper: &upper,
        range: (&lower, &upper),
    };
    let make = || LinkObjective::new(cases, layout, &settings.fixed);
    let found = multistart::search(&make, points, &search, observer)?;
    let best = found.best().clone();
    let theta = objective.theta(&best.parameters);
    let chain = layout.chain(&theta)?;
    let mut r = vec![0.0; objective.residual_count()];
    let mut jacobian = DMatrix::zeros(r.len(), free.len());
    if !objective.evaluate(&best.parameters, &mut r, Some(&mut jacobian)) {
        return Err(AllFailed {
            starts: settings.starts,
        }
        .into());
    }
    let parameters = layout.parameters();
    let series = Series::contiguous(cases.iter().map(LoadCase::residual_len));
    let u = uncertainty(&Estimated {
        parameters: &parameters,
        theta: &theta,
        free: &free,
        p: &best.parameters,
        bounds: (&lower, &upper),
        residuals: &r,
        jacobian: &jacobian,
        series: &series,
        correlation: Correlation::Spectral,
    });
    let fits = cases
        .iter()
        .map(|case| {
            let y = objective::simulate(case, &chain)?;
            Ok((case.name.clone(), case.fit(&y).1))
        })
        .collect::<Result<Vec<_>, LinkIdentError>>()?;
    let plastic_sets = plastic_sets(cases, &objective, &theta, &u)?;
    let barrier = cases
        .iter()
        .find(|c| objective::frame(c) == bumpsim_core::chain::Frame::Forward);
    let front = barrier
        .map(|case| front::front_link(case, &chain))
        .transpose()?;
    Ok(LinkIdentification {
        layout,
        parameters,
        theta,
        chain,
        fits,
        force_fits: vec![],
        scales: vec![],
        moved: vec![],
        objective: best.objective,
        uncertainty: u,
        plastic_sets,
        front,
        path: None,
        rebound: None,
        starts: found.starts,
    })
}

/// The explored start points of the multi-start search in log parameters:
/// `first` clamped into `bounds`, then draws 3 log units around it (the
/// estimation layer's [`Draws`]), each clamped, as many as
/// [`exploring`] explores for `starts` starts.
pub(crate) fn start_points(
    first: &[f64],
    (lower, upper): (&[f64], &[f64]),
    starts: usize,
    seed: u64,
) -> Vec<Vec<f64>> {
    let clamped = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .zip(lower.iter().zip(upper))
            .map(|(p, (l, h))| p.clamp(*l, *h))
            .collect()
    };
    let first = clamped(first);
    let drawn = (1..exploring(starts, 1))
        .map(|k| clamped(&Draws::new(seed, k as u64).around(&first, 3.0)))
        .collect::<Vec<_>>();
    std::iter::once(first).chain(drawn).collect()
}

/// The plastic set of every link at the end of every case, with the
/// delta-method interval on the engine's covariance of the free log
/// parameters ([`into_wall::intervals`]), each set's gradient exact by
/// dual numbers through the run ([`objective::jacobian::tangents`]).
fn plastic_sets(
    cases: &[LoadCase],
    objective: &LinkObjective,
    theta: &[f64],
    u: &Uncertainty,
) -> Result<Vec<PlasticSet>, LinkIdentError> {
    let layout = objective.layout();
    let chain = layout.chain(theta)?;
    let sets = |theta: &[objective::jacobian::Tangent]| {
        let values = objective::jacobian::values(layout, &chain, theta);
        let mut out = Vec::with_capacity(cases.len() * (layout.dof - 1));
        for case in cases {
            let motion = chain.motion(&objective::drive(case), &values).ok()?;
            out.extend(motion.plastic_set);
        }
        Some(out)
    };
    let free = objective.free();
    let (values, gradients) =
        objective::jacobian::tangents(theta, free, &sets).ok_or(AllFailed { starts: 1 })?;
    let links = layout.dof - 1;
    Ok(into_wall::intervals(&values, &gradients, u, theta, free)
        .into_iter()
        .enumerate()
        .map(|(at, (value, ci95))| {
            PlasticSet::new(cases[at / links].name.clone(), at % links + 1, value, ci95)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plastic_set_is_read_without_round_off_and_its_interval_clipped_at_zero() {
        let set = |v: f64, ci: [f64; 2]| PlasticSet::new("c".into(), 1, v, Some(ci));
        // a link that never yields: ±1e-17 m of round-off is no set
        let none = set(-1.7e-18, [-1.4e-17, 1.4e-17]);
        assert_eq!((none.value, none.ci95), (0.0, Some([0.0, 0.0])));
        // the delta method's symmetric interval reaching below zero
        let small = set(1.132e-3, [-11.24e-3, 13.50e-3]);
        assert_eq!(small.ci95, Some([0.0, 13.50e-3]));
        assert!((small.value - 1.132e-3).abs() < 1e-15);
        // a set well inside its interval is kept as it is
        let kept = set(0.5949, [0.5694, 0.6204]);
        assert_eq!(kept.ci95, Some([0.5694, 0.6204]));
        assert!(PlasticSet::new("c".into(), 1, 0.1, None).ci95.is_none());
    }

    #[test]
    fn the_layout_names_every_parameter_in_order() {
        let names: Vec<String> = Layout { dof: 3 }
            .parameters()
            .into_iter()
            .map(|p| p.name)
            .collect();
        let expected = "m1 m2 m3 c1 c2 k1 k2 Fy1 Fy2 r1 r2 u1 u2";
        assert_eq!(names.join(" "), expected);
    }

    #[test]
    fn hostile_settings_and_parameters_are_refused_with_their_name() {
        let layout = Layout { dof: 2 };
        let good = vec![10.0, 1000.0, 100.0, 1e6, 1e5, 0.2, 5.0];
        assert!(layout.chain(&good).is_ok());
        let mut bad = good.clone();
        bad[4] = -1.0;
        let e = layout.chain(&bad).unwrap_err().to_string();
        assert!(e.starts_with("link 1: yield_force = -1 N"), "{e}");
        bad = good.clone();
        bad[1] = f64::NAN;
        assert!(
            layout
                .chain(&bad)
                .unwrap_err()
                .to_string()
                .starts_with("m2 = NaN kg")
        );
        assert!(layout.chain(&good[..6]).is_err());
        let cases: Vec<LoadCase> = vec![];
        let one = LinkSettings::new(1, 4, vec![1.0]);
        assert!(matches!(
            identify(&cases, &one, &bumpsim_estimate::observer::Silent),
            Err(LinkIdentError::Settings(_))
        ));
        let mut s = LinkSettings::new(2, 4, good.clone());
        s.lower[3] = 0.0;
        let e = identify(&cases, &s, &bumpsim_estimate::observer::Silent)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("k1: bounds"), "{e}");
        let s = LinkSettings::new(2, 0, good);
        assert!(identify(&cases, &s, &bumpsim_estimate::observer::Silent).is_err());
    }
}
