//! CSV tables with unit headers (docs/formats.md).
//!
//! The first row names each column as `name [unit]`; the first column is
//! time. Units are converted to SI with [`bumpsim_core::units::Unit`]. Lines
//! starting with `#` are comments (for provenance notes). The separator is a
//! comma, or a semicolon when the header has semicolons and no commas (a
//! common spreadsheet export).
//!
//! Checks, each reported with the file and line: a header cell without a
//! unit or with an unknown one; a time column whose unit is not a time; a
//! row with another number of cells than the header (ragged); a cell that is
//! not a number, or is NaN or infinite; fewer than two samples; time not
//! increasing; time not uniformly sampled; a sampling interval outside
//! [`SAMPLING_INTERVAL`]; more than
//! [`MAX_INPUT_SAMPLES`] data rows (refused at the first row beyond, before
//! the rows are all held). Uniform means every interval lies
//! within 1 % of the median interval and every sample within 1 % of an
//! interval of its place on the uniform grid of the mean interval (what printing times with a few digits
//! leaves; a dropped or repeated sample is far outside).
//!
//! ```
//! use bumpsim_io::table::Table;
//! let text = "time [ms],force [kN]\n0,0\n0.1,1.5\n0.2,3.0\n";
//! let table = Table::parse(text, "inline.csv".as_ref()).unwrap();
//! let force = table.column("force").unwrap();
//! assert_eq!(force.values[2], 3000.0);
//! assert!((table.step - 1e-4).abs() < 1e-15);
//! ```

use bumpsim_core::files::MAX_INPUT_SAMPLES;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, Unit, UnitError};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

/// Sampling intervals a test channel may have, s: 1 ns (1 GHz, far beyond
/// crash-test data acquisition, 10 kHz to 1 MHz) to 1 s (a channel sampled
/// less than once a second holds nothing of an impact, which lasts about
/// 0.1 s). A 1e308 s interval put the peak at `inf ms`. The CSV tables, the
/// ISO-MME and the EV5 readers hold to it. docs/limits.md.
pub const SAMPLING_INTERVAL: RangeInclusive<f64> = 1e-9..=1.0;

mod checks;
mod error;
use checks::{check_column_names, check_values};
pub use error::TableError;

/// A data column, values in SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Name without the unit.
    pub name: String,
    /// The unit the file used (values are already converted to SI).
    pub unit: Unit,
    /// Values, SI.
    pub values: Vec<f64>,
}

/// A CSV file read into a uniform time base and SI columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Where it came from.
    pub path: PathBuf,
    /// Time of the first row, s.
    pub start: f64,
    /// Sample interval (mean of the file's intervals), s.
    pub step: f64,
    /// The data columns (time excluded).
    pub columns: Vec<Column>,
}

/// Splits a `name [unit]` header into its parts (the one rule of such
/// labels, [`bumpsim_core::units::split_unit`]).
pub use bumpsim_core::units::split_unit as split_header;

impl Table {
    /// Reads a CSV file.
    pub fn read(path: &Path) -> Result<Table, TableError> {
        let bytes = bumpsim_core::files::read_bytes(path)?;
        let text = String::from_utf8(bytes).map_err(|e| TableError::Syntax {
            path: path.to_path_buf(),
            line: line_of_offset(e.as_bytes(), e.utf8_error().valid_up_to()),
            message: "not UTF-8 text".into(),
        })?;
        Self::parse(&text, path)
    }

    /// Parses CSV text; `path` is used in messages. Rows are read one at
    /// a time into the columns (no copy of the text's cells is kept), at
    /// most [`MAX_INPUT_SAMPLES`] of them.
    pub fn parse(text: &str, path: &Path) -> Result<Table, TableError> {
        Self::parse_within(text, path, MAX_INPUT_SAMPLES)
    }

