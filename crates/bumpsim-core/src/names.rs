//! Names a user gives to cases, heads and tests: the one rule for all.
//!
//! Such a name names results, table rows, plots, report files, folders and
//! `--case` selections, so each must be non-empty, printable and differ
//! from the others of its file, ignoring case and surrounding spaces as
//! file names on some systems do. *Printable* excludes every character that
//! shows nothing or changes how the rest shows ([`invisible`]): controls,
//! line and paragraph separators, Unicode's format characters (category
//! Cf: direction marks, overrides and isolates, zero-width spaces and
//! joiners, soft hyphen, byte-order mark, tags), the other default-ignorable
//! code points (variation selectors, Hangul fillers) and the blank braille
//! pattern. The character lists follow Unicode 16 (`DerivedCoreProperties`
//! `Default_Ignorable_Code_Point`, `UnicodeData` category Cf, Zl, Zp); they
//! are written out here because the standard library has no category
//! tables and this one rule does not need a Unicode-data crate.
//!
//! A name that becomes part of a file or folder name goes through
//! [`file_name`]: ASCII letters, digits, `-` and `_` kept ([`file_safe`]),
//! anything else `_`, at most [`FILE_NAME_CHARS`] characters, so that the
//! same name gives the same file on every file system; [`is_file_name`]
//! tells a name that is already one, and [`unique_name`] keeps two names
//! that give the same file apart.

/// Why a list of names cannot be used (numbers count the file's tables,
/// e.g. `[[case]]`, from 1).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum NameError {
    /// The name is empty or only spaces.
    #[error("{table} number {number}: an empty name")]
    Empty {
        /// The table the name is in (`[[case]]`).
        table: &'static str,
        /// The table's number.
        number: usize,
    },
    /// The name holds control or invisible characters.
    #[error(
        "{table} number {number}: the name \"{escaped}\" holds control or invisible characters (tab, escape, line separators, direction marks, zero-width spaces): they would reach the terminal and the file names; use printable text"
    )]
    Invisible {
        /// The table the name is in.
        table: &'static str,
        /// The table's number.
        number: usize,
        /// The name as a TOML basic string spells it (`\u001B` for escape).
        escaped: String,
    },
    /// The name is longer than [`MAX_NAME_BYTES`].
    #[error(
        "{table} number {number}: a name of {bytes} bytes: at most {MAX_NAME_BYTES} in UTF-8 (it names files and folders, whose names the file system limits to 255 bytes)"
    )]
    Long {
        /// The table the name is in.
        table: &'static str,
        /// The table's number.
        number: usize,
        /// Its length in UTF-8 bytes.
        bytes: usize,
    },
    /// Two tables share a name.
    #[error(
        "{table} number {number}: name '{name}' is already used by '{first}'{how}; give each its own name"
    )]
    Repeated {
        /// The table the name is in.
        table: &'static str,
        /// The later table's number.
        number: usize,
        /// Its name.
        name: String,
        /// The earlier table's name.
        first: String,
        /// Empty, or how two names that print alike differ.
        how: &'static str,
    },
}

/// The longest name, in UTF-8 bytes (200 letters of the Latin alphabet,
/// 66 of Chinese): with a suffix such as `.mme` or `-x.svg` it still fits
/// the 255 bytes a file name may have on common file systems.
pub const MAX_NAME_BYTES: usize = 200;

/// Checks the names of one file's `table`s, in file order (see the module).
///
/// ```
/// use bumpsim_core::names::{NameError, check_names};
/// assert!(check_names("[[case]]", ["flat", "angled"]).is_ok());
/// assert!(matches!(
///     check_names("[[case]]", ["flat", " Flat"]),
///     Err(NameError::Repeated { number: 2, .. })
/// ));
/// assert!(check_names("[[case]]", ["FL\u{2028}AT"]).is_err()); // a line separator
/// ```
pub fn check_names<'a>(
    table: &'static str,
    names: impl IntoIterator<Item = &'a str>,
) -> Result<(), NameError> {
    let key = |name: &str| name.trim().to_lowercase();
    let mut seen: Vec<&str> = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        let number = i + 1;
        if key(name).is_empty() {
            return Err(NameError::Empty { table, number });
        }
        if name.len() > MAX_NAME_BYTES {
            let bytes = name.len();
            return Err(NameError::Long {
                table,
                number,
                bytes,
            });
        }
        if name.chars().any(invisible) {
            let escaped = escaped(name);
            return Err(NameError::Invisible {
                table,
                number,
                escaped,
            });
        }
        if let Some(first) = seen.iter().find(|s| key(s) == key(name)) {
            let how = match *first == name {
                true => "",
                false => " (they differ only in case, surrounding spaces or look-alike letters)",
            };
            return Err(NameError::Repeated {
                table,
                number,
                name: name.to_string(),
                first: first.to_string(),
                how,
            });
        }
        seen.push(name);
    }
    Ok(())
}

