//! The least-squares problem of a planar identification, in `p = ln θ`:
//! each case replayed ([`crate::drive`]) with the car of `θ`, the residuals
//! the modelled minus the measured sensor readings over each case's window
//! (sensors interleaved), each times its sensor's weight
//! ([`PlanarCase::weight`]), and their exact Jacobian from the replay on
//! dual numbers ([`jacobian`], [`crate::sensitivity`]; forward differences,
//! [`bumpsim_estimate::difference`] with step 1e-6 in ln θ, only for
//! unknowns that module does not know). The
//! replay's steps are fixed per template car, so the objective does not
//! jump where a trial car's own step would change: the template's
//! critical step with its progressive links' slopes at the crush the
//! case's loads can reach ([`crate::car::PlanarCar::within_force`]), not
//! at their limits.

use super::{PlanarCase, Unknowns};
use crate::car::PlanarError;
use crate::drive::Load;
use crate::drive::{sensor_readings, substeps};
use bumpsim_estimate::difference::forward_jacobian;
use bumpsim_estimate::domain::Domain;
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::uncertainty::Series;
use nalgebra::DMatrix;
use std::sync::{Arc, Mutex};

mod jacobian;

/// The fraction of the template's critical step a replay takes: an 8-fold
/// margin to the stability limit for trial cars stiffer or lighter than the
/// start (a trial car beyond it diverges and its step is refused), and at
/// most `(ω T)² / 24 ≈ 0.3 %` of phase error per step at the stiffest link
/// (the impact simulation's 0.05 is for resolving crush onsets, which a
/// replay of given forces has none of).
pub const REPLAY_SAFETY: f64 = 0.25;

/// The least-squares problem over all cases.
#[derive(Debug)]
pub(crate) struct Objective<'a> {
    /// The cases as replayed: their same-direction loads on the bumper
    /// line merged ([`merged`]).
    cases: Arc<Vec<PlanarCase>>,
    unknowns: &'a Unknowns,
    count: usize,
    /// Integration steps per sample of each case.
    substeps: Vec<usize>,
    /// What each unknown is in the replay (`None`: forward differences).
    slots: Option<Vec<jacobian::Slot>>,
    /// The last point evaluated without its Jacobian and its residuals: LM
    /// asks for the Jacobian at a trial point it has just evaluated.
    last: Mutex<Option<(Vec<f64>, Vec<f64>)>>,
    /// Where the accelerometers are compared ([`compared`]).
    domain: Domain,
    /// Their biases ([`debiased`]).
    bias: Bias,
    /// With [`Bias::Nuisance`], each case's bias reading and its profile
    /// factor ([`bias_readings`]), made once: the objective is evaluated
    /// thousands of times.
    readings: Arc<Vec<Option<BiasReading>>>,
}

/// A clone starts with no remembered point (one per solver run).
impl Clone for Objective<'_> {
    fn clone(&self) -> Self {
        Objective {
            cases: Arc::clone(&self.cases),
            unknowns: self.unknowns,
            count: self.count,
            substeps: self.substeps.clone(),
            slots: self.slots.clone(),
            last: Mutex::new(None),
            domain: self.domain,
            bias: self.bias,
            readings: Arc::clone(&self.readings),
        }
    }
}

