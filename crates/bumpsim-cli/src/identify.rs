//! `bumpsim identify` and `bumpsim predict`: argument conversion and output
//! around bumpsim-ident and the identification report.

use anyhow::{Context, Result};
use bumpsim_engine::sizes::{Asked, Done, Identified, Size};
use bumpsim_ident::dofs::DofList;
use bumpsim_ident::estimate::Identification;
use bumpsim_ident::posterior::{Posterior, Request};
use bumpsim_ident::sizes::{Observer, Order, Overrides, Watch};
use bumpsim_ident::study::{DofSpec, Study};
use bumpsim_ident::text::{case_lines, dof_table, parameter_table};
use bumpsim_io::kind::{ModelKind, Role};
use indicatif::{ProgressBar, ProgressStyle};
use std::cell::RefCell;
use std::path::PathBuf;

/// Arguments of `identify`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study file (TOML, see docs/identify.md).
    study: PathBuf,
    /// Number of masses: `3`, a range `1..5` or a list `1,2,3` (default: the study's).
    #[arg(long)]
    dof: Option<String>,
    /// Number of starts (default: the study's).
    #[arg(long, value_parser = crate::count::<100_000>)]
    starts: Option<usize>,
    /// Seed of the random starts (default: the study's).
    #[arg(long)]
    seed: Option<u64>,
    /// Write the result as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write SVG plots and an HTML report into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Write the ±3 % sensitivity of the objective (last DOF) as CSV.
    #[arg(long)]
    sensitivity: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Planar studies: write the identified car as a planar car file (TOML).
    #[arg(long = "car", id = "car_out")]
    car: Option<PathBuf>,
    /// Sample the posterior of the parameters (ensemble sampler, seeded by
    /// --seed): 90 % intervals next to the local ones, diagnostics, a
    /// corner plot in the report (docs/uncertainty.md). With several DOF,
    /// the recommended one.
    #[arg(long)]
    posterior: bool,
    /// Walkers of the posterior run: even, at least 2 q + 2 for q free
    /// parameters (default: the larger of that and 32).
    #[arg(long, requires = "posterior", value_parser = crate::count::<10_000>)]
    walkers: Option<usize>,
    /// Steps of the posterior run, a quarter of them burnt (default 4000).
    #[arg(long, requires = "posterior", value_parser = crate::count::<1_000_000>)]
    steps: Option<usize>,
}

/// Arguments of `predict`.
#[derive(Debug, clap::Args)]
pub struct PredictArgs {
    /// A chain study: an identification result (JSON) or car file (TOML).
    /// A planar study: a planar car file (TOML; `identify --car` writes the
    /// identified one).
    model: PathBuf,
    /// The study file that defines the load cases.
    study: PathBuf,
    /// Case names to simulate (default: all); repeatable.
    #[arg(long = "case")]
    cases: Vec<String>,
    /// Write SVG plots of measured vs simulated into this folder.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write the fits as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
}

fn parse_dofs(text: &str) -> Result<Vec<usize>> {
    let dofs: DofList = text.parse().map_err(|e| anyhow::anyhow!("--dof {e}"))?;
    Ok(dofs.0)
}

fn progress(quiet: bool, dof: usize, starts: usize) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(starts as u64);
    let style = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} starts ({elapsed})")
        .unwrap_or(ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar.set_message(format!("{dof}-DOF"));
    bar
}

