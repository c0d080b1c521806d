//! Identification of the planar car from several load cases at once (spec §9,
//! the planar extension of the thesis's ch. 3 identification).
//!
//! **Model.** Each case is replayed with [`crate::drive`]: the measured
//! barrier or pole forces act at their lateral positions on the bumper
//! line, the car starts at the test speed, and the model's left and right
//! sensor points move. The unknowns θ are the body mass M and yaw inertia
//! I_z, every mass, damper and spring of the left and right chains (their
//! sizes from the template car, the start), optionally the lateral tyre
//! friction coefficient μ_y and the cornering stiffness C_α of both axles
//! (the longitudinal ones, rolling resistance or brakes, stay the
//! template's), and the lateral position of every force whose line of
//! action the study asks to estimate (module `unknowns`; a linear-scale
//! parameter). The geometry (CG, side members, wheelbase, track) is the
//! template's. The result is checked for plausibility with the reasons
//! (module `plausible`).
//!
//! **Objective.** `F(θ) = Σ_cases Σ_k Σ_s w_s² (ŝ_k − s_k)²` over each
//! case's window and sensors, each sensor compared in its domain
//! ([`crate::drive::Sensor::integrations`]): x accelerometers as world-x
//! displacements (integrated twice, `w = 1`, m), a yaw-rate sensor as the
//! yaw rate as measured, a displacement channel as measured, each weighted
//! by the x accelerometers' noise over its own ([`crate::cases`]), so F
//! stays in m². The two sills carry equal weight, so their mean (x) and
//! half difference (yaw times the sensor half-spacing) do too; a yaw-rate
//! sensor observes the yaw directly, where the sills' difference of two
//! double integrals is mostly drift at a small yaw.
//!
//! **Search.** The estimation layer's ([`bumpsim_estimate`], shared with
//! the 1-D chain): bounded Levenberg–Marquardt on `p = ln θ`, each
//! parameter within a factor [`REACH`] of its start, the exact Jacobian of
//! the replay on dual numbers (module `objective`); the staged multi-start from the
//! template and log-uniform points within a factor `spread` of it (seeded
//! by `seed + start index`), refining rounds around the best when there are
//! more than eight starts, the best few polished, every start tallied.
//!
//! **Uncertainty**, as the layer gives it: `Cov(ln θ) = σ² τ (JᵀJ)⁻¹` at
//! the optimum, intervals `θ exp(± t SE)`, rank and determination flags,
//! the weakest direction. Each sensor's residuals are weighed by its
//! pre-trigger noise ([`crate::cases`]); σ² is the weighted residuals'
//! variance and τ their integrated autocorrelation time (Sokal's window,
//! [`bumpsim_estimate::effective`], the estimator of the 1-D chain's
//! intervals; [`CORRELATION`]): displacements integrated from
//! accelerations have strongly correlated errors. The stated priors enter
//! at their own spreads, not at the noise the search weighed them by
//! ([`bumpsim_estimate::information`]): the covariance is the Gaussian
//! posterior's, `(J_dᵀJ_d/(σ²τ) + Σ_p⁻¹)⁻¹`.
//!
//! **Fit** of a case ([`predict`]), as for the 1-D identification:
//! `100 (1 − √(SSE/SST))` %, for x (mean of the sensors) and for the yaw:
//! the yaw-rate sensor's integral where the case has one, else
//! `ψ = asin((x_R − x_L)/(η_L − η_R))`; a negative fit is a warning.
//!
//! **Advice**: the reduced car when a chain link is undetermined or not
//! needed (module `reduce`), in the same words as the 1-D chain's.

mod bumper;
mod check;
pub mod free_bias;
mod links;
mod objective;
mod plausible;
mod predict;
mod priors;
mod reduce;
mod staged;
mod unknowns;

