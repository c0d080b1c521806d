//! The tyres of the planar car: their law per axle ([`TyreLaw`], [`Axle`],
//! [`Tyres`]) and the checks a car's tyres pass at construction. The force
//! laws themselves are in [`crate::tyre`]; this module holds the parameters
//! (Pacejka 2012 ch. 1.2, 4.3.2 and 7; Gillespie 1992 ch. 4 and 6; Wong 2008
//! ch. 1.2).

use super::{PlanarError, positive, require};
use serde::Serialize;

/// How the tyres of an axle meet the ground (see [`Axle`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TyreLaw {
    /// Free-rolling wheels (a car in neutral, brakes released: every
    /// RCAR/IIHS low-speed test): the lateral force builds up with the
    /// slip angle through the cornering stiffness and saturates at μ_y N;
    /// along the wheel, rolling resistance μ_x N.
    #[default]
    Rolling,
    /// Locked or braked wheels sliding: Coulomb friction of the contact
    /// point, μ N against its sliding velocity (regularised by the slip
    /// speed), both directions coupled.
    Sliding,
}

/// The tyres of one axle: their law, friction coefficients and, rolling,
/// their cornering stiffness and relaxation length.
///
/// **Rolling** (the stretched-string tyre, Pacejka 2012 ch. 1.2 and 7): the
/// contact patch of each wheel deflects laterally by y with
/// `ẏ = v_y − (|v_x| / σ) y` (v_x, v_y the wheel centre's velocity along and
/// across the wheel, body frame), and the ground pushes back with
/// `F_y = −(C_α / σ) y`, clamped to `|F_y| ≤ μ_y N` (the patch slides). In
/// steady rolling `y = σ v_y/|v_x|`, so `F_y = −C_α v_y/|v_x| ≈ −C_α α`, the
/// slip-angle law; at standstill the tyre is a lateral spring `C_α/σ`,
/// which keeps the law finite where `α = atan(v_y/v_x)` is not. With
/// `relaxation_length = 0` the law is instantaneous,
/// `F_y = −μ_y N tanh(C_α α / (μ_y N))` with `α = atan(v_y / √(v_x² + v_s²))`
/// (the step then follows its damping `C_α/v_s`). Along the wheel, rolling
/// resistance `F_x = −μ_x N v_x/√(v_x² + v_s²)`.
///
/// With a [`shape`](Axle::shape) C the rolling tyre's lateral force follows
/// the Magic Formula instead of the clamped line or the tanh.
///
/// **Sliding**: `F = −μ N v/√(v_x² + v_y² + v_s²)` per direction with μ_x and μ_y.
///
/// Rolling resistance and sliding grip are two coefficients (issue 45): a
/// rolling tyre resists along the wheel with `rolling_resistance` (about
/// 0.01–0.015 for passenger tyres on asphalt: Gillespie, *Fundamentals of
/// Vehicle Dynamics* 1992, ch. 4; Wong, *Theory of Ground Vehicles*, 4th ed.
/// 2008, ch. 1.2), a locked one slides along it with `mu_longitudinal`
/// (about 0.7–0.8 on dry asphalt: Wong 2008, table 1.3, sliding peak
/// 0.75 against 0.8–0.9 at the peak; locked-wheel skid tests give 0.7–0.8),
/// so `--tyres sliding` on a rolling car takes the sliding grip, not the
/// rolling resistance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axle {
    /// Sliding friction coefficient along the wheel μ_x, 1: a locked
    /// wheel's grip (sliding law; about 0.7–0.8 on dry asphalt). A car
    /// file without it takes `mu_lateral` (a locked tyre slides alike in
    /// every direction).
    #[serde(default)]
    pub mu_longitudinal: f64,
    /// Rolling resistance coefficient along the wheel, 1 (rolling law;
    /// about 0.01–0.015).
    #[serde(default)]
    pub rolling_resistance: f64,
    /// Lateral friction coefficient μ_y (the saturation of a rolling tyre), 1.
    #[serde(default)]
    pub mu_lateral: f64,
    /// The law: rolling (default) or sliding.
    #[serde(default)]
    pub law: TyreLaw,
    /// Cornering stiffness C_α of each tyre, N/rad (rolling; passenger-car
    /// tyres at their nominal load: 30–120 kN/rad, [`CORNERING_STIFFNESS`]).
    #[serde(default = "default_cornering_stiffness")]
    pub cornering_stiffness: f64,
    /// Relaxation length σ, m (rolling; about the tyre's radius, 0.2–0.6 m;
    /// 0: the instantaneous slip-angle law).
    #[serde(default = "default_relaxation_length")]
    pub relaxation_length: f64,
    /// The Magic-Formula shape factor C of the lateral force, 1 (rolling
    /// only: a sliding tyre ignores it; `None`: the linear law clamped at
    /// μ_y N, or its tanh without relaxation). With it the rolling tyre
    /// pushes back with `F_y = −μ_y N sin(C atan(B α'))`,
    /// `B = C_α / (C μ_y N)`, `α' = y/σ` the relaxed slip (or the slip
    /// angle α without relaxation): the same cornering stiffness at small
    /// slip, a rounded peak μ_y N at `B α' = tan(π/(2C))`, and, for C > 1,
    /// a fall towards `μ_y N sin(Cπ/2)` at large slip, as real tyres do
    /// (Pacejka 2012, ch. 4.3.2: C ≈ 1.3 for the lateral force; 1 ≤ C < 2).
    /// It is the Magic Formula with E = 0, no shifts and a load-independent
    /// peak μ_y N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<f64>,
}

