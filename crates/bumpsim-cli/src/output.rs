//! Every file and folder the commands write, in one place: the inputs are
//! registered and each output checked against them before a command runs
//! ([`guard_paths`]); single files are written atomically ([`write()`]),
//! multi-file folders are staged and appear together ([`Folder`]); and all
//! outputs of one command are one transaction ([`commit`], [`abandon`]):
//! they appear together when the command has succeeded, or none does. The
//! guard itself lives in [`bumpsim_io::output`]; this module maps clap's
//! arguments onto it.

use anyhow::{Context, Result};
use bumpsim_io::output::Shape;
use std::path::Path;
use std::sync::Mutex;

/// The `wrote ...` lines of the command's outputs, printed once they are
/// in place.
static WROTE: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Says that an output was written (printed by [`commit`], when it is).
pub(crate) fn wrote(line: String) {
    WROTE.lock().unwrap_or_else(|p| p.into_inner()).push(line);
}

/// Ends the command's transaction: checks every output once more, prints
/// what was written and moves it all into place.
pub(crate) fn commit() -> Result<()> {
    bumpsim_io::output::check_pending().context("no output was written")?;
    let lines = std::mem::take(&mut *WROTE.lock().unwrap_or_else(|p| p.into_inner()));
    lines.iter().for_each(|line| println!("{line}"));
    bumpsim_io::output::finish().context("the outputs could not all be moved into place")?;
    Ok(())
}

/// Drops the command's outputs (it failed); returns how many there were.
pub(crate) fn abandon() -> usize {
    if let Ok(mut lines) = WROTE.try_lock() {
        lines.clear();
    }
    bumpsim_io::output::abandon()
}

/// Argument ids that name outputs; the rest that exist on disk are inputs.
const OUTPUT_IDS: [&str; 11] = [
    "output",
    "car_out",
    "work",
    "json",
    "csv",
    "sensitivity",
    "report",
    "plot",
    "iso_mme",
    "html",
    "export_dir",
];

/// What the output of argument `id` is: folders (`output` only for
/// `synth` and `campaign init`) with the kinds of file they write.
fn output_shape(command: &str, id: &str) -> Shape {
    match id {
        "report" | "plot" => Shape::Folder(&["html", "svg", "png"]),
        "iso_mme" => Shape::Folder(&[]),
        // fe impact checks its own solver files' names (bumpsim_fe::run::in_work)
        "work" | "export_dir" => Shape::Checked,
        "output" if matches!(command, "synth" | "init") => Shape::Folder(&[]),
        _ => Shape::File,
    }
}

/// The command-line option of an output argument id (`iso_mme`:
/// `--iso-mme`), as a refusal names it.
fn option_name(id: &str) -> String {
    match id {
        "car_out" => "--car".into(),
        other => format!("--{}", other.replace('_', "-")),
    }
}

/// The result files of a simulation command (`impact`, `planar`).
#[derive(Debug, clap::Args)]
pub(crate) struct ResultFiles {
    /// Write the results (and histories) as JSON.
    #[arg(long)]
    pub json: Option<std::path::PathBuf>,
    /// Write the time histories as CSV (SI).
    #[arg(long)]
    pub csv: Option<std::path::PathBuf>,
    /// Write SVG plots and an HTML report into this folder.
    #[arg(long)]
    pub report: Option<std::path::PathBuf>,
}

impl ResultFiles {
    /// The files asked for, as [`outcome`] writes them.
    pub(crate) fn written(&self) -> Written<'_> {
        Written {
            json: self.json.as_deref(),
            csv: self.csv.as_deref(),
            report: self.report.as_deref(),
            ..Written::default()
        }
    }
}

/// Where a request's outcome goes: each file or folder asked for.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Written<'a> {
    /// The JSON document (`--json`).
    pub json: Option<&'a Path>,
    /// The histories (`--csv`).
    pub csv: Option<&'a Path>,
    /// The report folder (`--report`).
    pub report: Option<&'a Path>,
    /// The identified car (`identify --car`).
    pub car: Option<&'a Path>,
    /// The plots' folder (`predict --plot`).
    pub plot: Option<&'a Path>,
}

/// Prints a library request's outcome (its text, then its warnings, counted
/// for `--strict` with those the text printed) and writes the files asked for.
pub(crate) fn outcome(outcome: bumpsim_engine::Outcome, files: &Written) -> Result<()> {
    print!("{}", outcome.text);
    crate::count_warnings(outcome.printed_warnings);
    outcome.warnings.iter().for_each(|w| crate::warn(w));
    if let Some(path) = files.json {
        write(path, &outcome.json)?;
    }
    if let Some(path) = files.csv {
        write(path, &outcome.csv)?;
    }
    if let (Some(path), Some(car)) = (files.car, &outcome.car) {
        write(path, car)?;
    }
    if let (Some(dir), Some(report)) = (files.report, outcome.report) {
        let json = (outcome.json, files.json);
        let inputs: Vec<&Path> = report.inputs.iter().map(|p| p.as_path()).collect();
        Folder::viewed_report(dir, &report.html, report.figures, json, &inputs)?;
    }
    if let Some(dir) = files.plot {
        let folder = Folder::stage(dir)?;
        for (name, svg) in &outcome.plots {
            folder.write(name, svg)?;
        }
        folder.commit()?;
    }
    Ok(())
}

