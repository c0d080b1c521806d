//! The campaign folder written whole, fast: `init` writes every file into
//! a hidden staging folder beside the target (a
//! [`bumpsim_io::output::StagedFolder`]), flushes them all to disk with
//! one `syncfs(2)` (`sync -f`), and only then moves the folder into place
//! (one `rename(2)`, its parent synced), so a campaign folder exists whole
//! or not at all: an `init` killed or cut off by a power loss leaves only
//! the hidden staging folder, which the next `init` removes, never a
//! campaign of fewer points.
//!
//! One sync of the file system rather than one `fsync` per file: on ext4
//! every `fsync` ends with a flush of the disk's write cache, about 0.5 to
//! 3 ms each on this machine, which at 100 000 point folders was minutes
//! (docs/benchmarks.md). The staging folder is this process's own, so its
//! files need none of the checks of a user-given path (an input, a link,
//! a second output of one name); the folder itself is checked
//! ([`bumpsim_io::output::Outputs::stage_folder`]), and over an existing
//! campaign (`init` again) each file it replaces is checked as an output
//! ([`bumpsim_io::output::Outputs::check_file`]) before any moves.

use crate::error::{CampaignError, Result};
use bumpsim_io::output::{Outputs, StagedFolder};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A campaign folder being written.
#[derive(Debug)]
pub struct Staging {
    staged: StagedFolder,
    /// The files written, relative to the folder, in order of writing.
    files: Vec<String>,
}

impl Staging {
    /// Opens a staging folder for campaign folder `dir`, checked against
    /// the command's inputs in `guard`.
    pub fn new(guard: &Outputs, dir: &Path) -> Result<Staging> {
        Ok(Staging {
            staged: guard.stage_folder(dir)?,
            files: Vec::new(),
        })
    }

    /// The staging folder.
    pub fn path(&self) -> &Path {
        self.staged.path()
    }

    /// The campaign folder it becomes.
    pub fn target(&self) -> &Path {
        self.staged.target()
    }

    /// Makes the folder `name` (relative, its parent made already).
    pub fn folder(&self, name: &str) -> Result<()> {
        let path = self.path().join(name);
        std::fs::create_dir(&path).map_err(|e| write_error(&path, e))
    }

    /// Writes the file `name` (relative, in a folder made already): one
    /// create and one write, no sync (the commit syncs them all).
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<()> {
        for part in name.split('/') {
            bumpsim_io::output::plain_name(part)?;
        }
        let path = self.path().join(name);
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .map_err(|e| write_error(&path, e))?;
        file.write_all(bytes).map_err(|e| write_error(&path, e))?;
        self.files.push(name.into());
        Ok(())
    }

    /// Flushes every file to disk and moves the folder into place: a new
    /// campaign folder in one rename; over an existing one file by file,
    /// in the order written (the state last), after checking them all.
    pub fn commit(self, guard: &Outputs) -> Result<()> {
        sync(self.path(), &self.files);
        let target = self.staged.target().to_path_buf();
        if !target.exists() {
            std::fs::rename(self.path(), &target).map_err(|e| write_error(&target, e))?;
        } else {
            for name in &self.files {
                guard.check_file(&target.join(name))?;
            }
            for name in &self.files {
                let to = target.join(name);
                if let Some(parent) = to.parent() {
                    std::fs::create_dir_all(parent).map_err(|e| write_error(parent, e))?;
                }
                std::fs::rename(self.path().join(name), &to).map_err(|e| write_error(&to, e))?;
            }
            sync(&target, &self.files);
        }
        sync_folder(target.parent().filter(|p| !p.as_os_str().is_empty()));
        Ok(())
        // dropped: the staging folder (empty, or gone with the rename) is removed
    }
}

/// Flushes the file system holding `folder` to disk (`sync -f`, one
/// syncfs(2)); where that fails, each of `files` (relative to `folder`)
/// and the folder itself are synced one by one.
fn sync(folder: &Path, files: &[String]) {
    let synced = std::process::Command::new("sync")
        .arg("-f")
        .arg(folder)
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if synced {
        return;
    }
    let mut parents: Vec<PathBuf> = vec![folder.into()];
    for name in files {
        let path = folder.join(name);
        if let Ok(file) = std::fs::File::open(&path) {
            let _ = file.sync_all();
        }
        let parent = path.parent().map(Path::to_path_buf);
        if let Some(parent) = parent.filter(|p| parents.last() != Some(p)) {
            parents.push(parent);
        }
    }
    parents.iter().for_each(|p| sync_folder(Some(p)));
}

/// Syncs a folder's entries (best effort; `None`: the working folder).
fn sync_folder(folder: Option<&Path>) {
    if let Ok(dir) = std::fs::File::open(folder.unwrap_or(Path::new("."))) {
        let _ = dir.sync_all();
    }
}

fn write_error(path: &Path, source: std::io::Error) -> CampaignError {
    CampaignError::WriteFile {
        path: PathBuf::from(path),
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nothing of an unfinished folder reaches the target; a committed
    /// one appears whole, and over an existing folder replaces its files.
    #[test]
    fn a_campaign_folder_appears_whole_or_not_at_all() {
        let root = std::env::temp_dir().join(format!("bumpsim-staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        let target = root.join("c");
        let guard = Outputs::new();
        let write = |text: &str| {
            let mut staging = Staging::new(&guard, &target).unwrap();
            staging.folder("points").unwrap();
            staging.folder("points/0001").unwrap();
            staging
                .write("points/0001/deck.inp", text.as_bytes())
                .unwrap();
            staging.write("state.journal", b"s\n").unwrap();
            staging
        };
        drop(write("interrupted"));
        let left: Vec<_> = std::fs::read_dir(&root).unwrap().collect();
        assert!(left.is_empty(), "{left:?}");
        write("one").commit(&guard).unwrap();
        write("two").commit(&guard).unwrap();
        let deck = std::fs::read_to_string(target.join("points/0001/deck.inp")).unwrap();
        assert_eq!(deck, "two");
        assert_eq!(
            std::fs::read_dir(&root).unwrap().count(),
            1,
            "no staging left"
        );
        let mut staging = write("three");
        let err = staging.write("../x", b"").unwrap_err().to_string();
        assert!(err.contains("not a plain name"), "{err}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
