//! Tables of factors and responses (CSV): a header of names, optionally with
//! units in brackets (`Kax [N/mm]`), then one row of numbers per run. Errors
//! name the file and line.

use std::path::{Path, PathBuf};

/// Why a table cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum DataError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A line is malformed.
    #[error("{path}:{line}: {message}")]
    Line {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// A table: column names (without units), units, rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Data {
    /// Column names.
    pub names: Vec<String>,
    /// Units as written (`None` without brackets).
    pub units: Vec<Option<String>>,
    /// Rows.
    pub rows: Vec<Vec<f64>>,
}

impl Data {
    /// Reads a CSV table (`#` lines are comments).
    pub fn read(path: &Path) -> Result<Data, DataError> {
        let text = std::fs::read_to_string(path).map_err(|source| DataError::Io {
            path: path.into(),
            source,
        })?;
        let line_error = |line: usize, message: String| DataError::Line {
            path: path.into(),
            line,
            message,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let (_, header) = lines
            .next()
            .ok_or_else(|| line_error(1, "no header row".into()))?;
        let (names, units): (Vec<String>, Vec<Option<String>>) = header
            .split(',')
            .map(|cell| match cell.split_once('[') {
                Some((name, unit)) => (
                    name.trim().to_string(),
                    Some(unit.trim_end_matches([']', ' ']).trim().to_string()),
                ),
                None => (cell.trim().to_string(), None),
            })
            .unzip();
        let mut rows = Vec::new();
        for (i, line) in lines {
            let cells: Vec<&str> = line.split(',').collect();
            if cells.len() != names.len() {
                return Err(line_error(
                    i + 1,
                    format!("{} cells, the header has {}", cells.len(), names.len()),
                ));
            }
            let row = cells
                .iter()
                .zip(&names)
                .map(|(c, n)| {
                    c.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| {
                            line_error(
                                i + 1,
                                format!(
                                    "column '{n}' holds '{}', expected a finite number",
                                    c.trim()
                                ),
                            )
                        })
                })
                .collect::<Result<Vec<f64>, _>>()?;
            rows.push(row);
        }
        Ok(Data { names, units, rows })
    }

    /// The values of a named column.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let i = self.names.iter().position(|n| n == name)?;
        Some(self.rows.iter().map(|r| r[i]).collect())
    }
}
