//! Identification of the planar car from several load cases at once (spec §9,
//! the planar extension of the thesis's ch. 3 identification).
//!
//! **Model.** Each case is replayed with [`crate::drive`]: the measured
//! barrier or pole forces act at their lateral positions on the bumper
//! line, the car starts at the test speed, and the model's left and right
//! sensor points move. The unknowns θ are the body mass M and yaw inertia
//! I_z, every mass, damper and spring of the left and right chains (their
//! sizes from the template car, the start), and optionally the lateral
//! tyre friction coefficient μ_y of both axles (the longitudinal ones, rolling
//! resistance or brakes, stay the template's). The geometry (CG,
//! side members, wheelbase, track) is the template's.
//!
//! **Objective.** `F(θ) = Σ_cases Σ_k (x̂_L − x_L)² + (x̂_R − x_R)²` over each
//! case's window, with `x_L`, `x_R` the world-x displacements of the left
//! and right sensors (accelerometers integrated twice). The two sensors
//! carry equal weight, so their mean (x) and half difference (yaw times the
//! sensor half-spacing) do too: yaw is observed through the left/right
//! difference, as in a test.
//!
//! **Search.** Bounded Levenberg–Marquardt ([`bumpsim_ident::lm`]) on
//! `p = ln θ`, each parameter within a factor 1000 of its start; the
//! Jacobian by forward differences (step 1e-6 in ln θ, columns in parallel):
//! the planar replay has no sensitivity recursion, and its steps are fixed
//! per car. Multi-start: the template, then log-uniform points within a
//! factor `spread` of it (ChaCha8 seeded by `seed + start index`), in parallel.
//!
//! **Uncertainty.** As [`bumpsim_ident::stats`]: `Cov(ln θ) = σ² (JᵀJ)⁻¹` at
//! the optimum with `σ² = F/(n − q)`, intervals `θ exp(± t SE)`, but with σ²
//! inflated by `(1 + ρ)/(1 − ρ)`, ρ the pooled lag-1 autocorrelation of the
//! residuals: displacements integrated from accelerations have strongly
//! correlated errors, and n samples of an AR(1) series carry only
//! `n (1 − ρ)/(1 + ρ)` independent observations (Bayley & Hammersley 1946).
//! Without it the intervals of a synthetic series were too narrow to cover
//! the truth.
//!
//! **Fit** of a case, as for the 1-D identification: `100 (1 − √(SSE/SST))` %,
//! for x (mean of the sensors) and for the yaw `ψ = asin((x_R − x_L)/(η_L − η_R))`.

use crate::car::{Body, PlanarCar, PlanarError, SideChain, parameter};
use crate::drive::{Drive, Driven, Sensor, drive, drive_substeps, substeps};
use bumpsim_ident::lm::{self, LeastSquares, Outcome};
use nalgebra::DMatrix;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

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
}

/// How well the model replays one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseFit {
    /// The case.
    pub name: String,
    /// Fit of x (mean of the two sensors), %.
    pub fit_x: f64,
    /// Fit of the yaw angle, %.
    pub fit_yaw: f64,
    /// Peak measured yaw, rad.
    pub peak_yaw: f64,
}

/// The starts' outcome.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Starts {
    /// Starts run.
    pub total: usize,
    /// Starts that converged.
    pub converged: usize,
    /// Starts within 1e-5 of the best objective.
    pub reached_best: usize,
}

/// The result of [`identify`]; serialised with the car's body, chains and
/// tyres (not its bumper beam, which is the template's).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanarIdentification {
    /// The identified car (the template's geometry, beam and tyres).
    #[serde(serialize_with = "car_parts")]
    pub car: PlanarCar,
    /// The estimates, in the order of [`names`].
    pub parameters: Vec<Estimate>,
    /// Objective F at the optimum, m².
    pub objective: f64,
    /// The starts.
    pub starts: Starts,
    /// Fits per case, %.
    pub fits: Vec<CaseFit>,
    /// The variance inflation `(1 + ρ)/(1 − ρ)` from the residuals' correlation, 1.
    pub inflation: f64,
    /// Warnings (parameters at a bound, a rank-deficient Jacobian).
    pub warnings: Vec<String>,
}