/// Runs `identify`: the model is the study's kind (bumpsim_io::kind).
pub fn run(args: &Args) -> Result<()> {
    match ModelKind::of_path(&args.study, Role::Study)? {
        ModelKind::Chain => {}
        kind => return run_engine(kind, args),
    }
    if args.car.is_some() {
        anyhow::bail!("--car: only a planar study identifies a planar car (docs/planar.md)");
    }
    let mut study = Study::read(&args.study)?;
    if let Some(text) = &args.dof {
        study.model.dof = DofSpec::Many(parse_dofs(text)?);
    }
    let dofs = study.dofs();
    let request = args.posterior.then(|| Request {
        walkers: args.walkers,
        steps: args.steps,
        seed: args.seed.unwrap_or(study.model.seed),
    });
    if let Some(request) = &request {
        // a run that cannot be made is refused before the identification
        for &dof in &dofs {
            request
                .ensemble(&study.settings(dof)?)
                .map_err(|e| anyhow::anyhow!("--{e}"))?;
        }
    }
    let overrides = Overrides {
        starts: args.starts,
        seed: args.seed,
    };
    let watch = Printed {
        quiet: args.quiet,
        many: dofs.len() > 1,
        bar: RefCell::new(None),
    };
    let sizes = bumpsim_ident::sizes::identify(&study, &overrides, &watch)?;
    let identified = Identified::of(sizes);
    if let (false, Some(Size::Failed { dof, error })) = (watch.many, identified.sizes.first()) {
        return Err(error.clone()).context(format!("{dof}-DOF identification"));
    }
    let results = identified.results();
    if results.len() > 1 {
        println!("\n{}", dof_table(&results));
    }
    let posterior = match &request {
        Some(request) => sample_posterior(args.quiet, &identified.done(), request)?,
        None => None,
    };
    // the ±3 % sweep (91 simulations per case) only when it is written
    let sweeps = match args.sensitivity.is_some() || args.report.is_some() {
        true => identified.sweeps()?,
        false => None,
    };
    let asked = Asked {
        study: &args.study,
        starts: args.starts.unwrap_or(study.model.starts),
        seed: args.seed.unwrap_or(study.model.seed),
        report: args.report.is_some(),
    };
    let posterior = posterior.as_ref().map(|(p, r)| (p, *r));
    let outcome = identified.outcome(&asked, sweeps.as_deref(), posterior)?;
    let files = crate::output::Written {
        json: args.json.as_deref(),
        csv: args.sensitivity.as_deref(),
        report: args.report.as_deref(),
        ..Default::default()
    };
    crate::output::outcome(outcome, &files)?;
    let failed: Vec<String> = identified
        .failed()
        .iter()
        .map(|f| f.dof.to_string())
        .collect();
    if !failed.is_empty() {
        // the others' results are complete: they are delivered, then the exit is 2
        crate::output::commit()?;
        anyhow::bail!(
            "{} of the {} models failed (DOF {}, see above); the others are reported",
            failed.len(),
            identified.sizes.len(),
            failed.join(", ")
        );
    }
    Ok(())
}

/// The identification over the sizes as the terminal shows it: notes,
/// a progress bar per size, each result as it is done.
struct Printed {
    quiet: bool,
    many: bool,
    bar: RefCell<Option<ProgressBar>>,
}

impl Watch for Printed {
    fn loaded(&self, notes: &[String], warnings: &[String]) {
        print_notes(notes);
        warnings.iter().for_each(|w| crate::warn(w));
    }

    fn starting(&self, dof: usize, starts: usize) -> Box<dyn Observer + '_> {
        let bar = progress(self.quiet, dof, starts);
        *self.bar.borrow_mut() = Some(bar.clone());
        Box::new(move || bar.inc(1))
    }

    fn done(&self, order: &Order) {
        if let Some(bar) = self.bar.borrow_mut().take() {
            bar.finish_and_clear();
        }
        match &order.result {
            Ok(result) => print_result(result),
            Err(e) if self.many => {
                eprintln!(
                    "error: {}-DOF model: {e} (the other models go on)",
                    order.dof
                )
            }
            Err(_) => {}
        }
    }
}

/// The selection notes (channels left out or used despite a mark).
fn print_notes(notes: &[String]) {
    for note in notes {
        println!("note: {note}");
    }
}

