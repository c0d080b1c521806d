//! Outputs that never land on an input and are written whole or not at all.
//!
//! Every command tells the [`Outputs`] guard each path it reads (files and
//! test folders). An output is then refused when it is an input, lies inside
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
//!   step; into an existing folder each staged file is renamed over its old
//!   version (files of the folder that the run does not write are kept). A
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
//! - two files of one output folder with the same name, or a folder's file
//!   that is another claimed output of the command, are errors: neither
//!   silently replaces the other.
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

use std::io::Write;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Most samples a channel may have when a command makes or resamples one
/// (about 160 MB of values): beyond it the command refuses instead of
/// exhausting memory (docs/limits.md).
pub const MAX_SAMPLES: usize = 20_000_000;

/// At most this many entries of an input folder are compared by inode.
pub const FOLDER_SCAN_LIMIT: usize = 100_000;

/// An output that cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The output is one of the inputs (same path or same file).
    #[error("{output}: refusing to write: it would overwrite the input {input}")]
    OnInput {
        /// The output path.
        output: PathBuf,
        /// The input it would replace.
        input: PathBuf,
    },
    /// The output lies inside an input folder.
    #[error("{output}: refusing to write inside the input folder {folder}")]
    InsideInput {
        /// The output path.
        output: PathBuf,
        /// The input folder.
        folder: PathBuf,
    },
    /// Two outputs of one command at the same path: the second would
    /// silently replace the first.
    #[error("{output}: refusing to write two outputs to one path (also given as {first})")]
    Twice {
        /// The second output path.
        output: PathBuf,
        /// The first one, as given.
        first: PathBuf,
    },
    /// A folder is needed but the path is an existing file.
    #[error("{path}: exists and is not a folder (a folder is needed here)")]
    NotAFolder {
        /// The path.
        path: PathBuf,
    },
    /// A file is needed but the path is an existing folder.
    #[error("{path}: is a folder (a file is needed here)")]
    IsAFolder {
        /// The path.
        path: PathBuf,
    },
    /// The path exists and is neither a regular file nor a folder (a
    /// device, pipe or socket): an output replaces its target by renaming,
    /// which would replace the special file itself.
    #[error(
        "{path}: exists and is not a regular file (a device, pipe or socket); give a file path"
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// Two files of one output folder would get the same name (for example
    /// two case names that differ only in characters a file name cannot hold).
    #[error("{path}: two files of one output would have this name; make the names differ")]
    SameName {
        /// The file's final path.
        path: PathBuf,
    },
    /// A name given for a file inside an output folder is not a plain name.
    #[error("'{name}': {reason}")]
    BadName {
        /// The name.
        name: String,
        /// Why it is refused.
        reason: String,
    },
    /// The file system refused.
    #[error("{path}: cannot write: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