fn car_parts<S: serde::Serializer>(car: &PlanarCar, serializer: S) -> Result<S::Ok, S::Error> {
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

/// The parameters' names and units for `template` (friction last, if estimated).
pub fn names(template: &PlanarCar, friction: bool) -> Vec<(String, &'static str)> {
    let mut out = vec![
        ("body.mass".to_string(), "kg"),
        ("body.yaw_inertia".to_string(), "kg·m²"),
    ];
    for (side, chain) in [("left", template.left()), ("right", template.right())] {
        for (what, unit) in [("masses", "kg"), ("dampers", "N·s/m"), ("springs", "N/m")] {
            for i in 0..chain.masses.len() {
                out.push((format!("{side}.{what}[{i}]"), unit));
            }
        }
    }
    if friction {
        out.push(("tyres.mu_lateral".to_string(), "-"));
    }
    out
}

/// The template's parameter values, in the order of [`names`].
fn values(car: &PlanarCar, friction: bool) -> Vec<f64> {
    let mut out = vec![car.body().mass, car.body().yaw_inertia];
    for chain in [car.left(), car.right()] {
        out.extend(
            [&chain.masses, &chain.dampers, &chain.springs]
                .into_iter()
                .flatten(),
        );
    }
    if friction {
        out.push(car.tyres().front.mu_lateral);
    }
    out
}

/// The car with parameters `theta` (SI, order of [`names`]).
pub fn car_with(
    template: &PlanarCar,
    theta: &[f64],
    friction: bool,
) -> Result<PlanarCar, PlanarError> {
    let mut next = theta.iter().copied();
    let mut take = |n: usize| next.by_ref().take(n).collect::<Vec<f64>>();
    let body = Body {
        mass: take(1)[0],
        yaw_inertia: take(1)[0],
        ..*template.body()
    };
    let mut chain = |n: usize| SideChain {
        masses: take(n),
        dampers: take(n),
        springs: take(n),
    };
    let left = chain(template.left().masses.len());
    let right = chain(template.right().masses.len());
    let mut tyres = *template.tyres();
    if friction {
        let mu = take(1)[0];
        tyres.front.mu_lateral = mu;
        tyres.rear.mu_lateral = mu;
    }
    PlanarCar::new(body, left, right, template.beam().clone(), tyres)
        .map(|c| c.with_name(template.name().map(str::to_string)))
}

/// Most starts of one planar identification.
pub const MAX_STARTS: usize = 10_000;

fn check(cases: &[PlanarCase], setup: &Setup) -> Result<Vec<f64>, PlanarError> {
    let setting =
        |name: &str, value: f64, unit, expected: &str| Err(parameter(name, value, unit, expected));
    if cases.is_empty() {
        return setting("cases", 0.0, "1", "at least one load case");
    }
    if setup.starts == 0 || setup.starts > MAX_STARTS {
        return setting(
            "starts",
            setup.starts as f64,
            "1",
            &format!("1 to {MAX_STARTS}"),
        );
    }
    if !(setup.spread.is_finite() && setup.spread > 1.0) {
        return setting("spread", setup.spread, "1", "a finite factor above 1");
    }
    for case in cases {
        check_case(case)?;
        crate::drive::validate(&setup.template, &case.drive).map_err(|e| PlanarError::Case {
            case: case.name.clone(),
            message: e.to_string(),
        })?;
    }
    let start = values(&setup.template, setup.friction);
    let names = names(&setup.template, setup.friction);
    for ((name, unit), value) in names.iter().zip(&start) {
        if !(value.is_finite() && *value > 0.0) {
            return setting(
                name,
                *value,
                unit,
                "the start must be positive to be estimated (on a log scale)",
            );
        }
    }
    Ok(start)
}

/// Lateral spacing η_L − η_R of the first two sensors when both are body
/// points, m; NaN otherwise.
fn spacing(case: &PlanarCase) -> f64 {
    match case.drive.sensors.as_slice() {
        [Sensor::Body(left), Sensor::Body(right), ..] => left[1] - right[1],
        _ => f64::NAN,
    }
}

fn check_case(case: &PlanarCase) -> Result<(), PlanarError> {
    let name = |what: &str| format!("case '{}': {what}", case.name);
    let samples = case.drive.loads.first().map_or(0, |l| l.force.len());
    let spacing = spacing(case);
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(parameter(
            &name("sensors"),
            spacing,
            "m",
            "the first two sensors on the body, left (larger η) then right",
        ));
    }
    if case.measured.len() != case.drive.sensors.len() {
        let n = case.measured.len() as f64;
        return Err(parameter(
            &name("measured"),
            n,
            "signals",
            &format!("one per sensor ({})", case.drive.sensors.len()),
        ));
    }
    for (s, m) in case.measured.iter().enumerate() {
        if m.len() != samples {
            return Err(parameter(
                &name(&format!("sensor[{s}] displacement")),
                m.len() as f64,
                "samples",
                &format!("as many samples as the forces ({samples})"),
            ));
        }
        if let Some(k) = m.iter().position(|v| !v.is_finite()) {
            return Err(parameter(
                &name(&format!("sensor[{s}] displacement[{k}]")),
                m[k],
                "m",
                "must be finite",
            ));
        }
    }
    let (a, b) = case.window;
    if !(a < b && b < samples) {
        return Err(parameter(
            &name("window end"),
            b as f64,
            "sample",
            &format!("a window of at least two samples within 0..{samples}"),
        ));
    }
    Ok(())
}

