//! Case names: the rule every study (centre-line and planar) applies.
//!
//! A case's name names its results, plots, report files and `--case`
//! selections, so each must be non-empty, printable (no control or
//! invisible characters, which would reach the terminal and the file
//! names) and differ from the others, ignoring case and surrounding spaces
//! as file names on some systems do.

/// Why a list of case names cannot be used (numbers count `[[case]]`
/// tables from 1).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CaseNameError {
    /// The name is empty or only spaces.
    #[error("[[case]] number {number}: an empty name")]
    Empty {
        /// The case's number.
        number: usize,
    },
    /// The name holds control or invisible characters.
    #[error(
        "[[case]] number {number}: the name \"{escaped}\" holds control or invisible characters (tab, escape, direction overrides, zero-width spaces): they would reach the terminal and the file names; use printable text"
    )]
    Invisible {
        /// The case's number.
        number: usize,
        /// The name as a TOML basic string spells it (`\u001B` for escape).
        escaped: String,
    },
    /// Two cases share a name.
    #[error(
        "[[case]] number {number}: name '{name}' is already used by case '{first}'; give each case its own name"
    )]
    Repeated {
        /// The later case's number.
        number: usize,
        /// Its name.
        name: String,
        /// The earlier case's name.
        first: String,
    },
}

/// Checks the case names of one study, in file order (see the module).
///
/// ```
/// use bumpsim_ident::study::{CaseNameError, check_case_names};
/// assert!(check_case_names(["flat", "angled"]).is_ok());
/// assert!(matches!(
///     check_case_names(["flat", " Flat"]),
///     Err(CaseNameError::Repeated { number: 2, .. })
/// ));
/// ```
pub fn check_case_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<(), CaseNameError> {
    let key = |name: &str| name.trim().to_lowercase();
    let mut seen: Vec<&str> = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        let number = i + 1;
        if key(name).is_empty() {
            return Err(CaseNameError::Empty { number });
        }
        if name.chars().any(invisible) {
            let escaped = toml_escaped(name);
            return Err(CaseNameError::Invisible { number, escaped });
        }
        if let Some(first) = seen.iter().find(|s| key(s) == key(name)) {
            return Err(CaseNameError::Repeated {
                number,
                name: name.to_string(),
                first: first.to_string(),
            });
        }
        seen.push(name);
    }
    Ok(())
}

/// A character that prints nothing a reader sees, or changes how the rest
/// prints: controls (tab, escape, ...), direction overrides and isolates,
/// zero-width spaces and joiners, word joiner, byte-order mark.
fn invisible(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{200B}'..='\u{200F}'
                | '\u{202A}'..='\u{202E}'
                | '\u{2060}'..='\u{2064}'
                | '\u{2066}'..='\u{2069}'
                | '\u{FEFF}'
        )
}

/// `text` as a TOML basic string would spell it: invisible characters as
/// `\uXXXX`, quotes and backslashes escaped, the rest as it is.
fn toml_escaped(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '"' | '\\' => format!("\\{c}"),
            c if invisible(c) => format!("\\u{:04X}", c as u32),
            c => c.to_string(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_invisible_and_repeated_names_are_named() {
        assert_eq!(
            check_case_names(["a", "  "]),
            Err(CaseNameError::Empty { number: 2 })
        );
        let err = check_case_names(["red\u{1b}[31m"]).unwrap_err();
        assert!(
            err.to_string()
                .contains(r#"the name "red\u001B[31m" holds"#),
            "{err}"
        );
        let err = check_case_names(["x\u{202E}y"]).unwrap_err();
        assert!(err.to_string().contains(r"x\u202Ey"), "{err}");
        assert_eq!(
            check_case_names(["Flat", "angled", "flat "]),
            Err(CaseNameError::Repeated {
                number: 3,
                name: "flat ".into(),
                first: "Flat".into()
            })
        );
        assert!(check_case_names(["a \"quoted\" name", "ünïcode"]).is_ok());
    }
}
