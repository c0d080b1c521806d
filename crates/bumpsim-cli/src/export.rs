//! `bumpsim export`: converts arguments into export options, writes decks and
//! reads CalculiX results back.

pub(crate) mod deck;
mod planar;

use crate::simulate::{force_series, refuse_overwriting_inputs};
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_export::calculix::{Analysis, CalculixOptions, read_results};
use bumpsim_export::car_deck::{
    below_minimum, calculix_car_deck, critical_time_step, lsdyna_car_include,
};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::LsDynaOptions;
use bumpsim_export::spring::{SpringCurve, SpringOptions, calculix_spring, lsdyna_spring};
use bumpsim_io::link_car::ChainCar;
use bumpsim_io::table::{OutputColumn, write_table};
use deck::{Solver, origin, spacing, time, write_output};
use std::path::{Path, PathBuf};

/// The export subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Write an LS-DYNA keyword include file of the model.
    Lsdyna(LsDynaArgs),
    /// Write a CalculiX/Abaqus deck; with --force a complete transient analysis.
    Calculix(CalculixArgs),
    /// Read the .dat results of a CalculiX run of an exported deck into CSV (SI).
    ReadCalculix(ReadArgs),
    /// Write the bumper characteristic (impact's bumper TOML) as a nonlinear
    /// discrete spring: LS-DYNA MAT_S06 or CalculiX SPRINGA.
    Bumper(BumperArgs),
    /// Write the planar car (planar TOML): an LS-DYNA include, or a CalculiX
    /// deck, with --force a complete transient analysis.
    Planar(planar::PlanarArgs),
}

/// Arguments of `bumpsim export bumper`.
#[derive(Debug, clap::Args)]
pub struct BumperArgs {
    /// The bumper characteristic (TOML: ramp, plateau, unloading; or curve, unloading).
    #[arg(value_name = "BUMPER.toml")]
    bumper: PathBuf,
    /// lsdyna (keyword include) or calculix (deck lines to *INCLUDE).
    #[arg(long)]
    solver: Solver,
    /// The deck to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Deck unit system: si, mm-s-t or mm-ms-kg.
    #[arg(long, default_value = "si")]
    units: UnitSystem,
    /// Added to every id written.
    #[arg(long, default_value_t = 0)]
    id_offset: u64,
    /// The spring element's nodes: barrier side, then the car's m1 node.
    #[arg(long, value_delimiter = ',', value_name = "FRONT,REAR", num_args = 1)]
    nodes: Vec<u64>,
    /// CalculiX set-name prefix (default BUMPSIM_); --solver calculix only.
    #[arg(long)]
    prefix: Option<String>,
}

/// Options both decks share.
#[derive(Debug, clap::Args)]
pub struct Common {
    /// The model: a car file (TOML) or an identification result (JSON).
    #[arg(value_name = "CAR.toml|RESULT.json")]
    model: PathBuf,
    /// The deck to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Deck unit system: si (kg, m, s, N), mm-s-t (t, mm, s, N) or mm-ms-kg (kg, mm, ms, kN).
    #[arg(long, default_value = "si")]
    units: UnitSystem,
    /// Global axis of the model's +x (direction of the bumper force on m1, towards mn).
    #[arg(long, default_value = "+x", allow_hyphen_values = true)]
    axis: Axis,
    /// Position of m1 as x,y,z, each in m or with a unit ("3.2,0,450 mm").
    #[arg(
        long,
        default_value = "0,0,0",
        allow_hyphen_values = true,
        value_name = "X,Y,Z"
    )]
    origin: String,
    /// Distance between neighbouring mass nodes, m or with a unit ("100 mm").
    #[arg(long, default_value = "0.1", allow_hyphen_values = true)]
    spacing: String,
    /// Initial velocity of every mass along the axis, m/s or with a unit ("16 km/h").
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    initial_velocity: Option<String>,
}

/// Arguments of `bumpsim export lsdyna`.
#[derive(Debug, clap::Args)]
pub struct LsDynaArgs {
    #[command(flatten)]
    common: Common,
    /// Added to every id of the include, to stay clear of the bumper model's ids.
    #[arg(long, default_value_t = 0)]
    id_offset: u64,
    /// Bumper attachment node ids (the user's model) rigidly coupled to m1, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "ID,ID,...")]
    attach: Vec<u64>,
    /// Force on m1 (CSV): `*DEFINE_CURVE` and `*LOAD_NODE_POINT`.
    #[arg(long, value_name = "FORCE.csv")]
    force: Option<PathBuf>,
    /// Force column, when the file has several force columns.
    #[arg(long, value_name = "NAME", requires = "force")]
    column: Option<String>,
    /// History outputs (nodout, deforc, glstat, mass nodes) every DT: s or with a unit ("0.1 ms").
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    output_interval: Option<String>,
    /// A complete run: `*CONTROL_TERMINATION` at the end of the force.
    #[arg(long, requires = "force")]
    standalone: bool,
    /// Warn when the car's critical explicit time step is below this: s or with a unit.
    #[arg(
        long,
        default_value = "1 us",
        value_name = "DT",
        allow_hyphen_values = true
    )]
    min_time_step: String,
}

