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

#[cfg(test)]
mod tests {
    use super::super::{Table, table_text};
    use super::*;

    /// A small deterministic generator (SplitMix64), so that every run
    /// tries the same tables.
    struct Draw(u64);

    impl Draw {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }

        fn pick<T: Copy>(&mut self, from: &[T]) -> T {
            from[(self.next() % from.len() as u64) as usize]
        }

        fn value(&mut self) -> f64 {
            let mantissa = (self.next() % 2_000_001) as f64 / 1e6 - 1.0;
            mantissa * 10f64.powi((self.next() % 601) as i32 - 300)
        }
    }

    /// Issue 34, the writer's property: whatever `table_text` writes (names
    /// with any of the characters a CSV treats specially, every unit, values
    /// from 1e-300 to 1e300), `Table::parse` reads back with the same names
    /// and units and the same values in the unit written; what it would
    /// not read back is refused before anything is written.
    #[test]
    fn whatever_the_table_writer_writes_the_reader_reads_back_equal() {
        let mut draw = Draw(34);
        let names = [
            "F", "a b", "x,y", "q\"", "[m]", "", " s", "time", "Ω", "t\u{7}", "F",
        ];
        let units = ["N", "kN", "g", "m/s", "mm", "s", "kg", "J", "deg"];
        let (mut written, mut refused) = (0, 0);
        for _ in 0..400 {
            let count = 1 + (draw.next() % 3) as usize;
            let rows = 2 + (draw.next() % 5) as usize;
            let time_unit = Unit::parse(draw.pick(&["s", "ms"])).unwrap();
            let start = (draw.next() % 2001) as f64 / 1000.0 - 1.0;
            let step = 10f64.powi(-((draw.next() % 6) as i32));
            let time: Vec<f64> = (0..rows).map(|k| start + k as f64 * step).collect();
            let data: Vec<(&str, Unit, Vec<f64>)> = (0..count)
                .map(|_| {
                    let unit = Unit::parse(draw.pick(&units)).unwrap();
                    let values = (0..rows).map(|_| draw.value()).collect();
                    (draw.pick(&names), unit, values)
                })
                .collect();
            let columns: Vec<OutputColumn> = data
                .iter()
                .map(|(name, unit, values)| OutputColumn {
                    name,
                    unit: *unit,
                    values,
                })
                .collect();
            let path = Path::new("p.csv");
            let Ok(text) = table_text(path, time_unit, &time, &columns) else {
                refused += 1;
                continue;
            };
            written += 1;
            let table = Table::parse(&text, path).unwrap_or_else(|e| panic!("{e}\n{text}"));
            assert_eq!(table.columns.len(), columns.len(), "{text}");
            for (read, given) in table.columns.iter().zip(&columns) {
                assert_eq!((read.name.as_str(), read.unit), (given.name, given.unit));
                let expected: Vec<f64> = given
                    .values
                    .iter()
                    .map(|v| given.unit.to_si(given.unit.from_si(*v)))
                    .collect();
                assert_eq!(read.values, expected, "{text}");
            }
            let first = time_unit.to_si(time_unit.from_si(time[0]));
            assert_eq!(table.start, first, "{text}");
        }
        assert!(
            written > 50 && refused > 50,
            "{written} written, {refused} refused"
        );
    }
}
