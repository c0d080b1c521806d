//! `bumpsim`: the command-line front end. It converts arguments and files
//! into calls of the library crates and prints their results; it holds no
//! computation of its own.
//!
//! Exit codes: 0 success; 2 for anything the user can fix (bad arguments,
//! unreadable or invalid files, a model the chosen method cannot run).

mod doe;
mod export;
mod identify;
mod impact;
mod signal;
mod simulate;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::path::Path;
use std::process::ExitCode;

/// Low-speed bumper impact toolkit: MSD car models from crash tests.
#[derive(Debug, Parser)]
#[command(name = "bumpsim", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Simulate an MSD car model under a measured or synthetic force on m1.
    Simulate(simulate::Args),
    /// Identify one MSD car model from several load cases (the main job).
    Identify(identify::Args),
    /// Simulate load cases of a study with an identified model and report the fit (validation).
    Predict(identify::PredictArgs),
    /// Simulate an impact: pendulum or barrier, bumper characteristic, MSD car.
    Impact(impact::ImpactArgs),
    /// Make a synthetic pendulum test series (ISO-MME and CSV) with a measurement chain.
    Synth(impact::SynthArgs),
    /// The reduced point mass of paper A: scale factor of a rigid test vehicle.
    MassReduction(impact::ReductionArgs),
    /// Design of Experiments: designs, regression, prediction, stiffness, reachable region.
    #[command(subcommand)]
    Doe(doe::Command),
    /// Crash-test signals: channel tables, export with filters, processing pipelines.
    #[command(subcommand)]
    Signal(signal::Command),
    /// Export the car model to FE solver decks (LS-DYNA, CalculiX/Abaqus).
    #[command(subcommand)]
    Export(export::Command),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Simulate(args) => simulate::run(&args),
        Command::Export(command) => export::run(&command),
        Command::Signal(command) => signal::run(&command),
        Command::Identify(args) => identify::run(&args),
        Command::Impact(args) => impact::run_impact(&args),
        Command::MassReduction(args) => impact::run_reduction(&args),
        Command::Synth(args) => impact::run_synth(&args),
        Command::Doe(command) => doe::run(&command),
        Command::Predict(args) => identify::run_predict(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {}", message(&error));
            ExitCode::from(2)
        }
    }
}

/// Writes a text output file (creating its folder) and says so.
pub(crate) fn write(path: &Path, text: &str) -> Result<()> {
    bumpsim_io::table::create_parent(path)
        .with_context(|| format!("cannot create the folder of {}", path.display()))?;
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The error and its causes, each cause once: library errors often already
/// quote their source in their own message.
fn message(error: &anyhow::Error) -> String {
    let mut text = error.to_string();
    for cause in error.chain().skip(1) {
        let cause = cause.to_string();
        if !text.contains(&cause) {
            text = format!("{text}: {cause}");
        }
    }
    text
}
