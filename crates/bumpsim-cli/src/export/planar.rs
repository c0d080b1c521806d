//! `bumpsim export planar`: converts arguments into the engine's export
//! request and writes the deck (docs/export.md, "The planar car").

use super::deck::{Solver, only_for, origin, spacing, time, write_output};
use crate::simulate::force_series;
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_engine::{ExportRequest, ForceLoad};
use bumpsim_export::layout::UnitSystem;
use bumpsim_io::kind::ModelKind;
use std::path::{Path, PathBuf};

/// Arguments of `bumpsim export planar`.
#[derive(Debug, clap::Args)]
pub struct PlanarArgs {
    /// The planar car (TOML, docs/planar.md).
    #[arg(value_name = "CAR.toml")]
    car: PathBuf,
    /// lsdyna (keyword include) or calculix (deck; with --force a complete analysis).
    #[arg(long)]
    solver: Solver,
    /// The deck to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Deck unit system: si (kg, m, s, N), mm-s-t (t, mm, s, N) or mm-ms-kg (kg, mm, ms, kN).
    #[arg(long, default_value = "si")]
    units: UnitSystem,
    /// Position of the body's CG as x,y,z, each in m or with a unit ("1200 mm,0,450 mm"); the car points along +x.
    #[arg(
        long,
        default_value = "0,0,0",
        allow_hyphen_values = true,
        value_name = "X,Y,Z"
    )]
    origin: String,
    /// Distance between neighbouring chain nodes along x, m or with a unit ("50 mm").
    #[arg(long, default_value = "0.1", allow_hyphen_values = true)]
    spacing: String,
    /// Added to every id, to stay clear of the bumper model's ids.
    #[arg(long, default_value_t = 0)]
    id_offset: u64,
    /// The user's node ids coupled to the left (+y) front mass, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "ID,ID,...")]
    attach_left: Vec<u64>,
    /// The user's node ids coupled to the right (−y) front mass, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "ID,ID,...")]
    attach_right: Vec<u64>,
    /// Initial forward (+x) speed of the whole car, m/s or with a unit ("8 km/h").
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    initial_velocity: Option<String>,
    /// Force on the bumper line (CSV): LS-DYNA curves and nodal loads, or the CalculiX analysis.
    #[arg(long, value_name = "FORCE.csv")]
    force: Option<PathBuf>,
    /// Force column, when the file has several force columns.
    #[arg(long, value_name = "NAME", requires = "force")]
    column: Option<String>,
    /// Lateral position of the force on the bumper line, left positive: m or with a unit.
    #[arg(
        long,
        default_value = "0",
        allow_hyphen_values = true,
        requires = "force"
    )]
    lateral: String,
    /// Direction of the force on the car (world x,y; normalised); -1,0 pushes rearwards.
    #[arg(
        long,
        default_value = "-1,0",
        allow_hyphen_values = true,
        value_name = "X,Y",
        requires = "force"
    )]
    direction: String,
    /// LS-DYNA: history outputs every DT, s or with a unit ("0.1 ms").
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    output_interval: Option<String>,
    /// CalculiX: fixed time increment, s or with a unit; default the force's sample interval.
    #[arg(
        long,
        value_name = "DT",
        requires = "force",
        allow_hyphen_values = true
    )]
    increment: Option<String>,
    /// CalculiX: write results every N increments (default 1).
    #[arg(long, value_name = "N")]
    output_every: Option<usize>,
    /// CalculiX: prefix of every set and amplitude name (default BUMPSIM_).
    #[arg(long)]
    prefix: Option<String>,
}

/// Runs `bumpsim export planar`: the options converted, the deck one
/// library request.
pub fn run(args: &PlanarArgs) -> Result<()> {
    let lsdyna = [("output-interval", args.output_interval.is_some())];
    only_for(args.solver, Solver::Lsdyna, &lsdyna)?;
    let calculix = [
        ("increment", args.increment.is_some()),
        ("output-every", args.output_every.is_some()),
        ("prefix", args.prefix.is_some()),
    ];
    only_for(args.solver, Solver::Calculix, &calculix)?;
    let series = args
        .force
        .as_deref()
        .map(|path| force_series(path, args.column.as_deref()))
        .transpose()?;
    let request = ExportRequest {
        car: &args.car,
        solver: match args.solver {
            Solver::Lsdyna => bumpsim_engine::Solver::Lsdyna,
            Solver::Calculix => bumpsim_engine::Solver::Calculix,
        },
        units: args.units,
        origin: origin(&args.origin)?,
        spacing: spacing(&args.spacing)?,
        id_offset: args.id_offset,
        attach: [args.attach_left.clone(), args.attach_right.clone()],
        speed: args
            .initial_velocity
            .as_deref()
            .map(|t| parse_quantity(t, Dimension::Velocity).context("--initial-velocity"))
            .transpose()?,
        force: series
            .as_ref()
            .map(|(series, _)| force(args, series.values(), series.step()))
            .transpose()?,
        output_interval: args
            .output_interval
            .as_deref()
            .map(|t| time("output-interval", t))
            .transpose()?,
        increment: args
            .increment
            .as_deref()
            .map(|t| time("increment", t))
            .transpose()?,
        output_every: args.output_every.unwrap_or(1),
        prefix: (args.prefix.as_deref())
            .unwrap_or(bumpsim_export::calculix::DEFAULT_PREFIX)
            .into(),
    };
    let deck = bumpsim_engine::export(ModelKind::Planar, &request)?;
    let inputs: Vec<&Path> = std::iter::once(args.car.as_path())
        .chain(args.force.as_deref())
        .collect();
    write_output(&args.output, args.units, &inputs, &deck.text, &deck.what)
}

/// The force on the bumper line: `--lateral` and `--direction` read.
fn force<'a>(args: &PlanarArgs, values: &'a [f64], step: f64) -> Result<ForceLoad<'a>> {
    let lateral = parse_quantity(&args.lateral, Dimension::Length).context("--lateral")?;
    let parts: Vec<&str> = args.direction.split(',').collect();
    let direction = match parts.as_slice() {
        [x, y] => [x.trim().parse::<f64>(), y.trim().parse::<f64>()],
        _ => bail!("--direction '{}': expected x,y", args.direction),
    };
    let [Ok(x), Ok(y)] = direction else {
        bail!("--direction '{}': expected two numbers x,y", args.direction);
    };
    Ok(ForceLoad {
        step,
        values,
        lateral,
        direction: [x, y],
    })
}