use crate::car::{Body, PlanarCar, PlanarError, SideChain};
use crate::drive::{Drive, Sensor};
use bumpsim_core::units::Dimension;
pub use bumpsim_estimate::domain::Domain;
use bumpsim_estimate::lm::{self, LeastSquares};
use bumpsim_estimate::multistart::{Searched, Starts};
use bumpsim_estimate::observer::Observer;
use bumpsim_estimate::prior::Priored;
use bumpsim_estimate::uncertainty::{Correlation, Estimated, Parameter, Uncertainty};
use nalgebra::DMatrix;
use objective::Objective;
pub use objective::{BIAS_INFLATION, Bias};
use serde::Serialize;

pub use bumper::{BumperFit, transformed, unloading_ratio};
pub use links::{LinkLaw, LinkLaws};
pub use plausible::{DYNAMIC_INDEX, MASS_TOLERANCE, MAX_MU};
pub use predict::{CaseFit, Prediction, predict};
pub use priors::{
    ARM_SPREAD, CELLS_WIDTH_SPREAD, MIRROR, MIRROR_SPREAD, MU, PriorSetting, TOTAL_MASS,
    WIDTH_SPREAD, priors, removing_all,
};
pub use staged::{CONFIRMED, CONFIRMING};
pub use unknowns::{ARM, ARM_REACH, EFFECTIVE_WIDTH, LINE_MARGIN, REACH, RELAXATION, Unknowns};

/// The reduced car, when a chain link is undetermined or not needed.
pub type Reduction = bumpsim_estimate::reduce::Reduction<PlanarCar>;

/// One load case: the replay and the measured sensor displacements.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarCase {
    /// Name, for reports.
    pub name: String,
    /// Forces, start speed and the sensors: the first two are body points
    /// left and right (x and yaw are theirs), more may follow (e.g. the
    /// side members' front ends).
    pub drive: Drive,
    /// Measured displacements of the left and right sensors, m, at the
    /// drive's samples: their body-x accelerations integrated twice
    /// ([`crate::drive::Driven::sensor_reading`]).
    pub measured: Vec<Vec<f64>>,
    /// Samples fitted, first and last (inclusive).
    pub window: (usize, usize),
    /// The loads (indices into `drive.loads`) whose lateral position is
    /// estimated (their `lateral` is the start): a single total force whose
    /// line of action no cell measured.
    pub estimated: Vec<usize>,
    /// The test's striker as the lab reports it (face, motion, speed), for
    /// the forward prediction of the whole test ([`crate::forward`]).
    pub striker: Option<crate::striker::Striker>,
    /// The instant of the test's record taken as t = 0, s of its files'
    /// time base (the force onset unless the study gives it, [`crate::cases::TimeZero`]).
    pub time_zero: f64,
    /// Each sensor's residual weight ([`crate::cases`]: 1 for the x
    /// accelerometers, their noise over its own for the others); empty:
    /// all 1.
    pub weights: Vec<f64>,
    /// How long a pre-trigger the accelerometers' biases were taken from,
    /// s (0: none): the spread of a bias nuisance's prior
    /// ([`Bias::Nuisance`]).
    pub pretrigger: f64,
    /// The CFC class (SAE J211-1) the measured channels were filtered at,
    /// if any: a forward prediction filters its simulated channels alike
    /// before it compares them ([`crate::forward`]).
    pub cfc: Option<f64>,
    /// Whether its accelerometers' remaining biases are unknowns (the
    /// study's `bias = "nuisance"`): [`predict`] then reads the sills' bias
    /// after the contact and removes it from the measured x before it
    /// scores x; `false`: the pre-trigger's mean only.
    pub nuisance: bool,
    /// The noise density of the sills' mean, (m/s²)·√s (`σ √h` of each
    /// accelerometer at its own step `h`, halved in quadrature; 0:
    /// unknown): the bias a mean over `T` s leaves in the measured x has
    /// the spread `x_noise / √T`, which the x bands carry
    /// ([`crate::bands`]).
    pub x_noise: f64,
}

