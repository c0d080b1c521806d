//! The checks of a study file's values on reading, where their keys can
//! be named: the global and per-parameter bounds, fixed values, case names
//! and initial velocities, the DOF list and the shape of `bounds`.

use super::error::StudyValueError;
use super::file::{Study, WindowSpec};
use crate::case::MAX_INITIAL_VELOCITY;
use crate::estimate::{usable_bounds, usable_fixed};
use bumpsim_core::names::check_names;
use bumpsim_core::units::short;
use bumpsim_io::numbers::Numbers;

/// The smallest and largest size of a channel's `scale` factor: a unit
/// conversion or a sign (−1, 9.80665, 1e-3, 1e6) lies far inside; 0 or a
/// factor of 1e-300 made an accelerometer silently zero (a mean of it and
/// its pair: half the car's motion) and 1e300 overflowed every simulation
/// ("all starts failed"), issue 44's hostile pass.
pub const SCALE_RANGE: (f64, f64) = (1e-9, 1e9);

const SCALE_EXPECTED: &str =
    "a finite factor from 1e-9 to 1e9 in size, either sign (a unit conversion, or -1 for a sign)";

/// Whether a channel's `scale` is finite and within [`SCALE_RANGE`] in size.
pub fn usable_scale(scale: f64) -> bool {
    scale.is_finite() && (SCALE_RANGE.0..=SCALE_RANGE.1).contains(&scale.abs())
}

impl Study {
    /// `lower_bound` and `upper_bound` apply to every parameter, `bounds`
    /// and `fixed` to one: checked here, where their keys can be named
    /// (the identification's own check names a parameter, m1 first, and
    /// not the file).
    pub(super) fn check_global_bounds(&self) -> Result<(), StudyValueError> {
        let lower = self.model.lower_bound;
        let upper = self.model.upper_bound.unwrap_or(f64::INFINITY);
        if !usable_bounds(lower, f64::INFINITY) {
            return Err(StudyValueError::LowerBound { value: lower });
        }
        if !usable_bounds(lower, upper) {
            return Err(StudyValueError::UpperBound { upper, lower });
        }
        for (name, pair) in &self.model.bounds {
            if let [lower, upper] = pair[..]
                && !usable_bounds(lower, upper)
            {
                let name = name.clone();
                return Err(StudyValueError::Bounds { name, lower, upper });
            }
        }
        match self.model.fixed.iter().find(|(_, v)| !usable_fixed(**v)) {
            Some((name, &value)) => Err(StudyValueError::Fixed {
                name: name.clone(),
                value,
            }),
            None => Ok(()),
        }
    }

    /// Case names follow [`bumpsim_core::names::check_names`]; each
    /// case's initial velocity is finite and at most
    /// [`MAX_INITIAL_VELOCITY`].
    pub(super) fn check_case_names(&self) -> Result<(), StudyValueError> {
        let names = self.case.iter().map(|c| c.name.as_str());
        check_names("[[case]]", names)?;
        let fast = |v: f64| !(v.is_finite() && v.abs() <= MAX_INITIAL_VELOCITY);
        match self.case.iter().find(|c| fast(c.initial_velocity)) {
            Some(case) => Err(StudyValueError::InitialVelocity {
                case: case.name.clone(),
                value: case.initial_velocity,
            }),
            None => Ok(()),
        }
    }

    /// Each case's fit window and bias window are two finite times in
    /// order, its CFC class is a positive finite number (the class the
    /// channel's sample rate allows is checked when it is loaded) and each
    /// channel's `scale` a factor [`usable_scale`] takes.
    pub(super) fn check_case_values(&self) -> Result<(), StudyValueError> {
        for case in &self.case {
            let error = |key, value: String, expected: &str| StudyValueError::CaseValue {
                case: case.name.clone(),
                key,
                value,
                expected: expected.into(),
            };
            let times = |[t0, t1]: [f64; 2]| t0.is_finite() && t1.is_finite() && t0 < t1;
            let pair = |[t0, t1]: [f64; 2]| format!("[{}, {}]", short(t0), short(t1));
            let expected = "two finite times in s, the first below the second";
            if let Some(WindowSpec::Times(Numbers(w))) = &case.window
                && !times(*w)
            {
                return Err(error("window", pair(*w), expected));
            }
            if let Some(b) = case.bias.filter(|b| !times(*b)) {
                return Err(error("bias", pair(b), expected));
            }
            if let Some(c) = case.cfc.filter(|c| !(c.is_finite() && *c > 0.0)) {
                return Err(error(
                    "cfc",
                    short(c),
                    "a positive CFC class (60, 180, 600, 1000)",
                ));
            }
            if let Some((what, channel)) = case.channels().find(|(_, c)| !usable_scale(c.scale)) {
                return Err(error(
                    "scale",
                    format!(
                        "{} (the {what} channel '{}')",
                        short(channel.scale),
                        channel.channel
                    ),
                    SCALE_EXPECTED,
                ));
            }
            let range = bumpsim_estimate::domain::NOISE_RANGE;
            if let Some(n) = case.noise.filter(|n| !range.contains(n)) {
                return Err(error(
                    "noise",
                    short(n),
                    "a positive standard deviation in the objective's unit (m, m/s or m/s²), from 1e-12 to 1e15",
                ));
            }
        }
        Ok(())
    }

