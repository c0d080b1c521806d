//! The chain with nonlinear links ([`bumpsim_core::chain`], car files of
//! [`bumpsim_io::link_car`], `kind = "links"`) as the engine runs it:
//! `impact` drives the car into a rigid wall ([`Drive::Barrier`]: every
//! mass at the impact speed, m1 at the wall; with a `[front]` link the wall
//! pushes m1 back by that link's force at the crush x1, else by a stiff
//! penalty contact), recorded every [`STEP`] for [`FIRST_DURATION`], the
//! run doubled while the wall still pushes in the last [`QUIET`], up to
//! [`LONGEST`].
//!
//! From the histories ([`Crush`]): the peak barrier force `max |F|`, each
//! link's largest compression and plastic set `δ_p = δ_max − F(δ_max)/k_u`
//! ([`bumpsim_core::link::LinkState::plastic_set`]; the front link's δ_max
//! is m1's largest travel into the wall), the contact time (the last
//! sample the wall pushes), the centre of mass's speed at the end, and the
//! energy balance at the end (J, [`bumpsim_core::chain`]):
//!
//! ```text
//! E_kin(0) = E_kin + E_stored + W_viscous + W_plastic + W_wall
//! ```
//!
//! with `W_viscous + W_plastic` the dissipated work and `W_wall = −W_force`
//! the penalty contact's (0 with a front link). A pendulum or a moving
//! barrier into the car (`--pendulum`, a preset of those kinds) is the
//! same run with the wall made a free striker ([`Drive::Striker`],
//! `struck.rs`); the striker's kinetic energy joins `E_kin`. `verdict`
//! judges a links car file with a `[damageability]` table in the
//! protocols' tests (`verdict.rs`).
//!
//! `identify` of a links study (the `identify` module) identifies the car
//! as it ran into the barrier and runs it forward; `predict` runs a links
//! car into the wall at each case's speed of a links study (`forward`).

mod forward;
mod identify;
mod struck;
mod synth;
mod text;
mod unloading;
mod verdict;

use crate::model::{
    CarModel, IdentifyRequest, ImpactRequest, Judged, PredictRequest, VerdictRequest,
};
use crate::{EngineError, Outcome};
use bumpsim_core::chain::{Chain, ChainResponse, Drive};
use bumpsim_core::link::LinkState;
use bumpsim_impact::presets::{Preset, ScenarioSpec};
use bumpsim_io::kind::ModelKind;
use bumpsim_io::link_car::LinkCar;
use std::path::Path;

/// Interval of the recorded histories, s.
pub const STEP: f64 = 1e-4;
/// The first run's duration, s.
pub const FIRST_DURATION: f64 = 0.25;
/// The longest run, s.
pub const LONGEST: f64 = 2.0;
/// The wall is done when it has not pushed for this long at the end, s.
pub const QUIET: f64 = 0.02;
/// Largest relative energy balance error of a usable result.
pub const ENERGY_TOLERANCE: f64 = 0.01;

/// The chain with nonlinear links, registered in [`crate::registry::registered`].
#[derive(Debug, Clone, Copy)]
pub struct Links;

impl CarModel for Links {
    fn kind(&self) -> ModelKind {
        ModelKind::Links
    }

    fn impact(&self, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
        let path = request.car_path()?;
        request.refuse_extras("a car with nonlinear links")?;
        let text =
            bumpsim_core::files::read_car_text(path).map_err(bumpsim_io::car::CarError::from)?;
        let car = LinkCar::parse(&text, path)?;
        let total: f64 = car.chain.masses().iter().sum();
        let spec = ScenarioSpec {
            case: request.case.map(str::to_string),
            pendulum: request.pendulum,
            barrier: request.barrier,
            speed: request.speed()?,
        };
        let (scenario, preset) = spec.scenario(total)?;
        let crush = Crush::of_scenario(&car.chain, scenario, path)?;
        let speed = crush.speed;
        let name = car
            .name
            .clone()
            .unwrap_or_else(|| path.display().to_string());
        text::outcome(
            &name,
            &label(preset, speed, crush.striker),
            &car.chain,
            &crush,
            request.report,
        )
    }

    fn synth(&self, path: &Path) -> Result<crate::model::Made, EngineError> {
        synth::make(path)
    }

    fn judges(&self) -> bool {
        true
    }

    fn verdict(&self, request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
        verdict::verdict(request)
    }

    fn end(
        &self,
        path: &Path,
        _text: &str,
    ) -> Result<bumpsim_verdict::prelude::CarEnd, EngineError> {
        Err(verdict::end(path))
    }

    fn identify(&self, request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
        identify::identify(request)
    }

    fn predict(&self, request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
        forward::requested(request)
    }
}

/// What hit what, as the heading says it (`striker`: its mass, kg).
fn label(preset: Option<&Preset>, speed: f64, striker: Option<f64>) -> String {
    let speed = bumpsim_core::units::format_number(speed * 3.6, 4) + " km/h";
    match preset {
        Some(p) => format!(
            "{} ({}, {speed}; {}){}",
            p.name,
            p.description,
            p.source,
            p.dropped_in_1d()
                .map(|d| format!("; 1-D: {d}"))
                .unwrap_or_default()
        ),
        None => struck::label(striker, &speed),
    }
}

