//! The result of a planar impact: histories sampled at a fixed interval,
//! peaks, energy and momentum balances (spec §9 outputs). Serialisable.
//!
//! Signs and frames: forces are those the striker exerts on the car, in the
//! world frame (x along the car's initial heading, y left), N. Body position
//! `x`, `y` (m) is the body's CG in the world, `yaw` ψ (rad) counter-clockwise,
//! `yaw_rate` (rad/s). Side-member forces are the compressive loads the
//! beam puts on the left (y = +b) and right (y = −b) side-member tips, N.
//! The line of action is the body-frame lateral position (m) where the
//! resultant striker force crosses the undeformed bumper line (`None` without
//! a longitudinal force).

use serde::Serialize;

/// Energies, J; the balance `E0 = kinetic + springs + bending + dampers + crush + friction + plastic`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// Initial kinetic energy of car and pendulum.
    pub initial: f64,
    /// Kinetic energy at the end.
    pub kinetic: f64,
    /// Elastic energy in the chain springs at the end.
    pub springs: f64,
    /// Elastic bending energy of the beam at the end.
    pub bending: f64,
    /// Dissipated by the chain dampers.
    pub dampers: f64,
    /// Work done on the bumper segments (crushed plus stored elastically).
    pub crush: f64,
    /// Dissipated by tyre friction.
    pub friction: f64,
    /// Plastic work of the side members' nonlinear links (issue 46; 0 and
    /// not serialised for linear ones).
    #[serde(skip_serializing_if = "is_zero")]
    pub plastic: f64,
    /// `|E0 − Σ| / E0` at the end.
    pub relative_error: f64,
    /// The largest `|E0 − Σ| / E0` over the recorded samples.
    pub max_relative_error: f64,
}

/// Momentum balance of car and pendulum: momentum change against the impulse
/// of the external forces (fixed striker, tyres, pendulum guide).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct MomentumBalance {
    /// Initial linear momentum, N·s.
    pub initial_linear: [f64; 2],
    /// Final linear momentum, N·s.
    pub final_linear: [f64; 2],
    /// Impulse of the external forces, N·s.
    pub external_impulse: [f64; 2],
    /// Largest `|P − P0 − J| / |P0|` over the samples.
    pub linear_residual: f64,
    /// Initial angular momentum about the world origin, N·m·s.
    pub initial_angular: f64,
    /// Final angular momentum about the world origin, N·m·s.
    pub final_angular: f64,
    /// Angular impulse of the external forces about the origin, N·m·s.
    pub external_angular_impulse: f64,
    /// Largest `|L − L0 − J_L| / (|P0| ℓ)` over the samples, ℓ = `reference_length`.
    pub angular_residual: f64,
    /// ℓ: CG to bumper line plus half the bumper width, m.
    pub reference_length: f64,
}

/// The instant a bumper bottomed: a segment's crush passed its depth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Bottomed {
    /// Time, s.
    pub time: f64,
    /// The segment (0 = rightmost).
    pub segment: usize,
    /// Its lateral centre, body frame, m.
    pub centre: f64,
}

/// The instant a crash box bottomed: its compression passed its depth
/// (`car::PlanarCar::crash_boxes`) and the force went on into the rail.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct BoxBottomed {
    /// Time, s.
    pub time: f64,
    /// The side.
    pub side: BoxSide,
    /// Its lateral position, body frame, m.
    pub y: f64,
}

/// The side of a crash box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BoxSide {
    /// y = +b.
    Left,
    /// y = −b.
    Right,
}

impl BoxSide {
    /// "left" or "right".
    pub fn name(self) -> &'static str {
        match self {
            BoxSide::Left => "left",
            BoxSide::Right => "right",
        }
    }
}

