//! Deck templates: any text file with `{{name}}` placeholders (spaces inside
//! the braces allowed). A name is a factor, a derived quantity or `run`
//! (the point's run number). Values are written in Rust's shortest
//! round-trip form (`0.0015`, `250000`), which every solver reads.
//!
//! ```
//! use bumpsim_campaign::template::Template;
//! use std::path::Path;
//! let t = Template::parse("*MASS\n{{ m2 }}\n", Path::new("deck.inp")).unwrap();
//! assert_eq!(t.render(&|_| Some(80.5)), "*MASS\n80.5\n");
//! assert!(t.check(&["k1".to_string()]).unwrap_err().to_string().contains("deck.inp:2"));
//! ```

use crate::error::{CampaignError, Result, read_error};
use std::path::{Path, PathBuf};

/// A parsed template: literal text and placeholders.
#[derive(Debug, Clone, PartialEq)]
pub struct Template {
    path: PathBuf,
    parts: Vec<Part>,
}

#[derive(Debug, Clone, PartialEq)]
enum Part {
    Text(String),
    /// A placeholder: name and 1-based line.
    Slot(String, usize),
}

impl Template {
    /// Reads a template file.
    pub fn read(path: &Path) -> Result<Template> {
        let text = std::fs::read_to_string(path).map_err(|e| read_error(path, e))?;
        Template::parse(&text, path)
    }

    /// Parses template text; `path` is used in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Template> {
        let mut parts = Vec::new();
        let mut rest = text;
        let mut line = 1;
        while let Some(start) = rest.find("{{") {
            let (before, after) = rest.split_at(start);
            line += before.matches('\n').count();
            parts.push(Part::Text(before.to_string()));
            let end = after.find("}}").ok_or_else(|| CampaignError::Invalid {
                path: path.into(),
                key: format!("line {line}"),
                message: "'{{' without a closing '}}'".into(),
            })?;
            let name = after[2..end].trim();
            if !crate::expr::is_name(name) {
                return Err(CampaignError::Invalid {
                    path: path.into(),
                    key: format!("line {line}"),
                    message: format!("placeholder {{{{{name}}}}}: expected a plain name"),
                });
            }
            parts.push(Part::Slot(name.to_string(), line));
            rest = &after[end + 2..];
        }
        parts.push(Part::Text(rest.to_string()));
        Ok(Template {
            path: path.into(),
            parts,
        })
    }

    /// The placeholder names, each once, in order.
    pub fn names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for part in &self.parts {
            if let Part::Slot(n, _) = part
                && !names.contains(&n.as_str())
            {
                names.push(n);
            }
        }
        names
    }

    /// Checks that every placeholder is one of `known` (or `run`); the
    /// error names the template file and line.
    pub fn check(&self, known: &[String]) -> Result<()> {
        for part in &self.parts {
            if let Part::Slot(name, line) = part
                && name != "run"
                && !known.iter().any(|k| k == name)
            {
                return Err(CampaignError::Placeholder {
                    path: self.path.clone(),
                    line: *line,
                    name: name.clone(),
                    known: known.join(", "),
                });
            }
        }
        Ok(())
    }

    /// Renders with `value` for each placeholder (checked before with
    /// [`Template::check`]; a name without a value renders as `nan`, which
    /// no solver accepts silently).
    pub fn render(&self, value: &dyn Fn(&str) -> Option<f64>) -> String {
        let mut out = String::new();
        for part in &self.parts {
            match part {
                Part::Text(t) => out.push_str(t),
                // the run number is a count: written as an integer
                Part::Slot(name, _) if name == "run" => {
                    out.push_str(&value(name).map_or("nan".into(), |v| format!("{v:.0}")))
                }
                Part::Slot(name, _) => out.push_str(&number(value(name).unwrap_or(f64::NAN))),
            }
        }
        out
    }
}

/// A value as a deck number: the shortest digits that read back exactly,
/// always with a decimal point (`400000.0`, `0.0015`), in exponent form
/// when the plain form would be long (`1.0e-20`, `2.5e300`): CalculiX and
/// Abaqus read an entry without a point as an integer (a degree of freedom
/// on `*SPRING`, for example).
pub fn number(value: f64) -> String {
    let plain = value.to_string();
    if !value.is_finite() {
        return plain;
    }
    let text = match plain.len() <= 16 {
        true => plain,
        false => format!("{value:e}"),
    };
    if text.contains('.') {
        return text;
    }
    match text.split_once('e') {
        Some((mantissa, exponent)) => format!("{mantissa}.0e{exponent}"),
        None => format!("{text}.0"),
    }
}

/// An LS-DYNA `*PARAMETER` include: one `R name value` card per value (for
/// decks that use `&name` parameters instead of placeholders).
pub fn lsdyna_parameters(values: &[(String, f64)]) -> String {
    let mut text = String::from(
        "*KEYWORD\n$ written by bumpsim campaign: the point's factors and derived quantities\n*PARAMETER\n",
    );
    for (name, value) in values {
        text += &format!("R {name:<9}{value:>10}\n", value = short(*value));
    }
    text + "*END\n"
}

/// A value in at most 10 characters (the `*PARAMETER` field width).
fn short(value: f64) -> String {
    let plain = number(value);
    match plain.len() <= 10 {
        true => plain,
        false => format!("{value:.3e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_lines_and_errors() {
        let t = Template::parse("a\n{{x}} {{ y }}\n{{x}}{{run}}", Path::new("t")).unwrap();
        assert_eq!(t.names(), ["x", "y", "run"]);
        let v = |n: &str| Some(if n == "x" { 1.5 } else { 2.0 });
        assert_eq!(t.render(&v), "a\n1.5 2.0\n1.52");
        assert_eq!(
            (
                number(4e5),
                number(1e-7),
                number(-2.5),
                number(1e-20),
                number(2.5e300)
            ),
            (
                "400000.0".into(),
                "0.0000001".into(),
                "-2.5".into(),
                "1.0e-20".into(),
                "2.5e300".into()
            )
        );
        let err = t.check(&["x".into()]).unwrap_err().to_string();
        assert!(
            err.starts_with("t:2: placeholder {{y}} has no factor"),
            "{err}"
        );
        assert!(Template::parse("{{x", Path::new("t")).is_err());
        assert!(Template::parse("{{x y}}", Path::new("t")).is_err());
    }

    #[test]
    fn parameter_cards_fit_their_fields() {
        let text = lsdyna_parameters(&[("t_rail".into(), 1.5), ("e".into(), 2.1e11 + 0.123)]);
        assert!(text.contains("R t_rail          1.5\n"), "{text}");
        assert!(text.contains("2.100e11"), "{text}");
    }
}