/// Whether `c` shows nothing a reader sees, or changes how the rest shows
/// (see the module for the classes).
///
/// ```
/// use bumpsim_core::names::invisible;
/// assert!(invisible('\u{1b}') && invisible('\u{202E}') && invisible('\u{3164}'));
/// assert!(!invisible('é') && !invisible(' ') && !invisible('Ω'));
/// ```
pub fn invisible(c: char) -> bool {
    c.is_control()
        || matches!(
            c as u32,
            0x00AD
                | 0x034F
                | 0x0600..=0x0605
                | 0x061C
                | 0x06DD
                | 0x070F
                | 0x0890..=0x0891
                | 0x08E2
                | 0x115F..=0x1160
                | 0x17B4..=0x17B5
                | 0x180B..=0x180F
                | 0x200B..=0x200F
                | 0x2028..=0x202E
                | 0x2060..=0x206F
                | 0x2800
                | 0x3164
                | 0xFE00..=0xFE0F
                | 0xFEFF
                | 0xFFA0
                | 0xFFF0..=0xFFFB
                | 0x110BD
                | 0x110CD
                | 0x13430..=0x1343F
                | 0x1BCA0..=0x1BCA3
                | 0x1D173..=0x1D17A
                | 0xE0000..=0xE0FFF
        )
}

/// `text` as a TOML basic string would spell it: [`invisible`] characters
/// as `\uXXXX` (`\UXXXXXXXX` beyond the basic plane), quotes and
/// backslashes escaped, the rest as it is. Also how text from a data file
/// (a channel code) is shown.
///
/// ```
/// use bumpsim_core::names::escaped;
/// assert_eq!(escaped("red\u{1b}[31m \"x\""), r#"red\u001B[31m \"x\""#);
/// ```
pub fn escaped(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '"' | '\\' => format!("\\{c}"),
            c if invisible(c) && (c as u32) < 0x10000 => format!("\\u{:04X}", c as u32),
            c if invisible(c) => format!("\\U{:08X}", c as u32),
            c => c.to_string(),
        })
        .collect()
}

/// `text` as it may be printed to a terminal: each [`invisible`]
/// character (escape, bell, direction marks...) spelled as [`escaped`]
/// spells it (`\u001B`), the rest as it is, so that a name read from a
/// file cannot send escape sequences to the user's terminal. Line breaks
/// are kept by [`printable_lines`].
///
/// ```
/// use bumpsim_core::names::printable;
/// assert_eq!(printable("a\u{7}b\u{1b}[31m \"x\""), r#"a\u0007b\u001B[31m "x""#);
/// ```
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(invisible) {
        return std::borrow::Cow::Borrowed(text);
    }
    let shown = text
        .chars()
        .map(|c| match c {
            c if invisible(c) => escaped(&c.to_string()),
            c => c.to_string(),
        })
        .collect();
    std::borrow::Cow::Owned(shown)
}

/// A whole message or table for the terminal: each line through
/// [`printable`], the line breaks kept.
///
/// ```
/// use bumpsim_core::names::printable_lines;
/// assert_eq!(printable_lines("car a\u{1b}[2J\nnext\n"), "car a\\u001B[2J\nnext\n");
/// ```
pub fn printable_lines(text: &str) -> String {
    text.split('\n')
        .map(printable)
        .collect::<Vec<_>>()
        .join("\n")
}

/// Why a user's name cannot name a folder ([`check_folder_name`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("\"{}\": {reason} (it names a folder)", escaped(.name))]
pub struct FolderNameError {
    /// The name.
    pub name: String,
    /// What is wrong.
    pub reason: &'static str,
}

/// The one rule for a user's name that becomes a folder (the heads of a
/// synthetic pendulum series, the tests of a planar series): not empty, no
/// spaces around it, and only ASCII letters, digits, `-`, `_` and inner
/// spaces, so that it is the same folder on every file system, stays inside
/// its parent and reads back from the study file written beside it.
///
/// ```
/// use bumpsim_core::names::check_folder_name;
/// assert!(check_folder_name("FLAT 8").is_ok());
/// assert!(check_folder_name("../x").unwrap_err().to_string().contains("not a plain name"));
/// assert!(check_folder_name(" FLAT").unwrap_err().to_string().contains("spaces before or after it"));
/// assert!(check_folder_name("Flät").is_err());
/// ```
pub fn check_folder_name(name: &str) -> Result<(), FolderNameError> {
    let reason = if name.is_empty() {
        Some("an empty name")
    } else if name.contains(['/', '\\', '.']) {
        Some("not a plain name: a folder's name holds no '/', '\\' or '.'")
    } else if name.trim() != name {
        Some("spaces before or after it")
    } else if !name.chars().all(|c| file_safe(c) || c == ' ') {
        Some("letters, digits, '-', '_' and inner spaces only")
    } else {
        None
    };
    match reason {
        None => Ok(()),
        Some(reason) => Err(FolderNameError {
            name: name.to_string(),
            reason,
        }),
    }
}

/// Longest part of a file name made from a user's name, in characters
/// (file systems allow 255 bytes; prefixes and suffixes are added).
pub const FILE_NAME_CHARS: usize = 64;

/// Whether `c` is kept in a file name made from a user's name: an ASCII
/// letter or digit, `-` or `_` (no spaces, no dots, nothing a shell, a file
/// system or an FE solver's include line reads differently).
pub fn file_safe(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '-' || c == '_'
}

