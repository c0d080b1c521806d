//! Minimal readers of LS-DYNA's ASCII time-history files (`*DATABASE_GLSTAT`,
//! `_NODOUT`, `_RCFORC`, `_DEFORC` with ASCII output), each returning one
//! quantity's history in the deck's units.
//!
//! Written from the files' layout (LS-DYNA Keyword User's Manual, database
//! options): labels and fixed-width `E` numbers, which may touch
//! (`x-1.2345E+01`, `0.0000E+00-1.2340E-03`). Every line is therefore split
//! into words with a space put before a sign that is not an exponent's
//! ([`bumpsim_core::fixed_width`]). Not yet checked against files written
//! by LS-DYNA itself (no solver here); a file whose layout they do not
//! recognise gives an error naming the quantity, never a zero.
//!
//! - `glstat`: `name ..... value` lines, one block per output time:
//!   quantity `kinetic energy`, `internal energy`, `total energy`, ...;
//! - `nodout`: blocks of a column header (`nodal point x-disp y-disp ...`)
//!   and one row per node: quantity `NODE COLUMN` (`1001 x-disp`);
//! - `rcforc`: `master ID time T x X y Y z Z mass M` lines (and `slave`):
//!   quantity `master ID x` (or `y`, `z`, `mass`, `slave ...`);
//! - `deforc`: per element a line with its id and `x-force= ...`,
//!   `y-force=`, `z-force=`, `resultant=` (and more) values: quantity
//!   `ELEMENT x-force`.

use super::{found, number, read_text};
use crate::error::ReadError;
use bumpsim_core::fixed_width;
use std::path::Path;

/// The words of a line: touching numbers separated by the one rule
/// ([`bumpsim_core::fixed_width::words`]), a space after every `=`, and
/// hyphenated labels that rule splits (`x-force=`) joined again.
pub fn words(line: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for w in fixed_width::words(&line.replace('=', "= ")) {
        let label_tail = w.starts_with('-') && w[1..].starts_with(char::is_alphabetic);
        match out.last_mut() {
            Some(last) if label_tail && last.ends_with(char::is_alphabetic) => last.push_str(&w),
            _ => out.push(w),
        }
    }
    out
}

/// `glstat`: the history of a `name ..... value` quantity.
pub fn glstat(path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    let text = read_text(path)?;
    let wanted = quantity.trim().to_ascii_lowercase();
    let mut values = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let Some((name, value)) = line.split_once("..") else {
            continue;
        };
        if name.trim().to_ascii_lowercase() == wanted {
            values.push(number(value.trim_start_matches('.').trim(), path, i + 1)?);
        }
    }
    found(values, path, quantity)
}

/// Splits `ID NAME` (`1001 x-disp`, `master 1 x`: the id is the numeric word).
fn id_and_name(quantity: &str) -> Result<(String, String), ReadError> {
    let parts: Vec<&str> = quantity.split_whitespace().collect();
    match parts.as_slice() {
        [id, name] => Ok((id.to_string(), name.to_ascii_lowercase())),
        _ => Err(ReadError::Quantity {
            quantity: quantity.into(),
            expected: "'ID NAME', e.g. '1001 x-disp'",
        }),
    }
}

/// `nodout`: the history of one column of one node.
pub fn nodout(path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    let (node, column) = id_and_name(quantity)?;
    let text = read_text(path)?;
    let mut header: Vec<String> = Vec::new();
    let mut values = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let w = words(line);
        if line.trim_start().starts_with("nodal point") {
            // "nodal point" counts as the node column
            header = w.iter().skip(2).map(|s| s.to_ascii_lowercase()).collect();
            continue;
        }
        if w.first() != Some(&node) || header.is_empty() {
            continue;
        }
        if let Some(j) = header.iter().position(|h| *h == column) {
            let word = w.get(j + 1).ok_or_else(|| ReadError::NamedColumn {
                path: path.into(),
                line: i + 1,
                column: column.clone(),
            })?;
            values.push(number(word, path, i + 1)?);
        }
    }
    found(values, path, quantity)
}

/// `rcforc`: `master|slave ID component` of the contact force lines.
pub fn rcforc(path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    let parts: Vec<&str> = quantity.split_whitespace().collect();
    let [side, id, component] = parts.as_slice() else {
        return Err(ReadError::Quantity {
            quantity: quantity.into(),
            expected: "'master|slave ID x|y|z|mass'",
        });
    };
    let text = read_text(path)?;
    let mut values = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let w = words(line);
        if w.len() < 2 || !w[0].eq_ignore_ascii_case(side) || w[1] != *id {
            continue;
        }
        values.push(labelled(&w, component, path, i + 1)?);
    }
    found(values, path, quantity)
}