    /// [`Table::parse`] with at most `max_rows` data rows.
    fn parse_within(text: &str, path: &Path, max_rows: usize) -> Result<Table, TableError> {
        let mut rows = Rows::new(text, path);
        let header = rows.next()?.ok_or_else(|| TableError::Empty {
            path: path.into(),
            what: "no header row",
        })?;
        let units = header_units(&rows.record, header, path)?;
        let mut values: Vec<Vec<f64>> = vec![Vec::new(); units.len()];
        let mut lines = Vec::new();
        while let Some(line) = rows.next()? {
            if lines.len() == max_rows {
                return Err(TableError::TooManyRows {
                    path: path.into(),
                    line,
                    limit: max_rows,
                });
            }
            if rows.record.len() != units.len() {
                return Err(TableError::Ragged {
                    path: path.into(),
                    line,
                    expected: units.len(),
                    found: rows.record.len(),
                });
            }
            for ((cell, (name, unit)), column) in rows.record.iter().zip(&units).zip(&mut values) {
                column.push(number(cell.trim(), name, unit, line, path)?);
            }
            lines.push(line);
        }
        if lines.len() < 2 {
            return Err(TableError::Empty {
                path: path.into(),
                what: "fewer than two data rows: no sample interval",
            });
        }
        let time = values.remove(0);
        let (start, step) = time_base(&time, &lines, path)?;
        let columns = units
            .into_iter()
            .skip(1)
            .zip(values)
            .map(|((name, unit), values)| Column { name, unit, values })
            .collect();
        Ok(Table {
            path: path.into(),
            start,
            step,
            columns,
        })
    }

    /// Finds a data column by name (`force`) or by its full header (`force [kN]`).
    pub fn column(&self, selector: &str) -> Result<&Column, TableError> {
        let wanted = split_header(selector).map_or(selector.trim(), |(name, _)| name);
        let mut found = self.columns.iter().filter(|c| c.name == wanted);
        match (found.next(), found.next()) {
            (Some(column), None) => Ok(column),
            (first, _) => Err(self.column_error(format!(
                "{} '{selector}'",
                if first.is_some() {
                    "more than one column named"
                } else {
                    "no column"
                }
            ))),
        }
    }

    /// The only data column of a given dimension, or an error asking to choose.
    pub fn only_column(&self, dimension: Dimension) -> Result<&Column, TableError> {
        let matching: Vec<&Column> = self
            .columns
            .iter()
            .filter(|c| c.unit.dimension == dimension)
            .collect();
        match matching.as_slice() {
            [one] => Ok(one),
            [] => Err(self.column_error(format!("no {dimension} column"))),
            _ => Err(self.column_error(format!(
                "{} {dimension} columns: choose one",
                matching.len()
            ))),
        }
    }

    /// A column as a uniform series (SI). A table read from a file always
    /// gives one (start, step and values were checked while reading); one
    /// built by hand may not.
    pub fn series(&self, column: &Column) -> Result<UniformSeries, TableError> {
        UniformSeries::new(self.start, self.step, column.values.clone()).map_err(|e| {
            TableError::Time {
                path: self.path.clone(),
                line: 0,
                reason: format!("column '{}': {e}", column.name),
            }
        })
    }

    fn column_error(&self, reason: String) -> TableError {
        let available = self
            .columns
            .iter()
            .map(|c| format!("{} [{}]", c.name, c.unit))
            .collect::<Vec<_>>()
            .join(", ");
        TableError::Column {
            path: self.path.clone(),
            reason,
            available,
        }
    }
}

fn line_of_offset(bytes: &[u8], offset: usize) -> u64 {
    1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count() as u64
}

/// The non-blank records of CSV text, one at a time into `record`; cells
/// are trimmed where they are read (the csv crate's own trimming rebuilt
/// every record and took two thirds of the reading time).
struct Rows<'t> {
    reader: csv::Reader<&'t [u8]>,
    record: csv::StringRecord,
    path: &'t Path,
}

