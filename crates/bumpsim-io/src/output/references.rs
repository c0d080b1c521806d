//! The inputs an input file names: a study names its tests and its start
//! car, a series its car and bumpers, a pipeline its tests. They are inputs
//! as much as the file itself, and are registered with it, before any
//! output is opened ([`Outputs::input_with_references`]).

use super::guard::Outputs;
use std::path::Path;

/// Keys whose string values name input files in bumpsim's TOML formats
/// (studies, planar studies, series, pipelines); relative to the file.
pub const INPUT_KEYS: [&str; 6] = ["path", "planar", "planar_car", "start", "car", "bumper"];

/// How deep named files are followed (a study names a car, which names no more).
const DEPTH: usize = 3;

/// Largest TOML file whose references are followed (a larger file is no
/// bumpsim input; its reader refuses it).
const MAX_TOML_BYTES: u64 = 16 << 20;

impl Outputs {
    /// Registers `path` as an input and, for a TOML file, every existing
    /// file its [`INPUT_KEYS`] name (relative to its folder), and theirs in
    /// turn, so that an output cannot replace a file the command reads
    /// through another one (`identify study.toml --car start.toml`).
    pub fn input_with_references(&mut self, path: &Path) {
        self.input(path);
        self.references(path, DEPTH);
    }

    fn references(&mut self, path: &Path, depth: usize) {
        let Some(table) = toml_table(path).filter(|_| depth > 0) else {
            return;
        };
        let base = path.parent().unwrap_or(Path::new(""));
        let mut named = Vec::new();
        collect(&toml::Value::Table(table), None, &mut named);
        for name in named.iter().filter(|n| !n.trim().is_empty()) {
            let referenced = base.join(name);
            if std::fs::symlink_metadata(&referenced).is_ok() {
                self.input(&referenced);
                self.references(&referenced, depth - 1);
            }
        }
    }
}

/// The file as a TOML table, if it is a small regular `.toml` file.
fn toml_table(path: &Path) -> Option<toml::Table> {
    let toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let meta = std::fs::metadata(path).ok()?;
    if !toml || !meta.is_file() || meta.len() > MAX_TOML_BYTES {
        return None;
    }
    std::fs::read_to_string(path).ok()?.parse().ok()
}

/// The string values under [`INPUT_KEYS`], anywhere in the tree.
fn collect(value: &toml::Value, key: Option<&str>, named: &mut Vec<String>) {
    match value {
        toml::Value::String(s) if key.is_some_and(|k| INPUT_KEYS.contains(&k)) => {
            named.push(s.clone())
        }
        toml::Value::Table(t) => t.iter().for_each(|(k, v)| collect(v, Some(k), named)),
        toml::Value::Array(a) => a.iter().for_each(|v| collect(v, key, named)),
        _ => {}
    }
}
