//! `bumpsim`: the command-line front end. It converts arguments and files
//! into calls of the library crates and prints their results; it holds no
//! computation of its own.
//!
//! Exit codes: 0 success; 2 for anything the user can fix (bad arguments,
//! unreadable or invalid files, a model the chosen method cannot run), and
//! under `--strict` for a result that failed its own checks (a warning).
//!
//! Outputs: every path on the command line that exists and is not an output
//! option is registered as an input with [`bumpsim_io::output`]; every output
//! is checked against them (and for file/folder kind) before the command
//! runs, and written atomically. The outputs of one command are one
//! transaction: they move into place together when it succeeds; a command
//! that fails (or cannot print its results) leaves every output as it was.

/// `println!` for the terminal: the text goes through
/// [`bumpsim_core::names::printable_lines`], so a name from a file (a car,
/// case, channel or test name holding `\x1b[31m`) reaches the terminal
/// escaped, whichever command prints it (issue 48 item 2). Defined before
/// the modules, it shadows the standard macro in all of them.
macro_rules! println {
    () => {
        std::println!()
    };
    ($($arg:tt)*) => {
        std::println!("{}", bumpsim_core::names::printable_lines(&format!($($arg)*)))
    };
}

/// `print!` for the terminal, as [`println!`].
macro_rules! print {
    ($($arg:tt)*) => {
        std::print!("{}", bumpsim_core::names::printable_lines(&format!($($arg)*)))
    };
}

mod campaign;
mod doe;
mod export;
mod fe;
mod identify;
mod impact;
mod output;
mod planar;
mod signal;
mod simulate;
mod verdict;
mod view;

pub(crate) use output::{Folder, write};

use bumpsim_core::names::printable_lines;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Low-speed bumper impact toolkit: MSD car models from crash tests.
#[derive(Debug, Parser)]
#[command(name = "bumpsim", version, about, long_about = None)]
struct Cli {
    /// Exit with code 2 when a result fails its own checks (energy balance,
    /// momentum, fit, non-finite values); without it they are warnings.
    #[arg(long, global = true)]
    strict: bool,
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
    /// Simulate an angled, offset, corner or pole impact of the planar car (yaw).
    Planar(planar::Args),
    /// Will it pass? A car in the low-speed protocols: verdicts with margins, bumper targets.
    Verdict(verdict::Args),
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
    /// FE coupling: a bumper mesh coupled to the MSD car, run in CalculiX.
    #[command(subcommand)]
    Fe(fe::Command),
    /// Campaigns: a DOE whose points are FE runs, run locally or on Slurm, collected and regressed.
    #[command(subcommand)]
    Campaign(campaign::Command),
    /// Look at tests and results in the browser: a local read-only server, or one page with --html.
    View(view::Args),
}

/// Parses a count of at least 1 and at most `MAX` (a documented resource
/// limit, docs/limits.md); clap names the option in its error.
pub(crate) fn count<const MAX: usize>(text: &str) -> std::result::Result<usize, String> {
    let n: usize = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}': expected a whole number from 1 to {MAX}"))?;
    if n == 0 || n > MAX {
        return Err(format!("{n}: expected 1 to {MAX} (resource limit)"));
    }
    Ok(n)
}

static WARNINGS: AtomicUsize = AtomicUsize::new(0);

/// Counts `n` warnings printed with a result (they belong to its block on
/// standard output) for `--strict`.
pub(crate) fn count_warnings(n: usize) {
    WARNINGS.fetch_add(n, Ordering::Relaxed);
}

/// Prints a warning about a result (stderr) and counts it for `--strict`.
pub(crate) fn warn(message: &str) {
    WARNINGS.fetch_add(1, Ordering::Relaxed);
    eprintln!("warning: {}", printable_lines(message));
}