/// A file name from a signal, case, test or point name: [`file_safe`]
/// characters kept, anything else `_`, at most [`FILE_NAME_CHARS`]
/// characters. Different names can give the same file name; a writer of
/// several makes them unique ([`unique_name`]).
///
/// ```
/// use bumpsim_core::names::file_name;
/// assert_eq!(file_name("a/b c"), "a_b_c");
/// assert_eq!(file_name("FLAT-1_x"), "FLAT-1_x");
/// ```
pub fn file_name(name: &str) -> String {
    name.chars()
        .take(FILE_NAME_CHARS)
        .map(|c| if file_safe(c) { c } else { '_' })
        .collect()
}

/// Whether `name` is already a file name by [`file_name`]'s rule: not
/// empty, [`file_safe`] characters only, at most [`FILE_NAME_CHARS`].
pub fn is_file_name(name: &str) -> bool {
    !name.is_empty() && name.chars().count() <= FILE_NAME_CHARS && name.chars().all(file_safe)
}

/// `name` itself when `taken` does not hold it, otherwise `name` with `-2`,
/// `-3`, ... before its extension: two cases `a/b` and `a_b` get two files.
pub fn unique_name(name: &str, taken: impl Fn(&str) -> bool) -> String {
    if !taken(name) {
        return name.to_string();
    }
    let (stem, extension) = match name.rsplit_once('.') {
        Some((stem, extension)) => (stem, format!(".{extension}")),
        None => (name, String::new()),
    };
    (2..)
        .map(|n| format!("{stem}-{n}{extension}"))
        .find(|candidate| !taken(candidate))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_invisible_and_repeated_names_are_named() {
        let case = |names: &[&str]| check_names("[[case]]", names.iter().copied());
        assert_eq!(
            case(&["a", "  "]),
            Err(NameError::Empty {
                table: "[[case]]",
                number: 2
            })
        );
        let err = case(&["red\u{1b}[31m"]).unwrap_err().to_string();
        assert!(err.contains(r#"the name "red\u001B[31m" holds"#), "{err}");
        for hidden in [
            "x\u{202E}y",
            "FL\u{061C}AT",
            "FL\u{2028}AT",
            "soft\u{00AD}",
            "\u{3164}",
            "\u{2800}",
            "tag\u{E0041}",
            "emoji\u{FE0F}",
            "x\u{206A}",
        ] {
            assert!(
                matches!(case(&[hidden]), Err(NameError::Invisible { .. })),
                "{hidden:?}"
            );
        }
        assert!(
            case(&["tag\u{E0041}"])
                .unwrap_err()
                .to_string()
                .contains(r"tag\U000E0041")
        );
        let err = case(&["Flat", "angled", "flat "]).unwrap_err();
        assert_eq!(
            err,
            NameError::Repeated {
                table: "[[case]]",
                number: 3,
                name: "flat ".into(),
                first: "Flat".into(),
                how: " (they differ only in case, surrounding spaces or look-alike letters)",
            }
        );
        // the Kelvin sign lowercases to k: the message says why two names
        // that print alike are one
        let err = case(&["\u{212A}1", "K1"]).unwrap_err().to_string();
        assert!(err.contains("look-alike"), "{err}");
        let err = check_names("[[head]]", ["A", "A"]).unwrap_err().to_string();
        assert_eq!(
            err,
            "[[head]] number 2: name 'A' is already used by 'A'; give each its own name"
        );
        assert!(case(&["a \"quoted\" name", "ünïcode", "Ω-2 π"]).is_ok());
        let long = "x".repeat(MAX_NAME_BYTES + 1);
        assert!(matches!(
            case(&[&long]),
            Err(NameError::Long { bytes: 201, .. })
        ));
        assert!(case(&[&"é".repeat(MAX_NAME_BYTES / 2)]).is_ok());
        assert!(case(&[&"車".repeat(67)]).is_err());
    }

    #[test]
    fn file_names_are_short_and_safe_and_unique_names_count_up() {
        assert_eq!(file_name("a/b c"), "a_b_c");
        assert_eq!(file_name("..\\x.y"), "___x_y");
        assert_eq!(file_name("é 車"), "___");
        assert_eq!(file_name(&"x".repeat(5000)).len(), FILE_NAME_CHARS);
        assert!(is_file_name("FLAT-1_x") && is_file_name(&"x".repeat(FILE_NAME_CHARS)));
        for not in [
            "",
            "a b",
            "a.b",
            "..",
            "é",
            &"x".repeat(FILE_NAME_CHARS + 1),
        ] {
            assert!(!is_file_name(not), "{not:?}");
        }
        let taken = ["fit-a_b.svg", "fit-a_b-2.svg"];
        let is_taken = |n: &str| taken.contains(&n);
        assert_eq!(unique_name("fit-c.svg", is_taken), "fit-c.svg");
        assert_eq!(unique_name("fit-a_b.svg", is_taken), "fit-a_b-3.svg");
        assert_eq!(unique_name("README", |n| n == "README"), "README-2");
    }
}
