//! Which car model a file is for (issue 46): the registry of model kinds and
//! the one place that decides a file's kind, so that no front end reads a
//! file's contents to choose a model.
//!
//! A file declares its kind with a top-level key, `kind = "chain"`,
//! `kind = "planar"` or `kind = "links"` (TOML; `"kind": "planar"` in JSON). Files written
//! before the key existed keep working: without it, [`ModelKind::of`] falls
//! back to the legacy detection, which lives here and nowhere else:
//!
//! | role | planar when (legacy) |
//! |---|---|
//! | [`Role::Study`] | a `[model]` table with a `planar` key (the start car) |
//! | [`Role::Car`] | a `[body]` table (the 1-D car file has none) |
//! | [`Role::Series`] | a `planar_car` key (a `synth` series) |
//! | [`Role::Result`] | JSON whose `result.car` has a `body` (`identify --json` of a planar study) |
//!
//!
//! A car file with `[[links]]` or `[front]` (the chain with nonlinear links,
//! [`crate::link_car`]) is [`ModelKind::Links`] without a key and also with
//! `kind = "chain"`, which such files declared before `links` existed.
//!
//! and the chain otherwise — also when the file cannot be read or parsed:
//! the chain's reader then reports what is wrong, as before the registry.
//!
//! Adding a model: a variant here, its name in [`ModelKind::NAMES`], and (only
//! if files without the key must be told apart) a legacy rule; see
//! docs/architecture.md.

use std::path::Path;

/// The car models bumpsim has (the registry).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelKind {
    /// The 1-D chain of masses, springs and dampers (bumpsim-ident,
    /// bumpsim-impact).
    Chain,
    /// The planar car: body with yaw, two side chains, segmented bumper
    /// beam, tyres (bumpsim-planar).
    Planar,
    /// The chain with nonlinear links: loading curves, unloading rules,
    /// a front crush zone (bumpsim_core::chain, [`crate::link_car`]; run by
    /// the engine, bumpsim-engine).
    Links,
}

/// What a file is to the command that reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// An identification study (`identify`, `predict`).
    Study,
    /// A car file (`impact`, `predict`), or a chain identification's JSON.
    Car,
    /// A synthetic test series (`synth`).
    Series,
    /// An identification's JSON (`identify --json`).
    Result,
}

/// A file whose kind cannot be told.
#[derive(Debug, thiserror::Error)]
pub enum KindError {
    /// The file cannot be read.
    #[error(transparent)]
    Read(#[from] std::io::Error),
    /// A car file beyond its size limit, refused before it is parsed.
    #[error(transparent)]
    TooLarge(#[from] bumpsim_core::files::ReadError),
    /// A device, pipe or socket (a FIFO given as a study blocked for ever
    /// when read): refused by name before it is opened.
    #[error(transparent)]
    NotAFile(bumpsim_core::files::ReadError),
    /// The declared kind is not one bumpsim has.
    #[error("{path}: kind = {value:?} is not a model bumpsim has (known: {known})")]
    Unknown {
        /// The file.
        path: String,
        /// The declared value.
        value: String,
        /// The known kinds, comma-separated.
        known: String,
    },
}

/// A declared kind that is not in the registry (its value).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("kind = {0:?} is not a model bumpsim has")]
pub struct UnknownKind(pub String);

impl ModelKind {
    /// Every kind with the name a file declares.
    pub const NAMES: &'static [(ModelKind, &'static str)] = &[
        (ModelKind::Chain, "chain"),
        (ModelKind::Planar, "planar"),
        (ModelKind::Links, "links"),
    ];

