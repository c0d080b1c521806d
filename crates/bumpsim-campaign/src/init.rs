//! `campaign init`: the design, one folder per point with its rendered deck,
//! the task script and the state file, in a new campaign folder:
//!
//! ```text
//! DIR/campaign.toml   the campaign file (a copy; `run`, `status`, `collect` read it)
//! DIR/design.csv      the design table (doe design's format)
//! DIR/run-point.sh    runs the solver of one point and records its exit status
//! DIR/points/0001/    the rendered deck and copied files of run 1, ...
//! DIR/state.journal  the state of every point (crate::state)
//! ```
//!
//! Everything is checked first (campaign file, template placeholders,
//! solver on PATH); the folder is staged and appears whole
//! ([`crate::staging`]: its files flushed to disk with one `sync -f` of
//! the file system rather than one `fsync` each, which at 100 000 points
//! is the difference between seconds and minutes; each point's input hash
//! taken from the bytes written, not read back).
//! Re-initialising over an existing campaign keeps the state of every
//! point whose inputs are unchanged (same hash), so a finished point is
//! never run again; a damaged state is refused (`campaign repair` first).

use crate::error::{CampaignError, Result};
use crate::lock::Lock;
use crate::spec::{MAX_POINTS, Spec, find_program};
use crate::staging::Staging;
use crate::state::{
    LEGACY_STATE_FILE, Point, STATE_FILE, State, Status, hash_inputs, point_folder,
};
use crate::task::{TASK_SCRIPT, task_script};
use crate::template::{Template, lsdyna_parameters};
use bumpsim_doe::design;
use bumpsim_io::output::Outputs;
use std::path::{Path, PathBuf};

/// The copy of the campaign file in the campaign folder.
pub const SPEC_FILE: &str = "campaign.toml";

/// One design point's values.
#[derive(Debug, Clone, PartialEq)]
pub struct PointValues {
    /// Standard order (1-based).
    pub standard: usize,
    /// Coded factor levels.
    pub coded: Vec<f64>,
    /// Factor and derived values by name, factors first.
    pub values: Vec<(String, f64)>,
}

/// What `init` did.
#[derive(Debug, Clone, PartialEq)]
pub struct InitSummary {
    /// Points of the design.
    pub points: usize,
    /// Points kept from an earlier state: done or in flight, inputs unchanged.
    pub kept: usize,
    /// The design's resolution (fractions).
    pub resolution: Option<usize>,
}

/// The design points of `spec` in run order, with derived values.
pub fn points(spec: &Spec, path: &Path) -> Result<(Vec<PointValues>, Option<usize>)> {
    let names: Vec<String> = spec.factor_names();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let (d, resolution) = design::make(spec.design_kind(path)?, &refs, &spec.design_options())?;
    if d.runs.len() > MAX_POINTS {
        return Err(CampaignError::Invalid {
            path: path.into(),
            key: "design".into(),
            message: format!(
                "{} points: at most {MAX_POINTS} (docs/limits.md)",
                d.runs.len()
            ),
        });
    }
    let derived = spec.derived_order(path)?;
    let order = d.order(spec.design.randomise, spec.design.seed);
    let mut out = Vec::with_capacity(order.len());
    for &i in &order {
        let coded = d.runs[i].clone();
        let mut values: Vec<(String, f64)> = spec
            .design
            .factors
            .iter()
            .zip(&coded)
            .map(|(f, z)| (f.name.clone(), f.physical(*z)))
            .collect();
        for (name, expr) in &derived {
            let lookup = |n: &str| values.iter().find(|(k, _)| k == n).map(|(_, v)| *v);
            let value = expr.eval(&lookup).map_err(|e| CampaignError::Invalid {
                path: path.into(),
                key: format!("derived.{name}"),
                message: format!("run {}: {e}", out.len() + 1),
            })?;
            values.push((name.clone(), value));
        }
        out.push(PointValues {
            standard: i + 1,
            coded,
            values,
        });
    }
    Ok((out, resolution))
}

/// The input files of a point (hashed): the deck, copied files, the parameter include.
pub fn input_files(spec: &Spec) -> Vec<String> {
    spec.point_files()
        .into_iter()
        .map(|(name, _)| name)
        .collect()
}

/// Checks that the solver's program can be found (relative paths from `dir`).
pub fn check_solver(spec: &Spec, dir: &Path) -> Result<PathBuf> {
    let program = &spec.solver.command[0];
    find_program(program, dir).ok_or_else(|| CampaignError::Program {
        what: "solver".into(),
        program: program.clone(),
        hint: "install it, load its module, or give its full path in solver.command".into(),
    })
}

