//! The model of the Sobol' bench and of `tests/sobol_impact.rs` (one copy:
//! the test includes this file by path): the peak force of a 1-D pendulum
//! impact on a 2-mass car behind a three-part bumper over six parameters.

use bumpsim_core::MsdModel;
use bumpsim_estimate::sobol::Input;
use bumpsim_impact::impact::{Options, simulate};
use bumpsim_impact::{Bumper, Scenario};

/// The inputs: car front mass and spring, bumper stiffness and plateau,
/// pendulum mass and speed.
pub const RANGES: [(&str, f64, f64); 6] = [
    ("m1 [kg]", 20.0, 60.0),
    ("k1 [N/m]", 3e5, 9e5),
    ("bumper stiffness [N/m]", 5e5, 2e6),
    ("plateau [N]", 1.5e4, 4e4),
    ("pendulum mass [kg]", 900.0, 1500.0),
    ("speed [m/s]", 1.0, 1.5),
];

/// The peak contact force, N (NaN for a car or bumper that cannot exist).
pub fn peak_force(x: &[f64]) -> f64 {
    let car = MsdModel::new(vec![x[0], 1200.0], vec![2e4], vec![x[1]]);
    let bumper = Bumper::three_part(x[2], x[3], 5e6);
    let (Ok(car), Ok(bumper)) = (car, bumper) else {
        return f64::NAN;
    };
    let pendulum = Scenario::Impactor {
        mass: x[4],
        speed: x[5],
    };
    let options = Options {
        duration: 0.3,
        output_step: 1e-3,
        ..Options::default()
    };
    simulate(&car, &bumper, pendulum, &options).map_or(f64::NAN, |r| r.peak_force)
}

/// The six inputs, uniform over [`RANGES`].
pub fn inputs() -> Vec<Input> {
    RANGES
        .iter()
        .map(|&(name, low, high)| Input::uniform(name, low, high))
        .collect()
}
