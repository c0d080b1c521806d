//! The pickled state of a `PlanarImpact`: the car's name, the striker as
//! it was asked for (made again by bumpsim-planar's presets) and the result
//! (bumpsim-planar).

use bumpsim_planar::PlanarResult;
use bumpsim_planar::result::{EnergyBalance, MomentumBalance};
use serde::{Deserialize, Serialize};

/// What a `PlanarImpact` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct PlanarImpactState {
    /// The car's name (or its file).
    pub name: String,
    /// The striker as asked for: case, angle (°), overlap (%), side, pole
    /// diameter (m), pole offset (m), pendulum mass (kg), speed (m/s).
    pub spec: StrikerArgs,
    /// The result.
    #[serde(with = "PlanarResultDef")]
    pub result: PlanarResult,
    /// The car's body (`to_json`'s `body`; absent from older pickles).
    #[serde(default)]
    pub body: Option<bumpsim_planar::car::Body>,
}

/// The arguments of `planar_impact` that say what hits the car.
#[derive(Serialize, Deserialize, PartialEq, Clone)]
pub struct StrikerArgs {
    /// A preset.
    pub case: Option<String>,
    /// Barrier angle, degrees.
    pub angle: Option<f64>,
    /// Overlap, % of the bumper width.
    pub overlap: Option<f64>,
    /// `left` or `right`.
    pub side: String,
    /// Pole diameter, m.
    pub pole: Option<f64>,
    /// Pole offset, m.
    pub pole_offset: f64,
    /// Pendulum mass, kg.
    pub pendulum: Option<f64>,
    /// Speed, m/s.
    pub speed: Option<f64>,
    /// The car's total mass, kg (a preset's pendulum of the vehicle's mass).
    #[serde(default)]
    pub car_mass: Option<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "EnergyBalance")]
struct EnergyBalanceDef {
    initial: f64,
    kinetic: f64,
    springs: f64,
    bending: f64,
    dampers: f64,
    crush: f64,
    friction: f64,
    // the side members' plastic work (issue 46; absent from older pickles)
    #[serde(default)]
    plastic: f64,
    relative_error: f64,
    max_relative_error: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "MomentumBalance")]
struct MomentumBalanceDef {
    initial_linear: [f64; 2],
    final_linear: [f64; 2],
    external_impulse: [f64; 2],
    linear_residual: f64,
    initial_angular: f64,
    final_angular: f64,
    external_angular_impulse: f64,
    angular_residual: f64,
    reference_length: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "PlanarResult")]
struct PlanarResultDef {
    segment_centres: Vec<f64>,
    time: Vec<f64>,
    force_x: Vec<f64>,
    force_y: Vec<f64>,
    force: Vec<f64>,
    line_of_action: Vec<Option<f64>>,
    side_force_left: Vec<f64>,
    side_force_right: Vec<f64>,
    crush: Vec<Vec<f64>>,
    segment_force: Vec<Vec<f64>>,
    x: Vec<f64>,
    y: Vec<f64>,
    yaw: Vec<f64>,
    yaw_rate: Vec<f64>,
    velocity_x: Vec<f64>,
    velocity_y: Vec<f64>,
    pendulum_travel: Vec<f64>,
    chain_displacement: Vec<Vec<f64>>,
    contact_start: Option<f64>,
    contact_end: Option<f64>,
    peak_force: f64,
    max_compression: f64,
    #[serde(default)]
    bottomed: Option<bumpsim_planar::result::Bottomed>,
    #[serde(default)]
    box_bottomed: Option<bumpsim_planar::result::BoxBottomed>,
    max_crush: Vec<f64>,
    #[serde(default)]
    damage: Vec<bumpsim_impact::bumper::BumperState>,
    remaining_crush: Vec<f64>,
    peak_yaw_rate: f64,
    #[serde(with = "EnergyBalanceDef")]
    energy: EnergyBalance,
    #[serde(with = "MomentumBalanceDef")]
    momentum: MomentumBalance,
    step: f64,
    warnings: Vec<String>,
    // the side members' links' sets (issue 46; absent from older pickles)
    #[serde(default)]
    link_set: Vec<f64>,
    #[serde(default)]
    link_reached: Vec<f64>,
}
