//! Study files (TOML): the load cases and settings of an identification.
//!
//! Paths are relative to the study file. Each case names its force
//! (channels summed when a selector matches several, e.g. the cells of a
//! load-cell wall) and either a displacement channel or accelerometer
//! channels (averaged, bias removed, filtered, integrated twice from the
//! initial velocity at t = 0). Force and acceleration get the same bias
//! removal (default: the mean before t = 0, when there are such samples) and
//! the optional CFC filter. The case starts at t = 0, where the initial
//! state applies; the fit window is the contact window of the force
//! (5 % rise, 2 % fall) or `[t0, t1]` s. See docs/identify.md.
//!
//! The parts: the file's layout (`file`), the checks of its values on
//! reading (`checks`), the loading of one case (`context`) and the errors
//! (`error`).

use bumpsim_core::model::{parameter_count, parameter_name};
use bumpsim_signal::loader::Loader;
use std::path::Path;

mod checks;
mod context;
mod error;
mod file;

use context::CaseContext;

pub use crate::case::MAX_INITIAL_VELOCITY;
pub use checks::{SCALE_RANGE, usable_scale};
pub use context::{CaseNote, LoadedCases};
pub use error::{DefinitionError, StudyError, StudyValueError};
pub use file::{
    CaseSpec, ChannelRef, DEFAULT_OBJECTIVE, DofSpec, IdentificationSpec, ModelSpec, OutputDof,
    ParameterSet, Study, WindowSpec,
};

use crate::case::LoadCase;
use crate::estimate::{Settings, uniform_bounds};

impl Study {
    /// Reads a study file.
    pub fn read(path: &Path) -> Result<Study, StudyError> {
        let error = |message: String| StudyError::File {
            path: path.to_path_buf(),
            message,
        };
        if let Some(kind) = test_data_kind(path) {
            return Err(error(not_a_study(kind)));
        }
        let text = std::fs::read_to_string(path).map_err(|e| error(format!("cannot read: {e}")))?;
        let mut study: Study = toml::from_str(&text).map_err(|e| {
            let parse = bumpsim_io::toml_message(&text, &e);
            error(match test_data_text(&text) {
                Some(kind) => not_a_study(kind),
                None => parse,
            })
        })?;
        study.base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        study.path = path.to_path_buf();
        if !study.model.method.eq_ignore_ascii_case("zoh") {
            return Err(error(format!(
                "method '{}': identification uses the exact zoh discretisation (its sensitivities are exact); use method = \"zoh\"",
                study.model.method
            )));
        }
        if study.links.is_some() && study.kind.as_deref() != Some("links") {
            return Err(error(
                "[links] holds the settings of a links study: declare kind = \"links\" (docs/identify.md), or leave [links] out".into(),
            ));
        }
        if study.case.is_empty() {
            return Err(error(
                "no [[case]]: a study needs at least one load case".into(),
            ));
        }
        let value = |source| StudyError::Value {
            path: path.to_path_buf(),
            source,
        };
        study.check_case_names().map_err(value)?;
        study.check_global_bounds().map_err(value)?;
        study.check_tables().map_err(value)?;
        study.check_dofs().map_err(value)?;
        study.check_case_values().map_err(value)?;
        study
            .objective()
            .map_err(|e| error(format!("[identification] {e}")))?;
        study.sheet_mass()?;
        study.prior_settings()?;
        Ok(study)
    }

    /// Settings for `dof` masses. `bounds` and `fixed` entries must name
    /// parameters of the largest model (of the study's DOF and `dof`); they
    /// apply to each model that has them. A `start` must fit one of those
    /// models (it is used for that one).
    pub fn settings(&self, dof: usize) -> Result<Settings, StudyError> {
        let largest = self.dofs().into_iter().chain([dof]).max().unwrap_or(dof);
        self.check_names(largest)?;
        let p = parameter_count(dof);
        let mut bounds = uniform_bounds(dof, self.model.lower_bound);
        if let Some(upper) = self.model.upper_bound {
            bounds.upper = vec![upper; p];
        }
        let names: Vec<String> = (0..p).map(|i| parameter_name(dof, i)).collect();
        let index = |name: &str| names.iter().position(|n| n == name);
        for (name, pair) in &self.model.bounds {
            if let (Some(i), [lo, hi]) = (index(name), pair.as_slice()) {
                (bounds.lower[i], bounds.upper[i]) = (*lo, *hi);
            }
        }
        for (name, value) in &self.model.fixed {
            if let Some(i) = index(name) {
                bounds.fixed[i] = Some(*value);
            }
        }
        let priors = self.priors_of(dof, largest)?;
        self.check_prior_names(&priors, dof, &bounds.fixed)?;
        Ok(Settings {
            dof,
            bounds,
            starts: self.model.starts,
            seed: self.model.seed,
            start: self.start(dof)?,
            sheet_mass: self.sheet_mass()?,
            default_priors: self.default_priors(),
            priors,
            ..Settings::new(dof, 1)
        })
    }