/// Argument ids that name one input file, never a folder, with what the
/// file is: a folder given there is refused as such before the outputs are
/// checked (`identify . --json r.json` said "refusing to write inside the
/// input folder ." instead of naming the study).
const FILE_IDS: [(&str, &str); 10] = [
    ("study", "the study (a TOML file)"),
    ("pipeline", "the pipeline (a TOML file)"),
    ("series", "the series (a TOML file)"),
    ("car", "the car (a TOML or JSON file)"),
    ("bumper", "the bumper (a TOML file)"),
    ("model", "the model (a TOML or JSON file)"),
    ("uncertainty", "the uncertainty (a TOML or JSON file)"),
    ("force", "the force (a CSV file)"),
    ("data", "the data (a CSV file)"),
    ("campaign", "the campaign (a TOML file)"),
];

/// Refuses a folder given where one input file is read (see [`FILE_IDS`]).
fn refuse_folder(id: &str, path: &Path) -> Result<()> {
    match FILE_IDS.iter().find(|(known, _)| *known == id) {
        Some((_, what)) if path.is_dir() => {
            anyhow::bail!("{}: is a folder; {what} must be a file", path.display())
        }
        _ => Ok(()),
    }
}

/// Refuses an input that is a device, pipe or socket (`/dev/zero` never
/// ends, a pipe without a writer blocks forever): no command reads a stream.
fn refuse_stream(path: &Path) -> Result<()> {
    match bumpsim_core::files::not_a_file(path) {
        Ok(Some(kind)) if kind != "a folder" => {
            let path = path.into();
            Err(bumpsim_core::files::ReadError::NotAFile { path, kind }.into())
        }
        _ => Ok(()),
    }
}

/// Registers the inputs and checks every output before anything runs.
pub(crate) fn guard_paths(matches: &clap::ArgMatches) -> Result<()> {
    let mut matches = matches;
    let mut command = String::new();
    let campaign = matches.subcommand_name() == Some("campaign");
    while let Some((name, sub)) = matches.subcommand() {
        command = name.to_string();
        matches = sub;
    }
    let values = |id: &str| -> Vec<std::path::PathBuf> {
        matches
            .get_raw(id)
            .into_iter()
            .flatten()
            .map(std::path::PathBuf::from)
            .collect()
    };
    let ids: Vec<String> = matches.ids().map(|id| id.to_string()).collect();
    for id in ids.iter().filter(|id| !OUTPUT_IDS.contains(&id.as_str())) {
        for path in values(id).iter().filter(|p| p.exists()) {
            refuse_stream(path)?;
            refuse_folder(id, path)?;
            // a study, series or pipeline names further inputs (tests, cars)
            match campaign {
                true => bumpsim_io::output::register_input(path),
                false => bumpsim_io::output::register_input_with_references(path),
            }
        }
    }
    for id in ids.iter().filter(|id| OUTPUT_IDS.contains(&id.as_str())) {
        for path in values(id) {
            let shape = output_shape(&command, id);
            bumpsim_io::output::claim_output_as(&path, &option_name(id), shape)?;
            match shape {
                Shape::Folder(kinds) => {
                    bumpsim_io::output::check_folder_of(&path, &option_name(id), kinds)?
                }
                Shape::Checked => bumpsim_io::output::check_folder(&path)?,
                Shape::File => bumpsim_io::output::check_file(&path)?,
            }
        }
    }
    Ok(())
}

/// Writes a text output file (creating its folder; atomically, never over
/// an input) and says so.
pub(crate) fn write(path: &Path, text: &str) -> Result<()> {
    bumpsim_io::output::write_file(path, text.as_bytes())?;
    wrote(format!("wrote {}", path.display()));
    Ok(())
}

/// A multi-file output folder: files are staged and appear together on
/// [`Folder::commit`]; a run that fails before leaves the old folder as it was.
pub(crate) struct Folder(bumpsim_io::output::StagedFolder);

impl Folder {
    /// Opens the staging for `dir`.
    pub(crate) fn stage(dir: &Path) -> Result<Folder> {
        Ok(Folder(bumpsim_io::output::stage_folder(dir)?))
    }

    /// The staging folder (for library writers that take a folder).
    pub(crate) fn path(&self) -> &Path {
        self.0.path()
    }

    /// Stages one file.
    pub(crate) fn write(&self, name: &str, text: &str) -> Result<()> {
        let path = self.0.write(name, text.as_bytes())?;
        wrote(format!("wrote {}", path.display()));
        Ok(())
    }

    /// Stages the report page and its figures (file name, SVG) and moves
    /// them into `dir` together.
    pub(crate) fn report(dir: &Path, html: &str, figures: &[(String, String)]) -> Result<()> {
        let folder = Folder::stage(dir)?;
        for (name, svg) in figures {
            folder.write(name, svg)?;
        }
        folder.write("index.html", html)?;
        folder.commit()
    }

    /// [`Folder::report`] whose figures name the viewer's command: the
    /// run's result, the `--json` file when one was written (`written`),
    /// else a copy kept beside the page as `result.json`, and the `inputs`
    /// the viewer also needs (a study's tests).
    pub(crate) fn viewed_report(
        dir: &Path,
        html: &str,
        mut figures: Vec<(String, String)>,
        (json, written): (String, Option<&Path>),
        inputs: &[&Path],
    ) -> Result<()> {
        let result = match written {
            Some(path) => path.to_path_buf(),
            None => {
                figures.push(("result.json".into(), json));
                dir.join("result.json")
            }
        };
        let files: Vec<String> = std::iter::once(result.as_path())
            .chain(inputs.iter().copied())
            .map(|f| f.display().to_string())
            .collect();
        let html = bumpsim_report::html::with_viewer(html, &files);
        Folder::report(dir, &html, &figures)
    }

    /// Hands the complete folder to the command's transaction (it moves
    /// into place with the command's other outputs).
    pub(crate) fn commit(self) -> Result<()> {
        bumpsim_io::output::commit(self.0)
            .with_context(|| "the output folder was left as it was".to_string())
    }
}
