//! The error type of the test-data readers and writers (ISO-MME, EV5).
//!
//! Every variant names the file; parse errors also name the 1-based line.

use std::path::PathBuf;

/// A problem with a crash-test file or a channel selection.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SignalFileError {
    /// The file cannot be read or written.
    #[error("{path}: {action}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// `cannot read`, `cannot write`, ...
        action: &'static str,
        /// The cause.
        source: std::io::Error,
    },
    /// A line does not hold what it should.
    #[error("{path}:{line}: {message}")]
    Line {
        /// The file (for a zip member: `archive.zip!member`).
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A whole-file problem (missing file, wrong layout).
    #[error("{path}: {message}")]
    File {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A channel selection matched nothing usable.
    #[error("{path}: channel '{selector}': {reason}")]
    Select {
        /// The test file.
        path: PathBuf,
        /// The selector as given.
        selector: String,
        /// Why it failed.
        reason: String,
    },
    /// Explicit sample times that do not make a uniform time base.
    #[error("{path}: {source}")]
    TimeBase {
        /// The file of the times.
        path: PathBuf,
        /// What is wrong with them.
        source: TimeBaseError,
    },
    /// A CSV test file's table error (it names the file and line itself).
    #[error(transparent)]
    Table(#[from] crate::table::TableError),
    /// The output is refused (it would land on an input) or cannot be written.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// The file is not a regular file or too large.
    #[error(transparent)]
    Read(#[from] bumpsim_core::files::ReadError),
}

/// Why explicit sample times (an ISO-MME time channel) are not a uniform
/// time base for a channel.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TimeBaseError {
    /// Not one time per sample of the channel, or fewer than two.
    #[error("the time channel has {times} samples, the channel {count}")]
    Count {
        /// Times given.
        times: usize,
        /// Samples of the channel.
        count: usize,
    },
    /// The last time is not after the first.
    #[error("time does not increase")]
    NotIncreasing,
    /// A time off the uniform interval by more than 1 % of it.
    #[error("sample {sample} at {time} s breaks the uniform interval {step} s")]
    Irregular {
        /// 1-based sample.
        sample: usize,
        /// Its time, s.
        time: f64,
        /// The interval of the first and last times, s.
        step: f64,
    },
}

impl SignalFileError {
    /// A line error.
    pub fn line(path: impl Into<PathBuf>, line: usize, message: impl Into<String>) -> Self {
        SignalFileError::Line {
            path: path.into(),
            line,
            message: message.into(),
        }
    }

    /// A whole-file error.
    pub fn file(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        SignalFileError::File {
            path: path.into(),
            message: message.into(),
        }
    }

    /// A read error.
    pub fn read(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        SignalFileError::Io {
            path: path.into(),
            action: "cannot read",
            source,
        }
    }

    /// A write error.
    pub fn write(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        SignalFileError::Io {
            path: path.into(),
            action: "cannot write",
            source,
        }
    }
}

/// Decodes bytes as UTF-8, or as Latin-1 when they are not valid UTF-8
/// (lab exports are often Latin-1). A UTF-8 byte-order mark is dropped.
pub fn decode(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(_) => bytes.iter().map(|&b| b as char).collect(),
    }
}

/// Reads and decodes a text file.
pub fn read_text(path: &std::path::Path) -> Result<String, SignalFileError> {
    Ok(decode(&read_bytes(path)?))
}

/// Reads a file whole within bounds ([`bumpsim_core::files::read_bytes`]):
/// a missing or unreadable file is [`SignalFileError::Io`], one that is no
/// regular file or too large [`SignalFileError::Read`].
pub fn read_bytes(path: &std::path::Path) -> Result<Vec<u8>, SignalFileError> {
    use bumpsim_core::files::ReadError;
    bumpsim_core::files::read_bytes(path).map_err(|e| match e {
        ReadError::Io { path, source } => SignalFileError::read(path, source),
        other => SignalFileError::Read(other),
    })
}

/// Parses a number as labs write it (`1.0E-4`, `9.999999999999999e-05`,
/// `+12`, `.5`), or `None`.
pub fn parse_number(text: &str) -> Option<f64> {
    let value: f64 = text.trim().parse().ok()?;
    value.is_finite().then_some(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latin1_and_numbers() {
        assert_eq!(decode(b"Stra\xDFe"), "Straße");
        assert_eq!(decode("\u{FEFF}ok".as_bytes()), "ok");
        assert_eq!(parse_number(" 1.0E-4 "), Some(1e-4));
        assert_eq!(
            parse_number("9.999999999999999e-05"),
            Some(9.999999999999999e-05)
        );
        assert_eq!(parse_number("NOVALUE"), None);
        assert_eq!(parse_number("inf"), None);
    }
}