/// Creates (or refreshes) campaign folder `dir` from campaign file `path`.
pub fn init(path: &Path, dir: &Path) -> Result<InitSummary> {
    let spec = Spec::read(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let templates = read_templates(&spec, base)?;
    check_solver(&spec, base)?;
    let (points, resolution) = points(&spec, path)?;
    // re-initialising a campaign: not while a controller runs it
    let campaign = dir.join(STATE_FILE).exists() || dir.join(LEGACY_STATE_FILE).exists();
    let _lock = match campaign {
        true => Some(Lock::acquire(dir)?),
        false => None,
    };
    // a damaged state is refused: `repair` keeps what it knows, init would not
    let old = State::existing(dir)?;
    let mut guard = Outputs::new();
    guard.input(path);
    guard.input(&base.join(&spec.template.file));
    if let Some(identify) = &spec.identify {
        guard.input(&base.join(&identify.study));
    }
    let mut staged = Staging::new(&guard, dir)?;
    let campaign_text = std::fs::read(path).map_err(|e| crate::error::read_error(path, e))?;
    staged.write(SPEC_FILE, &campaign_text)?;
    staged.write("design.csv", design_csv(&spec, &points).as_bytes())?;
    staged.write(TASK_SCRIPT, task_script(&spec.solver.command).as_bytes())?;
    let templates = (&templates.0, templates.1.as_ref());
    let state = stage_points(&mut staged, &spec, base, templates, &points, old.as_ref())?;
    let kept = state
        .points
        .iter()
        .filter(|p| p.status != Status::Pending)
        .count();
    staged.commit(&guard)?;
    Ok(InitSummary {
        points: points.len(),
        kept,
        resolution,
    })
}

/// The deck template and the optional study template, their placeholders checked.
fn read_templates(spec: &Spec, base: &Path) -> Result<(Template, Option<Template>)> {
    let mut known = spec.factor_names();
    known.extend(spec.derived.keys().cloned());
    let template = Template::read(&base.join(&spec.template.file))?;
    template.check(&known)?;
    let study = match &spec.identify {
        Some(identify) => {
            let study = Template::read(&base.join(&identify.study))?;
            study.check(&known)?;
            Some(study)
        }
        None => None,
    };
    Ok((template, study))
}

/// Writes every point folder into the staging and the state beside them
/// (last: over an existing campaign it is moved into place last).
fn stage_points(
    staged: &mut Staging,
    spec: &Spec,
    base: &Path,
    templates: (&Template, Option<&Template>),
    points: &[PointValues],
    old: Option<&State>,
) -> Result<State> {
    let mut state = State::new(&spec.name, Vec::with_capacity(points.len()));
    let copied = copied_files(spec, base)?;
    staged.folder("points")?;
    for (i, p) in points.iter().enumerate() {
        let folder = point_folder(i + 1);
        let files = point_files(spec, templates, &copied, p, i + 1);
        staged.folder(&folder)?;
        for (name, bytes) in &files {
            staged.write(&format!("{folder}/{name}"), bytes)?;
        }
        let named = files.iter().map(|(n, b)| (n.as_str(), b.as_slice()));
        let hash = hash_inputs(named, &spec.solver.command);
        state.points.push(carry_over(old, i + 1, hash));
    }
    let snapshot = state.snapshot(staged.target())?;
    staged.write(STATE_FILE, snapshot.as_bytes())?;
    Ok(state)
}

/// The files copied unchanged into each point folder: (name, contents).
fn copied_files(spec: &Spec, base: &Path) -> Result<Vec<(String, Vec<u8>)>> {
    let mut copied = Vec::with_capacity(spec.template.files.len());
    for file in &spec.template.files {
        let source = base.join(file);
        let bytes = std::fs::read(&source).map_err(|e| crate::error::read_error(&source, e))?;
        let name = file
            .file_name()
            .map_or("file".into(), |n| n.to_string_lossy().into_owned());
        copied.push((name, bytes));
    }
    Ok(copied)
}

/// The point's state: an earlier done or in-flight point with the same
/// input hash is kept (its task may still be running: it is adopted, not
/// started twice), anything else starts pending.
fn carry_over(old: Option<&State>, run: usize, hash: String) -> Point {
    let keep =
        |p: &&Point| p.input_hash == hash && (p.status == Status::Done || p.status.in_flight());
    match old.and_then(|s| s.points.get(run - 1)).filter(keep) {
        Some(p) => p.clone(),
        None => Point::new(run, hash),
    }
}

/// A point's input files (name, contents) in the order of [`input_files`]:
/// the rendered deck, the copied files, the LS-DYNA parameter include,
/// the rendered study.
fn point_files(
    spec: &Spec,
    (template, study): (&Template, Option<&Template>),
    copied: &[(String, Vec<u8>)],
    p: &PointValues,
    run: usize,
) -> Vec<(String, Vec<u8>)> {
    let value = |n: &str| match n {
        "run" => Some(run as f64),
        _ => p.values.iter().find(|(k, _)| k == n).map(|(_, v)| *v),
    };
    let mut files = vec![(spec.deck_name(), template.render(&value).into_bytes())];
    files.extend(copied.iter().cloned());
    if let Some(name) = &spec.template.lsdyna_parameters {
        files.push((name.clone(), lsdyna_parameters(&p.values).into_bytes()));
    }
    if let Some(study) = study {
        let name = crate::identify::STUDY_FILE.to_string();
        files.push((name, study.render(&value).into_bytes()));
    }
    files
}

/// The design table: `run`, `standard order`, factors (physical, with
/// units), derived values, coded factors: what `doe design` writes, plus
/// units and derived columns.
pub fn design_csv(spec: &Spec, points: &[PointValues]) -> String {
    let mut csv = String::from("run,standard order");
    for name in points.first().map_or(Vec::new(), |p| {
        p.values.iter().map(|(n, _)| n.clone()).collect()
    }) {
        let unit = spec.unit_of(&name);
        csv += &match unit {
            Some(u) => format!(",{name} [{u}]"),
            None => format!(",{name}"),
        };
    }
    spec.design
        .factors
        .iter()
        .for_each(|f| csv += &format!(",{} (coded)", f.name));
    csv.push('\n');
    for (i, p) in points.iter().enumerate() {
        csv += &format!("{},{}", i + 1, p.standard);
        p.values.iter().for_each(|(_, v)| csv += &format!(",{v}"));
        p.coded.iter().for_each(|z| csv += &format!(",{z}"));
        csv.push('\n');
    }
    csv
}