impl<'t> Rows<'t> {
    fn new(text: &'t str, path: &'t Path) -> Self {
        let first = text
            .lines()
            .find(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .unwrap_or("");
        let delimiter = if first.contains(';') && !first.contains(',') {
            b';'
        } else {
            b','
        };
        let reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .comment(Some(b'#'))
            .delimiter(delimiter)
            .from_reader(text.as_bytes());
        Rows {
            reader,
            record: csv::StringRecord::new(),
            path,
        }
    }

    /// Reads the next record with a non-empty cell; its 1-based line, or
    /// None at the end.
    fn next(&mut self) -> Result<Option<u64>, TableError> {
        loop {
            let more =
                self.reader
                    .read_record(&mut self.record)
                    .map_err(|e| TableError::Syntax {
                        path: self.path.into(),
                        line: e.position().map_or(0, |p| p.line()),
                        message: e.to_string(),
                    })?;
            if !more {
                return Ok(None);
            }
            if self.record.iter().any(|c| !c.trim().is_empty()) {
                return Ok(Some(self.record.position().map_or(0, |p| p.line())));
            }
        }
    }
}

fn header_units(
    header: &csv::StringRecord,
    line: u64,
    path: &Path,
) -> Result<Vec<(String, Unit)>, TableError> {
    let error = |column: usize, text: &str, reason: String| TableError::Header {
        path: path.into(),
        line,
        column,
        text: excerpt(text),
        reason,
    };
    let mut units = Vec::with_capacity(header.len());
    for (index, cell) in header.iter().map(str::trim).enumerate() {
        let (name, unit_text) = split_header(cell).ok_or_else(|| {
            error(
                index + 1,
                cell,
                "expected 'name [unit]', e.g. 'force [kN]'".into(),
            )
        })?;
        let unit = Unit::parse(unit_text).map_err(|UnitError { known, .. }| {
            error(
                index + 1,
                cell,
                format!("unknown unit '{unit_text}' (known: {known})"),
            )
        })?;
        if units.iter().any(|(n, _): &(String, Unit)| n == name) {
            return Err(error(
                index + 1,
                cell,
                format!("the name '{name}' is used twice"),
            ));
        }
        units.push((name.to_string(), unit));
    }
    match units.first() {
        Some((_, unit)) if unit.dimension != Dimension::Time => Err(error(
            1,
            header[0].trim(),
            format!(
                "the first column must be time (s, ms, ...), its unit is a {}",
                unit.dimension
            ),
        )),
        Some(_) if units.len() < 2 => Err(error(
            1,
            header[0].trim(),
            "no data columns after time".into(),
        )),
        _ => Ok(units),
    }
}

/// A cell as a finite number in SI.
fn number(cell: &str, name: &str, unit: &Unit, line: u64, path: &Path) -> Result<f64, TableError> {
    let column = || format!("{} [{unit}]", excerpt(name));
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() && unit.to_si(v).is_finite() => Ok(unit.to_si(v)),
        Ok(v) if v.is_finite() => Err(TableError::Overflow {
            path: path.into(),
            line,
            column: column(),
            text: excerpt(cell),
        }),
        _ => Err(TableError::Number {
            path: path.into(),
            line,
            column: column(),
            text: excerpt(cell),
        }),
    }
}

/// A cell as an error message quotes it: at most 60 characters, then how
/// long it is (a 1 GB cell of NUL bytes was echoed whole to stderr).
/// Control characters (NUL, ESC, ...) are shown escaped, not sent to the
/// terminal.
pub fn excerpt(text: &str) -> String {
    const SHOWN: usize = 60;
    let shown: String = text
        .chars()
        .take(SHOWN)
        .map(|c| match c.is_control() {
            true => c.escape_debug().to_string(),
            false => c.to_string(),
        })
        .collect();
    match text.chars().nth(SHOWN) {
        None => shown,
        Some(_) => format!("{shown}… ({} bytes)", text.len()),
    }
}

/// Start and mean interval of a time column, after the uniformity checks
/// and the series' own rule (a first time within 1e15 intervals of zero).
fn time_base(time: &[f64], lines: &[u64], path: &Path) -> Result<(f64, f64), TableError> {
    let (start, step) = uniform_time_base(time, lines, path)?;
    let interval = SAMPLING_INTERVAL;
    if !interval.contains(&step) {
        let (low, high) = interval.into_inner();
        return Err(TableError::Time {
            path: path.into(),
            line: lines[1],
            reason: format!(
                "the times give a sampling interval of {} s: expected {} to {} s (SAMPLING_INTERVAL, as the ISO-MME and EV5 readers)",
                format_number(step),
                format_number(low),
                format_number(high)
            ),
        });
    }
    UniformSeries::new(start, step, vec![0.0]).map_err(|e| TableError::Time {
        path: path.into(),
        line: lines[0],
        reason: e.to_string(),
    })?;
    Ok((start, step))
}