/// The default cornering stiffness of a passenger-car tyre, N/rad, and the
/// plausible range the identification checks against (per tyre at its
/// nominal load; Pacejka 2012, table 1.1 and fig. 1.9; Gillespie 1992
/// ch. 6: 500–1500 N/deg).
pub const CORNERING_STIFFNESS: (f64, std::ops::RangeInclusive<f64>) = (60e3, 20e3..=150e3);

/// The default relaxation length, m (about a passenger tyre's radius).
pub const RELAXATION_LENGTH: f64 = 0.4;

/// The shortest relaxation length a car takes, m, other than 0 (the
/// instantaneous law): shorter, the relaxation rate `|v|/σ` of a tyre at
/// road speed overflows (σ = 1e-320 m: ∞ · 0 = NaN at y = 0), and the tyre's standstill
/// spring `C_α/σ` would ask for a step the run refuses anyway.
pub const SHORTEST_RELAXATION: f64 = 1e-6;

fn default_cornering_stiffness() -> f64 {
    CORNERING_STIFFNESS.0
}

fn default_relaxation_length() -> f64 {
    RELAXATION_LENGTH
}

impl Default for Axle {
    /// Frictionless rolling tyres with the default cornering stiffness and
    /// relaxation length.
    fn default() -> Self {
        Axle {
            mu_longitudinal: 0.0,
            rolling_resistance: 0.0,
            mu_lateral: 0.0,
            law: TyreLaw::Rolling,
            cornering_stiffness: CORNERING_STIFFNESS.0,
            relaxation_length: RELAXATION_LENGTH,
            shape: None,
        }
    }
}

impl Axle {
    /// Sliding tyres with these coefficients (locked or braked).
    pub fn sliding(mu_longitudinal: f64, mu_lateral: f64) -> Axle {
        Axle {
            mu_longitudinal,
            mu_lateral,
            law: TyreLaw::Sliding,
            ..Axle::default()
        }
    }

    /// Rolling tyres with `rolling_resistance`, grip `mu_lateral` (also
    /// their sliding grip along the wheel, should they lock) and the
    /// default cornering stiffness and relaxation.
    pub fn rolling(rolling_resistance: f64, mu_lateral: f64) -> Axle {
        Axle {
            mu_longitudinal: mu_lateral,
            rolling_resistance,
            mu_lateral,
            ..Axle::default()
        }
    }
}

/// The tyres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tyres {
    /// Front axle.
    pub front: Axle,
    /// Rear axle.
    pub rear: Axle,
    /// Regularisation speed v_s of the Coulomb law, m/s (> 0).
    pub slip_speed: f64,
}

impl Default for Tyres {
    /// Frictionless tyres (μ = 0), v_s = 0.05 m/s.
    fn default() -> Self {
        Tyres {
            front: Axle::default(),
            rear: Axle::default(),
            slip_speed: 0.05,
        }
    }
}

pub(crate) fn check_tyres(tyres: &Tyres) -> Result<(), PlanarError> {
    for (axle, a) in [("front", tyres.front), ("rear", tyres.rear)] {
        for (kind, mu) in [
            ("mu_longitudinal", a.mu_longitudinal),
            ("rolling_resistance", a.rolling_resistance),
            ("mu_lateral", a.mu_lateral),
        ] {
            let name = format!("tyres.{axle}.{kind}");
            require(
                &name,
                mu,
                "1",
                "must be finite and not negative (0: no friction)",
                mu >= 0.0,
            )?;
        }
        positive(
            &format!("tyres.{axle}.cornering_stiffness"),
            a.cornering_stiffness,
            "N/rad",
        )?;
        require(
            &format!("tyres.{axle}.relaxation_length"),
            a.relaxation_length,
            "m",
            "must be 0 (the instantaneous slip-angle law) or from 1e-6 m to 10 m",
            a.relaxation_length == 0.0
                || (SHORTEST_RELAXATION..=10.0).contains(&a.relaxation_length),
        )?;
        check_shape(axle, a.shape)?;
    }
    positive("tyres.slip_speed", tyres.slip_speed, "m/s")
}

/// The Magic Formula's shape factor C, when given, lies in [1, 2).
fn check_shape(axle: &str, shape: Option<f64>) -> Result<(), PlanarError> {
    let Some(c) = shape else { return Ok(()) };
    require(
        &format!("tyres.{axle}.shape"),
        c,
        "1",
        "must lie in [1, 2) (the Magic Formula's shape factor C; about 1.3 for the lateral force)",
        (1.0..2.0).contains(&c),
    )
}
