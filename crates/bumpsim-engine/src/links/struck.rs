//! A pendulum or a moving barrier into a car with nonlinear links
//! ([`bumpsim_core::chain::Drive::Striker`]): a rigid striker of mass M at
//! V hits m1 of the car at rest, through the `[front]` link or the stiff
//! penalty contact, pushing only. The run and its figures are the
//! barrier's ([`super::Crush`]) with the front link's crush taken
//! relative to the striker's face, `x_1 − x_s`, and, along the impact
//! (the striker's direction, positive forwards):
//!
//! - the striker's speed at the end, `−v_s` (negative: it rebounds);
//! - the car's centre of mass at the end, `−Σ m_i v_i / Σ m_i`;
//!
//! momentum `M V = M (−v_s) + Σ m_i (−v_i)` holds at every step of the
//! leapfrog, and the energy balance is the barrier's with the striker's
//! kinetic energy in `E_kin`.

use super::{Crush, EngineError};
use bumpsim_core::chain::{Chain, ChainResponse};
use bumpsim_impact::impact::Scenario;
use serde::Serialize;
use std::path::Path;

impl Crush {
    /// The run of a 1-D scenario: the car into the rigid barrier, or a
    /// striker (pendulum, moving barrier) into the car at rest.
    pub fn of_scenario(
        chain: &Chain,
        scenario: Scenario,
        path: &Path,
    ) -> Result<Crush, EngineError> {
        match scenario {
            Scenario::Barrier { speed } => Crush::run(chain, speed, path),
            Scenario::Impactor { mass, speed } => Crush::struck(chain, mass, speed, path),
        }
    }

    /// A striker of `mass` kg at `speed` m/s into `chain` at rest, the
    /// duration doubled as [`Crush::run`]'s until the contact has ended.
    pub fn struck(chain: &Chain, mass: f64, speed: f64, path: &Path) -> Result<Crush, EngineError> {
        Crush::driven(chain, speed, Some(mass), path)
    }

    /// The striker's figures (None: the rigid barrier).
    pub fn striker_figures(&self) -> Option<StrikerFigures> {
        let mass = self.striker?;
        let speed = self.response.striker_velocity.last().copied()?;
        Some(StrikerFigures {
            mass,
            final_speed: -speed,
            car_final_speed: -self.final_speed,
        })
    }
}

/// The striker's figures at the end of the run, along the impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StrikerFigures {
    /// Its mass, kg.
    pub mass: f64,
    /// Its speed at the end, m/s (negative: rebounding).
    pub final_speed: f64,
    /// The car's centre of mass at the end, m/s.
    pub car_final_speed: f64,
}

/// The front link's crush at each sample: m1's travel into the wall, or
/// into the striker's face `x_1 − x_s`.
pub(super) fn front_crush(r: &ChainResponse) -> impl Iterator<Item = f64> + '_ {
    let face = r
        .striker_displacement
        .iter()
        .copied()
        .chain(std::iter::repeat(0.0));
    r.displacement[0].iter().zip(face).map(|(x, s)| x - s)
}

/// What hit the car without a preset: the barrier, or a pendulum of
/// `striker` kg; `speed` as printed.
pub(super) fn label(striker: Option<f64>, speed: &str) -> String {
    match striker {
        None => format!("rigid barrier at {speed}"),
        Some(mass) => format!(
            "pendulum of {} into the car at rest at {speed}",
            bumpsim_core::units::format_quantity(mass, bumpsim_core::units::Dimension::Mass)
        ),
    }
}

/// The summary's line of the contact (`contact`: its time, as printed)
/// and the speeds at the end.
pub(super) fn summary(contact: &str, figures: &StrikerFigures) -> String {
    let speed =
        |v: f64| bumpsim_core::units::format_quantity(v, bumpsim_core::units::Dimension::Velocity);
    format!(
        "  contact time {contact}; speeds at the end along the impact: striker {} (negative: rebounding), the car's centre of mass {}\n",
        speed(figures.final_speed),
        speed(figures.car_final_speed)
    )
}
