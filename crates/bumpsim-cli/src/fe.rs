//! `bumpsim fe`: argument conversion and output around bumpsim-fe (the
//! bumper mesh coupled to the MSD car, run in CalculiX).

use crate::{Folder, write};
use anyhow::{Context, Result};
use bumpsim_core::units::{Dimension, format_quantity, parse_quantity};
use bumpsim_export::layout::UnitSystem;
use bumpsim_fe::bumper::BumperMesh;
use bumpsim_fe::run::{FeRun, run_in};
use bumpsim_impact::impact::Scenario;
use bumpsim_io::car::Car;
use std::path::PathBuf;

/// The `fe` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Run a bumper mesh coupled to the MSD car in CalculiX: barrier or pendulum impact.
    Impact(ImpactArgs),
    /// Write the same coupled model as an LS-DYNA keyword deck.
    Lsdyna(LsDynaArgs),
}

/// Arguments of `bumpsim fe lsdyna`.
#[derive(Debug, clap::Args)]
pub struct LsDynaArgs {
    #[command(flatten)]
    case: Case,
    /// The deck to write.
    #[arg(short, long, value_name = "DECK.k")]
    output: PathBuf,
    /// Deck unit system: si, mm-s-t or mm-ms-kg.
    #[arg(long, default_value = "si")]
    units: UnitSystem,
    /// Termination time: s or with a unit; default 1.3 × the estimated contact time.
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    duration: Option<String>,
    /// Interval of the history outputs: s or with a unit; default duration / 1000.
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    output_interval: Option<String>,
}

/// The car, the bumper mesh and the load case.
#[derive(Debug, clap::Args)]
pub struct Case {
    /// The car (TOML or identification JSON).
    #[arg(long)]
    car: PathBuf,
    /// The parametric bumper mesh (TOML: beam, crash boxes, materials).
    #[arg(long)]
    bumper: PathBuf,
    /// A pendulum of this mass, kg, hits the car at rest.
    #[arg(long, conflicts_with = "barrier", allow_negative_numbers = true)]
    pendulum: Option<f64>,
    /// The car hits a rigid barrier.
    #[arg(long, required_unless_present = "pendulum")]
    barrier: bool,
    /// Impact speed: m/s or with a unit ("8 km/h").
    #[arg(long)]
    speed: String,
}

impl Case {
    fn read(&self) -> Result<(Car, BumperMesh, Scenario)> {
        let car = Car::read_model_file(&self.car)?;
        let mesh = BumperMesh::read(&self.bumper)?;
        let speed = parse_quantity(&self.speed, Dimension::Velocity)
            .with_context(|| format!("--speed '{}'", self.speed))?;
        let scenario = match self.pendulum {
            Some(mass) => Scenario::Impactor { mass, speed },
            None => Scenario::Barrier { speed },
        };
        Ok((car, mesh, scenario))
    }
}

/// Arguments of `bumpsim fe impact`.
#[derive(Debug, clap::Args)]
pub struct ImpactArgs {
    #[command(flatten)]
    case: Case,
    /// Folder for the deck and CalculiX's files (kept for inspection). The run
    /// works in a hidden sibling folder that replaces this folder's files
    /// with the command's other outputs once it has succeeded.
    #[arg(long, value_name = "DIR")]
    work: PathBuf,
    /// Fixed time increment: s or with a unit; default duration / 1500.
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    increment: Option<String>,
    /// Simulated time: s or with a unit; default 1.3 × the estimated contact time.
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    duration: Option<String>,
    /// The CalculiX command.
    #[arg(long, default_value = "ccx")]
    solver: String,
    #[command(flatten)]
    files: crate::output::ResultFiles,
}

/// Runs an `fe` subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Impact(args) => impact(args),
        Command::Lsdyna(args) => lsdyna(args),
    }
}

fn time(option: &str, text: &Option<String>) -> Result<Option<f64>> {
    text.as_deref()
        .map(|t| crate::export::deck::time(option, t))
        .transpose()
}

fn impact(args: &ImpactArgs) -> Result<()> {
    let (car, mesh, scenario) = args.case.read()?;
    let mut settings = FeRun::new(mesh, car.model.clone(), scenario, args.work.clone());
    settings.increment = time("increment", &args.increment)?;
    settings.duration = time("duration", &args.duration)?;
    settings.solver = args.solver.clone();
    for path in [&args.files.json, &args.files.csv].into_iter().flatten() {
        if bumpsim_fe::run::in_work(&args.work, path) {
            anyhow::bail!(
                "{}: the run writes a file of this name in --work {}: give the output another path",
                path.display(),
                args.work.display()
            );
        }
    }
    println!("running CalculiX in {} ...", args.work.display());
    // the deck must be on disk while CalculiX runs: it runs in the staging
    // folder, which joins the command's transaction with the other outputs
    let work = Folder::stage(&args.work)?;
    let fe = run_in(&settings, work.path())?;
    let r = &fe.impact;
    let warnings = bumpsim_fe::text::warnings(&fe);
    warnings.iter().for_each(|w| crate::warn(w));
    let summary = bumpsim_fe::text::summary(&fe);
    let label = match scenario {
        Scenario::Impactor { mass, .. } => {
            format!("{} pendulum", format_quantity(mass, Dimension::Mass))
        }
        Scenario::Barrier { .. } => "rigid barrier".into(),
    };
    println!(
        "{} with {}: {label}",
        car.name.as_deref().unwrap_or("car"),
        args.case.bumper.display()
    );
    print!("{summary}");
    if let Some(path) = &args.files.json {
        write(
            path,
            &serde_json::to_string_pretty(&bumpsim_fe::text::json(&fe, &warnings))?,
        )?;
    }
    if let Some(path) = &args.files.csv {
        write(path, &bumpsim_impact::text::histories(r))?;
    }
    if let Some(dir) = &args.files.report {
        let title = format!("FE: {} — {label}", args.case.bumper.display());
        let inputs = bumpsim_fe::text::inputs(&settings, &args.case.car, &args.case.bumper);
        let notes = [bumpsim_fe::text::FORCE_AT_START];
        let (html, figures) =
            bumpsim_report::impact::impact_page(&title, &inputs, &notes, &summary, r)?;
        Folder::report(dir, &html, &figures)?;
    }
    crate::output::wrote(format!(
        "wrote {} (the deck and CalculiX's files)",
        args.work.display()
    ));
    work.commit()
}

fn lsdyna(args: &LsDynaArgs) -> Result<()> {
    let (car, mesh, scenario) = args.case.read()?;
    let duration = match time("duration", &args.duration)? {
        Some(t) => t,
        None => 1.3 * bumpsim_fe::run::equivalent(&mesh, &car.model, scenario)?.contact_time,
    };
    let run = bumpsim_fe::lsdyna::LsDynaRun {
        units: args.units,
        duration,
        output_interval: time("output-interval", &args.output_interval)?
            .unwrap_or(duration / 1000.0),
    };
    let deck = bumpsim_fe::lsdyna::lsdyna_deck(&mesh, &car.model, scenario, &run)?;
    write(&args.output, &deck)?;
    println!(
        "LS-DYNA deck of the coupled model: units {}, termination {}",
        args.units,
        format_quantity(duration, Dimension::Time)
    );
    Ok(())
}