/// Histories and results of a planar impact.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct PlanarResult {
    /// Lateral centres of the bumper segments, body frame, m (right to left).
    pub segment_centres: Vec<f64>,
    /// Sample times, s.
    pub time: Vec<f64>,
    /// Striker force on the car, world x, N.
    pub force_x: Vec<f64>,
    /// Striker force on the car, world y, N.
    pub force_y: Vec<f64>,
    /// Magnitude of the striker force, N.
    pub force: Vec<f64>,
    /// Line of action: lateral position on the bumper line, body frame, m.
    pub line_of_action: Vec<Option<f64>>,
    /// Left side-member force (compression positive), N.
    pub side_force_left: Vec<f64>,
    /// Right side-member force (compression positive), N.
    pub side_force_right: Vec<f64>,
    /// Crush of each segment (outer index: segment), m.
    pub crush: Vec<Vec<f64>>,
    /// Force of each segment including its bending share, N.
    pub segment_force: Vec<Vec<f64>>,
    /// Body CG x, m.
    pub x: Vec<f64>,
    /// Body CG y, m.
    pub y: Vec<f64>,
    /// Yaw ψ, rad.
    pub yaw: Vec<f64>,
    /// Yaw rate, rad/s.
    pub yaw_rate: Vec<f64>,
    /// Body CG velocity, world x, m/s.
    pub velocity_x: Vec<f64>,
    /// Body CG velocity, world y, m/s.
    pub velocity_y: Vec<f64>,
    /// Pendulum travel along −x, m (zeros for a fixed striker).
    pub pendulum_travel: Vec<f64>,
    /// Displacement u_i of each chain mass along the body axis, m (outer:
    /// masses, left chain first, each from the front).
    pub chain_displacement: Vec<Vec<f64>>,
    /// First time a segment carries force, s.
    pub contact_start: Option<f64>,
    /// First time afterwards that no segment carries force, s.
    pub contact_end: Option<f64>,
    /// Largest striker force magnitude, N.
    pub peak_force: f64,
    /// Largest crush of any segment, m.
    pub max_compression: f64,
    /// When and where a segment first crushed past its depth and the beam
    /// blocked (`car::Block`; None: it never did, or the car has no depth).
    pub bottomed: Option<Bottomed>,
    /// When and where a crash box first compressed past its depth and
    /// blocked (None: it never did, or the car has no crash-box depth).
    pub box_bottomed: Option<BoxBottomed>,
    /// Largest crush of each segment, m.
    pub max_crush: Vec<f64>,
    /// Each segment's history at the end (its largest crush so far and
    /// that force): the damage a next test on the same car starts from
    /// (`PlanarCar::with_damage`). Not serialised.
    #[serde(skip)]
    pub damage: Vec<bumpsim_impact::bumper::BumperState>,
    /// Permanent crush of each segment after unloading, m.
    pub remaining_crush: Vec<f64>,
    /// The yaw rate of largest magnitude, rad/s (signed).
    pub peak_yaw_rate: f64,
    /// Energy balance.
    pub energy: EnergyBalance,
    /// Momentum balance.
    pub momentum: MomentumBalance,
    /// Integration step, s.
    pub step: f64,
    /// Things the user should know (e.g. contact not ended within the duration).
    pub warnings: Vec<String>,
    /// Each side-member link's plastic set at the end, m (left chain
    /// first, link j behind mass j; empty for linear links, and then not
    /// serialised).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub link_set: Vec<f64>,
    /// Each side-member link's largest compression, m (as `link_set`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub link_reached: Vec<f64>,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl PlanarResult {
    /// An empty result with room for `samples` samples of `segments` segments.
    pub(crate) fn with_capacity(segments: usize, masses: usize, samples: usize) -> PlanarResult {
        let v = || Vec::with_capacity(samples);
        // one each (`vec![v(); n]` clones, and a clone keeps no capacity)
        let each = |n: usize| (0..n).map(|_| v()).collect();
        PlanarResult {
            time: v(),
            force_x: v(),
            force_y: v(),
            force: v(),
            line_of_action: Vec::with_capacity(samples),
            side_force_left: v(),
            side_force_right: v(),
            crush: each(segments),
            segment_force: each(segments),
            x: v(),
            y: v(),
            yaw: v(),
            yaw_rate: v(),
            velocity_x: v(),
            velocity_y: v(),
            pendulum_travel: v(),
            chain_displacement: each(masses),
            ..PlanarResult::default()
        }
    }
}
