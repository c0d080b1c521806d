//! Outputs that never land on an input and are written whole or not at all.
//!
//! Every command tells the [`Outputs`] guard each path it reads (files and
//! test folders, and the files a study, series or pipeline names:
//! [`Outputs::input_with_references`]). An output is then refused when it is an input, lies inside
//! an input folder, or is the same file as an input under another name: the
//! comparison uses the canonical path (symbolic links resolved) **and** the
//! device + inode pair, so hard links count; for an input folder the files in
//! it are compared too (up to [`FOLDER_SCAN_LIMIT`] entries).
//!
//! Writing:
//! - a file is written to a temporary file in the same folder, flushed to
//!   disk (`fsync`) and renamed over the target only when complete, so a
//!   reader (or a run killed half-way) sees the complete old or the complete
//!   new file, never a truncated one;
//! - a multi-file output (report folder, ISO-MME test, synthetic series) is
//!   staged in a sibling temporary folder ([`StagedFolder`]) and moved into
//!   place only by [`StagedFolder::commit`]: a new folder is renamed in one
//!   step; an existing folder is swapped whole with the staged one (one
//!   `renameat2(RENAME_EXCHANGE)` on Linux) after the entries of the old
//!   folder that the run does not write are carried over as hard links, so
//!   the folder is at every moment entirely old or entirely new and files
//!   bumpsim did not write stay (`swap`). A
//!   failed run leaves the old outputs untouched; a killed one (`kill -9`)
//!   leaves its hidden temporary file or folder, which the next write of
//!   the same output removes (on Linux, where `/proc` tells that the
//!   process is gone).
//! - a path that is an existing non-folder where a folder is needed (or an
//!   existing folder where a file is needed), or an existing device, pipe
//!   or socket (which the rename would replace) is an error before anything
//!   is written ([`Outputs::check_file`], [`Outputs::check_folder`]);
//! - an output given as a symbolic link updates the file it points to; the
//!   link stays;
//! - the outputs of one command are one transaction ([`begin`], [`finish`],
//!   [`abandon`]): each waits complete in its temporary file or folder until
//!   the command has succeeded, is checked again then (inputs registered
//!   meanwhile count), and only then moved into place; a command that fails
//!   half-way leaves every output as it was;
//! - two files of one output folder with the same name, or a folder's file
//!   that is another claimed output of the command, are errors: neither
//!   silently replaces the other; an output inside another output where one
//!   would replace or drop the other is refused when it is claimed, before
//!   the command runs ([`Outputs::claim_as`], [`Shape`]).
//!
//! A command line tool uses the process-wide guard through the free
//! functions ([`register_input`], [`write_file`], [`stage_folder`], ...); the
//! library writers ([`crate::table::write_table`], [`crate::car::Car::write`],
//! [`crate::isomme::write`]) write through it as well.
//!
//! ```
//! use bumpsim_io::output::Outputs;
//! let dir = std::env::temp_dir().join(format!("bumpsim-doc-output-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let input = dir.join("in.csv");
//! std::fs::write(&input, "x").unwrap();
//! let mut guard = Outputs::new();
//! guard.input(&input);
//! assert!(guard.write_file(&input, b"y").is_err());
//! guard.write_file(&dir.join("out.csv"), b"y").unwrap();
//! assert_eq!(std::fs::read(&input).unwrap(), b"x");
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```
//!
//! The parts: [`Outputs`] and its checks (`guard`), whole-or-nothing file
//! writing (`write`), staged folders and plain names (`staged`), the swap
//! of an existing folder (`swap`), the
//! process-wide guard (`global`), the transaction of one command
//! (`transaction`) and [`OutputError`] (`error`).

mod error;
mod global;
mod guard;
mod references;
mod staged;
mod swap;
mod transaction;
mod write;

#[cfg(test)]
mod tests;

pub use error::{Clash, Nesting, OutputError};
pub use global::{
    abandon, begin, check_file, check_folder, check_folder_of, check_pending, claim_output,
    claim_output_as, commit, finish, register_input, register_input_with_references, stage_folder,
    write_file, write_rendered,
};
pub use guard::{FOLDER_SCAN_LIMIT, Outputs, Shape};
pub use references::INPUT_KEYS;
pub use staged::{StagedFolder, plain_name};
pub use write::write_atomic;

/// Most samples a channel may have when a command makes or resamples one
/// (about 160 MB of values): beyond it the command refuses instead of
/// exhausting memory (docs/limits.md).
pub const MAX_SAMPLES: usize = 20_000_000;

/// Most tests one synthetic series may hold (`synth`, every model's
/// series; docs/limits.md). A series is made in one run, with no progress
/// shown, and its folder written whole (staged, then moved into place), as
/// a campaign's design is refused beyond its `MAX_POINTS` before any point
/// runs: 2000 tests of the bundled pendulum series ran past 120 s without
/// a word (about 0.1 s a test in the debug build, 0.3 MB of files each).
/// A larger set of tests is several series, or a campaign.
pub const MAX_TESTS: usize = 1000;

/// A series with more than [`MAX_TESTS`] tests.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{table}: {count} tests: a series holds at most {max} (limit MAX_TESTS, docs/limits.md: it is made in one run and written whole); split it into several series files",
    max = MAX_TESTS
)]
pub struct TooManyTests {
    /// The table of tests (`[[head]]`, `[[test]]`).
    pub table: &'static str,
    /// The tests given.
    pub count: usize,
}

/// Refuses a series of more than [`MAX_TESTS`] tests, before any is made.
///
/// ```
/// use bumpsim_io::output::{MAX_TESTS, series_size};
/// assert!(series_size("[[head]]", 3).is_ok());
/// let err = series_size("[[test]]", MAX_TESTS + 1).unwrap_err().to_string();
/// assert!(err.starts_with("[[test]]: 1001 tests: a series holds at most 1000"));
/// ```
pub fn series_size(table: &'static str, count: usize) -> Result<(), TooManyTests> {
    match count > MAX_TESTS {
        true => Err(TooManyTests { table, count }),
        false => Ok(()),
    }
}
