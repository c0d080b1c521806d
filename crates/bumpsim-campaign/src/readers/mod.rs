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

use crate::error::ReadError;
use crate::response::ResponseSpec;
use std::path::Path;

/// The file's text.
fn read_text(path: &Path) -> Result<String, ReadError> {
    std::fs::read_to_string(path).map_err(|source| ReadError::Read {
        path: path.into(),
        source,
    })
}

/// The values found of `quantity` in `path`; none is an error.
fn found(values: Vec<f64>, path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    match values.is_empty() {
        true => Err(ReadError::NoValues {
            path: path.into(),
            quantity: quantity.into(),
        }),
        false => Ok(values),
    }
}

/// `word` as a finite number, or an error naming the file and line.
fn number(word: &str, path: &Path, line: usize) -> Result<f64, ReadError> {
    word.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| ReadError::NotANumber {
            path: path.into(),
            line,
            word: word.into(),
        })
}

/// Reads one response of the point in `folder`.
pub fn read(folder: &Path, r: &ResponseSpec) -> Result<f64, ReadError> {
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
pub fn statistic(values: &[f64], stat: &str) -> Result<f64, ReadError> {
    if values.is_empty() {
        return Err(ReadError::Empty);
    }
    if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
        return Err(ReadError::NonFinite { value });
    }
    let fold = |init: f64, f: fn(f64, f64) -> f64| values.iter().copied().fold(init, f);
    Ok(match stat {
        "max" => fold(f64::NEG_INFINITY, f64::max),
        "min" => fold(f64::INFINITY, f64::min),
        "max-abs" => values.iter().map(|v| v.abs()).fold(0.0, f64::max),
        _ => values[values.len() - 1],
    })
}

fn msd_deck(deck: &Path, r: &ResponseSpec) -> Result<Vec<f64>, ReadError> {
    let results = bumpsim_export::calculix::read_results(deck)?;
    let mass = r.mass.unwrap_or(1);
    let x = |i: usize| {
        results
            .displacement
            .get(i - 1)
            .ok_or_else(|| ReadError::Mass {
                deck: deck.into(),
                mass: i,
                masses: results.displacement.len(),
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

fn csv_column(path: &Path, column: &str) -> Result<Vec<f64>, ReadError> {
    let table = bumpsim_io::table::Table::read(path)?;
    Ok(table.column(column)?.values.clone())
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
