//! CalculiX results of any deck (the coupled bumper–car deck, a user's
//! own): the `.dat` file's `*NODE PRINT` / `*EL PRINT` blocks and the
//! `.frd` file's nodal result blocks, in the deck's units. Layouts as
//! CalculiX 2.20 writes them (the tests hold blocks of real output).

use super::{found, number, read_text};
use crate::error::ReadError;
use crate::response::ResponseSpec;
use bumpsim_core::fixed_width::words;
use std::path::Path;

/// `.dat`: blocks headed `NAME (columns) for set SET and time T`, then one
/// row per node or element (`ID v1 v2 ...`) or, for totals, one row of
/// values (read by [`bumpsim_export::dat`], the one `.dat` reader). The
/// history of `column` (1-based, after the id) of the rows of `entity` (or
/// the id-less row) in the blocks named `r.quantity`.
pub fn dat(path: &Path, r: &ResponseSpec) -> Result<Vec<f64>, ReadError> {
    let text = read_text(path)?;
    let blocks = bumpsim_export::dat::parse(&text, path)?;
    let wanted = r.quantity.trim().to_ascii_lowercase();
    let column = r.column.unwrap_or(1);
    let sets = blocks.iter().filter(|((name, set), _)| {
        *name == wanted && r.set.as_ref().is_none_or(|s| s.eq_ignore_ascii_case(set))
    });
    let mut values = Vec::new();
    for row in sets.flat_map(|(_, b)| b.iter().flat_map(|b| b.rows.iter())) {
        if row.id != r.entity {
            continue;
        }
        let value = row
            .values
            .get(column.saturating_sub(1))
            .ok_or_else(|| ReadError::Column {
                path: path.into(),
                line: row.line,
                column,
            })?;
        values.push(*value);
    }
    found(values, path, &r.quantity)
}

/// CalculiX `.frd`: blocks `-4 DATASET`, `-5 COMPONENT` lines naming the
/// columns, `-1 NODE values` rows, `-3` at the end; one value per block of
/// the dataset for the node.
pub fn frd(path: &Path, quantity: &str) -> Result<Vec<f64>, ReadError> {
    let parts: Vec<&str> = quantity.split_whitespace().collect();
    let [dataset, component, node] = parts.as_slice() else {
        return Err(ReadError::Quantity {
            quantity: quantity.into(),
            expected: "'DATASET COMPONENT NODE'",
        });
    };
    let text = read_text(path)?;
    let (mut inside, mut columns) = (false, Vec::<String>::new());
    let mut values = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let w = words(line);
        match w.first().map(String::as_str) {
            Some("-4") => {
                inside = w.get(1).is_some_and(|d| d.eq_ignore_ascii_case(dataset));
                columns.clear();
            }
            Some("-5") if inside => columns.extend(w.get(1).cloned()),
            Some("-3") => inside = false,
            Some("-1") if inside && w.get(1).map(String::as_str) == Some(*node) => {
                let word = component_value(&w, &columns, path, i + 1, (dataset, component))?;
                values.push(number(word, path, i + 1)?);
            }
            _ => {}
        }
    }
    found(values, path, quantity)
}