impl<'a> Objective<'a> {
    /// The problem, each case replayed with the step of the template at a
    /// safety factor of [`REPLAY_SAFETY`] (its progressive links as the
    /// case's loads can crush them).
    pub fn new(
        cases: &[PlanarCase],
        unknowns: &'a Unknowns,
        (domain, bias): (Domain, Bias),
    ) -> Result<Objective<'a>, PlanarError> {
        let spacing = unknowns.template().beam().side_member_spacing;
        let cases: Vec<PlanarCase> = cases.iter().map(|c| merged(c, 0.5 * spacing)).collect();
        let count = cases
            .iter()
            .map(|c| c.measured.len() * (c.window.1 - c.window.0 + 1))
            .sum();
        let substeps = cases
            .iter()
            .map(|c| {
                let reach = unknowns.template().within_force(peak_load(c))?;
                substeps(&reach, c.drive.step, REPLAY_SAFETY)
            })
            .collect::<Result<_, _>>()?;
        let slots = jacobian::slots(unknowns, &cases);
        let readings = match bias {
            Bias::Nuisance => bias_readings(&cases, domain),
            Bias::Pretrigger => Vec::new(),
        };
        Ok(Objective {
            cases: Arc::new(cases),
            unknowns,
            count,
            substeps,
            slots,
            last: Mutex::new(None),
            domain,
            bias,
            readings: Arc::new(readings),
        })
    }

    /// What it estimates.
    pub fn unknowns(&self) -> &'a Unknowns {
        self.unknowns
    }

    /// The residual series: per case and sensor, interleaved by sensor.
    pub fn series(&self) -> Vec<Series> {
        let mut out = Vec::new();
        let mut at = 0;
        for case in self.cases.iter() {
            let (n, sensors) = (case.window.1 - case.window.0 + 1, case.measured.len());
            out.extend((0..sensors).map(|side| Series {
                start: at + side,
                len: n,
                stride: sensors,
            }));
            at += sensors * n;
        }
        out
    }

    /// `r`, residuals or a Jacobian column in displacement, in the
    /// objective's domain ([`compared`]) and with its biases ([`debiased`]).
    fn transformed(&self, r: &mut [f64]) {
        compared(&self.cases, self.domain, r);
        if self.bias == Bias::Nuisance {
            debiased(&self.cases, &self.readings, r);
        }
    }

    /// Each case's sensor readings up to its window's end with the car of `p`.
    fn replays(&self, p: &[f64]) -> Option<Vec<Vec<Vec<f64>>>> {
        let theta = self.unknowns.theta(p);
        let car = self.unknowns.car(&theta).ok()?;
        self.cases
            .iter()
            .zip(&self.substeps)
            .enumerate()
            .map(|(i, (c, &n))| {
                let located = self.unknowns.case(&theta, i, c);
                let drive = &located.as_ref().unwrap_or(c).drive;
                sensor_readings(&car, drive, n, c.window.1 + 1).ok()
            })
            .collect()
    }

    fn residuals(&self, p: &[f64], r: &mut [f64]) -> bool {
        let Some(replays) = self.replays(p) else {
            return false;
        };
        let mut at = 0;
        for (case, replay) in self.cases.iter().zip(&replays) {
            for k in case.window.0..=case.window.1 {
                for (s, (model, measured)) in replay.iter().zip(&case.measured).enumerate() {
                    r[at] = case.weight(s) * (model[k] - measured[k]);
                    at += 1;
                }
            }
        }
        self.transformed(r);
        r.iter().all(|v| v.is_finite())
    }
}

/// How the accelerometers' constant biases are handled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Bias {
    /// Removed as the pre-trigger's mean (the cases module), nothing more:
    /// the mean's error (σ/√n) stays in the data.
    #[default]
    Pretrigger,
    /// Removed as the pre-trigger's mean and, per case and accelerometer, a
    /// remaining bias b estimated with the car as a nuisance value under
    /// the pre-trigger mean's own uncertainty as its prior (see the objective's `debiased`).
    Nuisance,
}

/// The data's per-sample count against the bias's prior in the objective's `debiased`:
/// the displacement and velocity residuals are strongly correlated
/// (variance inflation 50–230 on issue 44's yaw-rate series), so a
/// white-noise count would make the prior negligible; 100 counts the data
/// at about one effective sample per hundred. Chosen among 10, 100 and
/// 1000 on the varied cars (docs/planar.md, "The objective's domain").
pub const BIAS_INFLATION: f64 = 100.0;

