//! The `[priors]` table of a planar study ([`crate::identify::priors`]):
//! each key a prior's name (`total_mass`, `body.yaw_inertia`,
//! `"left.springs[0]"`; dotted keys may be written as TOML's nested
//! tables), each value `"none"` (no prior) or `{ value = …, spread = … }`
//! (either may be left to the default). A value is SI, or text with a unit
//! for a mass, spring or damper (`"1239 kg"`, `"900 N/mm"`); a spread is
//! the standard deviation of ln θ, a positive number (0.2 ≈ ±20 %). The
//! reading is the estimation layer's ([`bumpsim_estimate::stated`]), one
//! for the 1-D and the planar studies; this module names the dimensions.

use crate::identify::PriorSetting;
use bumpsim_core::units::Dimension;

pub use bumpsim_estimate::stated::PriorsError;

/// The settings of a `[priors]` table (read as the 1-D study's,
/// [`bumpsim_estimate::stated::settings`]).
pub fn settings(table: &toml::Table) -> Result<Vec<PriorSetting>, PriorsError> {
    bumpsim_estimate::stated::settings(table, &dimension)
}

/// The dimension of a value given with a unit, by the prior's name.
fn dimension(name: &str) -> Option<Dimension> {
    if name.starts_with(crate::identify::MIRROR) {
        None
    } else if name == crate::identify::TOTAL_MASS
        || name == "body.mass"
        || name.contains(".masses[")
    {
        Some(Dimension::Mass)
    } else if name.contains(".springs[") {
        Some(Dimension::Stiffness)
    } else if name.contains(".dampers[") {
        Some(Dimension::Damping)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<PriorSetting>, PriorsError> {
        settings(&toml::from_str(text).unwrap())
    }

    #[test]
    fn dotted_keys_units_and_none_are_read() {
        let s = read(
            "body.yaw_inertia = { value = 2300, spread = 0.2 }\ntyres.mu_lateral = \"none\"\ntotal_mass = { value = \"1.239 t\" }\n\"left.springs[0]\" = { value = \"900 N/mm\", spread = 0.5 }",
        )
        .unwrap();
        let by = |n: &str| s.iter().find(|p| p.name == n).unwrap().clone();
        assert_eq!(by("body.yaw_inertia").value, Some(2300.0));
        assert!(by("tyres.mu_lateral").removed);
        assert!((by("total_mass").value.unwrap() - 1239.0).abs() < 1e-9);
        assert!((by("left.springs[0]").value.unwrap() - 9e5).abs() < 1e-6);
        let ratio = read("\"left/right.springs[0]\" = { value = 1.1, spread = 0.2 }").unwrap();
        assert_eq!((ratio[0].value, ratio[0].spread), (Some(1.1), Some(0.2)));
    }

    #[test]
    fn hostile_entries_name_their_key() {
        for (text, key) in [
            ("body.mass = { value = nan }", "body.mass"),
            ("body.mass = { spread = -0.1 }", "body.mass"),
            ("body.mass = { spread = 0.0 }", "body.mass"),
            ("body.mass = { value = \"fast\" }", "body.mass"),
            (
                "body.yaw_inertia = { value = \"2300 kg\" }",
                "body.yaw_inertia",
            ),
            ("body.mass = { centre = 3 }", "body.mass"),
            ("body.mass = 3", "body.mass"),
            ("body.mass = \"some\"", "body.mass"),
            // a left/right ratio is a number, not a stiffness
            (
                "\"left/right.springs[0]\" = { value = \"900 N/mm\" }",
                "left/right.springs[0]",
            ),
        ] {
            let e = read(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("[priors] {key}")), "{text}: {e}");
        }
    }
}
