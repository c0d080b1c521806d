//! bumpsim-export: the identified MSD car model as input for FE solvers, so it
//! can sit behind a bumper mesh (thesis ch. 3.3, paper B; spec §8).
//!
//! - [`lsdyna`]: an LS-DYNA keyword include file (fixed-format cards);
//! - [`calculix`]: a CalculiX/Abaqus deck, optionally a complete transient
//!   analysis under a force history, and reading its results back;
//! - [`layout`]: unit systems, axis and node placement shared by both.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_export::lsdyna::{lsdyna_include, LsDynaOptions};
//! let car = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5]).unwrap();
//! let deck = lsdyna_include(&car, &LsDynaOptions { id_offset: 900_000, ..Default::default() }).unwrap();
//! assert!(deck.contains("*ELEMENT_DISCRETE"));
//! ```

pub mod calculix;
pub mod layout;
pub mod lsdyna;

use std::path::PathBuf;

/// Why a deck cannot be written or its results read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// Ids out of range or clashing.
    #[error("{0}")]
    Ids(String),
    /// An option out of range.
    #[error("{0}")]
    Option(String),
    /// A results file that cannot be read.
    #[error("{}{}: {reason}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
    Dat {
        /// The file.
        path: PathBuf,
        /// 1-based line (0: the file as a whole).
        line: usize,
        /// What is wrong.
        reason: String,
    },
}
