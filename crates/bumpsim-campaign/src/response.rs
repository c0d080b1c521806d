//! The `[[response]]` section of a campaign file: what is read back per
//! point (reader, file, quantity, statistic), and its check before
//! anything runs. The readers ([`crate::readers`]) read by it; the
//! campaign file ([`crate::spec`]) holds a list of it.

use crate::expr::is_name;
use serde::{Deserialize, Serialize};

/// The readers a response may name.
pub const READERS: [&str; 8] = [
    "calculix",
    "calculix-dat",
    "calculix-frd",
    "csv",
    "lsdyna-glstat",
    "lsdyna-nodout",
    "lsdyna-rcforc",
    "lsdyna-deforc",
];

/// The statistics of a history a response may take.
pub const STATS: [&str; 4] = ["max", "min", "final", "max-abs"];

/// One response read back per point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResponseSpec {
    /// Column name in the collected table.
    pub name: String,
    /// `calculix` (the `.dat` of a bumpsim MSD deck), `calculix-dat` (any
    /// `*NODE PRINT`/`*EL PRINT` block of any deck's `.dat`), `calculix-frd`,
    /// `csv` (a `time,...` table
    /// with unit headers), `lsdyna-glstat`, `lsdyna-nodout`, `lsdyna-rcforc`
    /// or `lsdyna-deforc`.
    pub reader: String,
    /// The file in the point folder (`calculix`: the deck; the `.dat` beside it is read).
    pub file: String,
    /// `calculix`: `displacement` of `mass`, or `compression` x_mass − x_(mass+1);
    /// `calculix-dat`: the block name (`displacements`, `forces`, `total force`,
    /// `stresses`, ...); `calculix-frd`: `DATASET COMPONENT NODE`;
    /// `csv`: the column; `lsdyna-glstat`: the quantity (`kinetic energy`, ...);
    /// `lsdyna-nodout`: `NODE COLUMN` (`1001 x-disp`); `lsdyna-rcforc`:
    /// `master|slave ID x|y|z|mass`; `lsdyna-deforc`: `ELEMENT LABEL` (`12 x-force`).
    pub quantity: String,
    /// `calculix`: the 1-based mass.
    #[serde(default)]
    pub mass: Option<usize>,
    /// `calculix-dat`: the node or element id of the rows to read (absent:
    /// the row without an id, as in `total force` blocks).
    #[serde(default)]
    pub entity: Option<u64>,
    /// `calculix-dat`: the 1-based value column after the id (default 1).
    #[serde(default)]
    pub column: Option<usize>,
    /// `calculix-dat`: only blocks of this set (default: any).
    #[serde(default)]
    pub set: Option<String>,
    /// max | min | final | max-abs.
    #[serde(default = "default_stat")]
    pub stat: String,
    /// Unit of the value (SI), for the table header.
    #[serde(default)]
    pub unit: Option<String>,
}

fn default_stat() -> String {
    "max".into()
}

/// Why a `[[response]]` specification is refused (the campaign file's
/// error adds the file and the response).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ResponseError {
    /// The name is not a plain name.
    #[error("the name must be letters, digits and _")]
    Name,
    /// No reader of this name.
    #[error("reader '{reader}': expected {}", READERS.join(", "))]
    Reader {
        /// The reader given.
        reader: String,
    },
    /// No statistic of this name.
    #[error("stat '{stat}': expected {}", STATS.join(", "))]
    Stat {
        /// The statistic given.
        stat: String,
    },
    /// The file is not inside the point folder.
    #[error("file '{file}': a file inside the point folder")]
    File {
        /// The file given.
        file: String,
    },
    /// The `calculix` reader without its quantity and mass.
    #[error("calculix: quantity = \"displacement\" or \"compression\" with mass = 1, 2, ...")]
    Calculix,
    /// A quantity not of the reader's form.
    #[error("quantity '{quantity}': expected {expected}")]
    Quantity {
        /// The quantity given.
        quantity: String,
        /// The reader's form of it.
        expected: &'static str,
    },
}

impl ResponseSpec {
    /// Checks the specification: a plain name, a known reader and
    /// statistic, a file inside the point folder, a quantity of the
    /// reader's form.
    pub fn check(&self) -> Result<(), ResponseError> {
        if !is_name(&self.name) {
            return Err(ResponseError::Name);
        }
        if !READERS.contains(&self.reader.as_str()) {
            let reader = self.reader.clone();
            return Err(ResponseError::Reader { reader });
        }
        if !STATS.contains(&self.stat.as_str()) {
            let stat = self.stat.clone();
            return Err(ResponseError::Stat { stat });
        }
        if self.file.is_empty() || self.file.contains("..") || self.file.starts_with('/') {
            let file = self.file.clone();
            return Err(ResponseError::File { file });
        }
        self.check_quantity()
    }

    /// The quantity has the reader's form (`calculix`: a mass too).
    fn check_quantity(&self) -> Result<(), ResponseError> {
        let words = self.quantity.split_whitespace().count();
        let expected = match (self.reader.as_str(), self.quantity.as_str(), self.mass) {
            ("calculix", "displacement" | "compression", Some(m)) if m >= 1 => return Ok(()),
            ("calculix", _, _) => return Err(ResponseError::Calculix),
            ("lsdyna-nodout" | "lsdyna-deforc", _, _) if words != 2 => {
                "'ID NAME' (\"1001 x-disp\", \"12 x-force\")"
            }
            ("lsdyna-rcforc", _, _) if words != 3 => "'master|slave ID x|y|z|mass'",
            _ => return Ok(()),
        };
        Err(ResponseError::Quantity {
            quantity: self.quantity.clone(),
            expected,
        })
    }
}