impl PlanarCase {
    /// A case of `drive` and its `measured` sensor readings: every sample
    /// in its window, time zero at its first sample, no striker, estimated
    /// line of action, pre-trigger, filter, weights or nuisance biases; a
    /// case with more sets them by struct update.
    ///
    /// ```
    /// use bumpsim_planar::drive::{Drive, Load, Sensor};
    /// use bumpsim_planar::identify::PlanarCase;
    /// let load = Load { lateral: 0.0, anchor: None, cell: None, direction: [-1.0, 0.0], force: vec![1e4; 10] };
    /// let sensors = vec![Sensor::Body([0.6, 0.7]), Sensor::Body([0.6, -0.7])];
    /// let drive = Drive { step: 1e-4, loads: vec![load], speed: 2.0, arm: 1.0, sensors };
    /// let case = PlanarCase { pretrigger: 0.02, ..PlanarCase::replayed("push", drive, vec![vec![0.0; 10]; 2]) };
    /// assert_eq!(case.window, (0, 9));
    /// ```
    pub fn replayed(name: &str, drive: Drive, measured: Vec<Vec<f64>>) -> PlanarCase {
        let n = measured.iter().map(Vec::len).min().unwrap_or(0);
        PlanarCase {
            name: name.into(),
            drive,
            measured,
            window: (0, n.saturating_sub(1)),
            estimated: Vec::new(),
            striker: None,
            time_zero: 0.0,
            weights: Vec::new(),
            pretrigger: 0.0,
            cfc: None,
            nuisance: false,
            x_noise: 0.0,
        }
    }

    /// Sensor `k`'s residual weight.
    pub fn weight(&self, k: usize) -> f64 {
        self.weights.get(k).copied().unwrap_or(1.0)
    }

    /// The index of its yaw-rate sensor, if it has one.
    pub fn yaw_rate(&self) -> Option<usize> {
        self.drive
            .sensors
            .iter()
            .position(|s| *s == Sensor::YawRate)
    }
}

/// How to identify.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// The start: its chains' sizes and values, body, geometry and tyres.
    pub template: PlanarCar,
    /// Number of starts (≥ 1; the first is the template).
    pub starts: usize,
    /// Seed of the random starts.
    pub seed: u64,
    /// Random starts lie within this factor of the template (> 1).
    pub spread: f64,
    /// Estimate the lateral friction coefficient μ_y of both axles (else the template's).
    pub friction: bool,
    /// Estimate the cornering stiffness C_α of every tyre (else the template's).
    pub cornering: bool,
    /// Estimate the rolling tyres' relaxation length σ of both axles (else
    /// the template's; [`Unknowns::with_relaxation`]).
    pub relaxation: bool,
    /// The test sheet's total mass of the car, kg: the identified car's is
    /// checked against it ([`crate::identify`]'s plausibility).
    pub mass: Option<f64>,
    /// The study's settings of the stated priors ([`priors`]): overrides,
    /// removals, additions of the defaults.
    pub priors: Vec<PriorSetting>,
    /// Search a symmetric car first and start the full search from it
    /// (module `staged`); false: the starts are the template and random
    /// points around it.
    pub staged: bool,
    /// Fit the bumper's law and contact rate to the training tests' forward
    /// runs once the car is identified ([`crate::bumper_fit::identified`]);
    /// false: the template's bumper.
    pub bumper: bool,
    /// With `bumper`, polish the searched car and the bumper's law together
    /// on the replays and the training tests' forward runs, the forward
    /// runs weighing this much (β) against the replays at the start
    /// (the joint final stage of [`crate::bumper_fit`], `[model] joint`); None: the bumper fitted to
    /// the car as searched.
    pub joint: Option<f64>,
    /// Where the accelerometers are compared (module `objective`):
    /// displacement (the thesis's, m²), velocity or acceleration; the
    /// yaw-rate sensor and displacement channels as measured.
    pub domain: Domain,
    /// The accelerometers' constant biases: removed over the pre-trigger
    /// alone (the default) or also estimated as nuisances with the
    /// pre-trigger's prior ([`Bias`]).
    pub bias: Bias,
    /// Estimate each case's wall cells' arm as a nuisance with its stated
    /// prior ([`Unknowns::with_arms`]); false (the default, chosen by
    /// docs/planar.md's measurement): the segments' rule.
    pub arms: bool,
    /// Estimate the bumper's effective width, a property of the car with
    /// its stated prior ([`Unknowns::with_width`], `[model]
    /// effective_width`; a study's default: true when a training case has
    /// a wall's load cells, docs/planar.md); false: the start car's.
    pub width: bool,
    /// With `bumper`, compare a training test's forward run with a wall's
    /// load cells one by one ([`crate::cell_force`], `[model] cells`), in
    /// the bumper fit and the joint stage, the effective width's prior then
    /// [`CELLS_WIDTH_SPREAD`] wide with the joint stage; false: by the
    /// total force (a study's
    /// default: true with the bumper fitted and a wall's load cells in
    /// training, docs/planar.md).
    pub cells: bool,
    /// Run the full search again from its polished best with the priors
    /// weighed at the noise there, until its starts ran within a factor
    /// [`CONFIRMED`] of the final noise (at most [`CONFIRMING`] more
    /// searches), so that the starts search the final objective itself, not
    /// only their continuations end in it (module `staged`, `[model] confirm`; two or three times the search's
    /// time); false (the default): once, the starts weighing the priors at
    /// the symmetric optimum's noise.
    pub confirm: bool,
}