/// Every option that takes a value takes a negative number too: `--speed -1`
/// reaches the command's own check, which refuses it by name and range, where
/// clap answered "unexpected argument '-1'". An option of one value takes
/// any value starting with '-' (`--speed "-3 m/s"`, a quantity with a unit)
/// for the same reason; options of several values keep clap's reading, or a
/// hyphen value would swallow the flags after it, and so do paths, or
/// `--json --report r` would write a file named `--report`.
fn negative_values(command: clap::Command) -> clap::Command {
    command
        .mut_args(|arg| {
            let takes = arg.get_action().takes_values();
            let one = arg
                .get_num_args()
                .is_none_or(|n| n.min_values() == 1 && n.max_values() == 1);
            let option = arg.get_long().is_some() || arg.get_short().is_some();
            // a path never: `--json --quiet` wrote a file named "--quiet"
            let path =
                arg.get_value_parser().type_id() == std::any::TypeId::of::<std::path::PathBuf>();
            arg.allow_negative_numbers(takes)
                .allow_hyphen_values(takes && one && option && !path)
        })
        .mut_subcommands(negative_values)
}

fn main() -> ExitCode {
    abandon_on_panic();
    let matches = negative_values(Cli::command()).get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    if let Err(error) = output::guard_paths(&matches) {
        eprintln!("error: {}", message(&error));
        return ExitCode::from(2);
    }
    // `fe run` writes its deck through the guard and runs CalculiX on it
    // in the same command: its outputs are written one by one as before
    // `view` serves until it is ended; its exports are written one by one
    if !matches!(cli.command, Command::Fe(_) | Command::View(_)) {
        bumpsim_io::output::begin();
    }
    let result = run(cli.command).and_then(|()| output::commit());
    let warnings = WARNINGS.load(Ordering::Relaxed);
    match result {
        Ok(()) if cli.strict && warnings > 0 => {
            eprintln!("error: --strict: the results carry {warnings} warning(s) (see above)");
            ExitCode::from(2)
        }
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            let abandoned = output::abandon();
            eprintln!("error: {}", message(&error));
            if abandoned > 0 {
                eprintln!(
                    "note: none of the command's outputs was written (they are written together or not at all)"
                );
            }
            ExitCode::from(2)
        }
    }
}

fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Simulate(args) => simulate::run(&args),
        Command::Export(command) => export::run(&command),
        Command::Fe(command) => fe::run(&command),
        Command::Signal(command) => signal::run(&command),
        Command::Identify(args) => identify::run(&args),
        Command::Impact(args) => impact::run_impact(&args),
        Command::Planar(args) => planar::run(&args),
        Command::Verdict(args) => verdict::run(&args),
        Command::MassReduction(args) => impact::run_reduction(&args),
        Command::Synth(args) => impact::run_synth(&args),
        Command::Doe(command) => doe::run(&command),
        Command::Predict(args) => identify::run_predict(&args),
        Command::Campaign(command) => campaign::run(&command),
        Command::View(args) => view::run(&args),
    }
}

/// A closed pipe (`bumpsim ... | head`) ends the process quietly with exit
/// code 141 (128 + SIGPIPE, what a shell reports for other Unix tools)
/// instead of a panic in `println!`: the Rust runtime ignores SIGPIPE, std
/// has no stable switch to restore it, and the workspace forbids the
/// `unsafe` call that would. Any other failure to print (`> /dev/full`, a
/// full disk) is an error with exit code 2. Either way, and on any panic,
/// the command's outputs are abandoned: results that could not be printed
/// are not half delivered.
fn abandon_on_panic() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let text = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        output::abandon();
        if text.starts_with("failed printing to std") && text.contains("Broken pipe") {
            std::process::exit(141);
        }
        if text.starts_with("failed printing to std") {
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "error: cannot print the results: {text}; no output was written"
            );
            std::process::exit(2);
        }
        default(info)
    }));
}

/// The error and its causes, each cause once: library errors often already
/// quote their source in their own message.
/// The error and its causes in one text, each file's words printable
/// ([`printable_lines`]: no escape sequence from a file reaches the terminal).
fn message(error: &anyhow::Error) -> String {
    let mut text = error.to_string();
    for cause in error.chain().skip(1) {
        let cause = cause.to_string();
        if !text.contains(&cause) {
            text = format!("{text}: {cause}");
        }
    }
    printable_lines(&text)
}
