//! `bumpsim signal`: test metadata, channel export and processing pipelines.
//! Converts arguments to calls of bumpsim-io and bumpsim-signal and prints.

use crate::simulate::refuse_overwriting_inputs;
use anyhow::{Context, Result, bail};
use bumpsim_core::channel::Channel;
use bumpsim_core::units::{
    Dimension, Unit, choose_units, format_in, format_quantity, format_time_at, short,
};
use bumpsim_io::isomme;
use bumpsim_io::table::{OutputColumn, write_table_in};
use bumpsim_io::test_data::{TestData, Validity};
use bumpsim_signal::pipeline::{Pipeline, PipelineResult, export, extremes};
use bumpsim_signal::process::{Combine, Step, align, resampling};
use clap::{Subcommand, ValueEnum};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `writeln!` into a String (cannot fail).
macro_rules! outln {
    ($out:expr, $($arg:tt)*) => {{
        let _ = writeln!($out, $($arg)*);
    }};
}

/// Prints long output; a closed pipe (`| head`) ends it quietly.
fn emit(text: &str) -> Result<()> {
    use std::io::Write;
    let text = bumpsim_core::names::printable_lines(text);
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.context("cannot print the results to standard output"),
    }
}

/// The `signal` subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Test metadata and the channel table of an ISO-MME test, an NHTSA EV5 file or a CSV file.
    Info(InfoArgs),
    /// Select channels, process them, and write CSV (and optionally ISO-MME).
    Export(ExportArgs),
    /// Run a processing pipeline file (TOML) and print its signals.
    Process(ProcessArgs),
}

/// Arguments of `signal info`.
#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// ISO-MME folder, .mme or .zip; NHTSA .EV5; or .csv.
    path: PathBuf,
}

/// Arguments of `signal process`.
#[derive(Debug, clap::Args)]
pub struct ProcessArgs {
    /// The pipeline file.
    pipeline: PathBuf,
    /// CSV output (default: the pipeline's `output`).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Write SVG plots of raw vs processed signals into this folder.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write the plots and an HTML report into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Also write the processed signals as an ISO-MME test folder.
    #[arg(long)]
    iso_mme: Option<PathBuf>,
}

/// How several channels of one selector are combined.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum CombineArg {
    /// Arithmetic mean.
    Mean,
    /// Sum.
    Sum,
}

/// Arguments of `signal export`. Processing runs in this order: bias,
/// CFC filter, scale, integrations, trim, resample.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// ISO-MME folder, .mme or .zip; NHTSA .EV5; or .csv.
    path: PathBuf,
    /// Channel number, code (wildcards ? and *) or name substring; repeatable.
    #[arg(long = "channel", short = 'c', required = true)]
    channels: Vec<String>,
    /// CFC filter class (60, 180, 600, 1000 or any positive number).
    #[arg(long)]
    cfc: Option<f64>,
    /// Use the ISO 6487 constant for --cfc instead of SAE J211-1's (with --cfc).
    #[arg(long, requires = "cfc")]
    iso_6487: bool,
    /// Remove the mean of the samples before t = 0.
    #[arg(long)]
    bias: bool,
    /// Multiply by this factor (e.g. -1 to change sign).
    #[arg(long, allow_negative_numbers = true)]
    scale: Option<f64>,
    /// Combine the channels of each --channel into one signal.
    #[arg(long, value_enum)]
    combine: Option<CombineArg>,
    /// Integrate with this initial value (SI, or with a unit such as "57.09 km/h"); repeat to integrate twice.
    #[arg(long, allow_negative_numbers = true)]
    integrate: Vec<String>,
    /// Keep only T0,T1 (s).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    trim: Option<Vec<f64>>,
    /// Resample to this interval (s).
    #[arg(long)]
    resample: Option<f64>,
    /// CSV output: `time [s]` and one `CODE [unit]` column per signal, SI.
    #[arg(short, long)]
    output: PathBuf,
    /// Write columns of this unit's dimension in it instead of SI (e.g. kN, mm, g); repeatable.
    #[arg(long)]
    unit: Vec<String>,
    /// Also write the processed signals as an ISO-MME test folder.
    #[arg(long)]
    iso_mme: Option<PathBuf>,
    /// Write SVG plots of raw vs processed signals into this folder.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// Runs a `signal` subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Info(args) => info(&args.path),
        Command::Export(args) => run_export(args),
        Command::Process(args) => process(args),
    }
}

