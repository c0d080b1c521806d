//! The pickled states of an `Impact` (its scenario and result) and a
//! `Bumper` (bumpsim-impact).

use bumpsim_impact::bumper::Loading;
use bumpsim_impact::impact::{EnergyBalance, ImpactResult, Scenario};
use serde::{Deserialize, Serialize};

/// What an `Impact` holds.
#[derive(Serialize, Deserialize)]
pub struct ImpactState {
    /// What hit what.
    #[serde(with = "ScenarioDef")]
    pub scenario: Scenario,
    /// The result.
    #[serde(with = "ImpactResultDef")]
    pub result: ImpactResult,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Scenario")]
enum ScenarioDef {
    Impactor { mass: f64, speed: f64 },
    Barrier { speed: f64 },
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "EnergyBalance")]
struct EnergyBalanceDef {
    initial: f64,
    kinetic: f64,
    springs: f64,
    dampers: f64,
    bumper: f64,
    relative_error: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "ImpactResult")]
struct ImpactResultDef {
    bodies: Vec<String>,
    time: Vec<f64>,
    force: Vec<f64>,
    compression: Vec<f64>,
    displacements: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
    contact_start: f64,
    contact_time: f64,
    max_compression: f64,
    remaining_compression: f64,
    peak_force: f64,
    absorbed_energy: f64,
    #[serde(with = "EnergyBalanceDef")]
    energy: EnergyBalance,
    step: f64,
}

/// What a `Bumper` holds: its loading curve and unloading slope (the
/// bumper is made again through its validating constructors).
#[derive(Serialize, Deserialize)]
pub struct BumperState {
    /// The loading curve.
    #[serde(with = "LoadingDef")]
    pub loading: Loading,
    /// The unloading slope, N/m.
    pub unloading: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Loading")]
enum LoadingDef {
    ThreePart {
        ramp: f64,
        plateau: f64,
    },
    Table {
        compression: Vec<f64>,
        force: Vec<f64>,
    },
}
