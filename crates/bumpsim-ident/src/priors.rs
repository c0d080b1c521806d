//! The stated priors of a chain identification (issue 44, item 3): what
//! an engineer knows of the car before the tests, as Gaussian priors on
//! `ln θ` ([`bumpsim_estimate::prior`], the planar identification's), each
//! printed with how far the data moved it.
//!
//! Defaults, in the velocity and acceleration domains (a study's
//! `objective = "displacement"`, the thesis's, has only the priors its
//! `[priors]` states):
//!
//! | name | centre | spread (sd of ln θ) | source |
//! |---|---|---|---|
//! | `total_mass` (the free masses) | the test sheet's `[model] mass`, less the fixed masses | [`SHEET_SPREAD`] (±1 %) | the test sheet (none without one) |
//! | each free damper and spring (`c1`, `k1`, …) | the start (the user's `[model] start`, else the data-derived one) | [`ELEMENT_SPREAD`] (a factor 10 at 2 sd) | the start |
//! | each free mass (`m1`, …) | the user's `[model] start`; with neither a start nor a test sheet, the data-derived one | [`ELEMENT_SPREAD`] | the start |
//!
//! A start is not knowledge: the data-derived one splits the mass the
//! impulse gives equally (on the bundled example 987 kg each, against a
//! 29 kg bumper mass: a prior there sat 3 sd from the data and warned that
//! they disagree). So where the test sheet states the car's mass, that sum
//! is what is known of the masses and the data-derived split adds no
//! prior; its stiffness (the window taken as a half period) and damping
//! (30 % of critical) still centre the factor-10 priors of the springs
//! and dampers. A user's start is what the user knows, and centres every
//! element. The price: on the bundled example nothing stated holds the
//! second mass, traded against the third along the direction the tests
//! cannot see, so long posteriors walk down that tail (m2's 95 % interval
//! from 3.8 kg at 12 000 steps; 70 kg at 16 000 with the equal split's
//! prior; the 1 kg bound with no priors at all): a stated `[priors] m2`
//! from the drawings is the remedy (docs/uncertainty.md). A study's
//! `[priors]` overrides each (`value`,
//! `spread`), removes it (`"none"`) or adds one
//! ([`bumpsim_estimate::stated`]).

use crate::settings::Settings;
use bumpsim_core::model::{ParameterKind, parameter_kind, parameter_name};
use bumpsim_core::units::Dimension;
use bumpsim_estimate::prior::Prior;
use bumpsim_estimate::stated::{PriorsError, apply};

/// The name of the prior on the sum of the free masses.
pub const TOTAL_MASS: &str = "total_mass";

/// The spread of the test sheet's total mass: ±1 % (a weighed car).
pub const SHEET_SPREAD: f64 = 0.01;

/// The spread of each element's default prior: a factor 10 at two
/// standard deviations, `ln 10 / 2` (the planar chain's).
pub const ELEMENT_SPREAD: f64 = std::f64::consts::LN_10 / 2.0;

/// The priors of a `settings.dof`-mass identification whose free
/// parameters are `free` (thesis order), started from `start` (SI, every
/// parameter): the defaults when `settings.default_priors`, with the
/// study's `settings.priors` applied. Terms index the free parameters.
pub fn priors(
    settings: &Settings,
    start: &[f64],
    free: &[usize],
) -> Result<Vec<Prior>, PriorsError> {
    let dof = settings.dof;
    let names: Vec<String> = free.iter().map(|&i| parameter_name(dof, i)).collect();
    let defaults = match settings.default_priors {
        true => defaults(settings, start, free),
        false => Vec::new(),
    };
    apply(defaults, &settings.priors, &names, &[TOTAL_MASS])
}