/// The least-squares problem over all cases, in `p = ln θ`.
struct Objective<'a> {
    cases: &'a [PlanarCase],
    setup: &'a Setup,
    count: usize,
    parameters: usize,
    /// Integration steps per sample of each case.
    substeps: Vec<usize>,
}

impl<'a> Objective<'a> {
    /// The problem, each case replayed with the step of the template at a
    /// safety factor of 0.05: a 40-fold margin to the stability limit for
    /// trial cars stiffer or lighter than the start.
    fn new(
        cases: &'a [PlanarCase],
        setup: &'a Setup,
        parameters: usize,
    ) -> Result<Objective<'a>, PlanarError> {
        let count = cases
            .iter()
            .map(|c| c.measured.len() * (c.window.1 - c.window.0 + 1))
            .sum();
        let substeps = cases
            .iter()
            .map(|c| substeps(&setup.template, c.drive.step, 0.05))
            .collect::<Result<_, _>>()?;
        Ok(Objective {
            cases,
            setup,
            count,
            parameters,
            substeps,
        })
    }

    fn replays(&self, p: &[f64]) -> Option<Vec<Driven>> {
        let theta: Vec<f64> = p.iter().copied().map(f64::exp).collect();
        let car = car_with(&self.setup.template, &theta, self.setup.friction).ok()?;
        self.cases
            .iter()
            .zip(&self.substeps)
            .map(|(c, &n)| drive_substeps(&car, &c.drive, n).ok())
            .collect()
    }

    fn residuals(&self, p: &[f64], r: &mut [f64]) -> bool {
        let Some(replays) = self.replays(p) else {
            return false;
        };
        let mut at = 0;
        for (case, replay) in self.cases.iter().zip(&replays) {
            for k in case.window.0..=case.window.1 {
                for (model, measured) in replay.sensor_reading.iter().zip(&case.measured) {
                    r[at] = model[k] - measured[k];
                    at += 1;
                }
            }
        }
        r.iter().all(|v| v.is_finite())
    }
}

impl LeastSquares for Objective<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.parameters
    }

    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        if !self.residuals(p, r) {
            return false;
        }
        let Some(jac) = jacobian else {
            return true;
        };
        const H: f64 = 1e-6;
        let columns: Vec<Option<Vec<f64>>> = (0..p.len())
            .into_par_iter()
            .map(|j| {
                let mut shifted = p.to_vec();
                shifted[j] += H;
                let mut column = vec![0.0; r.len()];
                self.residuals(&shifted, &mut column).then(|| {
                    column
                        .iter()
                        .zip(r.iter())
                        .map(|(a, b)| (a - b) / H)
                        .collect()
                })
            })
            .collect();
        for (j, column) in columns.into_iter().enumerate() {
            let Some(column) = column else {
                return false;
            };
            jac.column_mut(j).copy_from_slice(&column);
        }
        true
    }
}