/// Each case's accelerometer bias `b` (left after the pre-trigger's mean
/// was removed) profiled out as a nuisance value with the prior
/// `N(0, σ²/n)` of a mean over the `n = T/h` pre-trigger samples
/// ([`PlanarCase::pretrigger`] `T`): `min_b ‖r − b g‖² + κ b²`, g the
/// bias's reading (`t²/2` differenced into `domain`), `κ = c n s²` with s
/// the accelerometer's per-sample noise in `domain` over the window for a
/// unit σ (the cases module's `domain_noise`) and c [`BIAS_INFLATION`]
/// (velocity: `κ = c T D / 2`, displacement `c T D³ / 12`). The profiled
/// objective is `‖A r‖²` with `A = I − (1 − √(κ/(G+κ))) ĝĝᵀ`, `G = gᵀg`:
/// linear in `r`, so Jacobian columns transform alike. A case with no
/// pre-trigger keeps its residuals.
fn debiased(cases: &[PlanarCase], readings: &[Option<BiasReading>], r: &mut [f64]) {
    let mut at = 0;
    for (case, reading) in cases.iter().zip(readings) {
        let (n, sensors) = (case.window.1 - case.window.0 + 1, case.measured.len());
        if let Some(BiasReading { g, gg, cut }) = reading {
            for (s, sensor) in case.drive.sensors.iter().enumerate() {
                if sensor.integrations() != 2 || sensor.displacement() {
                    continue;
                }
                let rg: f64 = (0..n).map(|k| r[at + k * sensors + s] * g[k]).sum();
                for (k, gk) in g.iter().enumerate() {
                    r[at + k * sensors + s] -= cut * rg / gg * gk;
                }
            }
        }
        at += sensors * n;
    }
}

/// A case's accelerometer bias reading for a unit bias, in the compared
/// domain (`g`), `G = gᵀg` and the profile factor `1 − √(κ/(G+κ))` of
/// [`debiased`].
#[derive(Debug)]
struct BiasReading {
    g: Vec<f64>,
    gg: f64,
    cut: f64,
}

/// Each case's [`BiasReading`] (None: no pre-trigger, fewer than 3
/// samples or a reading of no length).
fn bias_readings(cases: &[PlanarCase], domain: Domain) -> Vec<Option<BiasReading>> {
    cases
        .iter()
        .map(|case| {
            let n = case.window.1 - case.window.0 + 1;
            let h = case.drive.step;
            if case.pretrigger <= 0.0 || n < 3 {
                return None;
            }
            let duration = h * (n - 1) as f64;
            let unit = domain_noise(h, duration, 2 - domain.order());
            let kappa = BIAS_INFLATION * (case.pretrigger / h) * unit * unit;
            // the bias's reading b t²/2 for b = 1, in `domain`
            let mut g: Vec<f64> = (0..n)
                .map(|k| {
                    let t = (case.window.0 + k) as f64 * h;
                    0.5 * t * t
                })
                .collect();
            differenced(&mut g, (0, 1, n), domain.order(), h);
            let gg: f64 = g.iter().map(|v| v * v).sum();
            let cut = 1.0 - (kappa / (gg + kappa)).sqrt();
            (gg > 0.0).then_some(BiasReading { g, gg, cut })
        })
        .collect()
}

/// `r` (the displacement-domain residuals, or one Jacobian column) in
/// `domain` ([`bumpsim_estimate::domain`]): per case, each accelerometer's
/// series (integrated twice, [`crate::drive::Sensor::integrations`])
/// differenced `order` times over the case's step within the window (its
/// first `order` samples, which have no predecessor in the window, set to
/// 0), every other sensor (yaw rate, displacement) left as measured with
/// its weight rescaled from the accelerometers' displacement-domain noise
/// to theirs in `domain` (the cases module's `domain_noise`; `√6 / D` in
/// velocity over a window of `D` s). Linear in `r`, so the Jacobian's
/// columns transform alike. A constant accelerometer bias `b` reads as
/// `b t²/2` in displacement, `b t` in velocity, `b` in acceleration.
fn compared(cases: &[PlanarCase], domain: Domain, r: &mut [f64]) {
    let order = domain.order();
    if order == 0 {
        return;
    }
    let mut at = 0;
    for case in cases {
        let (n, sensors) = (case.window.1 - case.window.0 + 1, case.measured.len());
        let h = case.drive.step;
        let duration = h * (n - 1) as f64;
        let scale = domain_noise(h, duration, 2 - order) / domain_noise(h, duration, 2);
        for (s, sensor) in case.drive.sensors.iter().enumerate() {
            if sensor.integrations() != 2 {
                (0..n).for_each(|k| r[at + k * sensors + s] *= scale);
                continue;
            }
            differenced(r, (at + s, sensors, n), order, h);
        }
        at += sensors * n;
    }
}

