//! bumpsim-io: reading and writing the files engineers exchange.
//!
//! - [`table`]: CSV with `name [unit]` headers, converted to SI on reading;
//! - [`car`]: MSD car models in TOML;
//! - [`link_car`]: car files of a chain with nonlinear links;
//! - [`kind`]: which car model a file is for (its `kind` key; the legacy detection);
//! - [`response`]: simulation responses as CSV;
//! - [`test_data`]: one view of a crash test in any format, channel selection;
//! - [`isomme`] (`test_data::isomme`): ISO/TS 13499 ISO-MME folders, `.mme` and `.zip`, read and write;
//! - [`ev5`] (`test_data::ev5`): NHTSA EV5 ASCII X-Y downloads;
//! - [`output`]: the guard that keeps outputs off the inputs, atomic writes;
//! - [`signal_error`]: the error type of the test readers;
//! - [`speed`]: a speed in an input file, m/s or text with a unit;
//! - [`numbers`]: a fixed count of numbers (a curve point), no more, no fewer.
//!
//! Every error names the file and, where it applies, the line and column.
//!
//! A car file and a force table with units in their headers, read to SI:
//!
//! ```
//! use bumpsim_io::{Car, Table};
//! use std::path::Path;
//! let toml = "masses = [30.0, 400.0]\ndampers = [8e3]\nsprings = [1.2e6]\n";
//! let car = Car::parse(toml, Path::new("car.toml")).unwrap();
//! assert_eq!(car.model.dof(), 2);
//! let csv = "time [ms],force [kN]\n0,0\n1,2.5\n2,0\n";
//! let force = Table::parse(csv, Path::new("force.csv")).unwrap();
//! assert!((force.step - 1e-3).abs() < 1e-15); // s
//! assert!((force.column("force").unwrap().values[1] - 2500.0).abs() < 1e-9); // N
//! // a negative mass is refused, naming the parameter
//! let bad = Car::parse("masses = [-1.0]\ndampers = []\nsprings = []\n", Path::new("bad.toml"));
//! assert!(bad.unwrap_err().to_string().contains("bad.toml"));
//! ```

pub mod car;
pub mod kind;
pub mod link_car;
pub mod mass;
pub mod numbers;
pub mod output;
pub mod protocols;
pub mod response;
pub mod signal_error;
pub mod speed;
pub mod table;
pub mod test_data;

/// A TOML error as `TOML parse error at line L, column C: message`, without
/// the parser's quote of the offending line (the file may not be TOML at
/// all, and its content is not for echoing).
pub fn toml_message(text: &str, error: &toml::de::Error) -> String {
    let Some(span) = error.span() else {
        return format!("TOML parse error: {}", error.message().trim_end());
    };
    let before = &text.as_bytes()[..span.start.min(text.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let column = before.iter().rev().take_while(|&&b| b != b'\n').count() + 1;
    format!(
        "TOML parse error at line {line}, column {column}: {}",
        error.message().trim_end()
    )
}

pub use car::{Car, CarError};
pub use signal_error::SignalFileError;
pub use table::{Table, TableError};
pub use test_data::TestData;
/// The readers of each format live in [`test_data`]; these re-exports keep
/// the short paths (`bumpsim_io::isomme`, `bumpsim_io::ev5`) working.
pub use test_data::{ev5, isomme};

/// The types most readers need (the facade globs it).
pub mod prelude {
    pub use crate::car::{Car, CarError};
    pub use crate::signal_error::SignalFileError;
    pub use crate::table::{Table, TableError};
    pub use crate::test_data::TestData;
}
