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

/// The parameters of an identified model, as `bumpsim identify --json` writes
/// them (other keys are ignored): masses kg, dampers N·s/m, springs N/m.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct Identified {
    /// Masses, kg.
    pub masses: Vec<f64>,
    /// Dampers, N·s/m.
    pub dampers: Vec<f64>,
    /// Springs, N/m.
    pub springs: Vec<f64>,
}

impl Identified {
    /// Reads an identification result (one DOF).
    pub fn read(path: &Path) -> Result<Identified, DataError> {
        let text = std::fs::read_to_string(path).map_err(|source| DataError::Io {
            path: path.into(),
            source,
        })?;
        serde_json::from_str(&text).map_err(|e| DataError::Line {
            path: path.into(),
            line: e.line(),
            message: format!("not an identification result of one DOF: {e}"),
        })
    }
}

impl Data {
    /// The design table with one identification result per run appended as
    /// response columns `m1 [kg]`, ..., `c1 [Ns/m]`, ..., `k1 [N/m]` (stage 2
    /// of paper C). Every result must have the same number of masses.
    pub fn with_results(&self, results: &[Identified]) -> Result<Data, String> {
        if results.len() != self.rows.len() {
            return Err(format!(
                "{} results for {} design runs: give one per run, in run order",
                results.len(),
                self.rows.len()
            ));
        }
        let dof = results.first().map_or(0, |r| r.masses.len());
        if let Some((i, _)) = results.iter().enumerate().find(|(_, r)| {
            r.masses.len() != dof || r.dampers.len() + 1 != dof || r.springs.len() + 1 != dof
        }) {
            return Err(format!(
                "result {} is not a {dof}-DOF model like the first",
                i + 1
            ));
        }
        let mut out = self.clone();
        let columns = [
            ("m", dof, "kg"),
            ("c", dof - 1, "Ns/m"),
            ("k", dof - 1, "N/m"),
        ];
        for (letter, count, unit) in columns {
            for j in 1..=count {
                out.names.push(format!("{letter}{j}"));
                out.units.push(Some(unit.into()));
            }
        }
        for (row, r) in out.rows.iter_mut().zip(results) {
            row.extend(r.masses.iter().chain(&r.dampers).chain(&r.springs));
        }
        Ok(out)
    }

    /// The table as CSV with `name [unit]` headers.
    pub fn to_csv(&self) -> String {
        let header: Vec<String> = self
            .names
            .iter()
            .zip(&self.units)
            .map(|(n, u)| u.as_ref().map_or(n.clone(), |u| format!("{n} [{u}]")))
            .collect();
        let mut csv = header.join(",") + "\n";
        for row in &self.rows {
            csv += &row.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
            csv.push('\n');
        }
        csv
    }
}