/// Start and mean interval of a time column, after the uniformity checks.
fn uniform_time_base(time: &[f64], lines: &[u64], path: &Path) -> Result<(f64, f64), TableError> {
    let error = |k: usize, reason: String| TableError::Time {
        path: path.into(),
        line: lines[k],
        reason,
    };
    if let Some(k) = (1..time.len()).find(|&k| time[k] <= time[k - 1]) {
        return Err(error(
            k,
            format!(
                "time {} s does not increase (previous row {} s)",
                time[k],
                time[k - 1]
            ),
        ));
    }
    // increasing finite times can still span more than the largest number
    // (−1e308 to 1e308): the interval would be infinite
    let last = time.len() - 1;
    if !(time[last] - time[0]).is_finite() {
        return Err(error(
            last,
            format!(
                "time runs from {} s to {} s, a span too large to represent: expected a finite sample interval",
                format_number(time[0]),
                format_number(time[last])
            ),
        ));
    }
    // the median interval is the nominal one: a dropped or repeated sample
    // then shows up at its own row instead of shifting a mean
    let mut intervals: Vec<f64> = time.windows(2).map(|w| w[1] - w[0]).collect();
    intervals.sort_by(f64::total_cmp);
    let nominal = intervals[intervals.len() / 2];
    if let Some(k) =
        (1..time.len()).find(|&k| (time[k] - time[k - 1] - nominal).abs() > 0.01 * nominal)
    {
        return Err(error(
            k,
            format!(
                "time is not uniformly sampled: the interval before this row is {} s, the usual (median) interval is {nominal} s",
                time[k] - time[k - 1]
            ),
        ));
    }
    let step = (time[time.len() - 1] - time[0]) / (time.len() - 1) as f64;
    if let Some(k) =
        (1..time.len()).find(|&k| (time[k] - time[0] - k as f64 * step).abs() > 0.01 * step)
    {
        let grid = time[0] + k as f64 * step;
        return Err(error(
            k,
            format!(
                "time {} s is off the uniform grid ({grid} s expected from the mean interval {step} s)",
                time[k]
            ),
        ));
    }
    Ok((time[0], step))
}

/// A column to write: name, dimension (values are SI) and values.
#[derive(Debug, Clone, Copy)]
pub struct OutputColumn<'a> {
    /// Name without unit.
    pub name: &'a str,
    /// The unit to write in (values are converted from SI; the header names it).
    pub unit: Unit,
    /// Values, SI.
    pub values: &'a [f64],
}