    /// Refuses a `[priors]` entry that names no estimated parameter of the
    /// `dof`-mass model (none of the study's models, or one `fixed`), by
    /// the study file and the section: it was refused only after the
    /// search, without the file ("3-DOF identification: identification
    /// setting priors: [priors] m5: ..."; a hostile pass, issue 44).
    fn check_prior_names(
        &self,
        priors: &[bumpsim_estimate::stated::PriorSetting],
        dof: usize,
        fixed: &[Option<f64>],
    ) -> Result<(), StudyError> {
        let free: Vec<String> = (0..parameter_count(dof))
            .filter(|&i| fixed[i].is_none())
            .map(|i| parameter_name(dof, i))
            .collect();
        let total = crate::priors::TOTAL_MASS;
        let Some(unknown) = priors
            .iter()
            .find(|p| p.name != total && !free.contains(&p.name))
        else {
            return Ok(());
        };
        let is_fixed = self.model.fixed.contains_key(&unknown.name);
        let why = match is_fixed {
            true => "fixed ([model] fixed): a fixed parameter is not estimated and takes no prior",
            false => "no such estimated parameter",
        };
        Err(StudyError::File {
            path: self.path.clone(),
            message: format!(
                "[priors] {}: {why}; known for the {dof}-DOF model: {total}, {}",
                unknown.name,
                free.join(", ")
            ),
        })
    }

    /// Whether the default priors apply: in every domain but the thesis's
    /// displacements (which reproduce the thesis's figures; there only
    /// the study's `[priors]` apply).
    pub fn default_priors(&self) -> bool {
        !matches!(self.objective(), Ok(crate::case::Domain::Displacement))
    }

    /// The study's `[priors]` settings (empty without the table).
    pub fn prior_settings(
        &self,
    ) -> Result<Vec<bumpsim_estimate::stated::PriorSetting>, StudyError> {
        let Some(table) = &self.priors else {
            return Ok(Vec::new());
        };
        bumpsim_estimate::stated::settings(table, &crate::priors::dimension).map_err(|e| {
            StudyError::File {
                path: self.path.clone(),
                message: e.to_string(),
            }
        })
    }

    /// The `[priors]` settings for a `dof`-mass model of a sweep whose
    /// largest model has `largest` masses: one naming a parameter of the
    /// largest model applies to each model that has it, as `bounds` and
    /// `fixed` do (a `k2` prior failed the 1- and 2-DOF models of `dof = [1,
    /// 2, 3]`); any other name is left to the identification to refuse.
    fn priors_of(
        &self,
        dof: usize,
        largest: usize,
    ) -> Result<Vec<bumpsim_estimate::stated::PriorSetting>, StudyError> {
        let names = |n: usize| (0..parameter_count(n)).map(move |i| parameter_name(n, i));
        let elsewhere: Vec<String> = names(largest)
            .filter(|n| !names(dof).any(|m| m == *n))
            .collect();
        let mut settings = self.prior_settings()?;
        settings.retain(|s| !elsewhere.contains(&s.name));
        Ok(settings)
    }

    /// The test sheet's mass, kg (`[model] mass`), if given.
    pub fn sheet_mass(&self) -> Result<Option<f64>, StudyError> {
        let Some(value) = &self.model.mass else {
            return Ok(None);
        };
        match bumpsim_io::mass::sheet_mass(value) {
            Some(mass) => Ok(Some(mass)),
            None => Err(StudyError::File {
                path: self.path.clone(),
                message: format!(
                    "[model] mass = {}: {}",
                    bumpsim_io::mass::quoted(value),
                    bumpsim_io::mass::EXPECTED
                ),
            }),
        }
    }