impl Setup {
    /// Eight starts within a factor 10 of `template`, seed 1, friction fixed.
    pub fn new(template: PlanarCar) -> Setup {
        Setup {
            template,
            starts: 8,
            seed: 1,
            spread: 10.0,
            friction: false,
            cornering: false,
            relaxation: false,
            mass: None,
            priors: Vec::new(),
            staged: true,
            bumper: false,
            joint: None,
            domain: Domain::Displacement,
            bias: Bias::Pretrigger,
            arms: false,
            width: false,
            cells: false,
            confirm: false,
        }
    }
}

/// One estimated parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// Name as in the car file (`body.yaw_inertia`, `left.springs[0]`, `tyres.mu_lateral`).
    pub name: String,
    /// Unit of value, standard error and interval.
    pub unit: &'static str,
    /// The estimate.
    pub value: f64,
    /// Standard error (delta method), when the Jacobian allows one.
    pub standard_error: Option<f64>,
    /// 95 % interval.
    pub ci95: Option<[f64; 2]>,
    /// Whether the data determine it (its 95 % interval within a factor
    /// 1000; false at a bound or without an interval).
    pub determined: Option<bool>,
}

/// The result of [`identify`]; serialised with the car's body, chains and
/// tyres (not its bumper beam, which is the template's).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanarIdentification {
    /// The identified car (the template's geometry, beam and tyres).
    #[serde(serialize_with = "car_parts")]
    pub car: PlanarCar,
    /// The estimates, in the order of [`Unknowns::names`].
    pub parameters: Vec<Estimate>,
    /// Objective F at the optimum, in the square of [`Self::domain`]'s unit
    /// (m² for displacement, (m/s)² for velocity, (m/s²)² for acceleration).
    pub objective: f64,
    /// Where the x accelerometers were compared (the setup's), which gives
    /// the objective its unit.
    #[serde(skip)]
    pub domain: Domain,
    /// The starts (the layer's tally).
    pub starts: Starts,
    /// Solver iterations of the best start (screening and polishing).
    pub iterations: usize,
    /// Wall-clock time, s.
    pub run_time: f64,
    /// Fits per case, %.
    pub fits: Vec<CaseFit>,
    /// The variance inflation of the residuals' correlation ([`CORRELATION`]: their integrated autocorrelation time τ), ≥ 1.
    pub inflation: f64,
    /// The effective number of the data residuals at the optimum, spectral
    /// (`n/τ`, τ their integrated autocorrelation time,
    /// [`bumpsim_estimate::effective`]): the link verdict's BIC counts it.
    #[serde(skip)]
    pub effective: bumpsim_estimate::effective::Effective,
    /// The layer's uncertainty: intervals, correlations, determination,
    /// the weakest direction.
    pub uncertainty: Uncertainty,
    /// Warnings: parameters at a bound or not determined, starts, negative
    /// fits, the reduced car.
    pub warnings: Vec<String>,
    /// The stated priors ([`priors`]), each with the estimate and how far
    /// the data moved it, in prior standard deviations.
    pub priors: Vec<bumpsim_estimate::prior::Moved>,
    /// The noise of one residual the priors weigh against, m
    /// ([`bumpsim_estimate::prior::noise`]).
    pub prior_noise: f64,
    /// The noise the priors were weighed against while the search's starts
    /// ran, in the unit of [`PlanarIdentification::prior_noise`]: far above
    /// it, the starts searched near the priors' centres and their tally
    /// counts that basin, not the final objective's ([`Setup::confirm`]).
    pub search_noise: f64,
    /// The reduced car that fits as well, if any; its `model` serialised as
    /// the car's parts.
    #[serde(serialize_with = "reduction_parts")]
    pub reduction: Option<Reduction>,
    /// The bumper's law fitted to the training tests' forward runs, when the
    /// study asked (`[model] bumper = "fit"`); the car carries it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bumper: Option<BumperFit>,
}

