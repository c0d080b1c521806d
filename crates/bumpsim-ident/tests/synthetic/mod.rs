//! Synthetic load cases shared by issue 39's tests: half-sine pulses on a
//! known chain, simulated exactly, and Gaussian draws from a seeded stream
//! for their noise.

use bumpsim_core::model::MsdModel;
use bumpsim_ident::LoadCase;
use rand_chacha::ChaCha8Rng;
use rand_core::Rng;

/// A standard normal draw (Box–Muller).
pub fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    let mut unit = || ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    let (a, b) = (unit(), unit());
    (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
}

/// Case `pulse i`: the force `peak sin^shape(π t/duration)` until
/// `duration`, then 0, over `n` samples `step` apart, and the exact
/// response of `truth` at its first mass.
pub fn pulse(
    truth: &MsdModel,
    i: usize,
    (peak, duration, shape): (f64, f64, f64),
    (n, step): (usize, f64),
) -> LoadCase {
    let force = (0..n)
        .map(|k| {
            let t = k as f64 * step;
            match t < duration {
                true => peak * (std::f64::consts::PI * t / duration).sin().powf(shape),
                false => 0.0,
            }
        })
        .collect();
    let mut case = LoadCase {
        name: format!("pulse {i}"),
        start: 0.0,
        step,
        force,
        measured: vec![],
        output_dof: 1,
        initial_velocity: 0.0,
        window: (0, n - 1),
        compare: Default::default(),
    };
    case.measured = case.simulate(truth).unwrap();
    case
}