/// Writes `time [s]` and the columns as CSV with unit headers, creating the
/// folder if needed. Numbers are
/// written in their shortest round-trip form ([`format_number`]), so reading back
/// is exact. The file is replaced atomically and never over an input
/// registered with [`crate::output`].
pub fn write_table(
    path: &Path,
    time: &[f64],
    columns: &[OutputColumn<'_>],
) -> Result<(), TableError> {
    write_table_in(path, Unit::si(Dimension::Time), time, columns)
}

/// [`write_table`] with the time column in `time_unit` (`time [ms]`).
pub fn write_table_in(
    path: &Path,
    time_unit: Unit,
    time: &[f64],
    columns: &[OutputColumn<'_>],
) -> Result<(), TableError> {
    let text = table_text(path, time_unit, time, columns)?;
    crate::output::write_file(path, text.as_bytes())?;
    Ok(())
}

/// The CSV text [`write_table_in`] writes (`path` names the file in
/// errors), refused where [`Table::read`] would not read it back as
/// written: a column name that is empty, has surrounding spaces, holds `,`
/// `"` `[` `]` or a control character, or is another column's or `time`; a
/// column of another length than the times; a value that is not finite in
/// the unit written; times that are no uniform time base of two or more.
pub fn table_text(
    path: &Path,
    time_unit: Unit,
    time: &[f64],
    columns: &[OutputColumn<'_>],
) -> Result<String, TableError> {
    check_column_names(path, columns)?;
    let rows: Vec<u64> = (2..time.len() as u64 + 2).collect();
    if time.len() < 2 {
        return Err(TableError::Empty {
            path: path.into(),
            what: "fewer than two rows to write: no sample interval",
        });
    }
    check_values(path, time_unit, time, columns, &rows)?;
    time_base(time, &rows, path)?;
    let mut text = String::with_capacity(time.len() * (columns.len() + 1) * 16);
    text.push_str(&format!("time [{}]", time_unit.symbol));
    for c in columns {
        text.push_str(&format!(",{} [{}]", c.name, c.unit.symbol));
    }
    text.push('\n');
    for (k, t) in time.iter().enumerate() {
        text.push_str(&format_number(time_unit.from_si(*t)));
        for c in columns {
            text.push(',');
            text.push_str(&format_number(c.unit.from_si(c.values[k])));
        }
        text.push('\n');
    }
    Ok(text)
}

/// A number in its shortest round-trip form: plain decimal for ordinary
/// magnitudes, compact scientific (`1.5e-12`) for tiny or huge ones, so a
/// value such as 1e-300 takes 6 characters instead of 300.
pub fn format_number(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude != 0.0 && !(1e-5..1e12).contains(&magnitude) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Table, TableError> {
        Table::parse(text, Path::new("f.csv"))
    }

    #[test]
    fn long_and_control_cells_are_quoted_short() {
        assert_eq!(excerpt("1,5"), "1,5");
        assert_eq!(excerpt("a\u{1b}[2J"), "a\\u{1b}[2J");
        let huge = "\0".repeat(1_000_000);
        let shown = excerpt(&huge);
        assert!(
            shown.len() < 400 && shown.ends_with("… (1000000 bytes)"),
            "{shown}"
        );
    }

    #[test]
    fn headers_split_into_name_and_unit() {
        assert_eq!(split_header(" force [kN] "), Some(("force", "kN")));
        assert_eq!(split_header("a [b] [N/mm]"), Some(("a [b]", "N/mm")));
        assert_eq!(split_header("force"), None);
        assert_eq!(split_header("[kN]"), None);
    }

    #[test]
    fn padded_cells_and_rows_of_empty_cells_are_read() {
        let t =
            parse(" time [s] ,\tforce [kN]\n , \n 0 , 1\n0.001,\t2 \n  ,  \n0.002, 3\n").unwrap();
        assert_eq!(t.column("force").unwrap().values, vec![1e3, 2e3, 3e3]);
        let e = parse("time [s],force [kN]\n0, 1\n0.001, x \n").unwrap_err();
        assert!(
            e.to_string().contains(":3: column 'force [kN]' holds 'x'"),
            "{e}"
        );
        // a bad cell is named before the row count is judged
        let e = parse("time [s],force [kN]\n0,x\n").unwrap_err();
        assert!(
            e.to_string().contains(":2: column 'force [kN]' holds 'x'"),
            "{e}"
        );
        let e = parse("time [s],force [kN]\n0,1\n").unwrap_err();
        assert!(e.to_string().contains("fewer than two data rows"), "{e}");
    }

    #[test]
    fn rows_beyond_the_limit_are_refused_naming_the_line() {
        let text = "# note\ntime [s],f [N]\n0,1\n1,2\n2,3\n3,4\n";
        let path = Path::new("f.csv");
        assert_eq!(
            Table::parse_within(text, path, 4).unwrap().columns[0]
                .values
                .len(),
            4
        );
        let e = Table::parse_within(text, path, 3).unwrap_err();
        assert!(
            matches!(
                e,
                TableError::TooManyRows {
                    line: 6,
                    limit: 3,
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string().starts_with("f.csv:6: more than 3 data rows"),
            "{e}"
        );
    }

    #[test]
    fn semicolons_comments_and_blank_lines_are_accepted() {
        let t = parse("# from the lab\ntime [s];x1 [mm]\n\n0;1\n0.001;2\n0.002;3\n").unwrap();
        assert_eq!(t.column("x1 [mm]").unwrap().values, vec![1e-3, 2e-3, 3e-3]);
    }

    #[test]
    fn line_numbers_count_comments() {
        let err = parse("# note\ntime [s],f [N]\n0,1\n0.1,x\n").unwrap_err();
        assert!(
            err.to_string()
                .starts_with("f.csv:4: column 'f [N]' holds 'x'"),
            "{err}"
        );
    }

    #[test]
    fn each_bad_input_is_named() {
        let cases = [
            ("", "no header row"),
            ("time [s],f [N]\n0,1\n", "fewer than two data rows"),
            ("time,f [N]\n0,1\n1,2\n", "expected 'name [unit]'"),
            ("time [s],f [lbf]\n0,1\n1,2\n", "unknown unit 'lbf'"),
            ("x [mm],f [N]\n0,1\n1,2\n", "first column must be time"),
            ("time [s]\n0\n1\n", "no data columns"),
            ("time [s],f [N],f [kN]\n0,1,1\n1,2,2\n", "used twice"),
            (
                "time [s],f [N]\n0,1\n1,2,3\n",
                "f.csv:3: 3 cells, but the header has 2",
            ),
            ("time [s],f [N]\n0,1\n1,NaN\n", "holds 'NaN'"),
            ("time [s],f [N]\n0,1\n1,inf\n", "holds 'inf'"),
            ("time [s],f [N]\n0,1\n1,1\n1,1\n", "does not increase"),
            // a span beyond f64::MAX: the interval is infinite (was a panic in `series`)
            (
                "time [s],f [N]\n-1e308,1\n1e308,1\n",
                "f.csv:3: time runs from -1e308 s to 1e308 s",
            ),
            (
                "time [s],f [N]\n0,1\n1,1\n3,1\n4,1\n",
                "not uniformly sampled",
            ),
            // a sampling interval outside 1 ns..1 s, as ISO-MME and EV5
            (
                "time [s],f [N]\n0,1\n1e-300,1\n2e-300,1\n",
                "f.csv:3: the times give a sampling interval of 1e-300 s: expected 1e-9 to 1 s",
            ),
            (
                "time [s],f [N]\n0,1\n2,1\n",
                "f.csv:3: the times give a sampling interval of 2 s",
            ),
        ];
        for (text, expected) in cases {
            let err = parse(text).unwrap_err().to_string();
            assert!(err.contains(expected), "{text:?}: {err}");
        }
    }

    #[test]
    fn tiny_and_huge_numbers_are_written_compactly_and_exactly() {
        for v in [
            1e-300, -2.5e-7, 1.234e20, 0.0, 1.5, -42.0, 1e-5, 9.99e15, 123456.789,
        ] {
            let text = format_number(v);
            assert!(text.len() <= 12, "{v}: {text}");
            assert_eq!(text.parse::<f64>().unwrap(), v, "{text}");
        }
        assert_eq!(format_number(1e-300), "1e-300");
        assert_eq!(format_number(1.5), "1.5");
    }

    #[test]
    fn rounded_times_are_uniform_enough() {
        let mut text = String::from("time [ms],f [N]\n");
        for k in 0..1000 {
            text.push_str(&format!("{:.3},1\n", k as f64 / 3.0));
        }
        let t = parse(&text).unwrap();
        assert!((t.step - 1.0 / 3000.0).abs() < 1e-9);
    }

    #[test]
    fn column_selection_reports_the_choices() {
        let t = parse("time [s],a [N],b [kN]\n0,1,1\n1,2,2\n").unwrap();
        let err = t.column("c").unwrap_err().to_string();
        assert!(
            err.contains("no column 'c'") && err.contains("a [N], b [kN]"),
            "{err}"
        );
        assert!(
            t.only_column(Dimension::Force)
                .unwrap_err()
                .to_string()
                .contains("2 force columns")
        );
    }
}
