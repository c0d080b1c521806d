//! What [`super::write_table_in`] checks before it writes, so that
//! [`super::Table::read`] reads the file back as written: column names
//! (not empty, no surrounding spaces, none of `,` `"` `[` `]` or a control
//! character, none twice, none `time`), columns as long as the times, and
//! values finite in the unit written (RFC 4180 CSV, bumpsim's
//! `name [unit]` headers: docs/formats.md).

use super::{OutputColumn, TableError, format_number};
use bumpsim_core::units::Unit;
use std::path::Path;

/// Every column as long as the times, every value finite in its unit.
pub(super) fn check_values(
    path: &Path,
    time_unit: Unit,
    time: &[f64],
    columns: &[OutputColumn<'_>],
    rows: &[u64],
) -> Result<(), TableError> {
    let all = std::iter::once(("time", time_unit, time))
        .chain(columns.iter().map(|c| (c.name, c.unit, c.values)));
    for (name, unit, values) in all {
        if values.len() != time.len() {
            return Err(TableError::ColumnName {
                path: path.into(),
                name: name.escape_debug().to_string(),
                reason: "another number of values than there are times",
            });
        }
        if let Some(k) = values.iter().position(|v| !unit.from_si(*v).is_finite()) {
            return Err(TableError::Number {
                path: path.into(),
                line: rows[k],
                column: format!("{name} [{unit}]"),
                text: format_number(unit.from_si(values[k])),
            });
        }
    }
    Ok(())
}

/// Every column name one the reader reads back as written.
pub(super) fn check_column_names(
    path: &Path,
    columns: &[OutputColumn<'_>],
) -> Result<(), TableError> {
    for (i, c) in columns.iter().enumerate() {
        let reason = if c.name.trim().is_empty() {
            Some("an empty name")
        } else if c.name.trim() != c.name {
            Some("spaces around the name")
        } else if c.name.contains([',', '"', '[', ']']) || c.name.chars().any(char::is_control) {
            Some("a comma, quote, bracket or control character in the name")
        } else if c.name == "time" || columns[..i].iter().any(|d| d.name == c.name) {
            Some("another column's name")
        } else {
            None
        };
        if let Some(reason) = reason {
            return Err(TableError::ColumnName {
                path: path.into(),
                name: c.name.escape_debug().to_string(),
                reason,
            });
        }
    }
    Ok(())
}
