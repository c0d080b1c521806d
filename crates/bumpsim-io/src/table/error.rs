//! The errors of the CSV table reader and writer ([`super::Table`]); each
//! names the file, and the line where there is one.

use std::path::PathBuf;

/// A problem with a CSV file; every variant names the file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TableError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The CSV layer failed (e.g. invalid UTF-8).
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// What the parser said.
        message: String,
    },
    /// No header or no rows.
    #[error("{path}: {what}")]
    Empty {
        /// The file.
        path: PathBuf,
        /// What is missing.
        what: &'static str,
    },
    /// A header cell is not `name [unit]` with a known unit.
    #[error("{path}:{line}: column {column} '{text}': {reason}")]
    Header {
        /// The file.
        path: PathBuf,
        /// Line of the header.
        line: u64,
        /// 1-based column.
        column: usize,
        /// The cell.
        text: String,
        /// What is wrong.
        reason: String,
    },
    /// A row with a different number of cells than the header.
    #[error("{path}:{line}: {found} cells, but the header has {expected} (ragged row)")]
    Ragged {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// Header cells.
        expected: usize,
        /// Cells in this row.
        found: usize,
    },
    /// A cell that is not a finite number.
    #[error("{path}:{line}: column '{column}' holds '{text}', expected a finite number")]
    Number {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// Column header.
        column: String,
        /// The cell.
        text: String,
    },
    /// A finite number that is infinite once converted to SI (`1e308` kN).
    #[error(
        "{path}:{line}: column '{column}' holds '{text}', beyond the largest number once converted to SI"
    )]
    Overflow {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// Column header.
        column: String,
        /// The cell.
        text: String,
    },
    /// More data rows than [`bumpsim_core::files::MAX_INPUT_SAMPLES`],
    /// refused at the first row beyond it (before all are held).
    #[error(
        "{path}:{line}: more than {limit} data rows, the most a table may have (MAX_INPUT_SAMPLES): shorten the record or resample it"
    )]
    TooManyRows {
        /// The file.
        path: PathBuf,
        /// 1-based line of the first row beyond the limit.
        line: u64,
        /// The limit, rows.
        limit: usize,
    },
    /// The time base is not usable.
    #[error("{path}:{line}: {reason}")]
    Time {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u64,
        /// What is wrong.
        reason: String,
    },
    /// A selected column does not exist or is ambiguous.
    #[error("{path}: {reason}; columns: {available}")]
    Column {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
        /// The data columns there are.
        available: String,
    },
    /// A column the table reader would not read back as written (its name,
    /// or its length).
    #[error("{path}: column '{name}': {reason}: the file would not read back as written")]
    ColumnName {
        /// The file to write.
        path: PathBuf,
        /// The name (control characters escaped).
        name: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// A file cannot be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The output is refused (it would land on an input) or cannot be written.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// The file is not a regular file or too large.
    #[error(transparent)]
    Read(#[from] bumpsim_core::files::ReadError),
}