/// Arguments of `bumpsim export calculix`.
#[derive(Debug, clap::Args)]
pub struct CalculixArgs {
    #[command(flatten)]
    common: Common,
    /// Force on m1 (CSV) to make a complete transient analysis.
    #[arg(long, value_name = "FORCE.csv")]
    force: Option<PathBuf>,
    /// Force column, when the file has several force columns.
    #[arg(long, value_name = "NAME", requires = "force")]
    column: Option<String>,
    /// Fixed time increment, s or with a unit ("0.05 ms"); default the force's sample interval.
    #[arg(
        long,
        value_name = "DT",
        requires = "force",
        allow_hyphen_values = true
    )]
    increment: Option<String>,
    /// Write results every N increments.
    #[arg(long, default_value_t = 1, value_name = "N", requires = "force")]
    output_every: usize,
    /// Added to every node and element id, to stay clear of the main model's ids.
    #[arg(long, default_value_t = 0)]
    id_offset: u64,
    /// Prefix of every set and amplitude name, to stay clear of the main model's names.
    #[arg(long, default_value = bumpsim_export::calculix::DEFAULT_PREFIX)]
    prefix: String,
    /// Bumper attachment node ids (the main model's) tied to m1 along the axis, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "ID,ID,...")]
    attach: Vec<u64>,
}

/// Arguments of `bumpsim export read-calculix`.
#[derive(Debug, clap::Args)]
pub struct ReadArgs {
    /// The deck written by `bumpsim export calculix`; its .dat beside it is read.
    #[arg(value_name = "DECK.inp")]
    deck: PathBuf,
    /// Write `time [s]`, `x1 [m]`, ... as CSV.
    #[arg(short, long, value_name = "OUT.csv")]
    output: PathBuf,
}

/// Runs an export subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Lsdyna(args) => lsdyna(args),
        Command::Calculix(args) => calculix(args),
        Command::ReadCalculix(args) => read_calculix(args),
        Command::Bumper(args) => bumper(args),
        Command::Planar(args) => planar::run(args),
    }
}

fn layout(common: &Common) -> Result<Layout> {
    Ok(Layout {
        units: common.units,
        axis: common.axis,
        origin: origin(&common.origin)?,
        spacing: spacing(&common.spacing)?,
    })
}

fn initial_velocity(common: &Common) -> Result<Option<f64>> {
    common
        .initial_velocity
        .as_deref()
        .map(|text| parse_quantity(text, Dimension::Velocity).context("--initial-velocity"))
        .transpose()
}

fn write_deck(common: &Common, inputs: &[&Path], text: &str, what: &str) -> Result<()> {
    for note in bumpsim_export::car_deck::approximations(text) {
        crate::warn(&format!("the deck approximates: {note}"));
    }
    write_output(&common.output, common.units, inputs, text, what)
}

fn title(car: &ChainCar, path: &Path) -> String {
    format!(
        "{} (from {})",
        car.name().unwrap_or("MSD car model"),
        path.display()
    )
}

fn lsdyna(args: &LsDynaArgs) -> Result<()> {
    let common = &args.common;
    let car = ChainCar::read(&common.model)?;
    let model = bumpsim_engine::deck::model(&car);
    let force = args
        .force
        .as_deref()
        .map(|path| force_series(path, args.column.as_deref()))
        .transpose()?;
    let options = LsDynaOptions {
        layout: layout(common)?,
        id_offset: args.id_offset,
        attach: args.attach.clone(),
        initial_velocity: initial_velocity(common)?,
        title: title(&car, &common.model),
        force: force.map(|(series, _)| series),
        output_interval: args
            .output_interval
            .as_deref()
            .map(|t| time("output-interval", t))
            .transpose()?,
        standalone: args.standalone,
    };
    let step = critical_time_step(model);
    println!(
        "critical explicit time step of the car alone: {}",
        bumpsim_core::units::format_quantity(step, Dimension::Time)
    );
    let minimum = time("min-time-step", &args.min_time_step)?;
    let below = below_minimum(model, minimum)
        .with_context(|| format!("--min-time-step '{}'", args.min_time_step))?;
    if below.is_some() {
        crate::warn(&format!(
            "the car limits an explicit run to steps of {} (below --min-time-step {}): its stiffest or most damped link on a light mass governs",
            bumpsim_core::units::format_quantity(step, Dimension::Time),
            args.min_time_step
        ));
    }
    let deck = lsdyna_car_include(model, &options)?;
    let what = format!(
        "LS-DYNA include, {} masses on nodes {}..{}",
        model.dof(),
        args.id_offset + 1,
        args.id_offset + model.dof() as u64
    );
    let inputs: Vec<&Path> = std::iter::once(common.model.as_path())
        .chain(args.force.as_deref())
        .collect();
    write_deck(common, &inputs, &deck, &what)
}