impl OutputError {
    fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}

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
    pub fn new() -> Self {
        Self::default()
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
    fn check_unclaimed(&self, path: &Path) -> Result<(), OutputError> {
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

    /// Checks `path`, then writes `bytes` to it atomically (temporary file in
    /// the same folder, fsync, rename). Creates the folder if missing.
    pub fn write_file(&self, path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
        self.check_file(path)?;
        remove_stale(&through_link(path), "tmp");
        write_atomic(path, bytes)
    }

    /// Checks `path` as a folder output and opens a staging folder for it.
    pub fn stage_folder(&self, path: &Path) -> Result<StagedFolder, OutputError> {
        self.check_folder(path)?;
        StagedFolder::new(path)
    }
}

/// The absolute path with every existing part resolved (links followed) and
/// the missing rest appended lexically (`..` and `.` removed).
fn canonical(path: &Path) -> PathBuf {
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

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A hidden sibling name for temporary files and folders of `path`.
fn sibling(path: &Path, kind: &str) -> PathBuf {
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
fn remove_stale(path: &Path, kind: &str) {
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

fn create_parent(path: &Path) -> Result<(), OutputError> {
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

/// Checks `path` against the process-wide guard, lets `render` write a
/// hidden temporary file next to it (same extension, for writers that pick
/// the format by it), flushes it and renames it over `path`.
pub fn write_rendered(
    path: &Path,
    render: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), OutputError> {
    check_file(path)?;
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
fn through_link(path: &Path) -> PathBuf {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            std::fs::canonicalize(path).unwrap_or_else(|_| path.into())
        }
        _ => path.into(),
    }
}

/// Flushes the folder entry of a rename to disk (best effort).
fn sync_parent(path: &Path) {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if let Ok(dir) = std::fs::File::open(parent) {
        let _ = dir.sync_all();
    }
}

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
    target: PathBuf,
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
        create_parent(target)?;
        remove_stale(target, "staging");
        let staging = sibling(target, "staging");
        std::fs::create_dir_all(&staging).map_err(|e| OutputError::io(&staging, e))?;
        Ok(Self {
            target: target.into(),
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
    pub fn commit(mut self, guard: &Outputs) -> Result<(), OutputError> {
        let files = staged_files(&self.staging)?;
        for relative in &files {
            guard.check_file(&self.target.join(relative))?;
            guard.check_unclaimed(&self.target.join(relative))?;
        }
        sync_tree(&self.staging, &files);
        if !self.target.exists() {
            std::fs::rename(&self.staging, &self.target)
                .map_err(|e| OutputError::io(&self.target, e))?;
        } else {
            for relative in &files {
                let to = through_link(&self.target.join(relative));
                create_parent(&to)?;
                std::fs::rename(self.staging.join(relative), &to)
                    .map_err(|e| OutputError::io(&to, e))?;
            }
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        sync_parent(&self.target);
        self.committed = true;
        Ok(())
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

fn sync_tree(root: &Path, files: &[PathBuf]) {
    for relative in files {
        if let Ok(file) = std::fs::File::open(root.join(relative)) {
            let _ = file.sync_all();
        }
    }
}

/// The process-wide guard used by the command line and the library writers.
static GUARD: Mutex<Outputs> = Mutex::new(Outputs {
    inputs: Vec::new(),
    claimed: Vec::new(),
});

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

#[cfg(test)]
mod tests {
    use super::*;
    #[cfg(unix)]
    use std::os::unix::fs::FileTypeExt;

    /// `planar --json x --csv x` wrote both to x with exit 0: the CSV
    /// silently replaced the JSON.
    #[test]
    fn one_path_cannot_take_two_outputs() {
        let dir = temp("twice");
        let mut guard = Outputs::new();
        let out = dir.join("same.json");
        guard.claim(&out).unwrap();
        guard.claim(&dir.join("other.csv")).unwrap();
        let err = guard.claim(&dir.join(".").join("same.json")).unwrap_err();
        assert!(matches!(err, OutputError::Twice { .. }), "{err}");
        assert!(err.to_string().contains("two outputs"), "{err}");
        // a hard link to an existing output is the same file
        std::fs::write(&out, "x").unwrap();
        std::fs::hard_link(&out, dir.join("link.json")).unwrap();
        let mut guard = Outputs::new();
        guard.claim(&out).unwrap();
        assert!(guard.claim(&dir.join("link.json")).is_err());
    }

    fn temp(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("bumpsim-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn inputs_links_and_folders_are_refused() {
        let dir = temp("refuse");
        let input = dir.join("in.toml");
        std::fs::write(&input, "a").unwrap();
        std::fs::hard_link(&input, dir.join("link.toml")).unwrap();
        let test = dir.join("TEST");
        std::fs::create_dir_all(test.join("Channel")).unwrap();
        std::fs::write(test.join("Channel/T.001"), "1").unwrap();
        std::fs::hard_link(test.join("Channel/T.001"), dir.join("t-link")).unwrap();
        let mut g = Outputs::new();
        g.input(&input);
        g.input(&test);
        for bad in [
            input.clone(),
            dir.join("link.toml"),
            dir.join("./sub/../in.toml"),
            test.join("Channel/T.001"),
            test.join("Channel/new.csv"),
            dir.join("t-link"),
        ] {
            assert!(g.write_file(&bad, b"x").is_err(), "{}", bad.display());
        }
        assert_eq!(std::fs::read(&input).unwrap(), b"a");
        assert_eq!(std::fs::read(test.join("Channel/T.001")).unwrap(), b"1");
        g.write_file(&dir.join("out/deep.csv"), b"ok").unwrap();
        assert_eq!(std::fs::read(dir.join("out/deep.csv")).unwrap(), b"ok");
        assert!(matches!(
            g.check_folder(&input),
            Err(OutputError::NotAFolder { .. }) | Err(OutputError::OnInput { .. })
        ));
        assert!(matches!(
            g.check_file(&dir.join("out")),
            Err(OutputError::IsAFolder { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn staged_folders_appear_only_on_commit() {
        let dir = temp("stage");
        let g = Outputs::new();
        let target = dir.join("report");
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("index.html"), "old").unwrap();
        std::fs::write(target.join("keep.txt"), "mine").unwrap();
        {
            let staged = g.stage_folder(&target).unwrap();
            staged.write("index.html", b"new").unwrap();
            // dropped: a failed run
        }
        assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"old");
        let staged = g.stage_folder(&target).unwrap();
        staged.write("index.html", b"new").unwrap();
        staged.write("fig/a.svg", b"<svg/>").unwrap();
        assert!(staged.write("../escape", b"x").is_err());
        staged.commit(&g).unwrap();
        assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"new");
        assert_eq!(std::fs::read(target.join("keep.txt")).unwrap(), b"mine");
        assert!(target.join("fig/a.svg").is_file());
        let fresh = dir.join("fresh");
        let staged = g.stage_folder(&fresh).unwrap();
        staged.write("a", b"1").unwrap();
        staged.commit(&g).unwrap();
        assert!(fresh.join("a").is_file());
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// `--json /dev/full` replaced the device node by a regular file; an
    /// output link was replaced by a file; two case names that map to one
    /// plot name lost a plot; `--json rep/index.html --report rep` lost the
    /// JSON. Each is now refused or written through.
    #[cfg(unix)]
    #[test]
    fn special_files_links_same_names_and_claimed_files() {
        let dir = temp("special");
        let mut g = Outputs::new();
        let device = Path::new("/dev/null");
        assert!(matches!(
            g.write_file(device, b"x"),
            Err(OutputError::NotAFile { .. })
        ));
        assert!(
            std::fs::metadata(device)
                .unwrap()
                .file_type()
                .is_char_device()
        );
        let target = dir.join("target.json");
        std::fs::write(&target, "old").unwrap();
        std::os::unix::fs::symlink(&target, dir.join("link.json")).unwrap();
        g.write_file(&dir.join("link.json"), b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(dir.join("link.json"))
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        let report = dir.join("report");
        g.claim(&report.join("index.html")).unwrap();
        g.claim(&report).unwrap();
        let staged = g.stage_folder(&report).unwrap();
        staged.write("fit-a_b.svg", b"1").unwrap();
        assert!(matches!(
            staged.write("fit-a_b.svg", b"2"),
            Err(OutputError::SameName { .. })
        ));
        staged.write("index.html", b"<html/>").unwrap();
        assert!(matches!(staged.commit(&g), Err(OutputError::Twice { .. })));
        assert!(!report.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// kill -9 during a write left `.out.csv.PID-N.tmp` and
    /// `.report.PID-N.staging/` for good; the next write of the same output
    /// removes those of processes that no longer run.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_killed_run_s_temporary_files_go_with_the_next_write() {
        let dir = temp("stale");
        let dead = u32::MAX - 7; // above any pid_max
        let stale_file = dir.join(format!(".out.csv.{dead}-3.tmp"));
        std::fs::write(&stale_file, "half").unwrap();
        let stale_folder = dir.join(format!(".report.{dead}-0.staging"));
        std::fs::create_dir_all(stale_folder.join("fig")).unwrap();
        let alive = dir.join(format!(".out.csv.{}-9.tmp", std::process::id()));
        std::fs::write(&alive, "mine").unwrap();
        let unrelated = dir.join(".out.csv.notes.tmp");
        std::fs::write(&unrelated, "user").unwrap();
        let g = Outputs::new();
        g.write_file(&dir.join("out.csv"), b"x").unwrap();
        g.stage_folder(&dir.join("report"))
            .unwrap()
            .commit(&g)
            .unwrap();
        assert!(!stale_file.exists() && !stale_folder.exists());
        assert!(alive.exists() && unrelated.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn plain_names() {
        for bad in ["", "..", "/abs", "../../x", "a/b", ".hidden"] {
            assert!(plain_name(bad).is_err(), "{bad}");
        }
        assert!(plain_name("HEAD-1").is_ok());
    }
}