    /// Refuses `bounds` and `fixed` entries that name no parameter of a
    /// `largest`-mass model (names of smaller models are a subset).
    fn check_names(&self, largest: usize) -> Result<(), StudyError> {
        let valid: Vec<String> = (0..parameter_count(largest))
            .map(|i| parameter_name(largest, i))
            .collect();
        let tables = [
            ("bounds", self.model.bounds.keys().collect::<Vec<_>>()),
            ("fixed", self.model.fixed.keys().collect()),
        ];
        for (table, names) in tables {
            if let Some(name) = names.into_iter().find(|n| !valid.contains(n)) {
                return Err(StudyError::Parameter {
                    path: self.path.clone(),
                    table,
                    name: name.clone(),
                    dof: largest,
                    valid,
                });
            }
        }
        Ok(())
    }

    /// The user's start for a `dof`-mass model: used when it has `dof`
    /// masses, an error when it fits none of the models identified.
    fn start(&self, dof: usize) -> Result<Option<Vec<f64>>, StudyError> {
        let Some(s) = &self.model.start else {
            return Ok(None);
        };
        let n = s.masses.len();
        let consistent = n >= 1 && s.dampers.len() == n - 1 && s.springs.len() == n - 1;
        let mut dofs = self.dofs();
        dofs.push(dof);
        if consistent && dofs.contains(&n) {
            return Ok((n == dof).then(|| [&s.masses[..], &s.dampers, &s.springs].concat()));
        }
        dofs.sort_unstable();
        dofs.dedup();
        let sizes: Vec<String> = dofs
            .iter()
            .map(|d| format!("{d}, {}, {}", d - 1, d - 1))
            .collect();
        Err(StudyError::Start {
            path: self.path.clone(),
            masses: n,
            dampers: s.dampers.len(),
            springs: s.springs.len(),
            expected: format!(
                "the {} model needs {} (masses, dampers, springs)",
                dofs.iter()
                    .map(|d| format!("{d}-DOF"))
                    .collect::<Vec<_>>()
                    .join(" or "),
                sizes.join(" or ")
            ),
        })
    }

    /// Reads and processes every case for a `dof`-mass model.
    pub fn cases(&self, dof: usize) -> Result<Vec<LoadCase>, StudyError> {
        Ok(self.load(dof)?.cases)
    }

    /// Reads and processes every case for a `dof`-mass model, with the
    /// notes of the channel selections.
    pub fn load(&self, dof: usize) -> Result<LoadedCases, StudyError> {
        self.load_named(dof, &[])
    }

    /// The cases loaded once (for any DOF) adapted to `dof` masses: cases
    /// whose output is `"last"` measure mass `dof`. Saves reading and
    /// processing the test files again for every model size of a sweep.
    pub fn retarget(&self, cases: &[LoadCase], dof: usize) -> Vec<LoadCase> {
        let last = |spec: &CaseSpec| matches!(&spec.output_dof, Some(OutputDof::Named(s)) if s.eq_ignore_ascii_case("last"));
        cases
            .iter()
            .zip(&self.case)
            .map(|(case, spec)| LoadCase {
                output_dof: if last(spec) { dof } else { case.output_dof },
                ..case.clone()
            })
            .collect()
    }

    /// Reads and processes the named cases (all when `names` is empty).
    pub fn cases_named(&self, dof: usize, names: &[String]) -> Result<Vec<LoadCase>, StudyError> {
        Ok(self.load_named(dof, names)?.cases)
    }

    /// Reads and processes the named cases (all when `names` is empty),
    /// with the notes of the channel selections.
    pub fn load_named(&self, dof: usize, names: &[String]) -> Result<LoadedCases, StudyError> {
        if let Some(name) = names
            .iter()
            .find(|n| !self.case.iter().any(|c| &&c.name == n))
        {
            let known: Vec<&str> = self.case.iter().map(|c| c.name.as_str()).collect();
            return Err(StudyError::File {
                path: self.path.clone(),
                message: format!("no case '{name}'; cases: {}", known.join(", ")),
            });
        }
        let mut loader = Loader::new();
        let mut loaded = LoadedCases {
            cases: Vec::new(),
            notes: Vec::new(),
            warnings: Vec::new(),
        };
        for spec in self
            .case
            .iter()
            .filter(|c| names.is_empty() || names.contains(&c.name))
        {
            let mut ctx = CaseContext {
                study: self,
                spec,
                loader: &mut loader,
                notes: Vec::new(),
            };
            let case = ctx.load_case(dof)?;
            loaded
                .warnings
                .extend(case.direction_warning_given(&spec.turned_channels()));
            loaded.cases.push(case);
            loaded.notes.append(&mut ctx.notes);
        }
        Ok(loaded)
    }
}

