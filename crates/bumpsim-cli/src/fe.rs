//! `bumpsim fe`: argument conversion and output around bumpsim-fe (the
//! bumper mesh coupled to the MSD car, run in CalculiX).

use crate::{Folder, write};
use anyhow::{Context, Result};
use bumpsim_core::units::{Dimension, format_quantity, parse_quantity};
use bumpsim_fe::bumper::BumperMesh;
use bumpsim_fe::run::{FeRun, run as run_fe};
use bumpsim_impact::impact::Scenario;
use bumpsim_io::car::Car;
use std::path::PathBuf;

/// The `fe` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Run a bumper mesh coupled to the MSD car in CalculiX: barrier or pendulum impact.
    Impact(ImpactArgs),
}

/// Arguments of `bumpsim fe impact`.
#[derive(Debug, clap::Args)]
pub struct ImpactArgs {
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
    /// Folder for the deck and CalculiX's files (kept for inspection).
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
    }
}

fn time(option: &str, text: &Option<String>) -> Result<Option<f64>> {
    text.as_deref()
        .map(|t| parse_quantity(t, Dimension::Time).with_context(|| format!("--{option} '{t}'")))
        .transpose()
}

fn impact(args: &ImpactArgs) -> Result<()> {
    let car = Car::read_model_file(&args.car)?;
    let mesh = BumperMesh::read(&args.bumper)?;
    let speed = parse_quantity(&args.speed, Dimension::Velocity)
        .with_context(|| format!("--speed '{}'", args.speed))?;
    let scenario = match args.pendulum {
        Some(mass) => Scenario::Impactor { mass, speed },
        None => Scenario::Barrier { speed },
    };
    let mut settings = FeRun::new(mesh, car.model.clone(), scenario, args.work.clone());
    settings.increment = time("increment", &args.increment)?;
    settings.duration = time("duration", &args.duration)?;
    settings.solver = args.solver.clone();
    println!("running CalculiX in {} ...", args.work.display());
    let fe = run_fe(&settings)?;
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
        args.bumper.display()
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
        let title = format!("FE: {} — {label}", args.bumper.display());
        let (html, figures) = bumpsim_report::impact::impact_report(&title, &summary, r)?;
        Folder::report(dir, &html, &figures)?;
    }
    Ok(())
}
