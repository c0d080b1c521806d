//! `bumpsim identify` and `bumpsim predict`: argument conversion and output
//! around bumpsim-ident and the identification report.

use crate::write;
use anyhow::{Context, Result, bail};
use bumpsim_ident::estimate::{Identification, identify};
use bumpsim_ident::explore::{predict, sensitivity};
use bumpsim_ident::report::{case_lines, dof_table, parameter_table};
use bumpsim_ident::study::Study;
use bumpsim_io::car::Car;
use bumpsim_report::identification::{DofOutcome, report};
use indicatif::{ProgressBar, ProgressStyle};
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
    #[arg(long)]
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
}

/// Arguments of `predict`.
#[derive(Debug, clap::Args)]
pub struct PredictArgs {
    /// An identification result (JSON) or car file (TOML).
    model: PathBuf,
    /// The study file that defines the load cases.
    study: PathBuf,
    /// Case names to simulate (default: all); repeatable.
    #[arg(long = "case")]
    cases: Vec<String>,
    /// Write SVG plots of measured vs simulated into this folder.
    #[arg(long)]
    plot: Option<PathBuf>,
}

fn parse_dofs(text: &str) -> Result<Vec<usize>> {
    let bad = || {
        format!(
            "--dof '{text}': expected a number (3), a range (1..5) or a list (1,2,3) of numbers ≥ 1"
        )
    };
    let list: Vec<usize> = if let Some((a, b)) = text.split_once("..") {
        let (a, b) = (
            a.trim().parse::<usize>().with_context(bad)?,
            b.trim().parse::<usize>().with_context(bad)?,
        );
        (a..=b).collect()
    } else {
        text.split(',')
            .map(|s| s.trim().parse::<usize>())
            .collect::<Result<_, _>>()
            .with_context(bad)?
    };
    if list.is_empty() || list.contains(&0) {
        bail!(bad());
    }
    Ok(list)
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

/// Runs `identify`.
pub fn run(args: &Args) -> Result<()> {
    let study = Study::read(&args.study)?;
    let dofs = match &args.dof {
        Some(text) => parse_dofs(text)?,
        None => study.dofs(),
    };
    let loaded = study.cases(dofs.iter().copied().max().unwrap_or(1))?;
    let mut outcomes = Vec::new();
    let mut done = Vec::new();
    for &dof in &dofs {
        let mut settings = study.settings(dof)?;
        settings.starts = args.starts.unwrap_or(settings.starts);
        settings.seed = args.seed.unwrap_or(settings.seed);
        let cases = study.retarget(&loaded, dof);
        let bar = progress(args.quiet, dof, settings.starts);
        let result = identify(&cases, &settings, &|| bar.inc(1));
        bar.finish_and_clear();
        match result {
            Ok(result) => {
                print_result(&result);
                let predictions = predict(&cases, &result.model());
                done.push((result.clone(), cases));
                outcomes.push(DofOutcome::Done {
                    result: Box::new(result),
                    predictions,
                });
            }
            Err(e) if dofs.len() > 1 => {
                eprintln!("error: {dof}-DOF model: {e}");
                outcomes.push(DofOutcome::Failed {
                    dof,
                    reason: e.to_string(),
                });
            }
            Err(e) => return Err(e).context(format!("{dof}-DOF identification")),
        }
    }
    let results: Vec<Identification> = done.iter().map(|(r, _)| r.clone()).collect();
    if results.len() > 1 {
        println!("\n{}", dof_table(&results));
    }
    let sweeps = done
        .last()
        .map(|(r, cases)| sensitivity(cases, &r.model(), 0.03, 13));
    write_outputs(args, &study, &results, &outcomes, sweeps.as_deref())
}

fn print_result(r: &Identification) {
    println!(
        "\n{}-DOF model: objective {} m², fit {} %",
        r.dof,
        bumpsim_core::units::format_number(r.objective, 5),
        bumpsim_core::units::format_number(r.fit_percent, 4)
    );
    print!("{}", parameter_table(r));
    print!("{}", case_lines(r));
    println!(
        "  starts: {} run, {} converged, {} reached the best objective, {} failed; {} iterations; {}",
        r.starts.total,
        r.starts.converged,
        r.starts.reached_best,
        r.starts.failed,
        r.iterations,
        bumpsim_core::units::format_quantity(r.run_time, bumpsim_core::units::Dimension::Time)
    );
    for w in &r.warnings {
        println!("  warning: {w}");
    }
}

fn write_outputs(
    args: &Args,
    study: &Study,
    results: &[Identification],
    outcomes: &[DofOutcome],
    sweeps: Option<&[bumpsim_ident::explore::Sweep]>,
) -> Result<()> {
    if let Some(path) = &args.json {
        let json = match results {
            [one] => serde_json::to_string_pretty(one)?,
            many => serde_json::to_string_pretty(&serde_json::json!({ "results": many }))?,
        };
        write(path, &json)?;
    }
    if let (Some(path), Some(sweeps)) = (&args.sensitivity, sweeps) {
        let mut csv = String::from("relative change [-]");
        sweeps
            .iter()
            .for_each(|s| csv += &format!(",objective {} [m^2]", s.name));
        csv.push('\n');
        for j in 0..sweeps.first().map_or(0, |s| s.relative_change.len()) {
            csv += &sweeps[0].relative_change[j].to_string();
            sweeps
                .iter()
                .for_each(|s| csv += &format!(",{}", s.objective[j]));
            csv.push('\n');
        }
        write(path, &csv)?;
    }
    if let Some(dir) = &args.report {
        let inputs = std::fs::read_to_string(&args.study).unwrap_or_default();
        let dofs: Vec<String> = outcomes
            .iter()
            .map(|o| match o {
                DofOutcome::Done { result, .. } => result.dof.to_string(),
                DofOutcome::Failed { dof, .. } => format!("{dof} (failed)"),
            })
            .collect();
        let starts = args.starts.unwrap_or(study.model.starts);
        let seed = args.seed.unwrap_or(study.model.seed);
        let settings = format!(
            "Study {}; DOF {}; {starts} starts, seed {seed}; exact zoh discretisation.",
            args.study.display(),
            dofs.join(", ")
        );
        let (html, figures) = report(
            "bumpsim identification",
            &inputs,
            &settings,
            outcomes,
            sweeps,
        )?;
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for (name, svg) in figures {
            write(&dir.join(name), &svg)?;
        }
        write(&dir.join("index.html"), &html)?;
    }
    Ok(())
}

/// Runs `predict`.
pub fn run_predict(args: &PredictArgs) -> Result<()> {
    let car = Car::read_model_file(&args.model).with_context(|| {
        format!(
            "{}: a result of `bumpsim identify --json` for one DOF, or a car file",
            args.model.display()
        )
    })?;
    let study = Study::read(&args.study)?;
    let cases = study.cases_named(car.model.dof(), &args.cases)?;
    let predictions = predict(&cases, &car.model);
    for p in &predictions {
        println!(
            "{}: fit {} %  SSE {} m²  ({} samples)",
            p.fit.name,
            bumpsim_core::units::format_number(p.fit.fit_percent, 4),
            bumpsim_core::units::format_number(p.fit.sse, 4),
            p.fit.samples
        );
    }
    if let Some(dir) = &args.plot {
        for p in &predictions {
            let svg = bumpsim_report::identification::fit_plot(p, car.model.dof())?;
            write(
                &dir.join(format!(
                    "predict-{}.svg",
                    bumpsim_report::file_name(&p.fit.name)
                )),
                &svg,
            )?;
        }
    }
    Ok(())
}
