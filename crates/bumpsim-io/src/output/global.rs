//! The process-wide guard of a command line run, and the free functions
//! through which the command and the library writers use it.

use super::error::OutputError;
use super::guard::Outputs;
use super::staged::StagedFolder;
use super::write::render_atomic;
use std::path::Path;
use std::sync::Mutex;

/// The process-wide guard used by the command line and the library writers.
static GUARD: Mutex<Outputs> = Mutex::new(Outputs::new());

fn guard() -> std::sync::MutexGuard<'static, Outputs> {
    GUARD
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Registers an input with the process-wide guard.
pub fn register_input(path: &Path) {
    guard().input(path);
}

/// [`Outputs::claim`] with the process-wide guard.
pub fn claim_output(path: &Path) -> Result<(), OutputError> {
    guard().claim(path)
}

/// [`Outputs::check_file`] with the process-wide guard.
pub fn check_file(path: &Path) -> Result<(), OutputError> {
    guard().check_file(path)
}

/// [`Outputs::check_folder`] with the process-wide guard.
pub fn check_folder(path: &Path) -> Result<(), OutputError> {
    guard().check_folder(path)
}

/// [`Outputs::write_file`] with the process-wide guard.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    guard().write_file(path, bytes)
}

/// [`Outputs::stage_folder`] with the process-wide guard.
pub fn stage_folder(path: &Path) -> Result<StagedFolder, OutputError> {
    guard().stage_folder(path)
}

/// [`StagedFolder::commit`] with the process-wide guard.
pub fn commit(staged: StagedFolder) -> Result<(), OutputError> {
    staged.commit(&guard())
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
    render_atomic(path, render)
}
