//! The front crush zone of an identified chain (Kamal 1970's spring between
//! the barrier and the engine), read off the identification itself.
//!
//! The force-driven identification applies the measured barrier force F to
//! m1, so the crush zone ahead of m1 never appears in it; but the
//! identified chain's m1 moves under F, and in a barrier test whose first
//! sample is the first contact the zone's crush is m1's travel x1 (the
//! wall does not move). Its loading curve is therefore the measured force
//! against the simulated x1 where x1 passes its largest value so far,
//! averaged over [`POINTS`] equal bins of crush (a tabulated curve, which
//! may fall after a fold buckles), and its unloading slope the drop of the
//! force from the largest crush to the end of the contact (or of the
//! window) over the crush recovered. With this front link the identified
//! car alone runs into a rigid wall ([`bumpsim_core::chain::Drive::Barrier`]).

use super::LinkIdentError;
use super::objective::frame;
use crate::case::LoadCase;
use bumpsim_core::chain::{Chain, Drive, Frame};
use bumpsim_core::link::{Curve, Link, Unloading};

/// Bins of crush of the front link's table.
pub const POINTS: usize = 40;

/// The front link of `chain` identified on the barrier case `case`.
pub fn front_link(case: &LoadCase, chain: &Chain) -> Result<Link, LinkIdentError> {
    let invalid =
        |reason: &str| LinkIdentError::Settings(format!("load case '{}': {reason}", case.name));
    if frame(case) != Frame::Forward {
        return Err(invalid(
            "a front link needs a barrier case (force on m1 mostly negative, the car moving)",
        ));
    }
    let drive = Drive::Force {
        force: &case.force,
        step: case.step,
        initial_velocity: case.initial_velocity,
        frame: Frame::Forward,
    };
    let run = chain.run(&drive).map_err(|source| LinkIdentError::Chain {
        case: case.name.clone(),
        source,
    })?;
    let x1 = &run.displacement[0];
    let crush: Vec<f64> = case.force.iter().map(|f| (-f).max(0.0)).collect();
    let (top, reached) =
        x1.iter().enumerate().fold(
            (0, 0.0_f64),
            |(k, m), (i, x)| if *x > m { (i, *x) } else { (k, m) },
        );
    if reached <= 0.0 {
        return Err(invalid("m1 never moves into the barrier"));
    }
    let mut sums = vec![(0.0, 0.0, 0usize); POINTS];
    let mut most = 0.0_f64;
    for (x, f) in x1.iter().zip(&crush).take(top + 1) {
        if *x > most {
            most = *x;
            let bin = ((x / reached * POINTS as f64) as usize).min(POINTS - 1);
            sums[bin].0 += x;
            sums[bin].1 += f;
            sums[bin].2 += 1;
        }
    }
    let points: Vec<[f64; 2]> = sums
        .iter()
        .filter(|s| s.2 > 0)
        .map(|s| [s.0 / s.2 as f64, s.1 / s.2 as f64])
        .filter(|p| p[0] > 0.0)
        .collect();
    let curve = Curve::table(points).map_err(|e| invalid(&format!("front link: {e}")))?;
    let end = (top + 1..x1.len())
        .find(|&k| crush[k] <= 0.0)
        .unwrap_or(x1.len() - 1);
    let recovered = reached - x1[end];
    let dropped = crush[top] - crush[end];
    let slope = if recovered > 0.0 && dropped > 0.0 {
        dropped / recovered
    } else {
        curve.steepest_slope()
    };
    Link::new(curve, Unloading::Slope(slope)).map_err(|e| invalid(&format!("front link: {e}")))
}
