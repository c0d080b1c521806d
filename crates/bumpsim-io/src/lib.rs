//! bumpsim-io: reading and writing the files engineers exchange.
//!
//! - [`table`]: CSV with `name [unit]` headers, converted to SI on reading;
//! - [`car`]: MSD car models in TOML;
//! - [`response`]: simulation responses as CSV;
//! - [`test_data`]: one view of a crash test in any format, channel selection;
//! - [`isomme`]: ISO/TS 13499 ISO-MME folders, `.mme` and `.zip`, read and write;
//! - [`ev5`]: NHTSA EV5 ASCII X-Y downloads;
//! - [`signal_error`]: the error type of the test readers.
//!
//! Every error names the file and, where it applies, the line and column.

pub mod car;
pub mod ev5;
pub mod isomme;
pub mod response;
pub mod signal_error;
pub mod table;
pub mod test_data;
