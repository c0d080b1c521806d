//! CalculiX `.dat` print blocks of any deck (CalculiX CrunchiX User's
//! Manual 2.20, `*NODE PRINT`, `*EL PRINT`): the one `.dat` reader of
//! bumpsim-fe's coupled runs and of campaigns.
//!
//! A block starts with a header ` <quantity> (<columns>) for set <SET> and
//! time <t>` and lists rows: `id v1 v2 ...` for nodes and elements, values
//! only for `TOTALS=ONLY`. CalculiX may print numbers touching
//! (`1.0E-03-2.0E-04`); they are split by [`bumpsim_core::fixed_width`]'s
//! one rule. A row that starts with a number but holds a non-number is an
//! error naming the line (a corrupt or truncated file is never read as
//! zeros); a line that starts with a word ends the block.

use crate::ExportError;
use bumpsim_core::fixed_width::words;
use std::collections::BTreeMap;
use std::path::Path;

/// One row of a block.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Node or element id (an integer first word); none for totals.
    pub id: Option<u64>,
    /// The values after the id.
    pub values: Vec<f64>,
    /// 1-based line in the file.
    pub line: usize,
}

/// One print block: its time and rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Time, in the deck's units.
    pub time: f64,
    /// Rows in file order.
    pub rows: Vec<Row>,
}

/// Every block, keyed by (quantity in lower case without its column list,
/// set in upper case), each key's blocks in file order.
pub type Blocks = BTreeMap<(String, String), Vec<Block>>;

/// Parses `.dat` text.
///
/// ```
/// use bumpsim_export::dat::parse;
/// let text = " displacements (vx,vy,vz) for set CAR and time  0.1E-03\n\n  1 1.0E-03-2.0E-04 0.0\n";
/// let blocks = parse(text, "x.dat".as_ref()).unwrap();
/// let rows = &blocks[&("displacements".to_string(), "CAR".to_string())][0].rows;
/// assert_eq!((rows[0].id, rows[0].values.clone()), (Some(1), vec![1e-3, -2e-4, 0.0]));
/// ```
pub fn parse(text: &str, path: &Path) -> Result<Blocks, ExportError> {
    let error = |line: usize, reason: String| ExportError::Dat {
        path: path.into(),
        line,
        reason,
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
        let words = words(line);
        let Some(first) = words.first() else { continue };
        if first.parse::<f64>().is_err() {
            current = None;
            continue;
        }
        let Some(block) = current
            .as_ref()
            .and_then(|k| blocks.get_mut(k))
            .and_then(|b| b.last_mut())
        else {
            continue;
        };
        let numbers: Option<Vec<f64>> = words
            .iter()
            .map(|w| w.parse().ok().filter(|v: &f64| v.is_finite()))
            .collect();
        let numbers = numbers.ok_or_else(|| {
            error(
                index + 1,
                format!("expected finite numbers, found '{}'", line.trim()),
            )
        })?;
        let id = first.parse::<u64>().ok();
        let values = numbers[usize::from(id.is_some())..].to_vec();
        block.rows.push(Row {
            id,
            values,
            line: index + 1,
        });
    }
    Ok(blocks)
}

/// A header's (quantity, set) and time.
fn header(line: &str) -> Option<((String, String), Option<f64>)> {
    let lower = line.to_ascii_lowercase();
    let at = lower.find(" for set ")?;
    let (quantity, rest) = (&lower[..at], &line[at + 9..]);
    let (set, time) = rest
        .split_once(" and time")
        .or_else(|| rest.split_once(" AND TIME"))?;
    let name = quantity.split('(').next()?.trim().to_string();
    let time = time.trim().parse().ok().filter(|t: &f64| t.is_finite());
    Some(((name, set.trim().to_ascii_uppercase()), time))
}

/// The blocks of one (quantity, set), if any.
pub fn history<'a>(blocks: &'a Blocks, quantity: &str, set: &str) -> Option<&'a [Block]> {
    let key = (quantity.to_ascii_lowercase(), set.to_ascii_uppercase());
    blocks
        .get(&key)
        .map(Vec::as_slice)
        .filter(|b| !b.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_rows_totals_and_bad_rows() {
        let text = " displacements (vx,vy,vz) for set CAR and time  0.1E-03\n\n  1 1.0 0.0 0.0\n  2 2.0 0.0 -1.5E+02\n\n total internal energy for set FE_EBOX and time  0.1E-03\n\n  5.5E+00\n";
        let b = parse(text, Path::new("x.dat")).unwrap();
        let d = history(&b, "displacements", "car").unwrap();
        assert_eq!(d[0].rows.len(), 2);
        assert_eq!(d[0].rows[1].values, vec![2.0, 0.0, -150.0]);
        let e = history(&b, "total internal energy", "FE_EBOX").unwrap();
        assert_eq!(
            (e[0].rows[0].id, e[0].rows[0].values.clone()),
            (None, vec![5.5])
        );
        assert!(history(&b, "velocities", "CAR").is_none());
        let err = parse(
            " displacements for set A and time 1.0\n\n 1 nan 0 0\n",
            Path::new("x.dat"),
        )
        .unwrap_err();
        assert!(err.to_string().contains("x.dat:3"), "{err}");
        let err = parse(
            " displacements for set A and time 1.0\n\n 1 1.0E-0x 0 0\n",
            Path::new("x.dat"),
        )
        .unwrap_err();
        assert!(err.to_string().contains("expected finite numbers"), "{err}");
    }
}
