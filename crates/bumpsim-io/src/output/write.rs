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
    let (Some(parent), Some(name), true) = (
        path.parent(),
        path.file_name(),
        Path::new("/proc/self").exists(),
    ) else {
        return;
    };
    let name = name.to_string_lossy();
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
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
            let _ = std::fs::remove_dir_all(entry.path())
                .or_else(|_| std::fs::remove_file(entry.path()));
        }
    }
}

pub(super) fn create_parent(path: &Path) -> Result<(), OutputError> {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => {
            std::fs::create_dir_all(parent).map_err(|e| OutputError::io(parent, e))
        }
        _ => Ok(()),
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder:
/// written, flushed to disk, then renamed over `path`. No input check; use
/// [`Outputs::write_file`] for a user-given path.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let path = &through_link(path);
    create_parent(path)?;
    let temp = sibling(path, "tmp");
    let result = (|| {
        let mut file = std::fs::File::create(&temp)?;
        file.write_all(bytes)?;
        if let Ok(old) = std::fs::metadata(path) {
            file.set_permissions(old.permissions())?;
        }
        file.sync_all()?;
        std::fs::rename(&temp, path)?;
        sync_parent(path);
        Ok(())
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        OutputError::io(path, e)
    })
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
/// extension, for writers that pick the format by it), flushes it and
/// renames it over `path`; the renderer's error is the file system's.
pub(super) fn render_atomic<E>(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), OutputError>
where
    E: Into<Box<dyn std::error::Error + Send + Sync>>,
{
    let path = &through_link(path);
    create_parent(path)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let temp = path.with_file_name(format!(".bumpsim-{}-{n}-{name}", std::process::id()));
    let result = render(&temp)
        .map_err(std::io::Error::other)
        .and_then(|()| std::fs::File::open(&temp)?.sync_all())
        .and_then(|()| std::fs::rename(&temp, path));
    result.map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        OutputError::io(path, e)
    })?;
    sync_parent(path);
    Ok(())
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