    /// The name a file declares (`kind = "..."`).
    pub fn name(self) -> &'static str {
        Self::NAMES
            .iter()
            .find(|(kind, _)| *kind == self)
            .map_or("chain", |(_, name)| name)
    }

    /// The kind of the file at `path` in its `role`: the declared one, else
    /// the legacy detection (see the module doc). Fails only when the file
    /// cannot be read, is a device, pipe or socket (never opened),
    /// declares an unknown kind or is a car file (TOML) beyond
    /// `bumpsim_core::files::MAX_CAR_BYTES`.
    pub fn of(path: &Path, role: Role) -> Result<ModelKind, KindError> {
        refuse_stream(path)?;
        let json = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"));
        if role == Role::Car && !json {
            // before its text is parsed (twice: here and by the model's reader)
            bumpsim_core::files::check_car_size(path)?;
        }
        let text = std::fs::read_to_string(path)?;
        Self::of_text(&text, role).map_err(|UnknownKind(value)| KindError::Unknown {
            path: path.display().to_string(),
            value,
            known: Self::NAMES
                .iter()
                .map(|(_, n)| *n)
                .collect::<Vec<_>>()
                .join(", "),
        })
    }

    /// [`ModelKind::of`] on the text of a file that may be unreadable: an
    /// unreadable file is the chain's (its reader says what is wrong).
    pub fn of_path(path: &Path, role: Role) -> Result<ModelKind, KindError> {
        match Self::of(path, role) {
            Err(KindError::Read(_)) => Ok(ModelKind::Chain),
            other => other,
        }
    }

    /// The kind of a file's text; `Err` holds an unknown declared value.
    pub fn of_text(text: &str, role: Role) -> Result<ModelKind, UnknownKind> {
        let (declared, planar) = match role {
            Role::Result => {
                let value = serde_json::from_str::<serde_json::Value>(text).ok();
                let declared = value
                    .as_ref()
                    .and_then(|v| v.get("kind"))
                    .and_then(|k| k.as_str())
                    .map(str::to_string);
                let planar = value.is_some_and(|v| v["result"]["car"]["body"].is_object());
                (declared, planar)
            }
            _ => {
                let table = toml::from_str::<toml::Table>(text).ok();
                if table.is_none() {
                    return Self::known(recovered(text, role));
                }
                let declared = table
                    .as_ref()
                    .and_then(|t| t.get("kind"))
                    .and_then(|k| k.as_str())
                    .map(str::to_string);
                let planar = table.as_ref().is_some_and(|t| legacy_planar(t, role));
                if table.is_some_and(|t| legacy_links(&t, role))
                    && declared.as_deref().is_none_or(|d| d == "chain")
                {
                    return Ok(ModelKind::Links);
                }
                (declared, planar)
            }
        };
        Self::known((declared, planar))
    }

    /// The kind a file declares, else the legacy detection's.
    fn known((declared, planar): (Option<String>, bool)) -> Result<ModelKind, UnknownKind> {
        match declared {
            Some(value) => Self::NAMES
                .iter()
                .find(|(_, name)| *name == value)
                .map(|(kind, _)| *kind)
                .ok_or(UnknownKind(value)),
            None if planar => Ok(ModelKind::Planar),
            None => Ok(ModelKind::Chain),
        }
    }
}

/// Refuses a device, pipe or socket by name without opening it (opening a
/// FIFO without a writer blocks); a folder passes, for its reader to name.
fn refuse_stream(path: &Path) -> Result<(), KindError> {
    match bumpsim_core::files::not_a_file(path) {
        Ok(Some(kind)) if kind != "a folder" => Err(KindError::NotAFile(
            bumpsim_core::files::ReadError::NotAFile {
                path: path.into(),
                kind,
            },
        )),
        _ => Ok(()),
    }
}

/// The legacy detection of a car file with nonlinear links written before
/// `kind = "links"` existed: `[[links]]` or `[front]` ([`crate::car::has_links`]),
/// with `kind = "chain"` or no key.
fn legacy_links(table: &toml::Table, role: Role) -> bool {
    role == Role::Car && crate::car::has_links(table)
}

/// The declared kind and the legacy planar clue of a text that is no
/// valid TOML (a syntax error, an integer beyond 64 bits), read with the
/// parser's recovery: the reader of the file's model then names the error
/// (a planar study with `starts = 99999999999999999999` was read as a
/// chain study and refused for its "unknown field `forces`").
fn recovered(text: &str, role: Role) -> (Option<String>, bool) {
    use toml::de::{DeTable, DeValue};
    let (table, _) = DeTable::parse_recoverable(text);
    let table = table.into_inner();
    fn get<'i>(t: &DeTable<'i>, key: &str) -> Option<DeValue<'i>> {
        t.iter()
            .find(|(k, _)| k.get_ref().as_ref() == key)
            .map(|(_, v)| v.get_ref().clone())
    }
    let declared = match get(&table, "kind") {
        Some(DeValue::String(kind)) => Some(kind.into_owned()),
        _ => None,
    };
    let planar = match role {
        Role::Study => {
            matches!(get(&table, "model"), Some(DeValue::Table(m)) if get(&m, "planar").is_some())
        }
        Role::Car => matches!(get(&table, "body"), Some(DeValue::Table(_))),
        Role::Series => get(&table, "planar_car").is_some(),
        Role::Result => false,
    };
    (declared, planar)
}

