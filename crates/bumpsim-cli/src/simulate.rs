//! `bumpsim simulate`: reads a car file and a force CSV, runs the core
//! simulation, prints a summary with units and optionally writes the response.

use anyhow::{Context, Result, bail};
use bumpsim_core::discrete::{Method, Substeps};
use bumpsim_core::names::printable;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::simulate::{InitialState, Simulator};
use bumpsim_core::units::{Dimension, format_number, format_quantity, parse_quantity};
use bumpsim_io::car::Car;
use bumpsim_io::response::write_response;
use bumpsim_io::table::Table;
use std::path::{Path, PathBuf};

/// Arguments of `bumpsim simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Car model: a car file (TOML: masses, dampers, springs in SI) or an identification result (JSON).
    #[arg(long, value_name = "CAR.toml")]
    car: PathBuf,
    /// Force on m1 (CSV: `time [unit]`, then columns `name [unit]`).
    #[arg(long, value_name = "FORCE.csv")]
    force: PathBuf,
    /// Force column by name or header; needed when the file has several force columns.
    #[arg(long, value_name = "NAME")]
    column: Option<String>,
    /// Discretisation: zoh (exact, default), foh, or taylor1 (thesis eq. 10).
    #[arg(long, default_value = "zoh")]
    method: Method,
    /// taylor1 only: sub-steps per sample, a number or `auto`.
    #[arg(long, value_name = "N|auto")]
    substeps: Option<String>,
    /// Initial velocity of every mass, m/s or with a unit ("16 km/h").
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    initial_velocity: Option<String>,
    /// Write the response (displacements, velocities, accelerations, link forces, energies) as CSV.
    #[arg(short, long, value_name = "OUT.csv")]
    output: Option<PathBuf>,
}

fn substeps(text: Option<&str>) -> Result<Substeps> {
    match text {
        None => Ok(Substeps::default()),
        Some("auto") => Ok(Substeps::Auto),
        Some(n) => n
            .parse::<u32>()
            .ok()
            .filter(|&n| n > 0)
            .map(Substeps::Count)
            .with_context(|| {
                format!("--substeps '{n}': expected a whole number of at least 1, or auto")
            }),
    }
}

/// Refuses an output path that is one of the inputs (same path, hard link
/// or inside an input folder; see [`bumpsim_io::output`]).
pub fn refuse_overwriting_inputs(output: &Path, inputs: &[&Path]) -> Result<()> {
    inputs
        .iter()
        .for_each(|input| bumpsim_io::output::register_input(input));
    bumpsim_io::output::check_file(output)
        .with_context(|| format!("-o {}: choose another output file", output.display()))
}

/// Reads the force column of a CSV file: the named one, or the only force column.
pub fn force_series(path: &Path, column: Option<&str>) -> Result<(UniformSeries, String)> {
    let table = Table::read(path)?;
    let column = match column {
        Some(name) => table.column(name)?,
        None => table.only_column(Dimension::Force)?,
    };
    if column.unit.dimension != Dimension::Force {
        bail!(
            "{}: column '{}' is a {} [{}], expected a force",
            table.path.display(),
            column.name,
            column.unit.dimension,
            column.unit
        );
    }
    Ok((table.series(column)?, column.name.clone()))
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    if let Some(output) = &args.output {
        refuse_overwriting_inputs(output, &[&args.car, &args.force])?;
    }
    let car = Car::read_model_file(&args.car)?;
    let (force, column) = force_series(&args.force, args.column.as_deref())?;
    let initial = match &args.initial_velocity {
        Some(text) => InitialState::UniformVelocity(
            parse_quantity(text, Dimension::Velocity).context("--initial-velocity")?,
        ),
        None => InitialState::Rest,
    };
    let simulator = Simulator::with_substeps(
        &car.model,
        args.method,
        force.step(),
        substeps(args.substeps.as_deref())?,
    )
    .with_context(|| {
        format!(
            "cannot simulate {} with {}",
            args.car.display(),
            args.method
        )
    })?;
    let response = simulator.run(&force, &initial).with_context(|| {
        format!(
            "cannot simulate {} with the force of {} ({}; check the car's parameters)",
            args.car.display(),
            args.force.display(),
            args.method
        )
    })?;
    if !response.is_finite() {
        let peak = force.peak().1;
        bail!(
            "the simulation of {} with the force of {} (peak {} N) produced non-finite values (inf or NaN): the model, force or initial velocity is beyond what the {} discretisation can represent",
            args.car.display(),
            args.force.display(),
            bumpsim_core::units::short(peak),
            args.method
        );
    }
    response.warnings().iter().for_each(|w| crate::warn(w));
    print_summary(args, &car, &column, &force, &simulator, &response, &initial);
    if let Some(output) = &args.output {
        let existed = output.exists();
        let columns = write_response(output, &response)?;
        let note = if existed {
            " (replaced the existing file)"
        } else {
            ""
        };
        crate::output::wrote(format!(
            "wrote {}: {} rows × {columns} columns, SI units{note}",
            output.display(),
            response.time.len()
        ));
    }
    Ok(())
}

fn print_summary(
    args: &Args,
    car: &Car,
    column: &str,
    force: &UniformSeries,
    simulator: &Simulator,
    response: &bumpsim_core::simulate::Response,
    initial: &InitialState,
) {
    let q = format_quantity;
    let model = &car.model;
    let name = printable(car.name.as_deref().unwrap_or("(unnamed)"));
    println!(
        "car       {name}: {} DOF, total mass {}",
        model.dof(),
        q(model.total_mass(), Dimension::Mass)
    );
    let (k_peak, f_peak) = force.peak();
    println!(
        "force     '{column}' from {}: {} samples at {} ({} Hz), {} to {}, peak {} at {}, impulse {} N·s",
        args.force.display(),
        force.len(),
        q(force.step(), Dimension::Time),
        format_number(1.0 / force.step(), 4),
        q(force.start(), Dimension::Time),
        q(force.end(), Dimension::Time),
        q(f_peak, Dimension::Force),
        q(force.time(k_peak), Dimension::Time),
        format_number(response.impulse.last().copied().unwrap_or(0.0), 4),
    );
    let discrete = simulator.discrete();
    let sub = if discrete.substeps() > 1 {
        format!(", {} sub-steps per sample", discrete.substeps())
    } else {
        String::new()
    };
    println!(
        "method    {} ({}){sub}",
        discrete.method(),
        discrete.method().description()
    );
    if let InitialState::UniformVelocity(v) = initial {
        println!(
            "initial   every mass at {} ({} km/h)",
            q(*v, Dimension::Velocity),
            format_number(v * 3.6, 4)
        );
    }
    for i in 0..response.dof() {
        let (t, x) = response.peak_displacement(i);
        let last = response.time.len() - 1;
        println!(
            "m{}        peak displacement {} at {}; final velocity {}",
            i + 1,
            q(x, Dimension::Length),
            q(t, Dimension::Time),
            q(response.velocity[i][last], Dimension::Velocity)
        );
    }
    let e = &response.energy;
    let last = e.work.len() - 1;
    println!(
        "energy    work of the force {}, dissipated {}, kinetic {} (start {}), spring {}",
        q(e.work[last], Dimension::Energy),
        q(e.dissipated[last], Dimension::Energy),
        q(e.kinetic[last], Dimension::Energy),
        q(e.kinetic[0], Dimension::Energy),
        q(e.spring[last], Dimension::Energy),
    );
    println!(
        "checks    energy balance error {} of the largest energy term, momentum error {} of the impulse",
        format_number(e.relative_error(), 2),
        format_number(response.momentum_error(), 2)
    );
}