fn info(path: &Path) -> Result<()> {
    let test = TestData::open(path)?;
    let mut out = String::new();
    outln!(
        out,
        "{} test {}: {}",
        test.format,
        path.display(),
        test.title
    );
    if let Some(v) = test.speed {
        outln!(
            out,
            "  impact speed   {} = {}",
            format_in(v, unit("km/h")),
            format_in(v, unit("m/s"))
        );
    }
    if let Some(m) = test.mass {
        outln!(out, "  test mass      {}", format_in(m, unit("kg")));
    }
    for (key, value) in test.metadata.iter().filter(|(_, v)| !v.is_empty()) {
        outln!(out, "  {key:<28} {value}");
    }
    let present = test.entries.iter().filter(|e| e.present).count();
    let invalid: Vec<_> = test
        .entries
        .iter()
        .filter(|e| e.validity != Validity::Valid)
        .collect();
    outln!(
        out,
        "{} channels listed, {present} with samples present, {} marked invalid",
        test.entries.len(),
        invalid.len()
    );
    outln!(
        out,
        "{:>5}  {:<24} {:<7} {:<8} name",
        "no.",
        "code",
        "unit",
        "data"
    );
    for e in &test.entries {
        let data = match (&e.validity, e.present) {
            (Validity::Invalid(_), true) => "INVALID",
            (Validity::Invalid(_), false) => "invalid",
            (Validity::Valid, true) => "present",
            (Validity::Valid, false) => "absent",
        };
        outln!(
            out,
            "{:>5}  {:<24} {:<7} {:<8} {}",
            e.number,
            e.code,
            e.unit,
            data,
            e.name
        );
    }
    for e in test.entries.iter().filter(|e| !e.present) {
        if let Some(why) = &e.absence {
            outln!(out, "absent: channel {} ({}): {why}", e.number, e.code);
        }
    }
    for e in invalid.iter().filter(|e| e.present) {
        if let Validity::Invalid(why) = &e.validity {
            outln!(
                out,
                "invalid: channel {} ({}) has samples but is marked: {why}",
                e.number,
                e.code
            );
        }
    }
    emit(&out)
}

fn unit(symbol: &str) -> Unit {
    Unit::parse(symbol).unwrap_or(Unit::si(Dimension::Dimensionless))
}

fn export_steps(args: &ExportArgs) -> Result<Vec<Step>> {
    let mut steps = Vec::new();
    if args.bias {
        steps.push(Step::PretriggerBias(true));
    }
    if let Some(class) = args.cfc {
        steps.push(if args.iso_6487 {
            Step::CfcIso(class)
        } else {
            Step::Cfc(class)
        });
    }
    if let Some(factor) = args.scale {
        steps.push(Step::Scale(factor));
    }
    for text in &args.integrate {
        let value = text.trim().parse::<f64>().or_else(|_| initial_value(text));
        steps.push(Step::Integrate(value?));
    }
    if let Some(t) = &args.trim {
        if t.len() != 2 {
            anyhow::bail!("--trim: expected T0,T1 (two numbers, s)");
        }
        steps.push(Step::Trim([t[0], t[1]]));
    }
    if let Some(step) = args.resample {
        steps.push(Step::Resample(step));
    }
    Ok(steps)
}

fn initial_value(text: &str) -> Result<f64> {
    bumpsim_core::units::parse_quantity(text, Dimension::Velocity).with_context(|| {
        format!("--integrate '{text}': expected a number (SI) or a velocity such as '57.09 km/h'")
    })
}

fn run_export(args: &ExportArgs) -> Result<()> {
    refuse_overwriting_inputs(&args.output, &[&args.path])?;
    args.iso_mme.as_deref().map(refuse_existing).transpose()?;
    let test = TestData::open(&args.path)?;
    let how = args.combine.map(|c| match c {
        CombineArg::Mean => Combine::Mean,
        CombineArg::Sum => Combine::Sum,
    });
    let result = export(&test, &args.channels, &export_steps(args)?, how)
        .map_err(|e| name_cfc(e.into(), args.cfc))
        .map_err(|e| name_resample(e, args.resample))
        .map_err(|e| name_trim(e, args.trim.as_deref()))?;
    report(&result);
    write_csv(&args.output, &result.signals, &output_units(&args.unit)?)?;
    if let Some(folder) = &args.iso_mme {
        write_iso_mme(folder, &isomme::test_header(&test), &result.signals)?;
    }
    plot(args.plot.as_deref(), &result).map(|_| ())
}