/// The number after `label` (or `label=`) in the words of a line.
fn labelled(w: &[String], label: &str, path: &Path, line: usize) -> Result<f64, ReadError> {
    let error = |at_end: bool| {
        let (path, label) = (path.into(), label.into());
        match at_end {
            true => ReadError::LabelValue { path, line, label },
            false => ReadError::Label { path, line, label },
        }
    };
    let at = w
        .iter()
        .position(|x| x.trim_end_matches('=').eq_ignore_ascii_case(label))
        .ok_or_else(|| error(false))?;
    let word = w.get(at + 1).ok_or_else(|| error(true))?;
    number(word, path, line)
}

/// `deforc`: `ELEMENT LABEL` of the discrete element lines.
pub fn deforc(path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    let (element, label) = id_and_name(quantity)?;
    let text = read_text(path)?;
    let mut values = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let w = words(line);
        let id_at = w.iter().position(|x| x == &element);
        let labelled_line = w.iter().any(|x| x.ends_with('='));
        if let (Some(at), true) = (id_at, labelled_line) {
            // the id is the element number, not a value: it precedes the labels
            if w[..at].iter().all(|x| !x.ends_with('=')) {
                values.push(labelled(&w, &label, path, i + 1)?);
            }
        }
    }
    found(values, path, quantity)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, text: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpsim-lsdyna-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn touching_numbers_and_labels_are_split() {
        assert_eq!(
            words("x-1.2E+01 y 2.0E-03"),
            ["x", "-1.2E+01", "y", "2.0E-03"]
        );
        assert_eq!(
            words("   1001 0.0000E+00-1.2340E-03"),
            ["1001", "0.0000E+00", "-1.2340E-03"]
        );
        assert_eq!(
            words("  12  x-force= -1.5E+02"),
            ["12", "x-force=", "-1.5E+02"]
        );
        assert_eq!(
            words("resultant=-1.5E+02 mass-2.0"),
            ["resultant=", "-1.5E+02", "mass", "-2.0"]
        );
    }

    #[test]
    fn glstat_histories() {
        let text = " time...........................   0.00000E+00\n kinetic energy..................   1.00000E+03\n internal energy.................   0.00000E+00\n\n time...........................   1.00000E-03\n kinetic energy..................   8.00000E+02\n internal energy.................   2.00000E+02\n";
        let path = file("glstat", text);
        assert_eq!(glstat(&path, "internal energy").unwrap(), [0.0, 200.0]);
        assert!(glstat(&path, "hourglass energy").is_err());
        let path = file("glstat-bad", "kinetic energy....  1.0E+0x\n");
        assert!(
            glstat(&path, "kinetic energy")
                .unwrap_err()
                .to_string()
                .contains("not a finite number")
        );
    }

    #[test]
    fn nodout_columns_of_one_node() {
        let header = " nodal point  x-disp     y-disp      z-disp      x-vel       y-vel       z-vel      x-accl      y-accl      z-accl      x-coor      y-coor      z-coor\n";
        let mut text = String::new();
        for (t, d) in [(0.0, "0.0000E+00"), (1e-3, "-1.2340E-03")] {
            text += &format!(
                " n o d a l   p r i n t   o u t   f o r   t i m e  s t e p       1   ( at time {t:.7E} )\n\n{header}"
            );
            text += &format!(
                "      1001 0.0000E+00{d} 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 1.0000E+00 2.0000E+00 3.0000E+00\n"
            );
            text += "      1002 5.0000E-01 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 1.0000E+00 2.0000E+00 3.0000E+00\n\n";
        }
        let path = file("nodout", &text);
        assert_eq!(nodout(&path, "1001 y-disp").unwrap(), [0.0, -1.234e-3]);
        assert_eq!(nodout(&path, "1002 x-disp").unwrap(), [0.5, 0.5]);
        assert!(nodout(&path, "9999 x-disp").is_err());
        assert!(nodout(&path, "1001").is_err());
    }

    #[test]
    fn rcforc_and_deforc_lines() {
        let text = "  master     1 time  1.00000E-03  x-1.23456E+01  y  0.00000E+00  z  0.00000E+00  mass 0.0000E+00\n    slave     1 time  1.00000E-03  x  1.23456E+01  y  0.00000E+00  z  0.00000E+00  mass 0.0000E+00\n  master     1 time  2.00000E-03  x-2.00000E+01  y  0.00000E+00  z  0.00000E+00  mass 0.0000E+00\n";
        let path = file("rcforc", text);
        assert_eq!(rcforc(&path, "master 1 x").unwrap(), [-12.3456, -20.0]);
        assert_eq!(rcforc(&path, "slave 1 x").unwrap(), [12.3456]);
        let text = " d i s c r e t e   e l e m e n t   o u t p u t   f o r   t i m e  1.00000E-03\n spring/damper number       12  x-force= -1.5000E+02 y-force=  0.0000E+00 z-force=  0.0000E+00 resultant=  1.5000E+02\n";
        let path = file("deforc", text);
        assert_eq!(deforc(&path, "12 x-force").unwrap(), [-150.0]);
        assert_eq!(deforc(&path, "12 resultant").unwrap(), [150.0]);
        assert!(deforc(&path, "13 x-force").is_err());
    }
}
