//! `bumpsim campaign`: argument conversion and output around bumpsim-campaign.

use anyhow::Result;
use bumpsim_campaign::run::RunOptions;
use bumpsim_campaign::{collect, init, repair, run, status};
use clap::Subcommand;
use std::io::IsTerminal;
use std::path::PathBuf;

/// The `campaign` subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Make the campaign folder: design, one folder per point with its deck, the state file.
    Init(InitArgs),
    /// Run what is not done (local process pool or Slurm job array); resumes after a restart.
    Run(RunArgs),
    /// Summarise the state: points per status, running jobs, failures with reasons.
    Status(StatusArgs),
    /// Read the results into the design table, fit the regression, write the report.
    Collect(DirArgs),
    /// Stop the campaign's running tasks (scancel, SIGTERM) and mark them pending.
    Abort(DirArgs),
    /// Rebuild a damaged or truncated state from the point folders' exit markers and outputs.
    Repair(DirArgs),
}

/// Arguments of `campaign init`.
#[derive(Debug, clap::Args)]
pub struct InitArgs {
    /// The campaign file (CAMPAIGN.toml).
    campaign: PathBuf,
    /// The campaign folder (default: the campaign file's name without .toml).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Then run the campaign with its executor and collect it (init, run, collect in one).
    #[arg(long)]
    run: bool,
    /// With --run: local | slurm (default: the campaign file's executor.kind).
    #[arg(long, requires = "run")]
    executor: Option<String>,
    /// With --run: local process slots (default: the campaign file's executor.slots).
    #[arg(long, requires = "run", value_parser = crate::count::<1024>)]
    slots: Option<usize>,
}

/// Arguments of `campaign run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// The campaign folder.
    // read and written: the output guard takes it as a working folder, not
    // as an input whose every file (500 000 at 100 000 points) it would scan
    #[arg(id = "work", value_name = "DIR")]
    dir: PathBuf,
    /// local | slurm (default: the campaign file's executor.kind).
    #[arg(long)]
    executor: Option<String>,
    /// Local process slots (default: the campaign file's executor.slots).
    #[arg(long, value_parser = crate::count::<1024>)]
    slots: Option<usize>,
    /// Give failed points a new set of attempts.
    #[arg(long)]
    retry_failed: bool,
}

/// Arguments of `campaign status`.
#[derive(Debug, clap::Args)]
pub struct StatusArgs {
    /// The campaign folder.
    // read and written: the output guard takes it as a working folder, not
    // as an input whose every file (500 000 at 100 000 points) it would scan
    #[arg(id = "work", value_name = "DIR")]
    dir: PathBuf,
    /// Print a JSON document instead: counts, controller, every point's record.
    #[arg(long)]
    json: bool,
}

/// A campaign folder.
#[derive(Debug, clap::Args)]
pub struct DirArgs {
    /// The campaign folder.
    // read and written: the output guard takes it as a working folder, not
    // as an input whose every file (500 000 at 100 000 points) it would scan
    #[arg(id = "work", value_name = "DIR")]
    dir: PathBuf,
}

/// Runs a `campaign` subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Init(args) => run_init(args),
        Command::Run(args) => run_run(args),
        Command::Status(args) => {
            let status = status::status(&args.dir)?;
            match args.json {
                true => println!("{}", serde_json::to_string_pretty(&status)?),
                false => print!("{}", status.text()),
            }
            Ok(())
        }
        Command::Collect(args) => run_collect(args),
        Command::Abort(args) => {
            let n = run::abort(&args.dir)?;
            println!("cancelled {n} tasks; they are pending again");
            Ok(())
        }
        Command::Repair(args) => run_repair(args),
    }
}

fn run_repair(args: &DirArgs) -> Result<()> {
    let r = repair::repair(&args.dir)?;
    println!(
        "repaired {}: {} done kept, {} in flight adopted, {} re-queued, {} failed, {} undecided, {} never run ({} records read from the old state)",
        args.dir.display(),
        r.kept.len(),
        r.adopted.len(),
        r.requeued.len(),
        r.failed.len(),
        r.undecided.len(),
        r.pending,
        r.salvaged
    );
    let lists = [
        ("adopted", &r.adopted),
        ("re-queued", &r.requeued),
        ("failed", &r.failed),
        ("undecided", &r.undecided),
    ];
    for (what, list) in lists {
        for (run, why) in list {
            println!("  run {run}: {what}: {why}");
        }
    }
    Ok(())
}

fn options(args: &RunArgs) -> RunOptions {
    RunOptions {
        executor: args.executor.clone(),
        slots: args.slots,
        retry_failed: args.retry_failed,
        progress: std::io::stderr().is_terminal(),
    }
}

fn run_init(args: &InitArgs) -> Result<()> {
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| args.campaign.with_extension(""));
    // the library moves the folder into place itself: a standard output that
    // cannot be printed to (`> /dev/full`) stops the command before it does
    println!(
        "initialising campaign {} from {}",
        dir.display(),
        args.campaign.display()
    );
    let summary = init::init(&args.campaign, &dir)?;
    if let Some(resolution) = summary.resolution {
        println!("resolution {resolution}");
    }
    println!(
        "campaign {}: {} points ({} kept from the earlier state: done or running, inputs unchanged)",
        dir.display(),
        summary.points,
        summary.kept
    );
    if args.run {
        let run_args = RunArgs {
            dir: dir.clone(),
            executor: args.executor.clone(),
            slots: args.slots,
            retry_failed: false,
        };
        run_run(&run_args)?;
        run_collect(&DirArgs { dir })?;
    }
    Ok(())
}

fn run_run(args: &RunArgs) -> Result<()> {
    let summary = run::run(&args.dir, &options(args))?;
    println!(
        "{} points done, {} failed ({} tasks submitted by this run)",
        summary.done,
        summary.failed.len(),
        summary.submitted
    );
    for (run, reason) in &summary.failed {
        crate::warn(&format!("run {run} failed: {reason}"));
    }
    Ok(())
}

fn run_collect(args: &DirArgs) -> Result<()> {
    let collected = collect::collect(&args.dir)?;
    print!("{}", collected.fit_text);
    let results = args.dir.join("results");
    println!(
        "wrote {}/table.csv ({} points), model.json and report/index.html",
        results.display(),
        collected.rows
    );
    println!(
        "the same regression: {}",
        collect::fit_command_for(&args.dir)?
    );
    for (run, why) in &collected.missing {
        crate::warn(&format!("run {run} left out of the table: {why}"));
    }
    Ok(())
}