/// What a path given as a study is, when it is crash-test data instead
/// (by its extension, or a folder): an ISO-MME test, an NHTSA EV5 test or a
/// CSV table.
fn test_data_kind(path: &Path) -> Option<&'static str> {
    if path.is_dir() {
        return Some("a folder (an ISO-MME test folder?)");
    }
    if !path.is_file() {
        return None;
    }
    let extension = path.extension()?.to_string_lossy().to_ascii_lowercase();
    match extension.as_str() {
        "mme" | "zip" => Some("an ISO-MME test"),
        "ev5" => Some("an NHTSA EV5 test"),
        "csv" => Some("a CSV table of signals"),
        e if e.len() == 3 && e.bytes().all(|b| b.is_ascii_digit()) => {
            Some("a channel file of a crash test")
        }
        _ => None,
    }
}

/// The same, by the first line of a file that is not TOML.
fn test_data_text(text: &str) -> Option<&'static str> {
    let first = text.lines().next().unwrap_or("").trim_start();
    let starts = |p: &str| first.to_ascii_lowercase().starts_with(p);
    if starts("data format edition number") {
        Some("an ISO-MME test")
    } else if first.starts_with('{') {
        Some("JSON (a result of `bumpsim identify --json`?)")
    } else if first.contains(',') && !first.contains('=') {
        Some("a CSV table of signals")
    } else {
        None
    }
}

