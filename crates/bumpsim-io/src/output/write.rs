//! Whole-or-nothing writing of one file: a hidden temporary sibling,
//! written, flushed to disk and renamed over the target; and the removal
//! of the temporary files a killed run left.

use super::error::OutputError;
use super::guard::Outputs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A hidden sibling name for temporary files and folders of `path`.
pub(super) fn sibling(path: &Path, kind: &str) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}-{n}.{kind}", std::process::id()))
}

/// Removes the temporary files or folders of the user's output `path`
/// that a killed run left (`kill -9` leaves no chance to clean up):
/// siblings named as [`sibling`] names them whose process no longer runs.
/// Once per user output (not in [`write_atomic`], which library writers
/// call per file inside staging folders). Only where `/proc` tells which
/// processes run (Linux); elsewhere they stay, hidden and harmless.
pub(super) fn remove_stale(path: &Path, kind: &str) {
    for stale in stale_siblings(path, kind) {
        let _ = std::fs::remove_dir_all(&stale).or_else(|_| std::fs::remove_file(&stale));
    }
}

/// The siblings of `path` named as [`sibling`] names them for `kind` whose
/// process no longer runs (Linux; elsewhere none).
pub(super) fn stale_siblings(path: &Path, kind: &str) -> Vec<PathBuf> {
    let mut stale = Vec::new();
    let (Some(parent), Some(name), true) = (
        path.parent(),
        path.file_name(),
        Path::new("/proc/self").exists(),
    ) else {
        return stale;
    };
    let name = name.to_string_lossy();
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return stale;
    };
    let (prefix, suffix) = (format!(".{name}."), format!(".{kind}"));
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(middle) = file
            .strip_prefix(&prefix)
            .and_then(|m| m.strip_suffix(&suffix))
        else {
            continue;
        };
        let Some((Ok(pid), Ok(_))) = middle
            .split_once('-')
            .map(|(pid, n)| (pid.parse::<u32>(), n.parse::<u64>()))
        else {
            continue;
        };
        let gone = !Path::new("/proc").join(pid.to_string()).exists();
        if pid != std::process::id() && gone {
            stale.push(entry.path());
        }
    }
    stale
}

/// Creates the missing folders above `path`; returns the topmost one it
/// created (to remove again when the output is abandoned).
pub(super) fn create_parent(path: &Path) -> Result<Option<PathBuf>, OutputError> {
    let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(None);
    };
    let created = parent
        .ancestors()
        .take_while(|a| !a.as_os_str().is_empty() && !a.exists())
        .last()
        .map(Path::to_path_buf);
    std::fs::create_dir_all(parent).map_err(|e| OutputError::io(parent, e))?;
    Ok(created)
}

/// Removes the empty folders from `path`'s parent up to `created` (the
/// topmost one [`create_parent`] made for an output that was abandoned).
pub(super) fn remove_created(path: &Path, created: Option<&Path>) {
    let Some(created) = created else { return };
    for folder in path.ancestors().skip(1) {
        if std::fs::remove_dir(folder).is_err() || folder == created {
            return;
        }
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder:
/// written, flushed to disk, then renamed over `path`. No input check; use
/// [`Outputs::write_file`] for a user-given path.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let staged = write_temp(path, bytes)?;
    staged.move_in()
}

/// A complete temporary file that waits to be renamed over its target.
#[derive(Debug)]
pub(super) struct TempFile {
    /// The hidden sibling holding the new content.
    pub temp: PathBuf,
    /// The file it replaces (a link resolved to the file it points to).
    pub target: PathBuf,
    /// The topmost folder made for it, removed again if it is abandoned.
    pub created: Option<PathBuf>,
}

impl TempFile {
    /// Renames the temporary file over its target and flushes the folder.
    pub fn move_in(self) -> Result<(), OutputError> {
        std::fs::rename(&self.temp, &self.target).map_err(|e| {
            let _ = std::fs::remove_file(&self.temp);
            OutputError::io(&self.target, e)
        })?;
        sync_parent(&self.target);
        Ok(())
    }

    /// Removes the temporary file and the folders made for it (the output
    /// is abandoned).
    pub fn discard(self) {
        let _ = std::fs::remove_file(&self.temp);
        remove_created(&self.target, self.created.as_deref());
    }
}

/// Writes `bytes` to a hidden temporary sibling of `path` and flushes it to
/// disk; the target is not touched yet.
pub(super) fn write_temp(path: &Path, bytes: &[u8]) -> Result<TempFile, OutputError> {
    let name = |target: &Path| sibling(target, "tmp");
    fill_temp(path, name, |temp, target| {
        let mut file = std::fs::File::create(temp)?;
        file.write_all(bytes)?;
        if let Ok(old) = std::fs::metadata(target) {
            file.set_permissions(old.permissions())?;
        }
        file.sync_all()
    })
}

/// The temporary file of `path` (its link resolved, its folder made), named
/// by `name` from the target, filled by `fill` (temporary file, target);
/// on an error it and the folders made for it are removed.
fn fill_temp(
    path: &Path,
    name: impl FnOnce(&Path) -> PathBuf,
    fill: impl FnOnce(&Path, &Path) -> std::io::Result<()>,
) -> Result<TempFile, OutputError> {
    let target = through_link(path);
    let created = create_parent(&target)?;
    let temp = name(&target);
    let result = fill(&temp, &target);
    let file = TempFile {
        temp,
        target,
        created,
    };
    match result {
        Ok(()) => Ok(file),
        Err(e) => {
            let error = OutputError::io(&file.target, e);
            file.discard();
            Err(error)
        }
    }
}

impl Outputs {
    /// Checks `path`, then writes `bytes` to it atomically (temporary file in
    /// the same folder, fsync, rename). Creates the folder if missing.
    pub fn write_file(&self, path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
        self.check_file(path)?;
        remove_stale(&through_link(path), "tmp");
        write_atomic(path, bytes)
    }
}

/// Lets `render` write a hidden temporary file next to `path` (same
/// extension, for writers that pick the format by it) and flushes it; the
/// renderer's error is the file system's. The target is not touched yet.
pub(super) fn render_temp<E>(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<TempFile, OutputError>
where
    E: Into<Box<dyn std::error::Error + Send + Sync>>,
{
    let name = |target: &Path| {
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        target.with_file_name(format!(".bumpsim-{}-{n}-{name}", std::process::id()))
    };
    fill_temp(path, name, |temp, _| {
        render(temp)
            .map_err(std::io::Error::other)
            .and_then(|()| std::fs::File::open(temp)?.sync_all())
    })
}

/// The file a symbolic link points to (so that an output given as a link
/// updates its target, as writing through the link would, instead of
/// replacing the link by a file); any other path as it is.
pub(super) fn through_link(path: &Path) -> PathBuf {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            std::fs::canonicalize(path).unwrap_or_else(|_| path.into())
        }
        _ => path.into(),
    }
}

/// Flushes the folder entry of a rename to disk (best effort).
pub(super) fn sync_parent(path: &Path) {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if let Ok(dir) = std::fs::File::open(parent) {
        let _ = dir.sync_all();
    }
}
