//! An existing output folder replaced by its staged successor in one step.
//!
//! The staged folder first receives every entry of the old folder that the
//! run does not write (the user's own files, earlier runs' figures, other
//! outputs of the command placed inside it): hard links (a copy for a
//! regular file where the file system refuses a link, a new link for a
//! symbolic link), folders made with the old folder's permissions. Then
//! the two folders change places: on Linux with one
//! `renameat2(RENAME_EXCHANGE)` (rustix; Linux 3.15, ext4, xfs, btrfs,
//! tmpfs, overlayfs), so the target path always names a complete folder,
//! old or new; where that call is refused (another system, a file system
//! without it) the old folder is renamed aside first and the new one
//! renamed in, a window in which the target is missing that the next write
//! of the same output closes by renaming the old folder back
//! ([`restore_aside`]). The old folder, now under the hidden staging name,
//! is removed last; a kill before that leaves it hidden, and the next
//! write removes it.
//!
//! A name that is a folder in one and a file in the other would drop the
//! old entry: refused before anything moves.

use super::error::OutputError;
use super::write::{sibling, stale_siblings};
use std::path::{Path, PathBuf};

/// Carries every entry of `old` that `new` lacks into `new` (see the
/// module docs); `target` names the old folder in errors.
pub(super) fn carry_over(old: &Path, new: &Path) -> Result<(), OutputError> {
    let mut pending = vec![PathBuf::new()];
    while let Some(relative) = pending.pop() {
        let dir = old.join(&relative);
        let entries = std::fs::read_dir(&dir).map_err(|e| OutputError::io(&dir, e))?;
        for entry in entries {
            let entry = entry.map_err(|e| OutputError::io(&dir, e))?;
            let name = relative.join(entry.file_name());
            let (from, to) = (old.join(&name), new.join(&name));
            let folder = entry.file_type().is_ok_and(|t| t.is_dir());
            match (folder, std::fs::symlink_metadata(&to).ok()) {
                (true, Some(there)) if there.is_dir() => pending.push(name),
                (true, Some(_)) => return Err(OutputError::IsAFolder { path: from }),
                (true, None) => {
                    make_folder_like(&from, &to)?;
                    pending.push(name);
                }
                (false, Some(there)) if there.is_dir() => {
                    return Err(OutputError::NotAFolder { path: from });
                }
                (false, Some(_)) => {} // the run writes it anew
                (false, None) => link_or_copy(&from, &to)?,
            }
        }
    }
    Ok(())
}

/// Makes folder `to` with the permissions of folder `from`.
fn make_folder_like(from: &Path, to: &Path) -> Result<(), OutputError> {
    std::fs::create_dir(to).map_err(|e| OutputError::io(to, e))?;
    same_permissions(from, to)
}

/// Gives `to` the permissions of `from`.
pub(super) fn same_permissions(from: &Path, to: &Path) -> Result<(), OutputError> {
    let mode = std::fs::metadata(from).map_err(|e| OutputError::io(from, e))?;
    std::fs::set_permissions(to, mode.permissions()).map_err(|e| OutputError::io(to, e))
}

/// A hard link `to` of `from` (not following a symbolic link); where the
/// file system refuses, a copy of a regular file or a new symbolic link.
fn link_or_copy(from: &Path, to: &Path) -> Result<(), OutputError> {
    let Err(refused) = std::fs::hard_link(from, to) else {
        return Ok(());
    };
    let kind = std::fs::symlink_metadata(from).map_err(|e| OutputError::io(from, e))?;
    let copied = if kind.is_file() {
        std::fs::copy(from, to).map(|_| ())
    } else {
        relink(from, to, refused)
    };
    copied.map_err(|e| OutputError::io(from, e))
}

#[cfg(unix)]
fn relink(from: &Path, to: &Path, refused: std::io::Error) -> std::io::Result<()> {
    match std::fs::read_link(from) {
        Ok(points_to) => std::os::unix::fs::symlink(points_to, to),
        Err(_) => Err(refused),
    }
}

#[cfg(not(unix))]
fn relink(_from: &Path, _to: &Path, refused: std::io::Error) -> std::io::Result<()> {
    Err(refused)
}

/// Puts folder `new` in the place of folder `target`; returns where the
/// old folder is then (for the caller to remove). On an error nothing
/// has moved.
pub(super) fn swap(new: &Path, target: &Path) -> Result<PathBuf, OutputError> {
    if exchange(new, target).map_err(|e| OutputError::io(target, e))? {
        return Ok(new.into());
    }
    let aside = sibling(target, "old");
    std::fs::rename(target, &aside).map_err(|e| OutputError::io(target, e))?;
    if let Err(e) = std::fs::rename(new, target) {
        let _ = std::fs::rename(&aside, target);
        return Err(OutputError::io(target, e));
    }
    Ok(aside)
}

/// Exchanges two folders in one step; `false` where the system or the file
/// system has no such call (nothing moved then).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<bool> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    use rustix::io::Errno;
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(true),
        Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => Ok(false),
        Err(e) => Err(e.into()),
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_a: &Path, _b: &Path) -> std::io::Result<bool> {
    Ok(false)
}

/// Puts back an old folder a killed swap left renamed aside (`target`
/// missing), or removes it (`target` is the complete new folder).
pub(super) fn restore_aside(target: &Path) {
    for aside in stale_siblings(target, "old") {
        if std::fs::symlink_metadata(target).is_err() {
            let _ = std::fs::rename(&aside, target);
        } else {
            let _ = std::fs::remove_dir_all(&aside);
        }
    }
}
