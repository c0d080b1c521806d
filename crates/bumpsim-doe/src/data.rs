//! Tables of factors and responses (CSV): a header of names, optionally with
//! units in brackets (`Kax [N/mm]`), then one row of numbers per run. Errors
//! name the file and line.

use crate::model::{Factor, FactorError};
use bumpsim_core::model::MsdModel;
use bumpsim_io::car::{Car, CarError};
use bumpsim_io::table::split_header;
use std::path::{Path, PathBuf};

/// Why a table cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
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
    /// Not a regular file, too large or not text.
    #[error(transparent)]
    Read(#[from] bumpsim_core::files::ReadError),
    /// An identification result or car file cannot be used.
    #[error(transparent)]
    Result(#[from] CarError),
}

/// Identification results that do not fit a design.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ResultsError {
    /// Not one result per design run.
    #[error("{results} results for {runs} design runs: give one per run, in run order")]
    Count {
        /// Results given.
        results: usize,
        /// Design runs.
        runs: usize,
    },
    /// A column of the results is already a column of the design.
    #[error(
        "the design already has a column '{name}': the results' columns m1.., c1.., k1.. must be new"
    )]
    Column {
        /// The column name.
        name: String,
    },
    /// A result with another number of masses than the first.
    #[error("result {result} is not a {dof}-DOF model like the first")]
    Dof {
        /// 1-based result number.
        result: usize,
        /// The first result's number of masses.
        dof: usize,
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
    /// Reads a CSV table (`#` lines are comments; cells may be quoted).
    /// Headers are split by [`bumpsim_io::table::split_header`], as for
    /// channel tables.
    pub fn read(path: &Path) -> Result<Data, DataError> {
        let text = bumpsim_core::files::read_text(path)?;
        Self::parse(&text, path)
    }

    /// Parses CSV text; `path` is used in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Data, DataError> {
        let line_error = |line: u64, message: String| DataError::Line {
            path: path.into(),
            line: line as usize,
            message,
        };
        let mut records = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .from_reader(text.as_bytes())
            .into_records();
        let header = records
            .next()
            .ok_or_else(|| line_error(1, "no header row".into()))?
            .map_err(|e| line_error(csv_line(&e), e.to_string()))?;
        let (names, units): (Vec<String>, Vec<Option<String>>) = header
            .iter()
            .map(|cell| match split_header(cell) {
                Some((name, unit)) => (name.to_string(), Some(unit.to_string())),
                None => (cell.to_string(), None),
            })
            .unzip();
        if let Some(i) = (0..names.len()).find(|&i| names[..i].contains(&names[i])) {
            return Err(line_error(
                header.position().map_or(1, csv::Position::line),
                format!("column '{}' is named twice", names[i]),
            ));
        }
        let mut rows = Vec::new();
        for record in records {
            let record = record.map_err(|e| line_error(csv_line(&e), e.to_string()))?;
            let line = record.position().map_or(0, csv::Position::line);
            if record.len() != names.len() {
                return Err(line_error(
                    line,
                    format!("{} cells, the header has {}", record.len(), names.len()),
                ));
            }
            let row = record
                .iter()
                .zip(&names)
                .map(|(c, n)| {
                    c.parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| {
                            line_error(
                                line,
                                format!("column '{n}' holds '{c}', expected a finite number"),
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

    /// The values of a named column, or an error listing the columns.
    pub fn values(&self, name: &str) -> Result<Vec<f64>, ColumnError> {
        self.column(name).ok_or_else(|| ColumnError::Missing {
            name: name.to_string(),
            columns: self.names.join(", "),
        })
    }

    /// The unit written in a named column's header, if any.
    pub fn unit(&self, name: &str) -> Option<String> {
        let i = self.names.iter().position(|n| n == name)?;
        self.units[i].clone()
    }

    /// Factors over the named columns (levels `low[i]`/`high[i]` where
    /// given, else the observed extremes) and the coded design matrix, one
    /// row per table row: what a regression of this table needs
    /// (`bumpsim doe fit`, the Python package).
    ///
    /// ```
    /// use bumpsim_doe::data::Data;
    /// let data = Data::parse("t [mm],y [kN]\n2,10\n4,14\n3,12\n", std::path::Path::new("d.csv")).unwrap();
    /// let (factors, coded) = data.coded(&["t".into()], &[], &[]).unwrap();
    /// assert_eq!((factors[0].low, factors[0].high), (2.0, 4.0));   // the observed extremes
    /// assert_eq!(coded, vec![vec![-1.0], vec![1.0], vec![0.0]]);
    /// assert_eq!(data.unit("y").as_deref(), Some("kN"));
    /// assert!(data.coded(&["w".into()], &[], &[]).unwrap_err().to_string().contains("columns: t, y"));
    /// ```
    pub fn coded(
        &self,
        names: &[String],
        low: &[f64],
        high: &[f64],
    ) -> Result<(Vec<Factor>, Vec<Vec<f64>>), ColumnError> {
        let columns = names
            .iter()
            .map(|name| self.values(name))
            .collect::<Result<Vec<_>, _>>()?;
        let factors = names
            .iter()
            .zip(&columns)
            .enumerate()
            .map(|(i, (name, values))| {
                let (lo, hi) = (low.get(i).copied(), high.get(i).copied());
                Factor::spanning(name, values, lo, hi, self.unit(name))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let coded = (0..self.rows.len())
            .map(|r| {
                factors
                    .iter()
                    .zip(&columns)
                    .map(|(f, c)| f.coded(c[r]))
                    .collect()
            })
            .collect();
        Ok((factors, coded))
    }
}

/// A table that lacks what a regression needs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ColumnError {
    /// A named column is not in the table.
    #[error("no column '{name}'; columns: {columns}")]
    Missing {
        /// The name asked for.
        name: String,
        /// The table's columns.
        columns: String,
    },
    /// A factor's levels are not valid.
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// Reads the model of an identification result (`bumpsim identify --json`
/// for one DOF) or a car file, through the one reader of both,
/// [`bumpsim_io::car::Car::read_model_file`].
pub fn read_result(path: &Path) -> Result<MsdModel, DataError> {
    Ok(Car::read_model_file(path)?.model)
}

/// The standard errors an identification result carries
/// (`uncertainty.names` and `uncertainty.standard_errors` of `bumpsim
/// identify --json`, SI): `(name, SE)` for each parameter whose SE is a
/// finite number; empty for a car file or a result without them.
pub fn read_standard_errors(path: &Path) -> Result<Vec<(String, f64)>, DataError> {
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if !is_json {
        return Ok(Vec::new());
    }
    let text = bumpsim_core::files::read_text(path)?;
    let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| DataError::Line {
        path: path.into(),
        line: e.line(),
        message: e.to_string(),
    })?;
    let uncertainty = &value["uncertainty"];
    let (Some(names), Some(errors)) = (
        uncertainty["names"].as_array(),
        uncertainty["standard_errors"].as_array(),
    ) else {
        return Ok(Vec::new());
    };
    Ok(names
        .iter()
        .zip(errors)
        .filter_map(|(n, e)| Some((n.as_str()?.to_string(), e.as_f64()?)))
        .filter(|(_, e)| e.is_finite() && *e >= 0.0)
        .collect())
}

/// The line of a CSV error, when known.
fn csv_line(error: &csv::Error) -> u64 {
    error.position().map_or(0, csv::Position::line)
}

impl Data {
    /// The design table with one identification result per run appended as
    /// response columns `m1 [kg]`, ..., `c1 [Ns/m]`, ..., `k1 [N/m]` (stage 2
    /// of paper C). Every result must have the same number of masses.
    pub fn with_results(&self, results: &[MsdModel]) -> Result<Data, ResultsError> {
        if results.len() != self.rows.len() {
            return Err(ResultsError::Count {
                results: results.len(),
                runs: self.rows.len(),
            });
        }
        let dof = results.first().map_or(0, MsdModel::dof);
        if let Some(i) = results.iter().position(|r| r.dof() != dof) {
            return Err(ResultsError::Dof { result: i + 1, dof });
        }
        let mut out = self.clone();
        let columns = [
            ("m", dof, "kg"),
            ("c", dof - 1, "Ns/m"),
            ("k", dof - 1, "N/m"),
        ];
        for (letter, count, unit) in columns {
            for j in 1..=count {
                let name = format!("{letter}{j}");
                if out.names.contains(&name) {
                    return Err(ResultsError::Column { name });
                }
                out.names.push(name);
                out.units.push(Some(unit.into()));
            }
        }
        for (row, r) in out.rows.iter_mut().zip(results) {
            row.extend(r.parameters());
        }
        Ok(out)
    }

    /// The table with a column `NAME.se [unit]` for each column `NAME`
    /// whose standard error every run's result carries (`errors[run]`, from
    /// [`read_standard_errors`]), in the table's column order: what `doe
    /// fit --se NAME` reads. Returns the table and the names given SEs.
    pub fn with_standard_errors(&self, errors: &[Vec<(String, f64)>]) -> (Data, Vec<String>) {
        let mut out = self.clone();
        let mut named = Vec::new();
        for (column, name) in self.names.iter().enumerate() {
            let of_run =
                |run: &Vec<(String, f64)>| run.iter().find(|(n, _)| n == name).map(|e| e.1);
            let Some(values) = errors.iter().map(of_run).collect::<Option<Vec<f64>>>() else {
                continue;
            };
            let se = format!("{name}.se");
            if errors.len() != self.rows.len() || self.names.contains(&se) {
                continue;
            }
            out.names.push(se);
            out.units.push(self.units[column].clone());
            out.rows
                .iter_mut()
                .zip(&values)
                .for_each(|(row, v)| row.push(*v));
            named.push(name.clone());
        }
        (out, named)
    }

    /// The table as CSV with `name [unit]` headers.
    pub fn to_csv(&self) -> String {
        let header: Vec<String> = self
            .names
            .iter()
            .zip(&self.units)
            .map(|(n, u)| u.as_ref().map_or(n.clone(), |u| format!("{n} [{u}]")))
            .map(|cell| quoted(&cell))
            .collect();
        let mut csv = header.join(",") + "\n";
        for row in &self.rows {
            csv += &row.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
            csv.push('\n');
        }
        csv
    }
}

/// A CSV cell as written: quoted (inner quotes doubled) when it holds a
/// separator, a quote, a line break or surrounding spaces, so that
/// [`Data::parse`] reads it back as it was.
fn quoted(cell: &str) -> String {
    let plain = !cell.contains([',', '"', '\n', '\r', '#']) && cell.trim() == cell;
    match plain {
        true => cell.to_string(),
        false => format!("\"{}\"", cell.replace('"', "\"\"")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Data, DataError> {
        Data::parse(text, Path::new("design.csv"))
    }

    #[test]
    fn headers_split_like_channel_tables_and_cells_may_be_quoted() {
        let data = parse("# design\nKax [N/mm],\"M [kg]\",run\n1,2,3\n\n4,\"5\",6\n").unwrap();
        assert_eq!(data.names, ["Kax", "M", "run"]);
        assert_eq!(data.units, [Some("N/mm".into()), Some("kg".into()), None]);
        assert_eq!(data.rows, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let err = parse("a,b\n1,2\n3\n").unwrap_err().to_string();
        assert_eq!(err, "design.csv:3: 1 cells, the header has 2");
        let err = parse("a,b\n1,nan\n").unwrap_err().to_string();
        assert_eq!(
            err,
            "design.csv:2: column 'b' holds 'nan', expected a finite number"
        );
    }

    #[test]
    fn results_must_fit_the_design() {
        let data = parse("a\n1\n2\n").unwrap();
        let two = MsdModel::new(vec![1.0, 2.0], vec![3.0], vec![4.0]).unwrap();
        let one = MsdModel::new(vec![1.0], vec![], vec![]).unwrap();
        let err = data.with_results(std::slice::from_ref(&two)).unwrap_err();
        assert_eq!(
            err,
            ResultsError::Count {
                results: 1,
                runs: 2
            }
        );
        let err = data.with_results(&[two.clone(), one]).unwrap_err();
        assert_eq!(err, ResultsError::Dof { result: 2, dof: 2 });
        let joined = data.with_results(&[two.clone(), two]).unwrap();
        assert_eq!(joined.names, ["a", "m1", "m2", "c1", "k1"]);
        assert_eq!(joined.rows[1], [2.0, 1.0, 2.0, 3.0, 4.0]);
    }
}