/// White noise of unit level sampled every `step` in the domain of
/// `integrations` integrals, its rms over `duration`.
fn domain_noise(step: f64, duration: f64, integrations: usize) -> f64 {
    bumpsim_estimate::domain::integrated_noise(1.0, step, duration, integrations)
}

/// The series `r[start + k stride]`, `k < n`, differenced `order` times
/// over `h` in place, backward; its first `order` samples 0.
fn differenced(r: &mut [f64], (start, stride, n): (usize, usize, usize), order: usize, h: f64) {
    let i = |k: usize| start + k * stride;
    for pass in 0..order.min(n) {
        for k in (pass + 1..n).rev() {
            r[i(k)] = (r[i(k)] - r[i(k - 1)]) / h;
        }
        r[i(pass)] = 0.0;
    }
}

impl LeastSquares for Objective<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.unknowns.names().len()
    }

    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        let remembered = match (&*last, jacobian.is_some()) {
            (Some((q, residuals)), true) if q.as_slice() == p => {
                r.copy_from_slice(residuals);
                true
            }
            _ => false,
        };
        if !remembered && !self.residuals(p, r) {
            return false;
        }
        let Some(jac) = jacobian else {
            *last = Some((p.to_vec(), r.to_vec()));
            return true;
        };
        drop(last);
        if let Some(slots) = &self.slots {
            let theta = self.unknowns.theta(p);
            let done = jacobian::jacobian(
                self.unknowns,
                &self.cases,
                &self.substeps,
                slots,
                &theta,
                jac,
            );
            if self.domain.order() > 0 || self.bias == Bias::Nuisance {
                let mut column = vec![0.0; jac.nrows()];
                for j in 0..jac.ncols() {
                    column.copy_from_slice(jac.column(j).as_slice());
                    self.transformed(&mut column);
                    jac.column_mut(j).copy_from_slice(&column);
                }
            }
            return done;
        }
        // forward differences, step 1e-6 in `p`
        let residuals = |q: &[f64], out: &mut [f64]| self.residuals(q, out);
        forward_jacobian(p, r, 1e-6, &residuals, jac)
    }
}

