//! The guard's knowledge: the registered inputs (by canonical path and by
//! device + inode) and the outputs claimed so far, and the checks that keep
//! an output off them.

use super::error::OutputError;
use std::path::{Component, Path, PathBuf};

/// At most this many entries of an input folder are compared by inode.
pub const FOLDER_SCAN_LIMIT: usize = 100_000;

/// One registered input.
#[derive(Debug, Clone)]
struct Input {
    given: PathBuf,
    canonical: PathBuf,
    folder: bool,
    /// Device and inode of the input and, for a folder, of the files in it.
    ids: Vec<(u64, u64)>,
}

/// The guard: knows the inputs, checks and writes the outputs.
#[derive(Debug, Default, Clone)]
pub struct Outputs {
    inputs: Vec<Input>,
    /// Outputs claimed so far: (as given, canonical).
    claimed: Vec<(PathBuf, PathBuf)>,
}

impl Outputs {
    /// A guard with no inputs yet.
    pub const fn new() -> Self {
        Outputs {
            inputs: Vec::new(),
            claimed: Vec::new(),
        }
    }

    /// Registers an input file or folder (a missing path is kept by name).
    /// For a `.mme` file, the `Channel` folder next to it is registered too.
    pub fn input(&mut self, path: &Path) {
        let canonical = canonical(path);
        let folder = canonical.is_dir();
        let mut ids = Vec::new();
        if folder {
            scan_ids(&canonical, &mut ids);
        } else if let Some(id) = file_id(&canonical) {
            ids.push(id);
        }
        let mme = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("mme"));
        self.inputs.push(Input {
            given: path.into(),
            canonical,
            folder,
            ids,
        });
        // an ISO-MME test given by its `.mme` file: its channel files are inputs too
        if let (true, Some(parent)) = (mme, path.parent()) {
            self.input(&parent.join("Channel"));
        }
    }

    /// Claims `path` as one of the command's outputs: refuses a path (or a
    /// link to a file) claimed before, so that `--json x --csv x` does not
    /// leave only the CSV with exit 0.
    pub fn claim(&mut self, path: &Path) -> Result<(), OutputError> {
        let target = canonical(path);
        let id = file_id(&target);
        let same = |(_, c): &&(PathBuf, PathBuf)| {
            *c == target || id.is_some_and(|id| file_id(c) == Some(id))
        };
        if let Some((first, _)) = self.claimed.iter().find(same) {
            return Err(OutputError::Twice {
                output: path.into(),
                first: first.clone(),
            });
        }
        self.claimed.push((path.into(), target));
        Ok(())
    }

    /// Checks that `path` may be written as a file: not an existing folder,
    /// not an input, not inside an input folder, not a link to an input.
    pub fn check_file(&self, path: &Path) -> Result<(), OutputError> {
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Err(OutputError::IsAFolder { path: path.into() }),
            Ok(m) if !m.is_file() => Err(OutputError::NotAFile { path: path.into() }),
            _ => self.check_against_inputs(path),
        }
    }

    /// Refuses a file of an output folder that is also a claimed output of
    /// its own (`--json report/index.html --report report`): one would
    /// silently replace the other.
    pub(super) fn check_unclaimed(&self, path: &Path) -> Result<(), OutputError> {
        let target = canonical(path);
        match self.claimed.iter().find(|(_, c)| *c == target) {
            Some((first, _)) => Err(OutputError::Twice {
                output: path.into(),
                first: first.clone(),
            }),
            None => Ok(()),
        }
    }

    /// Checks that `path` may receive a multi-file output: not an existing
    /// file, not an input, not inside an input folder.
    pub fn check_folder(&self, path: &Path) -> Result<(), OutputError> {
        if path.exists() && !path.is_dir() {
            return Err(OutputError::NotAFolder { path: path.into() });
        }
        self.check_against_inputs(path)
    }

    fn check_against_inputs(&self, path: &Path) -> Result<(), OutputError> {
        let target = canonical(path);
        let id = file_id(&target);
        for input in &self.inputs {
            if target == input.canonical || id.is_some_and(|id| input.ids.contains(&id)) {
                return Err(OutputError::OnInput {
                    output: path.into(),
                    input: input.given.clone(),
                });
            }
            if input.folder && target.starts_with(&input.canonical) {
                return Err(OutputError::InsideInput {
                    output: path.into(),
                    folder: input.given.clone(),
                });
            }
        }
        Ok(())
    }
}

/// The absolute path with every existing part resolved (links followed) and
/// the missing rest appended lexically (`..` and `.` removed).
pub(super) fn canonical(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    let mut clean = PathBuf::new();
    for part in absolute.components() {
        match part {
            Component::ParentDir => {
                clean.pop();
            }
            Component::CurDir => {}
            other => clean.push(other),
        }
    }
    let mut missing = Vec::new();
    let mut existing = clean.as_path();
    loop {
        if let Ok(resolved) = existing.canonicalize() {
            return missing
                .iter()
                .rev()
                .fold(resolved, |p: PathBuf, name| p.join(name));
        }
        match (existing.parent(), existing.file_name()) {
            (Some(parent), Some(name)) => {
                missing.push(name.to_os_string());
                existing = parent;
            }
            _ => return clean,
        }
    }
}

#[cfg(unix)]
fn file_id(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn file_id(_path: &Path) -> Option<(u64, u64)> {
    None
}

/// Device + inode of the files below `folder` (bounded walk, links not followed).
fn scan_ids(folder: &Path, ids: &mut Vec<(u64, u64)>) {
    let mut pending = vec![folder.to_path_buf()];
    let mut seen = 0usize;
    while let Some(dir) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            seen += 1;
            if seen > FOLDER_SCAN_LIMIT {
                return;
            }
            match entry.file_type() {
                Ok(t) if t.is_dir() => pending.push(entry.path()),
                Ok(t) if t.is_file() => ids.extend(file_id(&entry.path())),
                _ => {}
            }
        }
    }
}