/// The posterior of the identified order (or of the DOF table's
/// recommendation), printed; `None` when no order was identified.
fn sample_posterior<'a>(
    quiet: bool,
    done: &[&'a Done],
    request: &Request,
) -> Result<Option<(Posterior, &'a Identification)>> {
    let results: Vec<Identification> = done.iter().map(|d| d.result.clone()).collect();
    let dof = match results.as_slice() {
        [one] => Some(one.dof),
        _ => bumpsim_ident::text::recommended_dof(&results),
    };
    let Some(Done {
        result,
        cases,
        settings,
    }) = done.iter().copied().find(|d| Some(d.result.dof) == dof)
    else {
        return Ok(None);
    };
    let ensemble = request
        .ensemble(settings)
        .map_err(|e| anyhow::anyhow!("--{e}"))?;
    let bar = match quiet {
        true => ProgressBar::hidden(),
        false => ProgressBar::new(ensemble.steps as u64),
    };
    let style = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} steps ({elapsed})")
        .unwrap_or(ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar.set_message(format!("posterior {}-DOF", result.dof));
    let post = bumpsim_ident::posterior::run(cases, settings, result, request, &|| bar.inc(1));
    bar.finish_and_clear();
    let post = post.with_context(|| format!("--posterior of the {}-DOF model", result.dof))?;
    println!(
        "\n{}-DOF {}",
        result.dof,
        bumpsim_ident::posterior::lines(&post, result)
    );
    crate::count_warnings(post.diagnostics.warnings.len());
    Ok(Some((post, result)))
}

fn print_result(r: &Identification) {
    if !(r.objective.is_finite() && r.fit_percent.is_finite()) {
        crate::warn(&format!(
            "{}-DOF model: objective {} m², fit {} %: the measured data do not determine the model",
            r.dof, r.objective, r.fit_percent
        ));
    }
    let phrase = r.objective_phrase();
    let compared = match phrase.is_empty() {
        true => String::new(),
        false => format!(" ({phrase})"),
    };
    let unit = r.objective_unit();
    let unit = match unit.is_empty() {
        true => unit,
        false => format!(" {unit}"),
    };
    println!(
        "\n{}-DOF model: objective {}{unit}{compared}, fit {} %",
        r.dof,
        bumpsim_core::units::format_number(r.objective, 5),
        bumpsim_core::units::format_number(r.fit_percent, 4)
    );
    print!("{}", parameter_table(r));
    print!("{}", case_lines(r));
    if let Some(line) = bumpsim_ident::text::residuals_line(r) {
        println!("  {line}");
    }
    print!("{}", bumpsim_ident::text::prior_lines(r));
    println!("  {}", bumpsim_ident::text::starts_line(r));
    for w in &r.warnings {
        println!("  warning: {w}");
    }
    crate::count_warnings(r.warnings.len());
}

/// Runs `predict`: the car on a study of its kind, one library request
/// (the engine refuses a car and a study of different kinds).
pub fn run_predict(args: &PredictArgs) -> Result<()> {
    let request = bumpsim_engine::PredictRequest {
        car: &args.model,
        study: &args.study,
        cases: &args.cases,
        plot: args.plot.is_some(),
    };
    let files = crate::output::Written {
        json: args.json.as_deref(),
        plot: args.plot.as_deref(),
        ..Default::default()
    };
    crate::output::outcome(bumpsim_engine::predict(&request)?, &files)
}

/// A study of a model the engine identifies (the planar car's): one
/// library request, its progress on a bar.
fn run_engine(kind: ModelKind, args: &Args) -> Result<()> {
    let bar = Bar(match args.quiet {
        true => ProgressBar::hidden(),
        false => ProgressBar::new(0),
    });
    let request = bumpsim_engine::IdentifyRequest {
        study: &args.study,
        starts: args.starts,
        seed: args.seed,
        report: args.report.is_some(),
        posterior: args.posterior,
        sizes: args.dof.is_some(),
        sensitivity: args.sensitivity.is_some(),
        progress: &bar,
    };
    let files = crate::output::Written {
        json: args.json.as_deref(),
        report: args.report.as_deref(),
        car: args.car.as_deref(),
        ..Default::default()
    };
    crate::output::outcome(bumpsim_engine::identify(kind, &request)?, &files)
}

/// A progress bar of the starts.
struct Bar(ProgressBar);

impl bumpsim_engine::Progress for Bar {
    fn begin(&self, starts: u64) {
        self.0.set_length(starts);
    }

    fn start_finished(&self) {
        self.0.inc(1);
    }

    fn end(&self) {
        self.0.finish_and_clear();
    }
}