fn defaults(settings: &Settings, start: &[f64], free: &[usize]) -> Vec<Prior> {
    let dof = settings.dof;
    let is_mass = |i: usize| parameter_kind(dof, i).0 == ParameterKind::Mass;
    let mut out = Vec::new();
    let masses: Vec<usize> = (0..free.len()).filter(|&j| is_mass(free[j])).collect();
    let fixed_mass: f64 = (0..dof)
        .filter_map(|i| settings.bounds.fixed[i])
        .sum::<f64>();
    if let Some(sheet) = settings.sheet_mass
        && !masses.is_empty()
        && let Ok(prior) = Prior::sum(TOTAL_MASS, masses, sheet - fixed_mass, SHEET_SPREAD)
    {
        out.push(prior.from_source("the test sheet"));
    }
    // the data-derived split of the mass is no knowledge beside the sheet's
    let split_unknown = settings.sheet_mass.is_some() && settings.start.is_none();
    for (j, &i) in free.iter().enumerate() {
        if split_unknown && is_mass(i) {
            continue;
        }
        if let Ok(prior) = Prior::single(parameter_name(dof, i), j, start[i], ELEMENT_SPREAD) {
            out.push(prior.from_source("the start"));
        }
    }
    out
}

/// The dimension of a 1-D prior's value given with a unit, by its name.
pub fn dimension(name: &str) -> Option<Dimension> {
    match name.chars().next() {
        _ if name == TOTAL_MASS => Some(Dimension::Mass),
        Some('m') => Some(Dimension::Mass),
        Some('c') => Some(Dimension::Damping),
        Some('k') => Some(Dimension::Stiffness),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_name_the_sheet_and_the_start_and_a_study_overrides_them() {
        let mut settings = Settings::new(2, 1);
        settings.sheet_mass = Some(1000.0);
        settings.default_priors = true;
        settings.bounds.fixed[0] = Some(20.0);
        let start = [20.0, 900.0, 3e3, 8e5];
        settings.start = Some(start.to_vec()); // the user's: every element
        let free = [1, 2, 3];
        let p = priors(&settings, &start, &free).unwrap();
        let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, [TOTAL_MASS, "m2", "c1", "k1"]);
        assert_eq!((p[0].centre, p[0].terms.clone()), (980.0, vec![0]));
        assert_eq!(
            (p[3].centre, p[3].terms.clone(), p[3].spread),
            (8e5, vec![2], ELEMENT_SPREAD)
        );
        settings.priors = bumpsim_estimate::stated::settings(
            &toml::from_str("total_mass = \"none\"\nk1 = { value = \"900 N/mm\", spread = 0.3 }")
                .unwrap(),
            &dimension,
        )
        .unwrap();
        let p = priors(&settings, &start, &free).unwrap();
        assert_eq!(p.len(), 3);
        assert_eq!((p[2].centre, p[2].spread), (9e5, 0.3));
        settings.default_priors = false;
        let p = priors(&settings, &start, &free).unwrap();
        assert_eq!(p.len(), 1, "only what the study states");
        settings.default_priors = true;
        settings.start = None;
        settings.priors.clear();
        let p = priors(&settings, &start, &free).unwrap();
        let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(
            names,
            [TOTAL_MASS, "c1", "k1"],
            "the sheet, not the data-derived split, informs the masses"
        );
        settings.sheet_mass = None;
        let p = priors(&settings, &start, &free).unwrap();
        let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(
            names,
            ["m2", "c1", "k1"],
            "without a sheet the start's masses"
        );
        settings.sheet_mass = Some(1000.0);
        settings.priors = bumpsim_estimate::stated::settings(
            &toml::from_str("total_mass = \"none\"\nk1 = { value = \"900 N/mm\", spread = 0.3 }")
                .unwrap(),
            &dimension,
        )
        .unwrap();
        settings.priors[1].name = "m1".into();
        let e = priors(&settings, &start, &free).unwrap_err().to_string();
        assert!(
            e.starts_with("[priors] m1") && e.contains("known: total_mass, m2, c1, k1"),
            "{e}"
        );
    }
}