/// Identifies the planar car from `cases`; `progress` is called once per
/// finished start (from any thread).
pub fn identify(
    cases: &[PlanarCase],
    setup: &Setup,
    progress: &(dyn Fn() + Sync),
) -> Result<PlanarIdentification, PlanarError> {
    let start: Vec<f64> = check(cases, setup)?.iter().map(|v| v.ln()).collect();
    let reach = 1000f64.ln();
    let lower: Vec<f64> = start.iter().map(|p| p - reach).collect();
    let upper: Vec<f64> = start.iter().map(|p| p + reach).collect();
    let objective = Objective::new(cases, setup, start.len())?;
    let solver = lm::Settings {
        max_iterations: 300,
        ftol: 1e-10,
        xtol: 1e-8,
        ..lm::Settings::default()
    };
    let outcomes: Vec<Outcome> = (0..setup.starts)
        .into_par_iter()
        .map(|k| {
            let point = starting_point(&start, k, setup);
            let outcome = lm::minimise(&objective, &point, &lower, &upper, &solver);
            progress();
            outcome
        })
        .collect();
    let best = outcomes
        .iter()
        .filter(|o| o.objective.is_finite())
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .ok_or_else(|| PlanarError::Missing {
            name: "identification".into(),
            expected: format!(
                "no start of {} could be evaluated: check the forces and the template",
                setup.starts
            ),
        })?;
    let starts = Starts {
        total: outcomes.len(),
        converged: outcomes
            .iter()
            .filter(|o| o.objective.is_finite() && o.stop.converged())
            .count(),
        reached_best: outcomes
            .iter()
            .filter(|o| o.objective <= best.objective * (1.0 + 1e-5))
            .count(),
    };
    summarise(cases, setup, &objective, best, starts, (&lower, &upper))
}

