//! bumpsim-io: reading and writing the files engineers exchange.
//!
//! - [`table`]: CSV with `name [unit]` headers, converted to SI on reading;
//! - [`car`]: MSD car models in TOML;
//! - [`response`]: simulation responses as CSV.
//!
//! Every error names the file and, where it applies, the line and column.

pub mod car;
pub mod response;
pub mod table;