fn reduction_parts<S: serde::Serializer>(
    reduction: &Option<Reduction>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Reduced<'a> {
        parameter: &'a str,
        statement: &'a str,
        #[serde(serialize_with = "car_parts")]
        model: &'a PlanarCar,
        objective: f64,
        relative_objective: f64,
        p_value: f64,
    }
    reduction
        .as_ref()
        .map(|r| Reduced {
            parameter: &r.parameter,
            statement: &r.statement,
            model: &r.model,
            objective: r.objective,
            relative_objective: r.relative_objective,
            p_value: r.p_value,
        })
        .serialize(serializer)
}

fn car_parts<S: serde::Serializer, C: std::borrow::Borrow<PlanarCar>>(
    car: &C,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let car = car.borrow();
    #[derive(Serialize)]
    struct Parts<'a> {
        body: &'a Body,
        left: &'a SideChain,
        right: &'a SideChain,
        tyres: &'a crate::car::Tyres,
    }
    Parts {
        body: car.body(),
        left: car.left(),
        right: car.right(),
        tyres: car.tyres(),
    }
    .serialize(serializer)
}

/// The parameters of `result` as the estimation layer names and prints them.
pub fn parameters_of(result: &PlanarIdentification) -> Vec<Parameter> {
    result
        .parameters
        .iter()
        .map(|e| match e.unit {
            "kg" => Parameter::new(e.name.clone(), Dimension::Mass),
            "N·s/m" => Parameter::new(e.name.clone(), Dimension::Damping),
            "N/m" => Parameter::new(e.name.clone(), Dimension::Stiffness),
            "m" if e.name == "tyres.relaxation_length" => {
                Parameter::new(e.name.clone(), Dimension::Length)
            }
            "m" => Parameter::new(e.name.clone(), Dimension::Length).linear(f64::INFINITY),
            symbol => Parameter::with_symbol(e.name.clone(), symbol),
        })
        .collect()
}

/// Most starts of one planar identification.
pub const MAX_STARTS: usize = 10_000;

/// The largest factor the random starts are drawn within (`[model]
/// spread`): six decades each way of the start already reach past every
/// car (a spread of 1e300 drew starts of 0 and ∞ that failed, exit 0).
pub const MAX_SPREAD: f64 = 1e6;

/// Identifies the planar car from `cases`; `observer` hears of every
/// finished start (from any thread; a closure `|| bar.inc(1)` is one).
pub fn identify(
    cases: &[PlanarCase],
    setup: &Setup,
    observer: &dyn Observer,
) -> Result<PlanarIdentification, PlanarError> {
    identify_polished(cases, setup, observer, None)
}

/// A final stage on the search's best before the summary: given the
/// priored problem, the unknowns, the search and its bounds, the search
/// with its best run replaced (the joint final stage of
/// [`crate::bumper_fit`]).
pub(crate) type Polish<'a> = dyn Fn(
        (&(dyn LeastSquares + Sync), &Unknowns),
        Searched,
        (&[f64], &[f64]),
    ) -> Result<Searched, PlanarError>
    + 'a;