/// The error for crash-test data given where a study is expected.
fn not_a_study(kind: &str) -> String {
    format!(
        "this is {kind}, not a study. bumpsim identify reads a study file: TOML with a [model] table and one [[case]] per test naming its force and acceleration channels (docs/identify.md). List the test's channels with `bumpsim signal info FILE`, then write a study that names them: docs/your-own-tests.md walks through it"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_signal::loader::Note;
    use std::fmt::Write;
    use std::path::PathBuf;

    fn study(model: &str, case: &str, base: &Path) -> Study {
        let text = format!("[model]\n{model}\n[[case]]\nname = \"a\"\n{case}\n");
        let mut study: Study = toml::from_str(&text).unwrap();
        study.base = base.to_path_buf();
        study.path = base.join("study.toml");
        study
    }

    pub(super) const CASE: &str = "force = { path = \"t.EV5\", channel = \"0-LC-*-XG\" }\ndisplacement = { path = \"t.EV5\", channel = \"3\", scale = 2.0 }";

    /// An EV5 test: a force pulse (curve 1), an invalid load cell (2), a
    /// displacement (3), 0.02 s from t = −0.005 s at 10 kHz.
    fn ev5(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpsim-study-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let row = |vehicle: u8,
                   curve: usize,
                   kind: &str,
                   location: &str,
                   unit: &str,
                   comment: &str| {
            format!(
                "{vehicle}|{curve}|{kind}|00|{location}|XG|SEC|{unit}|0|S|01/JAN/2020|1|1|0|-50|149|100|AM|P|{comment}\n"
            )
        };
        let mut text = String::from("----- INSTRUMENTATION -----\n");
        text += &row(0, 1, "LC", "WALL", "NWT", "WALL FX");
        text += &row(0, 2, "LC", "WALX", "NWT", "No valid data");
        text += &row(1, 3, "DS", "CG", "MM", "CG DX");
        std::fs::write(dir.join("t.EV5"), text).unwrap();
        let pulse = |t: f64| {
            if (0.0..0.01).contains(&t) {
                1e4 * (t * 100.0 * std::f64::consts::PI).sin()
            } else {
                0.0
            }
        };
        let curves: [&dyn Fn(f64) -> f64; 3] = [&pulse, &|t| 5.0 * pulse(t), &|t| 1e-2 * pulse(t)];
        for (curve, value) in curves.iter().enumerate() {
            let mut samples = String::new();
            for k in -50..150 {
                let t = k as f64 * 1e-4;
                writeln!(samples, "{t}\t{}", value(t)).unwrap();
            }
            std::fs::write(dir.join(format!("t.{:03}", curve + 1)), samples).unwrap();
        }
        dir
    }

    /// Crash-test data given as a study: what it is and what to run, not
    /// "TOML parse error at line 1".
    #[test]
    fn test_data_given_as_a_study_is_named_with_the_way_on() {
        let dir = std::env::temp_dir().join(format!("bumpsim-not-study-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let cases = [
            (
                "FLAT.mme",
                "Data format edition number   :1.6\n",
                "an ISO-MME test",
            ),
            (
                "study.toml",
                "Data format edition number   :1.6\n",
                "an ISO-MME test",
            ),
            ("r.json", "{\"model\": 1}\n", "JSON"),
            ("s.csv", "time [s],F [N]\n0,1\n", "a CSV table"),
        ];
        for (name, text, kind) in cases {
            let path = dir.join(name);
            std::fs::write(&path, text).unwrap();
            let e = Study::read(&path).unwrap_err().to_string();
            assert!(e.contains(kind) && e.contains("signal info"), "{name}: {e}");
        }
        let e = Study::read(&dir).unwrap_err().to_string();
        assert!(e.contains("a folder"), "{e}");
        // a missing file is missing, whatever its extension
        let e = Study::read(&dir.join("none.mme")).unwrap_err().to_string();
        assert!(e.contains("cannot read"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A displacement sampled at half the force's rate, over a shorter
    /// span, was resampled and cut without a word.
    #[test]
    fn force_and_displacement_on_different_time_bases_get_a_note() {
        let dir = ev5("resampled");
        // 5 kHz from 0 to 0.009 s (the force: 10 kHz from -0.005 s to 0.0149 s)
        let mut csv = String::from("time [s],x [m]\n");
        for k in 0..46 {
            let t = k as f64 * 2e-4;
            writeln!(csv, "{t},{}", 1e-3 * t).unwrap();
        }
        std::fs::write(dir.join("x.csv"), csv).unwrap();
        let case = "force = { path = \"t.EV5\", channel = \"1\" }\ndisplacement = { path = \"x.csv\", channel = \"x\" }\nwindow = [0.0, 0.009]";
        let loaded = study("dof = 1", case, &dir).load(1).unwrap();
        let notes: Vec<&CaseNote> = loaded
            .notes
            .iter()
            .filter(|n| matches!(n.note, Note::Resampled(_)))
            .collect();
        assert_eq!(notes.len(), 1, "{:?}", loaded.notes);
        let Note::Resampled(r) = &notes[0].note else {
            unreachable!()
        };
        approx::assert_relative_eq!(r.step, 1e-4, max_relative = 1e-12);
        approx::assert_relative_eq!(r.span[1], 0.009, max_relative = 1e-9);
        assert_eq!(r.interpolated.len(), 1);
        assert_eq!(r.codes[r.interpolated[0].0], "x");
        approx::assert_relative_eq!(r.interpolated[0].1, 2e-4, max_relative = 1e-9);
        // the force's 50 samples before t = 0 and 59 after 0.009 s
        assert_eq!(r.trimmed, [(0, 50 + 59)]);
        let text = notes[0].to_string();
        assert_eq!(
            text,
            "case 'a': force '1' and displacement 'x' put on one time base, every 0.1000 ms from 0 ms to 9.000 ms; displacement (every 0.2000 ms) interpolated linearly; force: 109 samples outside that span left out"
        );
        // the displacement between its samples is the straight line
        let case = &loaded.cases[0];
        approx::assert_relative_eq!(case.measured[3], 1e-3 * 3e-4, max_relative = 1e-9);
    }

    /// Force and displacement that overlap in one sample were refused as
    /// "the force is zero everywhere", although the force file has a pulse.
    #[test]
    fn a_case_failing_on_its_overlap_says_how_the_channels_were_aligned() {
        let dir = ev5("overlap");
        let mut csv = String::from("time [s],x [m]\n");
        for k in 0..20 {
            writeln!(csv, "{},0", 0.0148 + k as f64 * 1e-4).unwrap();
        }
        std::fs::write(dir.join("x.csv"), csv).unwrap();
        let case = "force = { path = \"t.EV5\", channel = \"1\" }\ndisplacement = { path = \"x.csv\", channel = \"x\" }";
        let err = study("dof = 1", case, &dir).load(1).unwrap_err();
        assert!(
            matches!(
                &err,
                StudyError::Case {
                    source: DefinitionError::Resampled { .. },
                    ..
                }
            ),
            "{err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("(after force '1' and displacement 'x' put on one time base")
                && text.contains("displacement: 18 samples outside that span left out)"),
            "{text}"
        );
    }

    /// A window or bias window of three times lost its third without a
    /// word (serde reads `[f64; 2]` from the first two values; issue 34).
    #[test]
    fn a_window_or_bias_of_three_times_is_refused() {
        for line in ["window = [0.0, 0.01, 0.02]", "bias = [-0.005, 0.0, 1.0]"] {
            let text = format!("[model]\ndof = 2\n[[case]]\nname = \"a\"\n{CASE}\n{line}\n");
            let err = toml::from_str::<Study>(&text).unwrap_err().to_string();
            assert!(err.contains("line 7"), "{line}: {err}");
        }
        let text = format!(
            "[model]\ndof = 2\n[[case]]\nname = \"a\"\n{CASE}\nwindow = [0.0, 0.01]\nbias = [-0.005, 0.0]\n"
        );
        assert!(toml::from_str::<Study>(&text).is_ok());
    }

    #[test]
    fn unknown_bounds_and_fixed_names_are_errors_naming_them() {
        let base = Path::new("/study");
        let bad = study("dof = 3\nfixed = { M1 = 2.0 }", CASE, base);
        let err = bad.settings(3).unwrap_err();
        assert!(
            matches!(&err, StudyError::Parameter { table: "fixed", name, dof: 3, .. } if name == "M1")
        );
        let text = err.to_string();
        assert!(
            text.contains("'M1'") && text.contains("m1, m2, m3, c1, c2, k1, k2"),
            "{text}"
        );
        let bad = study("dof = 3\nbounds = { m9 = [1.0, 2.0] }", CASE, base);
        assert!(
            bad.settings(3)
                .unwrap_err()
                .to_string()
                .contains("bounds: no parameter 'm9'")
        );
        // a name of the largest model of a sweep applies where it exists
        let sweep = study(
            "dof = [1, 2, 3]\nfixed = { m3 = 7.0 }\nbounds = { k2 = [5.0, 9.0] }",
            CASE,
            base,
        );
        assert!(
            sweep
                .settings(2)
                .unwrap()
                .bounds
                .fixed
                .iter()
                .all(Option::is_none)
        );
        let three = sweep.settings(3).unwrap();
        assert_eq!(three.bounds.fixed[2], Some(7.0));
        assert_eq!((three.bounds.lower[6], three.bounds.upper[6]), (5.0, 9.0));
    }

    /// A prior on k2 in `dof = [1, 2, 3]` failed the 1- and 2-DOF models;
    /// it applies where k2 exists. A name of no model (m9) is refused with
    /// the study file when the settings are made, before any search (it
    /// was refused by the identification after its search, without the
    /// file), and so is a prior on a fixed parameter.
    #[test]
    fn a_sweep_s_prior_applies_to_the_models_that_have_its_parameter() {
        let priors = format!("{CASE}\n[priors]\nk2 = {{ value = 6e5 }}");
        let sweep = study("dof = [1, 2, 3]", &priors, Path::new("/study"));
        let names = |dof| -> Vec<String> {
            let settings = sweep.settings(dof).unwrap();
            settings.priors.into_iter().map(|p| p.name).collect()
        };
        assert!(names(1).is_empty() && names(2).is_empty());
        assert_eq!(names(3), ["k2"]);
        let unknown = format!("{CASE}\n[priors]\nm9 = \"none\"");
        let err = study("dof = [1, 2, 3]", &unknown, Path::new("/study"))
            .settings(2)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("/study/study.toml: [priors] m9: no such estimated parameter; known for the 2-DOF model: total_mass, m1, m2, c1, k1"),
            "{err}"
        );
        let fixed = study(
            "dof = 2\nfixed = { k1 = 5e5 }",
            &priors.replace("k2", "k1"),
            Path::new("/study"),
        );
        let err = fixed.settings(2).unwrap_err().to_string();
        assert!(
            err.ends_with("[priors] k1: fixed ([model] fixed): a fixed parameter is not estimated and takes no prior; known for the 2-DOF model: total_mass, m1, m2, c1"),
            "{err}"
        );
    }

    #[test]
    fn a_start_that_fits_no_model_is_an_error() {
        let base = Path::new("/study");
        let start = "[model.start]\nmasses = [1.0, 2.0]\ndampers = [3.0]\nsprings = [4.0]";
        let fits = study(&format!("dof = [2, 3]\n{start}"), CASE, base);
        assert_eq!(
            fits.settings(2).unwrap().start,
            Some(vec![1.0, 2.0, 3.0, 4.0])
        );
        assert_eq!(fits.settings(3).unwrap().start, None);
        let wrong = study(&format!("dof = 3\n{start}"), CASE, base);
        let err = wrong.settings(3).unwrap_err().to_string();
        assert!(
            err.contains("start: 2 masses") && err.contains("3-DOF model needs 3, 2, 2"),
            "{err}"
        );
        let ragged = "[model.start]\nmasses = [1.0, 2.0]\ndampers = [3.0, 1.0]\nsprings = [4.0]";
        assert!(matches!(
            study(&format!("dof = 2\n{ragged}"), CASE, base).settings(2),
            Err(StudyError::Start { dampers: 2, .. })
        ));
    }

    #[test]
    fn a_case_keeps_the_notes_of_its_channel_selection() {
        let dir = ev5("notes");
        let loaded = study("dof = 1", CASE, &dir).load(1).unwrap();
        let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
        assert_eq!(
            notes,
            ["case 'a': '0-LC-*-XG': left out channel 2 (0-LC-WALX-XG): marked invalid"]
        );
        let case = &loaded.cases[0];
        assert!(case.start.abs() < 1e-12, "{}", case.start);
        assert_eq!(case.force.len(), 150);
        // the invalid cell (5× the force) is not in the sum; the scale applies
        let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(*f));
        approx::assert_relative_eq!(peak, 1e4, max_relative = 1e-3);
        approx::assert_relative_eq!(
            case.measured[25],
            2.0 * 1e-5 * case.force[25],
            max_relative = 1e-9
        );
        assert_eq!(study("dof = 1", CASE, &dir).cases(1).unwrap(), loaded.cases);
    }

    #[test]
    fn a_window_in_seconds_takes_the_samples_inside() {
        let dir = ev5("window");
        let windowed = |w: &str| study("dof = 1", &format!("{CASE}\nwindow = {w}"), &dir).load(1);
        assert_eq!(
            windowed("[0.001, 0.005]").unwrap().cases[0].window,
            (10, 50)
        );
        // a start in the pre-trigger is the replay's start, t = 0
        assert_eq!(
            windowed("[-0.005, 0.00505]").unwrap().cases[0].window,
            (0, 50)
        );
        for empty in ["[-0.005, -0.002]", "[0.00101, 0.00109]"] {
            let err = windowed(empty).unwrap_err();
            assert!(
                matches!(
                    err,
                    StudyError::Case {
                        source: DefinitionError::EmptyWindow { .. },
                        ..
                    }
                ),
                "{empty}: {err}"
            );
        }
        // a window reaching past the record (-0.005 s to 0.0149 s) is
        // refused by the file, the case and the key with the record's span,
        // as a bias window is (it was cut to the record without a word)
        for (beyond, given) in [
            ("[0.0, 1e300]", "[0, 1e300]"),
            ("[0.001, 0.5]", "[0.001, 0.5]"),
            ("[-1.0, 0.005]", "[-1, 0.005]"),
            ("[0.5, 0.6]", "[0.5, 0.6]"),
        ] {
            let err = windowed(beyond).unwrap_err().to_string();
            assert!(
                err.contains(&format!("study.toml: [[case]] 'a': window = {given}: expected times within the record of the case's channels, -0.005000 s to 0.01490 s (0.01990 s long")),
                "{beyond}: {err}"
            );
        }
        assert_eq!(
            windowed("[0.001, 0.01495]").unwrap().cases[0].window,
            (10, 149)
        );
        let err = windowed("\"somewhere\"").unwrap_err().to_string();
        assert!(err.contains("case 'a': window 'somewhere'"), "{err}");
    }

    /// A CFC class positive and finite but outside what the channel's
    /// 10 kHz sample rate allows (from 0.0048 to below 2407) is refused on
    /// loading, naming the study file, the case and `cfc`; one inside loads.
    #[test]
    fn a_cfc_class_beyond_the_sample_rate_is_refused_naming_the_file() {
        let dir = ev5("cfc-rate");
        let with = |class: &str| study("dof = 1", &format!("{CASE}\ncfc = {class}"), &dir).load(1);
        for class in ["1e-308", "1e-5", "1e6"] {
            let err = with(class).unwrap_err().to_string();
            assert!(
                err.contains("study.toml: [[case]] 'a': cfc = ")
                    && err.contains("expected a class from 0.004813 to below 2407"),
                "{class}: {err}"
            );
        }
        assert!(with("180").is_ok());
    }
}