/// Start `k`: the template for k = 0, else log-uniform within `spread`.
fn starting_point(start: &[f64], k: usize, setup: &Setup) -> Vec<f64> {
    if k == 0 {
        return start.to_vec();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(setup.seed.wrapping_add(k as u64));
    let reach = setup.spread.ln();
    start
        .iter()
        .map(|p| {
            let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            p + reach * (2.0 * u - 1.0)
        })
        .collect()
}

fn summarise(
    cases: &[PlanarCase],
    setup: &Setup,
    objective: &Objective,
    best: &Outcome,
    starts: Starts,
    (lower, upper): (&[f64], &[f64]),
) -> Result<PlanarIdentification, PlanarError> {
    let p = &best.parameters;
    let theta: Vec<f64> = p.iter().copied().map(f64::exp).collect();
    let car = car_with(&setup.template, &theta, setup.friction)?;
    let mut r = vec![0.0; objective.residual_count()];
    let mut jac = DMatrix::zeros(r.len(), p.len());
    let mut warnings = Vec::new();
    let names = names(&setup.template, setup.friction);
    let mut parameters: Vec<Estimate> = names
        .iter()
        .zip(&theta)
        .map(|((name, unit), value)| Estimate {
            name: name.clone(),
            unit,
            value: *value,
            standard_error: None,
            ci95: None,
        })
        .collect();
    let mut inflation_used = 1.0;
    if objective.evaluate(p, &mut r, Some(&mut jac)) {
        inflation_used = inflation(cases, &r);
        intervals(
            &mut parameters,
            &jac,
            &r,
            inflation_used,
            (p, lower, upper),
            &mut warnings,
        );
    }
    let fits = cases
        .iter()
        .map(|case| predict(&car, case).map(|p| p.fit))
        .collect::<Result<Vec<_>, _>>()?;
    if starts.reached_best == 1 && starts.total > 1 {
        warnings.push(format!(
            "only 1 of {} starts reached the best objective: run more starts",
            starts.total
        ));
    }
    Ok(PlanarIdentification {
        car,
        parameters,
        objective: best.objective,
        starts,
        fits,
        inflation: inflation_used,
        warnings,
    })
}

/// `(1 + ρ)/(1 − ρ)` of the pooled lag-1 autocorrelation ρ of the residual
/// series (one per case and sensor; residuals interleave the sensors).
fn inflation(cases: &[PlanarCase], r: &[f64]) -> f64 {
    let (mut lag, mut power, mut at) = (0.0, 0.0, 0);
    for case in cases {
        let (n, sensors) = (case.window.1 - case.window.0 + 1, case.measured.len());
        for side in 0..sensors {
            let series = |k: usize| r[at + sensors * k + side];
            for k in 0..n {
                power += series(k) * series(k);
                if k + 1 < n {
                    lag += series(k) * series(k + 1);
                }
            }
        }
        at += sensors * n;
    }
    let rho = match power > 0.0 {
        true => (lag / power).clamp(0.0, 0.999_999),
        false => 0.0,
    };
    (1.0 + rho) / (1.0 - rho)
}

/// Standard errors and 95 % intervals from the Jacobian in ln θ.
fn intervals(
    parameters: &mut [Estimate],
    jac: &DMatrix<f64>,
    r: &[f64],
    inflation: f64,
    (p, lower, upper): (&[f64], &[f64], &[f64]),
    warnings: &mut Vec<String>,
) {
    let tolerance = 1e-6;
    let free: Vec<usize> = (0..p.len())
        .filter(|&j| p[j] - lower[j] > tolerance && upper[j] - p[j] > tolerance)
        .collect();
    for j in (0..p.len()).filter(|j| !free.contains(j)) {
        warnings.push(format!(
            "{} = {:.4e} {} is at a bound (a factor 1000 from its start): not identifiable from these data",
            parameters[j].name, parameters[j].value, parameters[j].unit
        ));
    }
    let (m, q) = (r.len(), free.len());
    if q == 0 || m <= q {
        return;
    }
    let je = DMatrix::from_fn(m, q, |i, c| jac[(i, free[c])]);
    let svd = je.svd(false, true);
    let (Some(v_t), largest) = (svd.v_t.as_ref(), svd.singular_values.max()) else {
        return;
    };
    if svd.singular_values.min() <= largest * 1e-12 {
        warnings.push("the Jacobian is rank deficient: no intervals".into());
        return;
    }
    let variance = r.iter().map(|v| v * v).sum::<f64>() / (m - q) as f64 * inflation;
    let t = StudentsT::new(0.0, 1.0, (m - q) as f64).map_or(1.96, |d| d.inverse_cdf(0.975));
    for (c, &j) in free.iter().enumerate() {
        let var_log: f64 = (0..q)
            .map(|s| (v_t[(s, c)] / svd.singular_values[s]).powi(2))
            .sum::<f64>()
            * variance;
        let se = var_log.sqrt();
        let value = parameters[j].value;
        let ci = [value * f64::exp(-t * se), value * f64::exp(t * se)];
        if se.is_finite() && ci.iter().all(|v| v.is_finite() && *v > 0.0) {
            parameters[j].standard_error = Some(value * se);
            parameters[j].ci95 = Some(ci);
        }
    }
}

/// A case replayed with a car: x and yaw, model and measured, and the fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// Time from the first sample, s.
    pub time: Vec<f64>,
    /// Model and measured x (mean of the sensors), m.
    pub x: [Vec<f64>; 2],
    /// Model and measured yaw, rad.
    pub yaw: [Vec<f64>; 2],
    /// The fit over the case's window.
    pub fit: CaseFit,
}

/// Replays `case` with `car` and compares it with the measurement.
pub fn predict(car: &PlanarCar, case: &PlanarCase) -> Result<Prediction, PlanarError> {
    check_case(case)?;
    let replay = drive(car, &case.drive, 0.05)?;
    let spacing = spacing(case);
    let mean = |s: &[Vec<f64>]| {
        s[0].iter()
            .zip(&s[1])
            .map(|(l, r)| 0.5 * (l + r))
            .collect::<Vec<_>>()
    };
    let yaw = |s: &[Vec<f64>]| {
        s[0].iter()
            .zip(&s[1])
            .map(|(l, r)| ((r - l) / spacing).clamp(-1.0, 1.0).asin())
            .collect::<Vec<_>>()
    };
    let x = [mean(&replay.sensor_reading), mean(&case.measured)];
    let yaw = [yaw(&replay.sensor_reading), yaw(&case.measured)];
    let (a, b) = case.window;
    let fit = CaseFit {
        name: case.name.clone(),
        fit_x: fit(&x[0][a..=b], &x[1][a..=b]),
        fit_yaw: fit(&yaw[0][a..=b], &yaw[1][a..=b]),
        peak_yaw: yaw[1][a..=b].iter().fold(0.0, |m: f64, v| m.max(v.abs())),
    };
    Ok(Prediction {
        time: replay.time,
        x,
        yaw,
        fit,
    })
}