fn calculix(args: &CalculixArgs) -> Result<()> {
    let common = &args.common;
    let car = ChainCar::read(&common.model)?;
    let analysis = match &args.force {
        Some(path) => Some(Analysis {
            force: force_series(path, args.column.as_deref())?.0,
            increment: args
                .increment
                .as_deref()
                .map(|t| parse_quantity(t, Dimension::Time).context("--increment"))
                .transpose()?,
            output_every: args.output_every,
        }),
        None => None,
    };
    let what = if analysis.is_some() {
        "CalculiX transient analysis (run: ccx JOB)"
    } else {
        "CalculiX model"
    };
    let options = CalculixOptions {
        layout: layout(common)?,
        initial_velocity: initial_velocity(common)?,
        analysis,
        title: title(&car, &common.model),
        id_offset: args.id_offset,
        prefix: args.prefix.clone(),
        attach: args.attach.clone(),
    };
    let deck = calculix_car_deck(bumpsim_engine::deck::model(&car), &options)
        .map_err(|e| name_output_every(e.into(), args.output_every))?;
    let inputs: Vec<&Path> = std::iter::once(common.model.as_path())
        .chain(args.force.as_deref())
        .collect();
    write_deck(common, &inputs, &deck, what)
}

/// Names `--output-every` in the refusal of a zero output interval (the
/// library names the interval, not the flag).
fn name_output_every(error: anyhow::Error, every: usize) -> anyhow::Error {
    use bumpsim_export::ExportError::OutputInterval;
    let zero = error.chain().any(|cause| {
        matches!(
            cause.downcast_ref::<bumpsim_export::ExportError>(),
            Some(OutputInterval)
        )
    });
    match zero {
        true => error.context(format!("--output-every {every}")),
        false => error,
    }
}

fn bumper(args: &BumperArgs) -> Result<()> {
    let prefix = [("prefix", args.prefix.is_some())];
    deck::only_for(args.solver, Solver::Calculix, &prefix)?;
    let bumper = bumpsim_impact::bumper::Bumper::read(&args.bumper)?;
    let curve = SpringCurve::new(bumper.loading_points(), bumper.unloading_slope())
        .with_context(|| format!("{}", args.bumper.display()))?;
    let nodes = match args.nodes.as_slice() {
        [] => None,
        [front, rear] => Some((*front, *rear)),
        other => bail!(
            "--nodes: expected two node ids FRONT,REAR, got {}",
            other.len()
        ),
    };
    let options = SpringOptions {
        units: args.units,
        id_offset: args.id_offset,
        nodes,
        title: format!("bumper characteristic from {}", args.bumper.display()),
        prefix: (args.prefix.as_deref())
            .unwrap_or(bumpsim_export::calculix::DEFAULT_PREFIX)
            .into(),
    };
    let (deck, what) = match args.solver {
        Solver::Lsdyna => (
            lsdyna_spring(&curve, &options)?,
            "LS-DYNA MAT_SPRING_GENERAL_NONLINEAR",
        ),
        Solver::Calculix => (
            calculix_spring(&curve, &options)?,
            "CalculiX nonlinear SPRINGA",
        ),
    };
    refuse_overwriting_inputs(&args.output, &[args.bumper.as_path()])?;
    bumpsim_io::output::write_file(&args.output, deck.as_bytes())?;
    crate::output::wrote(format!(
        "wrote {}: {what}, {} curve points, units {}",
        args.output.display(),
        curve.points().len(),
        args.units
    ));
    Ok(())
}

fn read_calculix(args: &ReadArgs) -> Result<()> {
    // the results are the .dat beside the deck: an input as much as the deck
    refuse_overwriting_inputs(&args.output, &[&args.deck.with_extension("dat")])?;
    let results = read_results(&args.deck)?;
    let names: Vec<String> = (1..=results.displacement.len())
        .map(|i| format!("x{i}"))
        .collect();
    let columns: Vec<OutputColumn<'_>> = names
        .iter()
        .zip(&results.displacement)
        .map(|(name, values)| OutputColumn {
            name,
            unit: bumpsim_core::units::Unit::si(Dimension::Length),
            values,
        })
        .collect();
    write_table(&args.output, &results.time, &columns)?;
    crate::output::wrote(format!(
        "wrote {}: {} times × {} masses, displacement along the model axis, SI",
        args.output.display(),
        results.time.len(),
        names.len()
    ));
    Ok(())
}