    /// At least one DOF, each once, each from 1 to `MAX_DOF`.
    pub(super) fn check_dofs(&self) -> Result<(), StudyValueError> {
        let dofs = self.dofs();
        let max = crate::estimate::MAX_DOF;
        if dofs.is_empty() {
            return Err(StudyValueError::NoDof);
        }
        if let Some(twice) = crate::dofs::repeated(&dofs) {
            return Err(StudyValueError::RepeatedDof { dof: twice });
        }
        match dofs.into_iter().find(|&n| n == 0 || n > max) {
            Some(dof) => Err(StudyValueError::DofRange { dof, max }),
            None => Ok(()),
        }
    }

    /// A `bounds` entry is two values; a parameter is fixed or bounded, not
    /// both (the fixed value silently won).
    pub(super) fn check_tables(&self) -> Result<(), StudyValueError> {
        if let Some((name, pair)) = self.model.bounds.iter().find(|(_, b)| b.len() != 2) {
            return Err(StudyValueError::BoundsShape {
                name: name.clone(),
                values: pair.clone(),
            });
        }
        match self
            .model
            .fixed
            .keys()
            .find(|n| self.model.bounds.contains_key(*n))
        {
            Some(name) => Err(StudyValueError::FixedAndBounded { name: name.clone() }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::StudyError;
    use crate::study::tests::CASE;
    use std::path::PathBuf;

    /// A temporary folder of its own, and a reader of a study file written
    /// there with the given text.
    fn reader(name: &str) -> (PathBuf, impl Fn(&str) -> Result<Study, StudyError>) {
        let dir = std::env::temp_dir().join(format!("bumpsim-study-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("study.toml");
        let read = move |text: &str| {
            std::fs::write(&path, text).unwrap();
            Study::read(&path)
        };
        (dir, read)
    }

    /// `lower_bound = -1` was blamed on m1, a name the study does not hold.
    #[test]
    fn global_bounds_are_refused_by_their_own_keys() {
        let (dir, file) = reader("bounds");
        let read = |model: &str| {
            let text = format!("[model]\ndof = 2\n{model}\n[[case]]\nname = \"a\"\n{CASE}\n");
            file(&text).map(|_| ())
        };
        let range = "expected a number from 1e-12 to below 1e15";
        for (model, expected) in [
            (
                "lower_bound = -1.0",
                format!("[model] lower_bound = -1.000: {range}"),
            ),
            (
                "lower_bound = nan",
                format!("[model] lower_bound = NaN: {range}"),
            ),
            (
                "lower_bound = 1e300",
                format!("[model] lower_bound = 1.000e300: {range}"),
            ),
            (
                "lower_bound = 1e-13",
                format!("[model] lower_bound = 1.000e-13: {range}"),
            ),
            (
                "upper_bound = 0.5",
                "[model] upper_bound = 0.5000: expected a number above lower_bound = 1.000".into(),
            ),
            ("upper_bound = nan", "[model] upper_bound = NaN".into()),
            (
                "lower_bound = 1e-12\nupper_bound = 1e-12",
                "[model] upper_bound = 1.000e-12: expected a number above lower_bound = 1.000e-12"
                    .into(),
            ),
            (
                "bounds = { k1 = [-1.0, 5.0] }",
                "bounds: k1 = [-1.000, 5.000]: expected 1e-12 <= lower < upper".into(),
            ),
            (
                "bounds = { c1 = [5.0, 5.0] }",
                "bounds: c1 = [5.000, 5.000]: expected".into(),
            ),
            (
                "fixed = { k1 = nan }",
                "fixed: k1 = NaN: expected a finite positive value".into(),
            ),
            ("fixed = { c1 = 0.0 }", "fixed: c1 = 0: expected".into()),
        ] {
            let err = read(model).unwrap_err().to_string();
            assert!(
                err.contains(&expected) && !err.contains("m1") && err.contains("study.toml"),
                "{model}: {err}"
            );
        }
        read("lower_bound = 1e-3\nupper_bound = inf").unwrap();
        read("upper_bound = 1e20\nbounds = { m2 = [0.5, 2.0] }").unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// `dof = []` ran nothing with exit 0; two cases named `flat` gave two
    /// `flat` rows; `dof = -2` said "untagged enum DofSpec".
    #[test]
    fn empty_dof_lists_repeated_case_names_and_wrong_shapes_are_errors() {
        let (dir, file) = reader("names");
        let read = |text: &str| file(text).unwrap_err().to_string();
        let case = |name: &str| format!("[[case]]\nname = \"{name}\"\n{CASE}\n");
        let err = read(&format!("[model]\ndof = [2, 3, 2]\n{}", case("a")));
        assert!(err.contains("dof: 2 is given twice"), "{err}");
        let err = read(&format!("[model]\ndof = []\n{}", case("a")));
        assert!(err.contains("dof = []: expected at least one DOF"), "{err}");
        let err = read(&format!(
            "[model]\ndof = 2\n{}{}",
            case("flat"),
            case(" Flat")
        ));
        assert!(
            err.contains("[[case]] number 2: name ' Flat' is already used by 'flat'"),
            "{err}"
        );
        let err = read(&format!("[model]\ndof = 2\n{}", case(" ")));
        assert!(err.contains("an empty name"), "{err}");
        let fast = format!("{}initial_velocity = 1e300\n", case("fast"));
        let err = read(&format!("[model]\ndof = 2\n{fast}"));
        assert!(
            err.contains("[[case]] 'fast': initial_velocity = 1.000e300 m/s: expected a finite speed of at most 1000 m/s"),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\n{}initial_velocity = nan\n",
            case("n")
        ));
        assert!(err.contains("initial_velocity = NaN m/s"), "{err}");
        let err = read(&format!("[model]\ndof = 2\n{}", case("red\\u001b[31m")));
        assert!(
            err.contains(r#"the name "red\u001B[31m" holds control or invisible characters"#),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\n{}",
            case("O'Brien \\\"q\\\" bidi\\u202Eevil")
        ));
        assert!(
            err.contains(r#"the name "O'Brien \"q\" bidi\u202Eevil""#),
            "{err}"
        );
        let err = read(&format!("[model]\ndof = 2\n{}", case("zw\\u200Bsp")));
        assert!(err.contains("zw\\u200Bsp"), "{err}");
        let err = read(&format!(
            "[model]\ndof = 2\nbounds = {{ m1 = [1.0, 2.0, 3.0] }}\n{}",
            case("a")
        ));
        assert!(
            err.contains("bounds: m1 = [1.0, 2.0, 3.0]: expected [lower, upper]"),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\nbounds = {{ m1 = [1.0, 20.0] }}\nfixed = {{ m1 = 30.0 }}\n{}",
            case("a")
        ));
        assert!(err.contains("m1 is both fixed and bounded"), "{err}");
        let err = read(&format!("[model]\ndof = -2\n{}", case("a")));
        assert!(
            err.contains("dof: expected a number of masses") && !err.contains("enum"),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Hostile pass 2026-11-26 (finding 16): `window = [0.0, inf]` and
    /// `cfc = 1e-308` were accepted (the class against the channel's
    /// sample rate: `study::tests`); a window or bias window that is not
    /// two finite times in order, and a CFC class that is not a positive
    /// finite number, are refused naming the file, the case and the key.
    #[test]
    fn case_windows_and_cfc_classes_are_refused_by_their_keys() {
        let (dir, file) = reader("case-values");
        for (line, expected) in [
            (
                "window = [0.0, inf]",
                "'a': window = [0, inf]: expected two finite times",
            ),
            (
                "window = [0.01, 0.0]",
                "'a': window = [0.01, 0]: expected two finite",
            ),
            (
                "bias = [nan, 0.0]",
                "'a': bias = [NaN, 0]: expected two finite",
            ),
            ("cfc = 0.0", "'a': cfc = 0: expected a positive CFC class"),
            (
                "cfc = -180.0",
                "'a': cfc = -180: expected a positive CFC class",
            ),
            ("cfc = inf", "'a': cfc = inf: expected a positive CFC class"),
            (
                "noise = 1e-300",
                "'a': noise = 1e-300: expected a positive standard",
            ),
            (
                "noise = nan",
                "'a': noise = NaN: expected a positive standard",
            ),
        ] {
            let text = format!("[model]\ndof = 2\n[[case]]\nname = \"a\"\n{CASE}\n{line}\n");
            let err = file(&text).unwrap_err().to_string();
            assert!(
                err.contains("study.toml: [[case]]") && err.contains(expected),
                "{line}: {err}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