/// Names `--cfc` in an error about the CFC class (the library names the
/// class and its range for the channel's sample rate, not the flag).
fn name_cfc(error: anyhow::Error, class: Option<f64>) -> anyhow::Error {
    use bumpsim_signal::FilterError;
    let about_class = error.chain().any(|cause| {
        matches!(
            cause.downcast_ref::<FilterError>(),
            Some(FilterError::Parameter {
                name: "CFC class",
                ..
            })
        )
    });
    match class {
        Some(class) if about_class && (class == 0.0 || (1e-3..1e7).contains(&class.abs())) => {
            error.context(format!("--cfc {class}"))
        }
        Some(class) if about_class => error.context(format!("--cfc {class:e}")),
        _ => error,
    }
}

/// Names `--resample` in an error of the resampling step (the library
/// names the step, `resample`, as a pipeline file spells it).
fn name_resample(error: anyhow::Error, step: Option<f64>) -> anyhow::Error {
    use bumpsim_signal::process::ProcessError;
    let about_step = error.chain().any(|cause| {
        matches!(
            cause.downcast_ref::<ProcessError>(),
            Some(ProcessError::Range {
                step: "resample",
                ..
            })
        )
    });
    match step {
        Some(step) if about_step => error.context(format!("--resample {step}")),
        _ => error,
    }
}

/// Names `--trim` in an error of the trim step (the library names the
/// step, `trim`, as a pipeline file spells it).
fn name_trim(error: anyhow::Error, window: Option<&[f64]>) -> anyhow::Error {
    use bumpsim_signal::process::ProcessError;
    let about_step = error.chain().any(|cause| {
        matches!(
            cause.downcast_ref::<ProcessError>(),
            Some(ProcessError::Range { step: "trim", .. })
        )
    });
    match window {
        Some(&[t0, t1]) if about_step => {
            error.context(format!("--trim {},{}", short(t0), short(t1)))
        }
        _ => error,
    }
}

/// Writes signals as the ISO-MME test `folder`, named after the folder.
fn write_iso_mme(folder: &Path, header: &[(String, String)], signals: &[Channel]) -> Result<()> {
    let name = folder
        .file_name()
        .map_or("bumpsim".into(), |n| n.to_string_lossy().into_owned());
    let mme = isomme::write(folder, &name, header, signals)?;
    crate::output::wrote(format!("wrote {}", mme.display()));
    Ok(())
}

fn output_units(texts: &[String]) -> Result<Vec<Unit>> {
    texts
        .iter()
        .map(|t| Unit::parse(t).with_context(|| format!("--unit '{t}'")))
        .collect()
}

fn refuse_existing(folder: &Path) -> Result<()> {
    let non_empty = std::fs::read_dir(folder).is_ok_and(|mut d| d.next().is_some());
    if non_empty {
        bail!(
            "--iso-mme {}: the folder exists and is not empty; choose a new folder",
            folder.display()
        );
    }
    Ok(())
}

