//! The guard's knowledge: the registered inputs (by canonical path and by
//! device + inode) and the outputs claimed so far, and the checks that keep
//! an output off them.

use super::error::{Clash, Nesting, OutputError};
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

/// One claimed output.
#[derive(Debug, Clone)]
struct Claim {
    given: PathBuf,
    canonical: PathBuf,
    /// What names it on the command line (`--json`), or empty.
    option: String,
    /// `None`: claimed without a shape ([`Outputs::claim`]), not nested-checked.
    shape: Option<Shape>,
}

/// What a claimed output is, for the check that no output lies inside
/// another ([`Outputs::claim_as`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// One file.
    File,
    /// A folder written whole, whose own files have these extensions (a
    /// report: `html`, `svg`, `png`); empty: a folder whose every name is
    /// the tool's (an ISO-MME test, a work or series folder).
    Folder(&'static [&'static str]),
    /// A folder written whole whose file names the command checks against
    /// its other outputs itself, before it runs (`fe impact --work`: the
    /// solver's files): a file output may lie in it, a folder output not.
    Checked,
}

/// The guard: knows the inputs, checks and writes the outputs.
#[derive(Debug, Default, Clone)]
pub struct Outputs {
    inputs: Vec<Input>,
    /// Outputs claimed so far.
    claimed: Vec<Claim>,
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
        // an EV5 test (NHTSA) given by its `.EV5` file: its channel files
        // `<stem>.NNN` beside it are inputs too (`-o v10146.093` replaced
        // the channel it had just read)
        for channel in ev5_channels(path) {
            self.input(&channel);
        }
    }

    /// Claims `path` as one of the command's outputs: refuses a path (or a
    /// link to a file) claimed before, so that `--json x --csv x` does not
    /// leave only the CSV with exit 0.
    pub fn claim(&mut self, path: &Path) -> Result<(), OutputError> {
        self.claim_shaped(path, "", None)
    }

    /// [`Outputs::claim`] of an output of `shape` named by `option` on the
    /// command line (`--json`), which also refuses, before the command
    /// runs and naming both options, an output inside another claimed
    /// output where one would replace or drop the other: anything inside a
    /// file, a folder inside a folder (`--report r --plot r/p`), and a file
    /// inside a folder of a kind that folder writes itself (`--json
    /// rep/index.html --report rep`). A file of another kind inside a
    /// report folder (`--json rep/result.json`) is allowed.
    pub fn claim_as(&mut self, path: &Path, option: &str, shape: Shape) -> Result<(), OutputError> {
        self.claim_shaped(path, option, Some(shape))
    }

    fn claim_shaped(
        &mut self,
        path: &Path,
        option: &str,
        shape: Option<Shape>,
    ) -> Result<(), OutputError> {
        let target = canonical(path);
        let id = file_id(&target);
        let same = |c: &&Claim| {
            c.canonical == target || id.is_some_and(|id| file_id(&c.canonical) == Some(id))
        };
        if let Some(first) = self.claimed.iter().find(same) {
            return Err(OutputError::Twice {
                output: path.into(),
                first: first.given.clone(),
            });
        }
        let claim = Claim {
            given: path.into(),
            canonical: target,
            option: option.into(),
            shape,
        };
        for other in &self.claimed {
            nested(&claim, other)
                .or_else(|| nested(other, &claim))
                .map_or(Ok(()), Err)?;
        }
        self.claimed.push(claim);
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
        match self.claimed.iter().find(|c| c.canonical == target) {
            Some(first) => Err(OutputError::Twice {
                output: path.into(),
                first: first.given.clone(),
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
        holds_working_folder(path)?;
        self.check_against_inputs(path)
    }

    /// [`Outputs::check_folder`] of a folder output named by `option` whose
    /// own files are of the kinds `kinds` (a report: `html`, `svg`, `png`):
    /// an input of one of those kinds inside it is refused first, naming the
    /// clash (`--report .` beside an input `index.html`: the report writes
    /// its own `index.html` there; the refusal named only the folder).
    pub fn check_folder_of(
        &self,
        path: &Path,
        option: &str,
        kinds: &[&str],
    ) -> Result<(), OutputError> {
        let target = canonical(path);
        let of_kind = |p: &Path| {
            p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| kinds.iter().any(|k| k.eq_ignore_ascii_case(e)))
        };
        let clash = self
            .inputs
            .iter()
            .find(|i| !i.folder && i.canonical.starts_with(&target) && of_kind(&i.canonical));
        match clash {
            Some(input) => Err(OutputError::InputOfItsKind(Box::new(Clash {
                output: path.into(),
                option: option.into(),
                input: input.given.clone(),
                kinds: kinds.join(", "),
            }))),
            None => self.check_folder(path),
        }
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

/// Refuses a folder output that is the working folder or above it (its
/// swap would move the working folder away: `--report .`).
pub(super) fn holds_working_folder(path: &Path) -> Result<(), OutputError> {
    let here = std::env::current_dir().map(|d| canonical(&d));
    match here {
        Ok(here) if here.starts_with(canonical(path)) => {
            Err(OutputError::HoldsWorkingFolder { path: path.into() })
        }
        _ => Ok(()),
    }
}

/// The refusal of `inner` when it lies inside `outer` where one would
/// replace or drop the other (see [`Outputs::claim_as`]).
fn nested(inner: &Claim, outer: &Claim) -> Option<OutputError> {
    let inside =
        inner.canonical != outer.canonical && inner.canonical.starts_with(&outer.canonical);
    let (Some(inner_shape), Some(outer_shape)) = (inner.shape, outer.shape) else {
        return None;
    };
    let reason = match (inner_shape, outer_shape) {
        _ if !inside => return None,
        (_, Shape::File) => "a file, which cannot hold another output".to_string(),
        (Shape::Folder(_) | Shape::Checked, _) => "a folder moved into place whole".to_string(),
        (Shape::File, Shape::Checked) => return None,
        (Shape::File, Shape::Folder([])) => "a folder bumpsim fills whole".to_string(),
        (Shape::File, Shape::Folder(kinds)) => {
            let kind = inner.canonical.extension().map(|e| e.to_string_lossy());
            if !kind.is_some_and(|k| kinds.iter().any(|w| k.eq_ignore_ascii_case(w))) {
                return None;
            }
            let kinds: Vec<String> = kinds.iter().map(|k| format!("*.{k}")).collect();
            format!("whose own files are {}", kinds.join(", "))
        }
    };
    Some(OutputError::InsideOutput(Box::new(Nesting {
        output: inner.given.clone(),
        option: inner.option.clone(),
        outer: outer.given.clone(),
        outer_option: outer.option.clone(),
        reason,
    })))
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

/// The channel files `<stem>.NNN` (digits, any case of the stem) beside an
/// EV5 test file `path`; none for another file.
fn ev5_channels(path: &Path) -> Vec<PathBuf> {
    let ev5 = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ev5"));
    let (Some(stem), Some(parent)) = (path.file_stem().and_then(|s| s.to_str()), path.parent())
    else {
        return Vec::new();
    };
    let folder = match parent.as_os_str().is_empty() {
        true => Path::new("."),
        false => parent,
    };
    let entries = match ev5 {
        true => std::fs::read_dir(folder),
        false => return Vec::new(),
    };
    let Ok(entries) = entries else {
        return Vec::new();
    };
    let channel = |p: &Path| {
        let same = p
            .file_stem()
            .and_then(|s| s.to_str())
            .is_some_and(|s| s.eq_ignore_ascii_case(stem));
        let digits = p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| !e.is_empty() && e.bytes().all(|b| b.is_ascii_digit()));
        same && digits
    };
    entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| channel(p))
        .collect()
}