/// The legacy detection of a planar file without a `kind` key (the rules of
/// the module doc's table; the only place they live).
fn legacy_planar(table: &toml::Table, role: Role) -> bool {
    match role {
        Role::Study => table
            .get("model")
            .and_then(|m| m.as_table())
            .is_some_and(|m| m.contains_key("planar")),
        Role::Car => table.get("body").is_some_and(toml::Value::is_table),
        Role::Series => table.contains_key("planar_car"),
        Role::Result => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_by_name_without_being_opened() {
        let dir = std::env::temp_dir().join(format!("bumpsim-kind-fifo-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("study.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        // opening it would block this test for ever; a refusal returns
        for role in [Role::Study, Role::Car, Role::Series, Role::Result] {
            let e = ModelKind::of(&fifo, role).unwrap_err();
            assert!(matches!(e, KindError::NotAFile(_)), "{e}");
            let text = e.to_string();
            assert!(
                text.contains("study.toml: is a device, pipe or socket"),
                "{text}"
            );
            assert!(ModelKind::of_path(&fifo, role).is_err(), "{role:?}");
        }
        let e = ModelKind::of(Path::new("/dev/zero"), Role::Study).unwrap_err();
        assert!(matches!(e, KindError::NotAFile(_)), "{e}");
        // a folder is its reader's to name, as before
        assert_eq!(
            ModelKind::of_path(&dir, Role::Study).unwrap(),
            ModelKind::Chain
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn legacy_files_are_told_apart_by_their_tables() {
        let study = |t| ModelKind::of_text(t, Role::Study).unwrap();
        assert_eq!(study("[model]\nplanar = \"start.toml\""), ModelKind::Planar);
        assert_eq!(study("[model]\ndof = 3"), ModelKind::Chain);
        assert_eq!(study("not toml ["), ModelKind::Chain);
        // no valid TOML, yet the reader of its model names the error
        let big = "[model]\nplanar = \"s.toml\"\nstarts = 99999999999999999999";
        assert_eq!(study(big), ModelKind::Planar);
        assert_eq!(
            study("kind = \"planar\"\n[model]\nx = ["),
            ModelKind::Planar
        );
        assert_eq!(study("[model]\ndof = 3\nx = ["), ModelKind::Chain);
        let series = |t| ModelKind::of_text(t, Role::Series).unwrap();
        assert_eq!(series("planar_car = \"car.toml\""), ModelKind::Planar);
        assert_eq!(
            series("car = \"car.toml\"\n[[head]]\nname = \"A\""),
            ModelKind::Chain
        );
        let car = |t| ModelKind::of_text(t, Role::Car).unwrap();
        assert_eq!(car("[body]\nmass = 1200.0"), ModelKind::Planar);
        assert_eq!(car("body = 3\nmasses = [1.0]"), ModelKind::Chain);
        let result = |t| ModelKind::of_text(t, Role::Result).unwrap();
        assert_eq!(
            result(r#"{"result": {"car": {"body": {}}}}"#),
            ModelKind::Planar
        );
        assert_eq!(result(r#"{"result": {"model": {}}}"#), ModelKind::Chain);
    }

    #[test]
    fn a_car_with_links_is_the_links_chain_declared_or_not() {
        let car = |t: &str| ModelKind::of_text(t, Role::Car).unwrap();
        let links = "masses = [1.0, 2.0]\n[[links]]\ncurve = \"linear\"";
        assert_eq!(car(links), ModelKind::Links);
        assert_eq!(car(&format!("kind = \"chain\"\n{links}")), ModelKind::Links);
        assert_eq!(car(&format!("kind = \"links\"\n{links}")), ModelKind::Links);
        assert_eq!(
            car("masses = [1.0]\n[front]\ncurve = \"linear\""),
            ModelKind::Links
        );
        assert_eq!(car("kind = \"links\"\nmasses = [1.0]"), ModelKind::Links);
        assert_eq!(
            car("masses = [1.0, 2.0]\nsprings = [3.0]"),
            ModelKind::Chain
        );
        let study = |t| ModelKind::of_text(t, Role::Study).unwrap();
        assert_eq!(study(links), ModelKind::Chain);
    }

    #[test]
    fn a_declared_kind_wins_and_an_unknown_one_is_refused() {
        let of = |t, r| ModelKind::of_text(t, r);
        assert_eq!(
            of("kind = \"planar\"\n[model]\ndof = 3", Role::Study),
            Ok(ModelKind::Planar)
        );
        assert_eq!(
            of("kind = \"chain\"\n[body]\nmass = 1.0", Role::Car),
            Ok(ModelKind::Chain)
        );
        assert_eq!(
            of(r#"{"kind": "planar"}"#, Role::Result),
            Ok(ModelKind::Planar)
        );
        assert_eq!(
            of("kind = \"tank\"", Role::Car),
            Err(UnknownKind("tank".to_string()))
        );
        for (kind, name) in ModelKind::NAMES {
            assert_eq!(kind.name(), *name);
        }
    }

    #[test]
    fn an_unreadable_file_is_left_to_the_chain_reader() {
        let missing = Path::new("/nonexistent/bumpsim/car.toml");
        assert!(matches!(
            ModelKind::of(missing, Role::Car),
            Err(KindError::Read(_))
        ));
        assert_eq!(
            ModelKind::of_path(missing, Role::Car).unwrap(),
            ModelKind::Chain
        );
    }
}