/// The largest sum of `case`'s load magnitudes at one sample, N: the most
/// its replay pushes on the car ([`crate::car::PlanarCar::within_force`]).
fn peak_load(case: &PlanarCase) -> f64 {
    let loads = &case.drive.loads;
    let samples = loads.iter().map(|l| l.force.len()).max().unwrap_or(0);
    (0..samples)
        .map(|k| {
            loads
                .iter()
                .filter_map(|l| l.force.get(k))
                .map(|f| f.abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

/// `case` with each group of three or more loads that act on the bumper
/// line (no anchor, no cell) along the same direction replaced by two loads
/// at the side-member tips `η = ±b`, carrying the group's force and its
/// moment: the bumper line is straight and the lever rule linear, so a
/// force's effect is affine in its lateral position and two loads carry any
/// group exactly (a load-cell wall of ten cells replays as two loads). A
/// case with estimated lines of action is left as it is.
fn merged(case: &PlanarCase, b: f64) -> PlanarCase {
    if !case.estimated.is_empty() || b <= 0.0 {
        return case.clone();
    }
    let plain = |l: &Load| l.anchor.is_none() && l.cell.is_none();
    let mut groups: Vec<([f64; 2], Vec<usize>)> = Vec::new();
    for (k, load) in case
        .drive
        .loads
        .iter()
        .enumerate()
        .filter(|(_, l)| plain(l))
    {
        match groups.iter_mut().find(|g| g.0 == load.direction) {
            Some(g) => g.1.push(k),
            None => groups.push((load.direction, vec![k])),
        }
    }
    groups.retain(|g| g.1.len() >= 3);
    if groups.is_empty() {
        return case.clone();
    }
    let mut out = case.clone();
    let grouped: Vec<usize> = groups.iter().flat_map(|g| g.1.clone()).collect();
    out.drive.loads = (0..case.drive.loads.len())
        .filter(|k| !grouped.contains(k))
        .map(|k| case.drive.loads[k].clone())
        .collect();
    for (direction, members) in groups {
        let loads: Vec<&Load> = members.iter().map(|&k| &case.drive.loads[k]).collect();
        let samples = loads[0].force.len();
        let (mut left, mut right) = (vec![0.0; samples], vec![0.0; samples]);
        for k in 0..samples {
            let total: f64 = loads.iter().map(|l| l.force[k]).sum();
            let moment: f64 = loads.iter().map(|l| l.force[k] * l.lateral).sum();
            left[k] = 0.5 * (total + moment / b);
            right[k] = 0.5 * (total - moment / b);
        }
        for (lateral, force) in [(b, left), (-b, right)] {
            out.drive.loads.push(Load {
                lateral,
                anchor: None,
                cell: None,
                direction,
                force,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{BiasReading, Domain, bias_readings, debiased, differenced};
    use crate::car::{Layout, PlanarCar};
    use crate::drive::Sensor;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// The profiled bias (`debiased`, velocity): on a sill, a residual that
    /// is exactly the bias's reading g is shrunk to √(κ/(G+κ)) g, one
    /// orthogonal to g is kept; the yaw-rate sensor's residual is not an
    /// accelerometer's and is kept whole.
    #[test]
    fn a_bias_reading_is_profiled_to_its_prior_and_nothing_else_moves() {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let mut case = crate::identify::tests::pushed(&car, "push", 0.0, Sensor::YawRate);
        case.pretrigger = 0.02;
        let cases = [case];
        let readings = bias_readings(&cases, Domain::Velocity);
        let BiasReading { g, gg, cut } = readings[0].as_ref().expect("a reading");
        assert!(*cut > 0.0 && *cut < 1.0, "{cut}");
        let (n, sensors) = (g.len(), cases[0].measured.len());
        let along = g.iter().sum::<f64>() / gg;
        let orthogonal: Vec<f64> = g.iter().map(|v| 1.0 - along * v).collect();
        let mut r = vec![0.0; n * sensors];
        for k in 0..n {
            r[k * sensors] = g[k];
            r[k * sensors + 1] = orthogonal[k];
            r[k * sensors + 3] = g[k];
        }
        debiased(&cases, &readings, &mut r);
        let kept = 1.0 - cut;
        for k in 0..n {
            let tolerance = 1e-12 * (1.0 + g[k].abs());
            assert!(
                (r[k * sensors] - kept * g[k]).abs() < tolerance,
                "sample {k}"
            );
            assert!(
                (r[k * sensors + 1] - orthogonal[k]).abs() < tolerance,
                "sample {k}"
            );
            assert_eq!(r[k * sensors + 2], 0.0);
            assert_eq!(r[k * sensors + 3], g[k]);
        }
    }

    /// A bias's displacement `t²/2` (two interleaved series, stride 2)
    /// differenced once reads `t − h/2`, twice `1`; the other series and
    /// the first `order` samples are left as stated.
    #[test]
    fn a_bias_reads_as_its_velocity_and_acceleration() {
        let h = 1e-3;
        let series = |k: usize| 0.5 * (k as f64 * h).powi(2);
        let mut r: Vec<f64> = (0..10).flat_map(|k| [series(k), -1.0]).collect();
        let mut once = r.clone();
        differenced(&mut once, (0, 2, 10), 1, h);
        differenced(&mut r, (0, 2, 10), 2, h);
        for k in 1..10 {
            let t = k as f64 * h;
            assert!((once[2 * k] - (t - 0.5 * h)).abs() < 1e-12, "{once:?}");
            assert_eq!(once[2 * k + 1], -1.0);
        }
        assert_eq!(once[0], 0.0);
        assert!(r[4..].iter().step_by(2).all(|v| (v - 1.0).abs() < 1e-9));
        assert_eq!((r[0], r[2]), (0.0, 0.0));
    }
}
