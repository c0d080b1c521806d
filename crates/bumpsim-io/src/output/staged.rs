//! Multi-file outputs (a report folder, an ISO-MME test, a synthetic
//! series): staged in a hidden sibling folder, moved into place only on
//! commit; and the plain names their files must have.

use super::error::OutputError;
use super::guard::{Outputs, holds_working_folder};
use super::swap::{carry_over, restore_aside, same_permissions, swap};
use super::write::{create_parent, remove_stale, sibling, sync_parent, through_link};
use std::path::{Path, PathBuf};

/// Checks that `name` is a plain file name: no folder separators, no `..`,
/// not absolute, not empty, not hidden.
pub fn plain_name(name: &str) -> Result<&str, OutputError> {
    let bad = |reason: &str| OutputError::BadName {
        name: name.into(),
        reason: reason.into(),
    };
    if name.is_empty() {
        return Err(bad("an empty name"));
    }
    if name.contains(['/', '\\', '\0']) || name == ".." || name == "." {
        return Err(bad(
            "not a plain name: it must not contain '/', '\\' or be '.' or '..'",
        ));
    }
    if name.starts_with('.') {
        return Err(bad("a name must not start with '.'"));
    }
    Ok(name)
}

/// A multi-file output being built in a sibling temporary folder; nothing
/// reaches the target until [`StagedFolder::commit`]. Dropped without
/// commit, the staging folder is removed.
#[derive(Debug)]
pub struct StagedFolder {
    /// The folder as given (named in messages).
    target: PathBuf,
    /// The folder itself (a symbolic link to a folder resolved: the link
    /// stays, the folder it points to is replaced).
    real: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl StagedFolder {
    /// Opens a staging folder next to `target` (no input check; use
    /// [`Outputs::stage_folder`] for a user-given path).
    pub fn new(target: &Path) -> Result<Self, OutputError> {
        if target.exists() && !target.is_dir() {
            return Err(OutputError::NotAFolder {
                path: target.into(),
            });
        }
        holds_working_folder(target)?;
        let real = through_link(target);
        create_parent(&real)?;
        restore_aside(&real);
        remove_stale(&real, "staging");
        let staging = sibling(&real, "staging");
        std::fs::create_dir_all(&staging).map_err(|e| OutputError::io(&staging, e))?;
        Ok(Self {
            target: target.into(),
            real,
            staging,
            committed: false,
        })
    }

    /// The staging folder: write the files of the output here.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The final folder.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Writes one file of the output, `name` relative to the folder.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        for part in name.split('/') {
            plain_name(part)?;
        }
        let path = self.staging.join(name);
        if path.exists() {
            return Err(OutputError::SameName {
                path: self.target.join(name),
            });
        }
        create_parent(&path)?;
        std::fs::write(&path, bytes).map_err(|e| OutputError::io(&path, e))?;
        Ok(self.target.join(name))
    }

    /// Moves the staged files into the target folder, checking each final
    /// file against `guard` first (all checks before any move).
    pub fn commit(self, guard: &Outputs) -> Result<(), OutputError> {
        self.check(guard)?;
        self.move_in()
    }

    /// The final paths of the staged files.
    pub(super) fn targets(&self) -> Result<Vec<PathBuf>, OutputError> {
        let files = staged_files(&self.staging)?;
        Ok(files.iter().map(|f| self.target.join(f)).collect())
    }

    /// Checks each final file against `guard`: not an input, not a folder,
    /// not another claimed output of the command.
    pub(super) fn check(&self, guard: &Outputs) -> Result<(), OutputError> {
        for target in self.targets()? {
            guard.check_file(&target)?;
            guard.check_unclaimed(&target)?;
        }
        Ok(())
    }

    /// Moves the staged folder into place: a new folder in one rename; an
    /// existing one is swapped whole with the staged folder once the old
    /// folder's other entries are carried over (the `swap` module), then
    /// removed.
    pub(super) fn move_in(mut self) -> Result<(), OutputError> {
        let old = self.real.is_dir();
        if old {
            carry_over(&self.real, &self.staging)?;
            same_permissions(&self.real, &self.staging)?;
        }
        sync_tree(&self.staging)?;
        let replaced = match old {
            true => Some(swap(&self.staging, &self.real)?),
            false => std::fs::rename(&self.staging, &self.real)
                .map(|()| None)
                .map_err(|e| OutputError::io(&self.target, e))?,
        };
        self.committed = true;
        sync_parent(&self.real);
        if let Some(replaced) = replaced {
            let _ = std::fs::remove_dir_all(replaced); // the old folder
        }
        Ok(())
    }
}

impl Outputs {
    /// Checks `path` as a folder output and opens a staging folder for it.
    pub fn stage_folder(&self, path: &Path) -> Result<StagedFolder, OutputError> {
        self.check_folder(path)?;
        StagedFolder::new(path)
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// The files below `root`, relative to it.
fn staged_files(root: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let mut files = Vec::new();
    let mut pending = vec![PathBuf::new()];
    while let Some(relative) = pending.pop() {
        let dir = root.join(&relative);
        let entries = std::fs::read_dir(&dir).map_err(|e| OutputError::io(&dir, e))?;
        for entry in entries {
            let entry = entry.map_err(|e| OutputError::io(&dir, e))?;
            let name = relative.join(entry.file_name());
            if entry.file_type().is_ok_and(|t| t.is_dir()) {
                pending.push(name);
            } else {
                files.push(name);
            }
        }
    }
    files.sort();
    Ok(files)
}

/// Flushes every file and folder below `root` (and `root`) to disk, so
/// that the rename that publishes them cannot outlive their contents.
fn sync_tree(root: &Path) -> Result<(), OutputError> {
    let mut paths: Vec<PathBuf> = staged_files(root)?.iter().map(|f| root.join(f)).collect();
    let folders: Vec<PathBuf> = paths
        .iter()
        .filter_map(|p| p.parent())
        .map(Path::to_path_buf)
        .collect();
    paths.extend(folders);
    paths.push(root.into());
    paths.dedup();
    for path in paths {
        if let Ok(file) = std::fs::File::open(path) {
            let _ = file.sync_all();
        }
    }
    Ok(())
}
