//! The process-wide guard of a command line run, and the free functions
//! through which the command and the library writers use it.

use super::error::OutputError;
use super::guard::{Outputs, Shape};
use super::staged::StagedFolder;
use super::transaction::{Pending, Transaction};
use super::write::{remove_stale, render_temp, through_link, write_temp};
use std::path::Path;
use std::sync::{Mutex, MutexGuard};

/// The process-wide guard used by the command line and the library writers.
static GUARD: Mutex<Outputs> = Mutex::new(Outputs::new());

/// The open transaction of the process, if any (always locked after
/// [`GUARD`] where both are needed).
static TRANSACTION: Mutex<Option<Transaction>> = Mutex::new(None);

fn guard() -> MutexGuard<'static, Outputs> {
    GUARD
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn transaction() -> MutexGuard<'static, Option<Transaction>> {
    TRANSACTION
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Opens the transaction of a command: from now on the outputs written
/// through the process-wide guard ([`write_file`], [`commit`],
/// [`write_rendered`], and the library writers that use them) are complete
/// temporary files until [`finish`] moves them all into place, or
/// [`abandon`] removes them (see the `transaction` module).
pub fn begin() {
    transaction().get_or_insert_with(Transaction::default);
}

/// Checks every output of the open transaction again (inputs registered
/// meanwhile count; two outputs on one file are refused) and moves them all
/// into place; returns how many outputs there were. On an error nothing is
/// moved and the temporary files are removed. The transaction stays open
/// for outputs that follow.
pub fn finish() -> Result<usize, OutputError> {
    let guard = guard();
    let mut open = transaction();
    match open.as_mut() {
        Some(t) => std::mem::take(t).commit(&guard),
        None => Ok(0),
    }
}

/// Checks the outputs of the open transaction as [`finish`] does, without
/// moving them (a caller that prints before it commits).
pub fn check_pending() -> Result<(), OutputError> {
    let guard = guard();
    match transaction().as_ref() {
        Some(t) => t.check(&guard),
        None => Ok(()),
    }
}

/// Removes the temporary files of every output of the open transaction
/// (the command failed); returns how many outputs were abandoned. Does not
/// wait for a lock another thread holds (it may be called from a panic).
pub fn abandon() -> usize {
    match TRANSACTION.try_lock() {
        Ok(mut open) => open.as_mut().map_or(0, |t| std::mem::take(t).discard()),
        Err(std::sync::TryLockError::Poisoned(p)) => p
            .into_inner()
            .as_mut()
            .map_or(0, |t| std::mem::take(t).discard()),
        Err(std::sync::TryLockError::WouldBlock) => 0,
    }
}

/// Registers an input with the process-wide guard.
pub fn register_input(path: &Path) {
    guard().input(path);
}

/// [`Outputs::input_with_references`] with the process-wide guard.
pub fn register_input_with_references(path: &Path) {
    guard().input_with_references(path);
}

/// [`Outputs::claim`] with the process-wide guard.
pub fn claim_output(path: &Path) -> Result<(), OutputError> {
    guard().claim(path)
}

/// [`Outputs::claim_as`] with the process-wide guard.
pub fn claim_output_as(path: &Path, option: &str, shape: Shape) -> Result<(), OutputError> {
    guard().claim_as(path, option, shape)
}

/// [`Outputs::check_file`] with the process-wide guard.
pub fn check_file(path: &Path) -> Result<(), OutputError> {
    guard().check_file(path)
}

/// [`Outputs::check_folder`] with the process-wide guard.
pub fn check_folder(path: &Path) -> Result<(), OutputError> {
    guard().check_folder(path)
}

/// [`Outputs::check_folder_of`] with the process-wide guard.
pub fn check_folder_of(path: &Path, option: &str, kinds: &[&str]) -> Result<(), OutputError> {
    guard().check_folder_of(path, option, kinds)
}

/// [`Outputs::write_file`] with the process-wide guard; inside a
/// transaction ([`begin`]) the file waits complete for [`finish`].
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let guard = guard();
    let mut open = transaction();
    match open.as_mut() {
        Some(t) => {
            guard.check_file(path)?;
            remove_stale(&through_link(path), "tmp");
            t.push(Pending::File(write_temp(path, bytes)?));
            Ok(())
        }
        None => guard.write_file(path, bytes),
    }
}

/// [`Outputs::stage_folder`] with the process-wide guard.
pub fn stage_folder(path: &Path) -> Result<StagedFolder, OutputError> {
    guard().stage_folder(path)
}

/// [`StagedFolder::commit`] with the process-wide guard; inside a
/// transaction ([`begin`]) the folder is checked now and waits complete for
/// [`finish`].
pub fn commit(staged: StagedFolder) -> Result<(), OutputError> {
    let guard = guard();
    let mut open = transaction();
    match open.as_mut() {
        Some(t) => {
            staged.check(&guard)?;
            t.push(Pending::Folder(staged));
            Ok(())
        }
        None => staged.commit(&guard),
    }
}

/// Checks `path` against the process-wide guard, lets `render` write a
/// hidden temporary file next to it (same extension, for writers that pick
/// the format by it), flushes it and renames it over `path`.
pub fn write_rendered<E>(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), OutputError>
where
    E: Into<Box<dyn std::error::Error + Send + Sync>>,
{
    check_file(path)?;
    let file = render_temp(path, render)?;
    match transaction().as_mut() {
        Some(t) => {
            t.push(Pending::File(file));
            Ok(())
        }
        None => file.move_in(),
    }
}
