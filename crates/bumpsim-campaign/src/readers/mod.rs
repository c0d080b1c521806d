//! Reading a point's responses back: each `[[response]]` names a reader, a
//! file in the point folder, a quantity and a statistic of its history.
//!
//! - `calculix`: the `.dat` results of a deck written by `bumpsim export
//!   calculix` (read by [`bumpsim_export::calculix::read_results`], SI):
//!   `displacement` of mass i, or `compression` x_i − x_(i+1), m;
//! - `calculix-dat`: any `*NODE PRINT` / `*EL PRINT` block of a deck's
//!   `.dat` ([`calculix::dat`]), in the deck's units;
//! - `calculix-frd`: a nodal result component of CalculiX's `.frd` file
//!   (`*NODE FILE` output): `DATASET COMPONENT NODE`, e.g. `DISP D1 1`,
//!   one value per result block, in the deck's units;
//! - `csv`: a column of a `time,...` table with unit headers (SI, read by
//!   [`bumpsim_io::table::Table`]);
//! - LS-DYNA ASCII outputs ([`lsdyna`]), in the deck's units:
//!   `lsdyna-glstat` (`kinetic energy`, `internal energy`, ...),
//!   `lsdyna-nodout` (`NODE x-disp`, ...), `lsdyna-rcforc` (`master 1 x`,
//!   ...) and `lsdyna-deforc` (`ELEMENT x-force`, ...).
//!
//! A missing, unreadable, empty or non-finite output is an error, never a
//! zero: the point is then marked failed.

pub mod calculix;
pub mod lsdyna;

use crate::spec::ResponseSpec;
use std::path::Path;

const READERS: [&str; 8] = [
    "calculix",
    "calculix-dat",
    "calculix-frd",
    "csv",
    "lsdyna-glstat",
    "lsdyna-nodout",
    "lsdyna-rcforc",
    "lsdyna-deforc",
];
const STATS: [&str; 4] = ["max", "min", "final", "max-abs"];

/// Checks a response specification (reader, statistic, quantity).
pub fn check(r: &ResponseSpec) -> Result<(), String> {
    if !crate::spec::is_name(&r.name) {
        return Err("the name must be letters, digits and _".into());
    }
    if !READERS.contains(&r.reader.as_str()) {
        return Err(format!(
            "reader '{}': expected {}",
            r.reader,
            READERS.join(", ")
        ));
    }
    if !STATS.contains(&r.stat.as_str()) {
        return Err(format!("stat '{}': expected {}", r.stat, STATS.join(", ")));
    }
    if r.file.is_empty() || r.file.contains("..") || r.file.starts_with('/') {
        return Err(format!("file '{}': a file inside the point folder", r.file));
    }
    match (r.reader.as_str(), r.quantity.as_str(), r.mass) {
        ("calculix", "displacement" | "compression", Some(m)) if m >= 1 => Ok(()),
        ("calculix", _, _) => Err(
            "calculix: quantity = \"displacement\" or \"compression\" with mass = 1, 2, ...".into(),
        ),
        ("lsdyna-nodout" | "lsdyna-deforc", q, _) if q.split_whitespace().count() != 2 => Err(
            format!("quantity '{q}': expected 'ID NAME' (\"1001 x-disp\", \"12 x-force\")"),
        ),
        ("lsdyna-rcforc", q, _) if q.split_whitespace().count() != 3 => Err(format!(
            "quantity '{q}': expected 'master|slave ID x|y|z|mass'"
        )),
        _ => Ok(()),
    }
}

/// Reads one response of the point in `folder`.
pub fn read(folder: &Path, r: &ResponseSpec) -> Result<f64, String> {
    let path = folder.join(&r.file);
    let history = match r.reader.as_str() {
        "calculix" => msd_deck(&path, r)?,
        "calculix-dat" => calculix::dat(&path, r)?,
        "calculix-frd" => calculix::frd(&path, &r.quantity)?,
        "csv" => csv_column(&path, &r.quantity)?,
        "lsdyna-glstat" => lsdyna::glstat(&path, &r.quantity)?,
        "lsdyna-nodout" => lsdyna::nodout(&path, &r.quantity)?,
        "lsdyna-rcforc" => lsdyna::rcforc(&path, &r.quantity)?,
        _ => lsdyna::deforc(&path, &r.quantity)?,
    };
    statistic(&history, &r.stat)
}

/// The statistic of a history; an empty or non-finite history is an error.
pub fn statistic(values: &[f64], stat: &str) -> Result<f64, String> {
    if values.is_empty() {
        return Err("no values".into());
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(format!("a value of {v}"));
    }
    let fold = |init: f64, f: fn(f64, f64) -> f64| values.iter().copied().fold(init, f);
    Ok(match stat {
        "max" => fold(f64::NEG_INFINITY, f64::max),
        "min" => fold(f64::INFINITY, f64::min),
        "max-abs" => values.iter().map(|v| v.abs()).fold(0.0, f64::max),
        _ => values[values.len() - 1],
    })
}

fn msd_deck(deck: &Path, r: &ResponseSpec) -> Result<Vec<f64>, String> {
    let results = bumpsim_export::calculix::read_results(deck).map_err(|e| e.to_string())?;
    let mass = r.mass.unwrap_or(1);
    let x = |i: usize| {
        results.displacement.get(i - 1).ok_or_else(|| {
            format!(
                "{}: mass {i}: the deck has {} masses",
                deck.display(),
                results.displacement.len()
            )
        })
    };
    match r.quantity.as_str() {
        "displacement" => Ok(x(mass)?.clone()),
        _ => Ok(x(mass)?
            .iter()
            .zip(x(mass + 1)?)
            .map(|(a, b)| a - b)
            .collect()),
    }
}

fn csv_column(path: &Path, column: &str) -> Result<Vec<f64>, String> {
    let table = bumpsim_io::table::Table::read(path).map_err(|e| e.to_string())?;
    Ok(table
        .column(column)
        .map_err(|e| e.to_string())?
        .values
        .clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_refuse_empty_and_non_finite_histories() {
        assert_eq!(statistic(&[1.0, -3.0, 2.0], "max").unwrap(), 2.0);
        assert_eq!(statistic(&[1.0, -3.0, 2.0], "max-abs").unwrap(), 3.0);
        assert_eq!(statistic(&[1.0, -3.0, 2.0], "final").unwrap(), 2.0);
        assert!(statistic(&[], "max").is_err());
        assert!(statistic(&[1.0, f64::NAN], "min").is_err());
    }
}