fn process(args: &ProcessArgs) -> Result<()> {
    let (path, plot_dir, report_dir) =
        (&args.pipeline, args.plot.as_deref(), args.report.as_deref());
    args.iso_mme.as_deref().map(refuse_existing).transpose()?;
    let pipeline = Pipeline::read(path)?;
    let output = args
        .output
        .clone()
        .or_else(|| pipeline.output.as_ref().map(|o| pipeline.base.join(o)));
    // the pipeline's own `output` is checked against the inputs before it runs
    if let (None, Some(output)) = (&args.output, &output) {
        bumpsim_io::output::claim_output(output)?;
        bumpsim_io::output::check_file(output)?;
    }
    let result = pipeline.run()?;
    report(&result);
    let mut balance = String::new();
    if let Some(b) = &result.balance {
        let force = pipeline.balance.as_ref().map(|spec| spec.force.as_str());
        let force = result
            .signals
            .iter()
            .find(|s| Some(s.code.as_str()) == force);
        let step = force.map_or(f64::NAN, |s| s.series.step());
        balance = format!(
            "momentum balance over {} .. {}: impulse {} vs momentum change {} of {} (relative difference {:+.2} %)",
            format_time_at(b.window[0], step),
            format_time_at(b.window[1], step),
            newton_seconds(b.impulse),
            newton_seconds(b.momentum_change),
            format_in(b.mass, unit("kg")),
            100.0 * b.relative_difference
        );
        println!("{balance}");
    }
    match &output {
        Some(output) => write_csv(output, &result.signals, &[])?,
        None => println!("no CSV written: give -o OUT.csv or 'output' in the pipeline"),
    }
    if let Some(folder) = &args.iso_mme {
        let title = format!("signals of the pipeline {}", path.display());
        let header = bumpsim_io::test_data::iso_header::test_header(&title, None, None);
        write_iso_mme(folder, &header, &result.signals)?;
    }
    plot(plot_dir, &result)?;
    let Some(dir) = report_dir else { return Ok(()) };
    let inputs = std::fs::read_to_string(path).unwrap_or_default();
    let summary = format!("{}{balance}", summary(&result));
    let plots = plot(Some(dir), &result)?;
    let html = bumpsim_report::signal::report(&bumpsim_report::signal::SignalPage {
        pipeline: &path.display().to_string(),
        inputs: &inputs,
        summary: &summary,
        warnings: &result.warnings,
        plots: &plots,
    });
    // the viewer opens what the run wrote and the tests it read
    let written = [output.as_deref(), args.iso_mme.as_deref()];
    let read = pipeline.signal.iter().filter_map(|s| s.path.as_ref());
    let mut files: Vec<String> = Vec::new();
    for f in written
        .into_iter()
        .flatten()
        .map(Path::to_path_buf)
        .chain(read.map(|p| pipeline.base.join(p)))
    {
        let f = f.display().to_string();
        if !files.contains(&f) {
            files.push(f);
        }
    }
    crate::write(
        &dir.join("index.html"),
        &bumpsim_report::html::with_viewer(&html, &files),
    )
}

fn newton_seconds(value: f64) -> String {
    format!("{} N·s", bumpsim_core::units::format_number(value, 4))
}

fn report(result: &PipelineResult) {
    for w in &result.warnings {
        crate::warn(w);
    }
    print!("{}", summary(result));
}

/// One line per signal: peak with its time, minimum and maximum, with units.
fn summary(result: &PipelineResult) -> String {
    let mut out = String::new();
    for s in &result.signals {
        let e = extremes(s);
        outln!(
            out,
            "{}: peak {} at {}; min {}, max {}",
            s.code,
            format_quantity(e.peak, s.dimension),
            format_time_at(e.peak_time, s.series.step()),
            format_quantity(e.min, s.dimension),
            format_quantity(e.max, s.dimension)
        );
    }
    out
}

fn write_csv(path: &Path, signals: &[Channel], units: &[Unit]) -> Result<()> {
    let (time, columns) = align(signals)?;
    if let Some(note) = resampling(signals).filter(|r| !r.trimmed.is_empty()) {
        crate::warn(&format!(
            "{}: {note} (one row per common time; an ISO-MME test keeps every channel's samples)",
            path.display()
        ));
    }
    let dimensions: Vec<Dimension> = std::iter::once(Dimension::Time)
        .chain(signals.iter().map(|s| s.dimension))
        .collect();
    let chosen = choose_units(units, &dimensions).map_err(|e| anyhow::anyhow!("--unit {e}"))?;
    let output: Vec<OutputColumn> = signals
        .iter()
        .zip(&columns)
        .zip(&chosen[1..])
        .map(|((s, values), &unit)| OutputColumn {
            name: &s.code,
            unit,
            values,
        })
        .collect();
    write_table_in(path, chosen[0], &time, &output)?;
    let note = if units.is_empty() {
        "SI units"
    } else {
        "units as asked"
    };
    crate::output::wrote(format!(
        "wrote {}: {} rows × {} signals, {note}",
        bumpsim_core::files::shown_path(path).display(),
        time.len(),
        signals.len()
    ));
    Ok(())
}

/// Writes raw-vs-processed plots into `folder`; returns (file name, SVG).
fn plot(folder: Option<&Path>, result: &PipelineResult) -> Result<Vec<(String, String)>> {
    let Some(folder) = folder else {
        return Ok(Vec::new());
    };
    let plots = bumpsim_report::signal::raw_and_processed(&result.raw, &result.signals)?;
    let staged = crate::Folder::stage(folder)?;
    for (name, svg) in &plots {
        staged.write(name, svg)?;
    }
    staged.commit()?;
    Ok(plots)
}