/// `100 (1 − √(SSE/SST))` of `model` against `measured`, %.
fn fit(model: &[f64], measured: &[f64]) -> f64 {
    let mean = measured.iter().sum::<f64>() / measured.len() as f64;
    let sse: f64 = model
        .iter()
        .zip(measured)
        .map(|(s, y)| (y - s).powi(2))
        .sum();
    let sst: f64 = measured.iter().map(|y| (y - mean).powi(2)).sum();
    match sst > 0.0 {
        true => 100.0 * (1.0 - (sse / sst).sqrt()),
        false => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::drive::Load;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car() -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    /// A case made by the model itself: a half-sine push at `lateral`,
    /// sills and both side members measured.
    fn case(truth: &PlanarCar, lateral: f64) -> PlanarCase {
        let force: Vec<f64> = (0..400)
            .map(|k| 4e4 * (std::f64::consts::PI * (k as f64 / 300.0).min(1.0)).sin())
            .collect();
        let load = Load {
            lateral,
            anchor: None,
            direction: [-1.0, 0.0],
            force,
        };
        let sensors = vec![
            Sensor::Body([0.6, 0.7]),
            Sensor::Body([0.6, -0.7]),
            Sensor::Chain(0),
            Sensor::Chain(1),
        ];
        let drive = Drive {
            step: 1e-4,
            loads: vec![load],
            speed: 2.0,
            sensors,
        };
        let replay = crate::drive::drive(truth, &drive, 0.05).unwrap();
        PlanarCase {
            name: "offset".into(),
            drive,
            measured: replay.sensor_reading,
            window: (0, 399),
        }
    }

    #[test]
    fn noise_free_data_of_the_model_are_fitted_exactly_and_the_truth_found() {
        let truth = car();
        let mut start = Setup::new(
            car_with(
                &truth,
                &[1000.0, 2500.0, 6.0, 1500.0, 1.2e6, 6.0, 1500.0, 1.2e6],
                false,
            )
            .unwrap(),
        );
        start.starts = 2;
        let r = identify(&[case(&truth, 0.4), case(&truth, -0.2)], &start, &|| {}).unwrap();
        let truth_values = values(&truth, false);
        for (p, t) in r.parameters.iter().zip(&truth_values) {
            assert!(
                (p.value - t).abs() < 1e-3 * t,
                "{} {} vs {t}",
                p.name,
                p.value
            );
        }
        assert!(
            r.fits[0].fit_x > 99.99 && r.fits[0].fit_yaw > 99.9,
            "{:?}",
            r.fits
        );
    }

    #[test]
    fn bad_settings_and_cases_are_refused_by_name() {
        let truth = car();
        let good = case(&truth, 0.4);
        let setup = Setup::new(truth.clone());
        let err = |cases: &[PlanarCase], setup: &Setup| {
            identify(cases, setup, &|| {}).unwrap_err().to_string()
        };
        assert!(err(&[], &setup).starts_with("cases"));
        assert!(
            err(
                std::slice::from_ref(&good),
                &Setup {
                    starts: 0,
                    ..setup.clone()
                }
            )
            .starts_with("starts")
        );
        assert!(
            err(
                std::slice::from_ref(&good),
                &Setup {
                    spread: f64::NAN,
                    ..setup.clone()
                }
            )
            .starts_with("spread")
        );
        let mut short = good.clone();
        short.window = (10, 4000);
        assert!(err(&[short], &setup).contains("window"));
        let mut swapped = good.clone();
        swapped.drive.sensors.swap(0, 1);
        assert!(err(&[swapped], &setup).contains("sensors"));
        let mut nan = good.clone();
        nan.measured[1][7] = f64::NAN;
        assert!(err(&[nan], &setup).contains("sensor[1] displacement[7]"));
        let frictionless = Setup {
            friction: true,
            ..setup
        };
        assert!(
            err(&[good], &frictionless).contains("tyres.mu_lateral"),
            "a zero start cannot be estimated on a log scale"
        );
    }
}
