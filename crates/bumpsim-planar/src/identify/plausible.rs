//! Whether an identified planar car is a car (issue 32): the checks, each
//! with its reason, that the identification adds to its warnings, so that
//! the summary, the JSON and the report name every implausible parameter
//! and `--strict` exits 2 on it.
//!
//! - **Yaw inertia.** The dynamic index `k²/(a b)` (k the radius of gyration
//!   `√(I_z/M)`, a and b the CG's distances to the axles) of passenger cars
//!   lies near 1, 0.8–1.2 (Milliken & Milliken 1995, ch. 5.5); outside
//!   [`DYNAMIC_INDEX`] it is not a car's. When the data do not determine
//!   I_z the warning says which tests would.
//! - **Grip.** A tyre's lateral μ above [`MAX_MU`] is no road tyre's.
//! - **Cornering stiffness.** Outside
//!   [`crate::car::CORNERING_STIFFNESS`]'s range per tyre.
//! - **Mass.** The identified car (body and chains) more than
//!   [`MASS_TOLERANCE`] off the test sheet's mass.

use super::{PlanarIdentification, Setup};
use crate::car::CORNERING_STIFFNESS;
use bumpsim_core::units::format_number;

/// The plausible dynamic index `k²/(a b)` of a car.
pub const DYNAMIC_INDEX: (f64, f64) = (0.6, 1.4);

/// The largest plausible lateral friction coefficient of a road tyre.
pub const MAX_MU: f64 = 1.5;

/// The identified total mass may differ from the test sheet's by this fraction.
pub const MASS_TOLERANCE: f64 = 0.02;

/// The warnings of the checks on `result` (see the module).
pub(super) fn checks(result: &PlanarIdentification, setup: &Setup) -> Vec<String> {
    let mut out = Vec::new();
    out.extend(yaw_inertia(result));
    out.extend(tyres(result));
    out.extend(mass(result, setup));
    out
}

fn estimate<'a>(result: &'a PlanarIdentification, name: &str) -> Option<&'a super::Estimate> {
    result.parameters.iter().find(|e| e.name == name)
}

fn yaw_inertia(result: &PlanarIdentification) -> Vec<String> {
    let body = result.car.body();
    let (a, b) = (
        body.cg_behind_front_axle,
        body.wheelbase - body.cg_behind_front_axle,
    );
    let mass = result.car.total_mass();
    let k = (body.yaw_inertia / mass).sqrt();
    let index = k * k / (a * b);
    let mut out = Vec::new();
    if !(DYNAMIC_INDEX.0..=DYNAMIC_INDEX.1).contains(&index) {
        out.push(format!(
            "body.yaw_inertia = {} kg·m² is not plausible: radius of gyration {} m, dynamic index k²/(a b) = {} outside {}–{} of passenger cars",
            format_number(body.yaw_inertia, 4),
            format_number(k, 3),
            format_number(index, 3),
            DYNAMIC_INDEX.0,
            DYNAMIC_INDEX.1
        ));
    }
    if estimate(result, "body.yaw_inertia").is_some_and(|e| e.determined == Some(false)) {
        out.push(
            "yaw inertia not determined: the tests hardly turn the car; add an angled, offset or off-centre pole test".into(),
        );
    }
    out
}

fn tyres(result: &PlanarIdentification) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(mu) = estimate(result, "tyres.mu_lateral").filter(|e| e.value > MAX_MU) {
        out.push(format!(
            "tyres.mu_lateral = {} is not plausible: a road tyre's grip is at most {MAX_MU}",
            format_number(mu.value, 3)
        ));
    }
    let range = &CORNERING_STIFFNESS.1;
    if let Some(c) =
        estimate(result, "tyres.cornering_stiffness").filter(|e| !range.contains(&e.value))
    {
        out.push(format!(
            "tyres.cornering_stiffness = {} N/rad is not plausible: a passenger-car tyre's lies within {}–{} N/rad",
            format_number(c.value, 4),
            range.start(),
            range.end()
        ));
    }
    out
}

fn mass(result: &PlanarIdentification, setup: &Setup) -> Option<String> {
    let sheet = setup.mass?;
    let total = result.car.total_mass();
    let off = (total - sheet) / sheet;
    (off.abs() > MASS_TOLERANCE).then(|| {
        format!(
            "the identified car weighs {} kg, {} % off the test sheet's {} kg (more than {} %)",
            format_number(total, 5),
            format_number(100.0 * off, 3),
            format_number(sheet, 5),
            100.0 * MASS_TOLERANCE
        )
    })
}
