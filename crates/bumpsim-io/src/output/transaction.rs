//! One command's outputs as one transaction: while a transaction is open
//! ([`super::begin`]), every output of the process-wide guard is written
//! complete and flushed to a hidden temporary file or staging folder, and
//! nothing reaches its target until [`super::finish`]. There every target
//! is checked again (inputs registered while the command ran count), two
//! outputs that would land on one file are refused, and only then are the
//! temporary files renamed into place. A command that fails (a refused
//! second output, a full disk, an error in its computation) leaves every
//! output as it was: [`super::abandon`] removes the temporary files.
//!
//! The renames themselves are not one step (POSIX has no rename of many
//! files at once), but each is a rename within its own folder, which needs
//! no space and fails only if the folder itself is taken away meanwhile.

use super::error::OutputError;
use super::guard::{Outputs, canonical};
use super::staged::StagedFolder;
use super::write::TempFile;
use std::path::PathBuf;

/// An output that waits for the end of the command.
#[derive(Debug)]
pub(super) enum Pending {
    /// A complete temporary file and its target.
    File(TempFile),
    /// A complete staging folder and its target.
    Folder(StagedFolder),
}

impl Pending {
    /// The final files this output writes.
    fn targets(&self) -> Result<Vec<PathBuf>, OutputError> {
        match self {
            Pending::File(file) => Ok(vec![file.target.clone()]),
            Pending::Folder(folder) => folder.targets(),
        }
    }

    fn check(&self, guard: &Outputs) -> Result<(), OutputError> {
        match self {
            Pending::File(file) => guard.check_file(&file.target),
            Pending::Folder(folder) => folder.check(guard),
        }
    }

    fn move_in(self) -> Result<(), OutputError> {
        match self {
            Pending::File(file) => file.move_in(),
            Pending::Folder(folder) => folder.move_in(),
        }
    }

    fn discard(self) {
        match self {
            Pending::File(file) => file.discard(),
            Pending::Folder(folder) => drop(folder),
        }
    }
}

/// The outputs of one command, in the order they were written.
#[derive(Debug, Default)]
pub(super) struct Transaction {
    pending: Vec<Pending>,
}

impl Transaction {
    /// Adds a complete output.
    pub fn push(&mut self, output: Pending) {
        self.pending.push(output);
    }

    /// Checks every output against `guard` and against each other (no two
    /// write one file), before anything moves.
    pub fn check(&self, guard: &Outputs) -> Result<(), OutputError> {
        let mut seen: Vec<(PathBuf, PathBuf)> = Vec::new();
        for output in &self.pending {
            output.check(guard)?;
            for target in output.targets()? {
                let key = canonical(&target);
                if let Some((first, _)) = seen.iter().find(|(_, k)| *k == key) {
                    return Err(OutputError::Twice {
                        output: target,
                        first: first.clone(),
                    });
                }
                seen.push((target, key));
            }
        }
        Ok(())
    }

    /// Checks, then moves every output into place; returns how many there
    /// were. A refusal moves nothing and removes the temporary files.
    pub fn commit(self, guard: &Outputs) -> Result<usize, OutputError> {
        if let Err(e) = self.check(guard) {
            self.discard();
            return Err(e);
        }
        let count = self.pending.len();
        let mut outputs = self.pending.into_iter();
        while let Some(output) = outputs.next() {
            if let Err(e) = output.move_in() {
                outputs.for_each(Pending::discard);
                return Err(e);
            }
        }
        Ok(count)
    }

    /// Removes every temporary file and staging folder; returns how many
    /// outputs were abandoned.
    pub fn discard(self) -> usize {
        let count = self.pending.len();
        self.pending.into_iter().for_each(Pending::discard);
        count
    }
}