/// [`identify()`] with `polish` run on the search's best, when given.
pub(crate) fn identify_polished(
    cases: &[PlanarCase],
    setup: &Setup,
    observer: &dyn Observer,
    polish: Option<&Polish>,
) -> Result<PlanarIdentification, PlanarError> {
    let clock = std::time::Instant::now();
    let unknowns = check::check(cases, setup)?;
    let stated = priors(&unknowns, setup)?;
    let (lower, upper) = unknowns.bounds(&unknowns.start());
    let objective = Objective::new(cases, &unknowns, (setup.domain, setup.bias))?;
    let plan = staged::Plan {
        unknowns: &unknowns,
        priors: &stated,
        starts: setup.starts,
        seed: setup.seed,
        spread: setup.spread,
        staged: setup.staged,
        solver: solver(),
        bounds: (&lower, &upper),
        confirm: setup.confirm,
    };
    let found = staged::search(&objective, &plan, observer).map_err(|e| PlanarError::Missing {
        name: "identification".into(),
        expected: format!(
            "no start of {} could be evaluated: check the forces and the template",
            e.starts
        ),
    })?;
    let priored =
        Priored::new(objective.clone(), stated, found.noise).map_err(|e| PlanarError::Missing {
            name: "[priors]".into(),
            expected: e.to_string(),
        })?;
    let searched = match polish {
        Some(polish) => polish((&priored, &unknowns), found.searched, (&lower, &upper))?,
        None => found.searched,
    };
    let result = summarise(cases, setup, &priored, &searched, (&lower, &upper), clock)?;
    Ok(PlanarIdentification {
        search_noise: found.search_noise,
        ..result
    })
}

/// The error model of the intervals: the residuals' integrated
/// autocorrelation time, the 1-D chain's estimator ([`Correlation::Spectral`]).
pub const CORRELATION: Correlation = Correlation::Spectral;

/// The solver's tolerances: 300 iterations, relative decrease 1e-10, step 1e-8.
fn solver() -> lm::Settings {
    lm::Settings {
        max_iterations: 300,
        ftol: 1e-10,
        xtol: 1e-8,
        ..lm::Settings::default()
    }
}

