//! Input files read whole, within bounds: only regular files are read (a
//! pipe with no writer blocks forever, a device such as `/dev/zero` never
//! ends, and bumpsim reads some inputs twice, which a stream cannot give),
//! and at most [`MAX_FILE_BYTES`], checked on the file's size before
//! anything is allocated and again while reading (a file that grows, or
//! one whose size the system does not know, as in `/proc`).
//!
//! ```
//! use bumpsim_core::files::{ReadError, read_text};
//! let path = std::env::temp_dir().join(format!("bumpsim-doc-files-{}.txt", std::process::id()));
//! std::fs::write(&path, "masses = [1.0]\n").unwrap();
//! assert_eq!(read_text(&path).unwrap(), "masses = [1.0]\n");
//! # #[cfg(unix)]
//! assert!(matches!(read_text("/dev/zero".as_ref()), Err(ReadError::NotAFile { .. })));
//! std::fs::remove_file(&path).unwrap();
//! ```

use std::io::Read;
use std::path::{Path, PathBuf};

/// Largest input file bumpsim reads (1 GiB; a CSV of the 20 million
/// samples a channel may have takes about 400 MB). docs/limits.md.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Largest car file (TOML) bumpsim reads: 4 MiB. A car of the most masses
/// (1000) with linear links takes about 100 kB, a loading table at its
/// 10 000-point limit (`bumpsim_core::link::MAX_TABLE_POINTS`) about
/// 300 kB with units, so a dozen such tables fit. Checked on the file's
/// size before it is read: a 20 MB table took 8 s of a debug build to parse
/// (twice: the model's kind, then the car) only to be refused by its point
/// count. docs/limits.md.
pub const MAX_CAR_BYTES: u64 = 4 << 20;

/// Most samples (rows) a channel of an input file may hold: 2 000 000,
/// 200 s at 10 kHz or 20 s at 100 kHz, far beyond a low-speed crash test
/// (0.1 to 0.3 s; ISO 6487 and NHTSA record at 10 to 20 kHz). Checked while
/// the samples are read, before they are all held: a 1 GiB file may hold
/// 75 million rows, and `simulate` holds about 520 bytes per row (its
/// response), so 2 000 000 rows take about 1 GB, 75 million 37 GB (an
/// out-of-memory kill instead of an error). Readers: CSV tables, ISO-MME and
/// EV5 channel files. docs/limits.md.
pub const MAX_INPUT_SAMPLES: usize = 2_000_000;

/// An input file that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// A folder, device, pipe or socket where a file is read.
    #[error("{path}: is {kind}, not a regular file: give a file (save a stream to a file first)")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },
    /// More bytes than [`MAX_FILE_BYTES`].
    #[error("{path}: larger than {limit} bytes, the most an input file may have (MAX_FILE_BYTES)")]
    TooLarge {
        /// The path.
        path: PathBuf,
        /// The limit, bytes.
        limit: u64,
    },
    /// A car file larger than [`MAX_CAR_BYTES`].
    #[error(
        "{path}: {size} bytes, larger than a car file may be ({limit} bytes, MAX_CAR_BYTES; docs/limits.md)"
    )]
    CarTooLarge {
        /// The path.
        path: PathBuf,
        /// Its size, bytes.
        size: u64,
        /// The limit, bytes.
        limit: u64,
    },
    /// Not UTF-8 text where text is read.
    #[error("{path}:{line}: not UTF-8 text")]
    NotText {
        /// The path.
        path: PathBuf,
        /// 1-based line of the first invalid byte.
        line: usize,
    },
    /// The system refused.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// What a path is, when it is not a regular file (links followed); `None`
/// for a regular file. Does not open it (opening a pipe blocks).
pub fn not_a_file(path: &Path) -> Result<Option<&'static str>, ReadError> {
    let meta = std::fs::metadata(path).map_err(|source| ReadError::Io {
        path: path.into(),
        source,
    })?;
    Ok(match meta.file_type() {
        t if t.is_file() => None,
        t if t.is_dir() => Some("a folder"),
        _ => Some("a device, pipe or socket"),
    })
}

/// Reads a regular file of at most [`MAX_FILE_BYTES`] whole.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, ReadError> {
    let io = |source| ReadError::Io {
        path: path.into(),
        source,
    };
    if let Some(kind) = not_a_file(path)? {
        return Err(ReadError::NotAFile {
            path: path.into(),
            kind,
        });
    }
    let too_large = || ReadError::TooLarge {
        path: path.into(),
        limit: MAX_FILE_BYTES,
    };
    let size = std::fs::metadata(path).map_err(io)?.len();
    if size > MAX_FILE_BYTES {
        return Err(too_large());
    }
    let mut bytes = Vec::with_capacity(size as usize);
    std::fs::File::open(path)
        .map_err(io)?
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Refuses a car file larger than [`MAX_CAR_BYTES`] by its size, before
/// it is read (a path whose size cannot be read passes: its reader says
/// why).
pub fn check_car_size(path: &Path) -> Result<(), ReadError> {
    match std::fs::metadata(path).map(|m| m.len()) {
        Ok(size) if size > MAX_CAR_BYTES => Err(ReadError::CarTooLarge {
            path: path.into(),
            size,
            limit: MAX_CAR_BYTES,
        }),
        _ => Ok(()),
    }
}

/// [`read_text`] of a car file, refused first by [`check_car_size`].
pub fn read_car_text(path: &Path) -> Result<String, ReadError> {
    check_car_size(path)?;
    read_text(path)
}

/// Reads a regular UTF-8 text file of at most [`MAX_FILE_BYTES`] whole.
pub fn read_text(path: &Path) -> Result<String, ReadError> {
    String::from_utf8(read_bytes(path)?).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        ReadError::NotText {
            path: path.into(),
            line: 1 + valid.iter().filter(|&&b| b == b'\n').count(),
        }
    })
}

/// `path` as it is shown to the user: `.` parts dropped and each
/// `folder/..` pair folded (`examples/x/../../out/a.csv` is `out/a.csv`), a
/// leading `..` kept. Only for printing: through a symbolic link `..` may
/// lead elsewhere, so files are opened by the path as given.
///
/// ```
/// use bumpsim_core::files::shown_path;
/// use std::path::Path;
/// assert_eq!(shown_path(Path::new("examples/x/../../out/a.csv")), Path::new("out/a.csv"));
/// assert_eq!(shown_path(Path::new("./a/../../b")), Path::new("../b"));
/// ```
pub fn shown_path(path: &Path) -> PathBuf {
    use std::path::Component;
    let mut parts: Vec<Component> = Vec::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir if matches!(parts.last(), Some(Component::Normal(_))) => {
                parts.pop();
            }
            Component::ParentDir if matches!(parts.last(), Some(Component::RootDir)) => {}
            other => parts.push(other),
        }
    }
    match parts.is_empty() {
        true => PathBuf::from("."),
        false => parts.iter().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn pipes_devices_and_folders_are_refused_without_blocking() {
        let dir = std::env::temp_dir().join(format!("bumpsim-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert!(matches!(read_text(&fifo), Err(ReadError::NotAFile { .. })));
        }
        for path in [Path::new("/dev/zero"), dir.as_path()] {
            let e = read_bytes(path).unwrap_err();
            assert!(matches!(e, ReadError::NotAFile { .. }), "{e}");
        }
        std::fs::write(dir.join("bad.txt"), b"ok\n\xff").unwrap();
        let e = read_text(&dir.join("bad.txt")).unwrap_err();
        assert!(e.to_string().ends_with("bad.txt:2: not UTF-8 text"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