/// The word of `component` in a `-1 NODE values` row `w` of a dataset
/// with `columns`.
fn component_value<'a>(
    w: &'a [String],
    columns: &[String],
    path: &Path,
    line: usize,
    (dataset, component): (&str, &str),
) -> Result<&'a str, ReadError> {
    let at = columns
        .iter()
        .position(|c| c.eq_ignore_ascii_case(component))
        .ok_or_else(|| ReadError::Component {
            path: path.into(),
            line,
            dataset: dataset.into(),
            component: component.into(),
            components: columns.join(", "),
        })?;
    w.get(2 + at)
        .map(String::as_str)
        .ok_or_else(|| ReadError::ComponentValue {
            path: path.into(),
            line,
            component: component.into(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn response(quantity: &str, entity: Option<u64>, column: Option<usize>) -> ResponseSpec {
        ResponseSpec {
            name: "r".into(),
            reader: "calculix-dat".into(),
            file: "deck.dat".into(),
            quantity: quantity.into(),
            mass: None,
            entity,
            column,
            set: None,
            stat: "max".into(),
            unit: None,
        }
    }

    /// Blocks of a real `ccx` 2.20 `.dat` (`*NODE PRINT, TOTALS=YES` of RF
    /// and U of the exported 3-DOF deck), the values of the second step
    /// made non-zero and touching.
    const DAT: &str = " forces (fx,fy,fz) for set BUMPSIM_NALL and time  0.1000000E-03

         1  0.000000E+00  0.000000E+00  0.000000E+00
         2  0.000000E+00  0.000000E+00  0.000000E+00

 total force (fx,fy,fz) for set BUMPSIM_NALL and time  0.1000000E-03

        0.000000E+00  0.000000E+00  0.000000E+00

 displacements (vx,vy,vz) for set BUMPSIM_NALL and time  0.1000000E-03

         1  0.000000E+00  0.000000E+00  0.000000E+00
         2  0.000000E+00  0.000000E+00  0.000000E+00

 forces (fx,fy,fz) for set BUMPSIM_NALL and time  0.2000000E-03

         1 -1.500000E+03  0.000000E+00  0.000000E+00
         2  1.500000E+03  0.000000E+00  0.000000E+00

 total force (fx,fy,fz) for set BUMPSIM_NALL and time  0.2000000E-03

        2.500000E+01  0.000000E+00  0.000000E+00

 displacements (vx,vy,vz) for set BUMPSIM_NALL and time  0.2000000E-03

         1  1.000000E-03-2.000000E-04  0.000000E+00
         2  5.000000E-04  0.000000E+00  0.000000E+00
";

    #[test]
    fn dat_blocks_rows_and_totals() {
        let dir = std::env::temp_dir().join(format!("bumpsim-dat-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("deck.dat");
        std::fs::write(&path, DAT).unwrap();
        assert_eq!(
            dat(&path, &response("displacements", Some(1), None)).unwrap(),
            [0.0, 1e-3]
        );
        assert_eq!(
            dat(&path, &response("displacements", Some(1), Some(2))).unwrap(),
            [0.0, -2e-4]
        );
        assert_eq!(
            dat(&path, &response("forces", Some(1), None)).unwrap(),
            [0.0, -1500.0]
        );
        assert_eq!(
            dat(&path, &response("total force", None, None)).unwrap(),
            [0.0, 25.0]
        );
        let other_set = ResponseSpec {
            set: Some("OTHER".into()),
            ..response("forces", Some(1), None)
        };
        assert!(
            dat(&path, &other_set)
                .unwrap_err()
                .to_string()
                .contains("no values")
        );
        assert!(
            dat(&path, &response("displacements", Some(1), Some(4)))
                .unwrap_err()
                .to_string()
                .contains("no column 4")
        );
        assert!(dat(&path, &response("stresses", Some(1), None)).is_err());
    }

    /// Two result blocks as CalculiX 2.20 writes them (`*NODE FILE` of the
    /// exported 3-DOF deck; the second block's m1 row made negative so the
    /// numbers touch).
    const FRD: &str = "    1PSTEP                         1           1           1          
  100CL  101 1.00000E-04           3                     1    1           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -5  D2          1    2    2    0
 -5  D3          1    2    3    0
 -5  ALL         1    2    0    0    1ALL
 -1         1 0.00000E+00 0.00000E+00 0.00000E+00
 -1         2 0.00000E+00 0.00000E+00 0.00000E+00
 -3
    1PSTEP                         2           2           1          
  100CL  102 2.00000E-04           3                     1    2           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -5  D2          1    2    2    0
 -5  D3          1    2    3    0
 -5  ALL         1    2    0    0    1ALL
 -1         1-1.35782E-01 2.50000E-02 0.00000E+00
 -1         2 1.35470E-01 0.00000E+00 0.00000E+00
 -3
 9999
";

    #[test]
    fn frd_components_of_one_node() {
        let dir = std::env::temp_dir().join(format!("bumpsim-frd-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("deck.frd");
        std::fs::write(&path, FRD).unwrap();
        assert_eq!(frd(&path, "DISP D1 1").unwrap(), [0.0, -0.135782]);
        assert_eq!(frd(&path, "DISP D2 1").unwrap(), [0.0, 0.025]);
        assert_eq!(frd(&path, "DISP D1 2").unwrap(), [0.0, 0.13547]);
        assert!(
            frd(&path, "DISP D9 1")
                .unwrap_err()
                .to_string()
                .contains("no component D9")
        );
        assert!(
            frd(&path, "STRESS SXX 1")
                .unwrap_err()
                .to_string()
                .contains("no values")
        );
        std::fs::write(&path, FRD.replace("2.50000E-02", "nan")).unwrap();
        assert!(
            frd(&path, "DISP D2 1")
                .unwrap_err()
                .to_string()
                .contains("not a finite number")
        );
    }
}
