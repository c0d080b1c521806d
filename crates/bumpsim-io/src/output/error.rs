//! Why an output cannot be written: each error names the path.

use std::path::{Path, PathBuf};

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
    /// A folder output that holds an input of the kinds of file it writes
    /// itself (an `index.html` in a report folder): the output could
    /// replace the input.
    #[error("{0}")]
    InputOfItsKind(Box<Clash>),
    /// Two outputs of one command at the same path: the second would
    /// silently replace the first.
    #[error("{output}: refusing to write two outputs to one path (also given as {first})")]
    Twice {
        /// The second output path.
        output: PathBuf,
        /// The first one, as given.
        first: PathBuf,
    },
    /// An output lies inside another output of the command (a file in a
    /// report folder, a plot folder in a work folder): the outer one, moved
    /// into place whole, would mix with or drop the inner one.
    #[error("{0}")]
    InsideOutput(Box<Nesting>),
    /// A folder output that is the working folder or a folder above it:
    /// replacing it whole would move the working folder away.
    #[error(
        "{path}: is the working folder or holds it; an output folder is replaced whole, \
         so give a folder beside or below the working folder"
    )]
    HoldsWorkingFolder {
        /// The path.
        path: PathBuf,
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

/// An output inside another output of one command ([`OutputError::InsideOutput`]).
#[derive(Debug)]
pub struct Nesting {
    /// The inner output's path.
    pub output: PathBuf,
    /// The option that names it (`--json`), or empty.
    pub option: String,
    /// The output it lies in.
    pub outer: PathBuf,
    /// The option that names that one (`--report`), or empty.
    pub outer_option: String,
    /// Why one would replace or drop the other.
    pub reason: String,
}

impl std::fmt::Display for Nesting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (inner, outer) = (named(&self.option, "the output"), self.outer.display());
        write!(
            f,
            "{inner} {}: refusing to write two outputs to one path: it lies inside {} {outer}, \
             another output of this command ({}); give {inner} a path outside {outer}",
            self.output.display(),
            named(&self.outer_option, "the output"),
            self.reason
        )
    }
}

/// A folder output holding an input of its own kinds of file
/// ([`OutputError::InputOfItsKind`]).
#[derive(Debug)]
pub struct Clash {
    /// The folder output.
    pub output: PathBuf,
    /// The option that names it (`--report`).
    pub option: String,
    /// The input inside it.
    pub input: PathBuf,
    /// The kinds of file the output writes (`html, svg, png`).
    pub kinds: String,
}

impl std::fmt::Display for Clash {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let option = named(&self.option, "the output");
        write!(
            f,
            "{option} {}: refusing to write: the folder holds the input {}, and this output \
             writes {} files of its own there (it could replace the input); give {option} \
             another folder or move the input",
            self.output.display(),
            self.input.display(),
            self.kinds
        )
    }
}

/// An option's name, or `otherwise` when none was given.
fn named<'a>(option: &'a str, otherwise: &'a str) -> &'a str {
    if option.is_empty() { otherwise } else { option }
}

impl OutputError {
    /// A refusal of the file system at `path`.
    pub(super) fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}
