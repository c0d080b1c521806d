//! The framing of the state journal (`state.journal`, docs/campaign.md):
//! one record per line, `CHECKSUM JSON`, where CHECKSUM is the first 8 hex
//! digits of the SHA-256 of the JSON text (FIPS 180-4). A line whose
//! checksum does not match, or that is not of that form, is damage; text
//! after the last newline is an append that has not finished (a writer at
//! work, or one killed or cut off by a power loss mid-write: never acted
//! upon, since the controller syncs a record before it acts on it) and is
//! left out. This is the framing of write-ahead logs (LevelDB's log
//! format, SQLite's WAL frames): every record checked on its own, a torn
//! tail told apart from a damaged middle.
//!
//! This module knows lines, checksums and appending; what a record means
//! (the header, a point) is [`crate::state`]'s.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The checksum of a record's text: the first 8 hex digits of its SHA-256.
///
/// ```
/// assert_eq!(bumpsim_campaign::journal::checksum(b"{}"), "44136fa3");
/// ```
pub fn checksum(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(bytes)[..4]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// One framed line: `CHECKSUM JSON\n`.
pub fn frame(json: &str) -> String {
    format!("{} {json}\n", checksum(json.as_bytes()))
}

/// The records of a journal's text, in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Records<'a> {
    /// (1-based line, JSON text) of every line whose checksum matches.
    pub lines: Vec<(usize, &'a str)>,
    /// (1-based line, what is wrong) of every damaged line.
    pub damage: Vec<(usize, String)>,
    /// Bytes of the text that are whole lines (the unfinished tail excluded).
    pub whole: usize,
    /// Bytes after the last newline (an append that has not finished).
    pub torn: usize,
}

/// Cuts `text` into checked records.
///
/// ```
/// use bumpsim_campaign::journal::{frame, records};
/// let text = frame("{\"a\":1}") + "00000000 {\"a\":2}\n" + &frame("{\"a\":3}")[..5];
/// let r = records(&text);
/// assert_eq!(r.lines, [(1, "{\"a\":1}")]);
/// assert_eq!(r.damage[0].0, 2);
/// assert_eq!(r.torn, 5);
/// ```
pub fn records(text: &str) -> Records<'_> {
    let whole = text.rfind('\n').map_or(0, |n| n + 1);
    let mut out = Records {
        whole,
        torn: text.len() - whole,
        ..Records::default()
    };
    for (i, line) in text[..whole].lines().enumerate() {
        match line.split_once(' ') {
            Some((sum, json)) if sum == checksum(json.as_bytes()) => out.lines.push((i + 1, json)),
            Some((sum, _)) if sum.len() == 8 => {
                out.damage.push((i + 1, "checksum mismatch".into()));
            }
            _ => out.damage.push((i + 1, "not a journal record".into())),
        }
    }
    out
}

/// An open journal file that records are appended to, each batch flushed
/// to disk (`fdatasync`) before [`Appender::append`] returns.
#[derive(Debug)]
pub struct Appender {
    file: std::fs::File,
    /// The same file opened for writing in place (the append handle
    /// writes only at the end, whatever the offset).
    head: std::fs::File,
    path: PathBuf,
}

impl Appender {
    /// Opens `path` for appending after its first `whole` bytes (an
    /// unfinished tail beyond them is cut off first).
    pub fn open(path: &Path, whole: usize) -> std::io::Result<Appender> {
        let file = std::fs::OpenOptions::new().append(true).open(path)?;
        if file.metadata()?.len() != whole as u64 {
            file.set_len(whole as u64)?;
            file.sync_data()?;
        }
        let head = std::fs::OpenOptions::new().write(true).open(path)?;
        Ok(Appender {
            file,
            head,
            path: path.into(),
        })
    }

    /// Overwrites the journal's first bytes in place with `bytes` (a line
    /// of the same length: the header); flushed to disk with the next
    /// [`Appender::append`].
    pub fn overwrite_head(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        use std::os::unix::fs::FileExt;
        self.head.write_all_at(bytes, 0)
    }

    /// Appends framed lines and flushes them to disk.
    pub fn append(&mut self, lines: &str) -> std::io::Result<()> {
        self.file.write_all(lines.as_bytes())?;
        self.file.sync_data()
    }

    /// The journal file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damage_is_found_line_by_line_and_a_torn_tail_left_out() {
        let text = [
            frame("{\"format\":2}"),
            frame("{\"run\":1}").replace("run", "rum"),
            "garbage\n".into(),
            frame("{\"run\":2}"),
            "4f2a".into(),
        ]
        .concat();
        let r = records(&text);
        assert_eq!(r.lines, [(1, "{\"format\":2}"), (4, "{\"run\":2}")]);
        assert_eq!(
            r.damage,
            [
                (2, "checksum mismatch".to_string()),
                (3, "not a journal record".to_string())
            ]
        );
        assert_eq!((r.whole, r.torn), (text.len() - 4, 4));
    }

    #[test]
    fn an_append_lands_after_the_whole_lines_only() {
        let dir = std::env::temp_dir().join(format!("bumpsim-journal-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("j");
        std::fs::write(&path, frame("{\"a\":1}") + "12ab {\"a\"").unwrap();
        let whole = records(&std::fs::read_to_string(&path).unwrap()).whole;
        let mut appender = Appender::open(&path, whole).unwrap();
        appender.append(&frame("{\"a\":2}")).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let r = records(&text);
        assert_eq!(r.lines.len(), 2);
        assert!(r.damage.is_empty() && r.torn == 0, "{text}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
