//! `bumpsim identify` and `bumpsim predict`: argument conversion around the
//! engine's requests (`bumpsim_engine::identify`, `bumpsim_engine::predict`),
//! whose outcome is printed and written.

use anyhow::Result;
use bumpsim_engine::PosteriorOptions;
use bumpsim_ident::dofs::DofList;
use bumpsim_io::kind::{ModelKind, Role};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

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

/// Runs `identify`: one library request of the study's kind
/// (bumpsim_io::kind), its progress on bars and its text as it comes.
pub fn run(args: &Args) -> Result<()> {
    let kind = ModelKind::of_path(&args.study, Role::Study)?;
    let sizes = args.dof.as_deref().map(parse_dofs).transpose()?;
    let bars = Bars {
        quiet: args.quiet,
        bar: Mutex::new(None),
        streamed: AtomicBool::new(false),
    };
    let request = bumpsim_engine::IdentifyRequest {
        study: &args.study,
        starts: args.starts,
        seed: args.seed,
        report: args.report.is_some(),
        posterior: args.posterior.then_some(PosteriorOptions {
            walkers: args.walkers,
            steps: args.steps,
        }),
        sizes: sizes.as_deref(),
        sensitivity: args.sensitivity.is_some(),
        car: args.car.is_some(),
        progress: &bars,
    };
    let outcome = bumpsim_engine::identify(kind, &request)?;
    let files = crate::output::Written {
        json: args.json.as_deref(),
        csv: args.sensitivity.as_deref(),
        report: args.report.as_deref(),
        car: args.car.as_deref(),
        ..Default::default()
    };
    let failure = outcome.failure.clone();
    // the text was printed as it came (Bars::text)
    let printed = match bars.streamed() {
        true => String::new(),
        false => outcome.text.clone(),
    };
    crate::output::outcome(
        bumpsim_engine::Outcome {
            text: printed,
            ..outcome
        },
        &files,
    )?;
    if let Some(failure) = failure {
        // the others' results are complete: they are delivered, then the exit is 2
        crate::output::commit()?;
        anyhow::bail!(failure);
    }
    Ok(())
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

/// The progress of an identification on the terminal: a bar per stage
/// (a model size's starts, the posterior's steps), the text printed as it
/// comes, a failed size said on standard error.
struct Bars {
    quiet: bool,
    bar: Mutex<Option<ProgressBar>>,
    /// Whether any text was printed as it came.
    streamed: AtomicBool,
}

impl Bars {
    /// Whether the request printed its text as it came (the chain's does).
    fn streamed(&self) -> bool {
        self.streamed.load(Ordering::Relaxed)
    }

    fn bar(&self) -> Option<ProgressBar> {
        self.bar.lock().unwrap_or_else(|p| p.into_inner()).clone()
    }
}

impl bumpsim_engine::Progress for Bars {
    fn begin(&self, starts: u64) {
        let bar = match self.quiet {
            true => ProgressBar::hidden(),
            false => ProgressBar::new(starts),
        };
        *self.bar.lock().unwrap_or_else(|p| p.into_inner()) = Some(bar);
    }

    fn stage(&self, name: &str, count: u64, unit: &str) {
        self.begin(count);
        if let Some(bar) = self.bar() {
            let template = format!("{{msg}} [{{bar:30}}] {{pos}}/{{len}} {unit} ({{elapsed}})");
            let style =
                ProgressStyle::with_template(&template).unwrap_or(ProgressStyle::default_bar());
            bar.set_style(style.progress_chars("=> "));
            bar.set_message(name.to_string());
        }
    }

    fn start_finished(&self) {
        if let Some(bar) = self.bar() {
            bar.inc(1);
        }
    }

    fn end(&self) {
        if let Some(bar) = self.bar.lock().unwrap_or_else(|p| p.into_inner()).take() {
            bar.finish_and_clear();
        }
    }

    fn text(&self, text: &str) {
        self.streamed.store(true, Ordering::Relaxed);
        print!("{text}");
    }

    fn part_failed(&self, why: &str) {
        eprintln!("error: {why}");
    }
}
