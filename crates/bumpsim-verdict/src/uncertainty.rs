//! The car's uncertainty for the probability of passing (issue 39, item
//! 4; [`crate::probability`]).
//!
//! The car's parameters are log-normal around the car file's values:
//! `ln θᵢ = ln θ̂ᵢ + σᵢ zᵢ`, `z ~ N(0, R)`, read from a planar
//! identification's JSON (`σᵢ = SEᵢ/θ̂ᵢ` and the correlation of the log
//! parameters) or a TOML `[uncertainty]` table of relative standard
//! deviations, or uniform over a range of a TOML `[ranges]` table
//! (`"bumper.force" = [0.8, 1.2]`, independent), and drawn with a seed. It lives with the planar car
//! ([`bumpsim_planar::uncertainty`], where the planar impact's prediction
//! bands use it too) and is re-exported here; this module adds what a
//! propagation of the verdict ran and gave ([`Propagation`]).

use bumpsim_estimate::propagate::Probability;
pub use bumpsim_planar::uncertainty::{
    Marginal, Part, Planar, Uncertainty, UncertaintyError, described, part, scaled,
};
use serde::Serialize;

/// What a propagation ran and gave.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Propagation {
    /// The uncertainty propagated.
    pub uncertainty: Uncertainty,
    /// Draws asked for.
    pub samples: usize,
    /// The seed.
    pub seed: u64,
    /// Draws whose car or run failed.
    pub failed: usize,
    /// The probability that every test passes.
    pub passing: Probability,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The planar car's uncertainty reads as it did here: an unknown name
    /// and a NaN spread are refused, a TOML table gives independent spreads.
    #[test]
    fn the_planar_uncertainty_reads_through_the_verdict() {
        let u = Uncertainty::independent("spreads", vec![("body.mass".into(), 0.02)]).unwrap();
        assert_eq!(u.correlation, vec![vec![1.0]]);
        assert!(Uncertainty::independent("s", vec![("body.mass".into(), f64::NAN)]).is_err());
        assert!(Uncertainty::independent("s", vec![("wheel.size".into(), 0.1)]).is_err());
        assert_eq!(part("bumper.force"), Some(Part::BumperForce));
    }
}
