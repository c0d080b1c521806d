//! Reading CalculiX `.dat` print blocks (CalculiX CrunchiX User's Manual
//! 2.20, `*NODE PRINT`, `*EL PRINT`).
//!
//! A block starts with a header ` <quantity> for set <SET> and time <t>`
//! and lists rows of numbers: `node v1 v2 v3` for node values, one total
//! for `TOTALS=ONLY` element values. Blocks are grouped by (quantity, set).

use crate::FeError;
use std::collections::BTreeMap;
use std::path::Path;

/// One print block: its time and rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Time, s.
    pub time: f64,
    /// Rows of numbers.
    pub rows: Vec<Vec<f64>>,
}

/// Every block of a `.dat` file, keyed by (quantity, set), in file order.
pub type Blocks = BTreeMap<(String, String), Vec<Block>>;

/// Parses `.dat` text; a non-numeric row or a non-finite value is an error
/// naming the line.
pub fn parse(text: &str, path: &Path) -> Result<Blocks, FeError> {
    let error = |line: usize, message: String| FeError::File {
        path: format!("{}:{line}", path.display()),
        message,
    };
    let mut blocks = Blocks::new();
    let mut current: Option<(String, String)> = None;
    for (index, line) in text.lines().enumerate() {
        if let Some((key, time)) = header(line) {
            let time =
                time.ok_or_else(|| error(index + 1, "block header without a finite time".into()))?;
            blocks
                .entry(key.clone())
                .or_default()
                .push(Block { time, rows: vec![] });
            current = Some(key);
            continue;
        }
        let (Some(key), false) = (&current, line.trim().is_empty()) else {
            continue;
        };
        let row: Option<Vec<f64>> = line.split_whitespace().map(|w| w.parse().ok()).collect();
        let row = row
            .filter(|r| r.iter().all(|v: &f64| v.is_finite()))
            .ok_or_else(|| {
                error(
                    index + 1,
                    format!("expected finite numbers, found '{}'", line.trim()),
                )
            })?;
        if let Some(block) = blocks.get_mut(key).and_then(|b| b.last_mut()) {
            block.rows.push(row);
        }
    }
    Ok(blocks)
}

fn header(line: &str) -> Option<((String, String), Option<f64>)> {
    let (quantity, rest) = line.split_once(" for set ")?;
    let (set, time) = rest.split_once(" and time")?;
    let time = time.trim().parse().ok().filter(|t: &f64| t.is_finite());
    Some((
        (quantity.trim().to_string(), set.trim().to_ascii_uppercase()),
        time,
    ))
}

/// The blocks of one (quantity, set), or an error naming what is missing.
pub fn series<'a>(
    blocks: &'a Blocks,
    quantity: &str,
    set: &str,
    path: &Path,
) -> Result<&'a [Block], FeError> {
    blocks
        .iter()
        .find(|((q, s), _)| q.starts_with(quantity) && s == set)
        .map(|(_, b)| b.as_slice())
        .filter(|b| !b.is_empty())
        .ok_or_else(|| FeError::File {
            path: path.display().to_string(),
            message: format!("no '{quantity}' blocks for set {set} (did the run end early?)"),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_are_grouped_and_bad_rows_are_named() {
        let text = " displacements (vx,vy,vz) for set CAR and time  0.1E-03\n\n  1 1.0 0.0 0.0\n  2 2.0 0.0 0.0\n\n total internal energy for set FE_EBOX and time  0.1E-03\n\n  5.5\n";
        let b = parse(text, Path::new("x.dat")).unwrap();
        let d = series(&b, "displacements", "CAR", Path::new("x.dat")).unwrap();
        assert_eq!(d[0].rows.len(), 2);
        assert_eq!(
            series(&b, "total internal energy", "FE_EBOX", Path::new("x")).unwrap()[0].rows,
            vec![vec![5.5]]
        );
        assert!(series(&b, "velocities", "CAR", Path::new("x")).is_err());
        let e = parse(
            " displacements for set A and time 1.0\n\n 1 nan 0 0\n",
            Path::new("x.dat"),
        )
        .unwrap_err();
        assert!(e.to_string().contains("x.dat:3"), "{e}");
    }
}
