//! The pieces every `bumpsim export` deck command shares: the solver
//! choice, the placement and time options, and writing the deck.

use crate::simulate::refuse_overwriting_inputs;
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_export::layout::UnitSystem;
use std::path::Path;

/// The solvers a deck is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Solver {
    /// LS-DYNA keyword include.
    Lsdyna,
    /// CalculiX/Abaqus deck lines.
    Calculix,
}

impl Solver {
    /// The `--solver` value.
    fn name(self) -> &'static str {
        match self {
            Solver::Lsdyna => "lsdyna",
            Solver::Calculix => "calculix",
        }
    }
}

/// Refuses a flag given (`true`) that only `meant`'s deck uses when the
/// deck is for `solver` (the flag would do nothing).
pub(crate) fn only_for(solver: Solver, meant: Solver, flags: &[(&str, bool)]) -> Result<()> {
    match flags.iter().find(|(_, given)| *given) {
        Some((flag, _)) if solver != meant => bail!(
            "--{flag} applies to --solver {} only: the {} deck has no use for it; leave it out",
            meant.name(),
            solver.name()
        ),
        _ => Ok(()),
    }
}

/// `--origin x,y,z`, each in m or with a unit.
pub(crate) fn origin(text: &str) -> Result<[f64; 3]> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        bail!("--origin '{text}': expected three coordinates x,y,z in m");
    };
    let coordinate = |part: &str| {
        parse_quantity(part, Dimension::Length).with_context(|| format!("--origin '{text}'"))
    };
    Ok([coordinate(x)?, coordinate(y)?, coordinate(z)?])
}

/// `--spacing`, positive, in m or with a unit.
pub(crate) fn spacing(text: &str) -> Result<f64> {
    let spacing = parse_quantity(text, Dimension::Length).context("--spacing")?;
    if spacing <= 0.0 {
        bail!("--spacing {spacing} m: the distance between mass nodes must be positive");
    }
    Ok(spacing)
}

/// Writes a deck atomically, never over an input, and says what it holds.
pub(crate) fn write_output(
    output: &Path,
    units: UnitSystem,
    inputs: &[&Path],
    text: &str,
    what: &str,
) -> Result<()> {
    refuse_overwriting_inputs(output, inputs)?;
    let existed = output.exists();
    bumpsim_io::output::write_file(output, text.as_bytes())?;
    let note = if existed {
        " (replaced the existing file)"
    } else {
        ""
    };
    crate::output::wrote(format!(
        "wrote {}: {what}, units {units}{note}",
        output.display()
    ));
    Ok(())
}

/// A time option (`--{option}`): s or with a unit.
pub(crate) fn time(option: &str, text: &str) -> Result<f64> {
    parse_quantity(text, Dimension::Time).with_context(|| format!("--{option} '{text}'"))
}