/// A barrier run and the figures read from it.
#[derive(Debug, Clone)]
pub struct Crush {
    /// The impact speed, m/s.
    pub speed: f64,
    /// The histories.
    pub response: ChainResponse,
    /// Largest |wall force|, N, and its time, s.
    pub peak: (f64, f64),
    /// The front link's largest crush and plastic set, m (with a front link).
    pub front: Option<(f64, f64)>,
    /// The last time the wall pushes, s.
    pub contact_time: f64,
    /// The centre of mass's speed at the end, m/s (negative: rebounding).
    pub final_speed: f64,
    /// Whether the wall stopped pushing before the run's end.
    pub ended: bool,
    /// The striker's mass, kg (None: the rigid barrier).
    pub striker: Option<f64>,
}

impl Crush {
    /// Runs `chain` into the wall at `speed` m/s (doubling the duration
    /// until the contact has ended, up to [`LONGEST`]).
    pub fn run(chain: &Chain, speed: f64, path: &Path) -> Result<Crush, EngineError> {
        Crush::driven(chain, speed, None, path)
    }

    /// [`Crush::run`], or with a striker of `striker` kg into the car at
    /// rest ([`Drive::Striker`]).
    fn driven(
        chain: &Chain,
        speed: f64,
        striker: Option<f64>,
        path: &Path,
    ) -> Result<Crush, EngineError> {
        let quiet = (QUIET / STEP).round() as usize;
        let mut duration = FIRST_DURATION;
        loop {
            let samples = (duration / STEP).round() as usize + 1;
            let drive = match striker {
                None => Drive::Barrier {
                    speed,
                    step: STEP,
                    samples,
                },
                Some(mass) => Drive::Striker {
                    mass,
                    speed,
                    step: STEP,
                    samples,
                },
            };
            let response = chain.run(&drive).map_err(|source| EngineError::Run {
                path: path.into(),
                source,
            })?;
            let ended = response.force.iter().rev().take(quiet).all(|f| *f == 0.0);
            if ended || duration >= LONGEST {
                return Ok(Crush::of(chain, speed, response, ended, striker));
            }
            duration = (2.0 * duration).min(LONGEST);
        }
    }

    fn of(
        chain: &Chain,
        speed: f64,
        response: ChainResponse,
        ended: bool,
        striker: Option<f64>,
    ) -> Crush {
        let (k, peak) = response
            .force
            .iter()
            .enumerate()
            .fold((0, 0.0_f64), |(kb, b), (k, f)| {
                if f.abs() > b { (k, f.abs()) } else { (kb, b) }
            });
        let front = chain.front().map(|link| {
            let reached = struck::front_crush(&response).fold(0.0_f64, |m, x| m.max(x));
            (reached, LinkState { reached }.plastic_set(link))
        });
        let last = response.force.iter().rposition(|f| *f != 0.0);
        let contact_time = last.map_or(0.0, |k| (k + 1) as f64 * response.step);
        let masses = chain.masses();
        let momentum: f64 = masses
            .iter()
            .zip(&response.velocity)
            .map(|(m, v)| m * v.last().copied().unwrap_or(0.0))
            .sum();
        let final_speed = momentum / masses.iter().sum::<f64>();
        Crush {
            speed,
            peak: (peak, k as f64 * response.step),
            front,
            contact_time,
            final_speed,
            ended,
            response,
            striker,
        }
    }

    /// The energy terms at the end, J: initial kinetic, kinetic, stored,
    /// viscous, plastic, the wall's penalty contact.
    pub fn energy(&self) -> Energy {
        let r = &self.response;
        let end = |v: &Vec<f64>| v.last().copied().unwrap_or(0.0);
        Energy {
            initial: r.kinetic.first().copied().unwrap_or(0.0),
            kinetic: end(&r.kinetic),
            stored: end(&r.stored),
            viscous: end(&r.viscous),
            plastic: end(&r.plastic),
            wall: -end(&r.work),
            relative_error: r.energy_error(),
        }
    }

    /// The result's own checks: every figure finite, the contact ended,
    /// the energy balance within [`ENERGY_TOLERANCE`].
    pub fn warnings(&self) -> Vec<String> {
        let e = self.energy();
        let mut out = Vec::new();
        let figures = [
            ("peak force", self.peak.0),
            ("energy balance error", e.relative_error),
        ];
        for (name, v) in figures.iter().filter(|(_, v)| !v.is_finite()) {
            out.push(format!("{name} is {v}: the result is not usable"));
        }
        if !self.ended {
            let what = self.striker.map_or("the wall", |_| "the striker");
            out.push(format!(
                "{what} still pushes at the end of the run ({LONGEST} s): the figures at the end are not the impact's final state"
            ));
        }
        if e.relative_error > ENERGY_TOLERANCE {
            out.push(format!(
                "energy balance error {:.3} of the largest energy exceeds the tolerance {ENERGY_TOLERANCE}",
                e.relative_error
            ));
        }
        out
    }
}

/// The energy balance at the end of the run, J.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Energy {
    /// Kinetic energy at the start.
    pub initial: f64,
    /// Kinetic energy at the end.
    pub kinetic: f64,
    /// Elastic energy left in the links.
    pub stored: f64,
    /// Work of the dampers.
    pub viscous: f64,
    /// Plastic work of the links.
    pub plastic: f64,
    /// Energy taken by the wall's penalty contact (0 with a front link).
    pub wall: f64,
    /// Largest |residual| of the balance over the run, relative to the
    /// largest energy term.
    pub relative_error: f64,
}

#[cfg(test)]
#[path = "tests.rs"]
mod tests;