fn summarise(
    cases: &[PlanarCase],
    setup: &Setup,
    priored: &Priored<Objective>,
    found: &Searched,
    bounds: (&[f64], &[f64]),
    clock: std::time::Instant,
) -> Result<PlanarIdentification, PlanarError> {
    let best = found.best();
    let p = &best.parameters;
    let objective = priored.problem();
    let unknowns = objective.unknowns();
    let theta = unknowns.theta(p);
    let car = unknowns.car(&theta)?;
    let mut r = vec![0.0; priored.residual_count()];
    let mut jacobian = DMatrix::zeros(r.len(), p.len());
    let parameters = unknowns.parameters();
    let free: Vec<usize> = (0..p.len()).collect();
    // a Jacobian that cannot be evaluated leaves every parameter undetermined
    let evaluated = priored.evaluate(p, &mut r, Some(&mut jacobian));
    let data: f64 = r[..objective.residual_count()].iter().map(|v| v * v).sum();
    let moved = bumpsim_estimate::prior::moved(priored.priors(), p);
    let series = objective.series();
    let effective = bumpsim_estimate::effective::of_residuals(
        &r[..objective.residual_count()],
        &series,
        bumpsim_estimate::effective::Method::Spectral,
    );
    // the data at the noise the intervals count, each prior at its spread
    bumpsim_estimate::information::counted(
        &mut r,
        &mut jacobian,
        &series,
        CORRELATION,
        priored.noise(),
    );
    let uncertainty = bumpsim_estimate::uncertainty::uncertainty(&Estimated {
        parameters: &parameters,
        theta: &theta,
        free: &free,
        p,
        bounds,
        residuals: &r,
        jacobian: &jacobian,
        series: &series,
        correlation: CORRELATION,
    });
    let uncertainty = match evaluated {
        true => uncertainty,
        false => bumpsim_estimate::uncertainty::unassessed(uncertainty),
    };
    let fits = cases
        .iter()
        .enumerate()
        .map(|(i, case)| {
            let located = unknowns.case(&theta, i, case);
            predict(&car, located.as_ref().unwrap_or(case)).map(|p| p.fit)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let negative = fits.iter().flat_map(CaseFit::warnings);
    let mut uncertainty = uncertainty;
    let prior_only = prior_only(priored, &theta, &mut uncertainty);
    let mut warnings = bumpsim_estimate::warnings(&uncertainty, &found.starts, best, negative);
    warnings.extend(bumpsim_estimate::prior::warnings(&moved));
    warnings.extend(prior_only);
    let estimates = estimates(unknowns, &theta, &uncertainty);
    let mut result = PlanarIdentification {
        car,
        parameters: estimates,
        objective: data,
        domain: setup.domain,
        starts: found.starts,
        iterations: best.iterations,
        run_time: clock.elapsed().as_secs_f64(),
        fits,
        inflation: uncertainty.inflation,
        effective,
        uncertainty,
        warnings,
        priors: moved,
        prior_noise: priored.noise(),
        // the search's own noise is the caller's (`identify_polished`)
        search_noise: priored.noise(),
        reduction: None,
        bumper: None,
    };
    let checks = plausible::checks(&result, setup);
    result.warnings.extend(checks);
    result.reduction = advice(cases, unknowns, &result, (setup.domain, setup.bias));
    if let Some(r) = &result.reduction {
        result.warnings.push(r.statement.clone());
    }
    Ok(result)
}

/// The parameters the data hardly inform (their posterior spread near
/// their prior's, [`bumpsim_estimate::prior::prior_only`]): marked not
/// determined, a warning each.
fn prior_only(priored: &Priored<Objective>, theta: &[f64], u: &mut Uncertainty) -> Vec<String> {
    let log_sd: Vec<Option<f64>> = u
        .standard_errors
        .iter()
        .zip(theta)
        .map(|(se, t)| se.map(|se| se / t.abs()))
        .collect();
    bumpsim_estimate::prior::prior_only(priored.priors(), &log_sd)
        .into_iter()
        .map(|(i, prior)| {
            u.determined[i] = Some(false);
            format!(
                "{} not determined by the data: its interval is mostly its prior's ({}, spread {} of ln θ)",
                prior.name, prior.source, bumpsim_estimate::prior::spread_text(prior.spread)
            )
        })
        .collect()
}

/// The estimates of the result, in the order of [`Unknowns::names`].
fn estimates(unknowns: &Unknowns, theta: &[f64], u: &Uncertainty) -> Vec<Estimate> {
    unknowns
        .names()
        .into_iter()
        .enumerate()
        .map(|(i, (name, unit))| Estimate {
            name,
            unit,
            value: theta[i],
            standard_error: u.standard_errors[i],
            ci95: u.ci95[i],
            determined: u.determined.get(i).copied().flatten(),
        })
        .collect()
}

/// The reduced car that fits as well (the layer's advice), if any.
fn advice(
    cases: &[PlanarCase],
    unknowns: &Unknowns,
    result: &PlanarIdentification,
    domain: (Domain, Bias),
) -> Option<Reduction> {
    let parameters = unknowns.parameters();
    let theta: Vec<f64> = result.parameters.iter().map(|e| e.value).collect();
    let residuals = cases
        .iter()
        .map(|c| c.measured.len() * (c.window.1 - c.window.0 + 1))
        .sum();
    let full = bumpsim_estimate::reduce::Full {
        parameters: &parameters,
        theta: &theta,
        uncertainty: &result.uncertainty,
        objective: result.objective,
        residuals,
    };
    let located = unknowns.located(&theta);
    let car = reduce::Car {
        cases,
        car: &result.car,
        unknowns: &located,
        solver: solver(),
        domain,
    };
    bumpsim_estimate::reduce::suggest(&car, &full)
}

#[cfg(test)]
mod tests;
