//! The workspace's structure as docs/architecture.md states it, checked on
//! every test run so it cannot drift (issue 31):
//!
//! - every crate sits on a floor and depends only on crates of lower floors
//!   (nothing depends upward; `bumpsim-planar` does not use `bumpsim-ident`);
//! - no module circle within a crate (module A uses B and B uses A);
//! - no `Result<_, String>` in a library crate (typed errors);
//! - no source file over 800 lines;
//! - the facade re-exports every library crate;
//! - the CLI's normal build holds no bitmap stack (`image`, `png`, `jpeg-decoder`);
//! - models plug in (issue 46): no front end (CLI, Python) reads a file's
//!   contents to choose a model (`bumpsim_io::kind` does, once); the loop of
//!   an identification over model sizes exists once (`bumpsim_ident::sizes`)
//!   and runs for the engine's identify request alone; no front end runs
//!   an identification over sizes or a verdict itself (they make the
//!   engine's requests);
//!   no front end names the planar crate or depends on it (the ceiling went
//!   down to none as the commands became the engine's requests: the
//!   command line's, then the Python module's).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The floors of docs/architecture.md: a crate may depend on crates of
/// lower floors only.
const FLOORS: &[(&str, usize)] = &[
    ("bumpsim-core", 0),
    ("bumpsim-peers", 0),
    ("bumpsim-io", 1),
    ("bumpsim-export", 1),
    ("bumpsim-doe", 2),
    ("bumpsim-signal", 2),
    ("bumpsim-estimate", 3),
    ("bumpsim-ident", 4),
    ("bumpsim-impact", 4),
    ("bumpsim-planar", 5),
    ("bumpsim-fe", 5),
    ("bumpsim-verdict", 6),
    ("bumpsim-report", 7),
    ("bumpsim-campaign", 8),
    ("bumpsim-engine", 8),
    ("bumpsim-view", 8),
    ("bumpsim-cli", 9),
    ("bumpsim-py", 9),
    ("bumpsim", 9),
];

/// Crates that are not libraries for users: the binaries and test support.
const NOT_LIBRARIES: &[&str] = &["bumpsim-cli", "bumpsim-py", "bumpsim-peers"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn crates() -> Vec<(String, PathBuf)> {
    let mut out: Vec<(String, PathBuf)> = std::fs::read_dir(root().join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").is_file())
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), p))
        .collect();
    out.sort();
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The source without `//` comments (line and doc comments).
fn code(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The `bumpsim-*` names in a manifest's `[dependencies]` (not dev or build).
fn dependencies(manifest: &Path) -> BTreeSet<String> {
    let text = std::fs::read_to_string(manifest).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    table
        .get("dependencies")
        .and_then(|d| d.as_table())
        .map(|d| {
            d.keys()
                .filter(|k| k.starts_with("bumpsim"))
                .cloned()
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn every_crate_depends_only_on_lower_floors() {
    let floor: BTreeMap<&str, usize> = FLOORS.iter().copied().collect();
    let mut manifests: Vec<(String, PathBuf)> = crates()
        .into_iter()
        .map(|(name, dir)| (name, dir.join("Cargo.toml")))
        .collect();
    manifests.push(("bumpsim".into(), root().join("Cargo.toml")));
    let mut wrong = Vec::new();
    for (name, manifest) in &manifests {
        let Some(&mine) = floor.get(name.as_str()) else {
            wrong.push(format!("{name} has no floor in docs/architecture.md"));
            continue;
        };
        for dep in dependencies(manifest) {
            match floor.get(dep.as_str()) {
                Some(&theirs) if theirs < mine => {}
                _ => wrong.push(format!("{name} (floor {mine}) depends on {dep}")),
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    assert!(
        !dependencies(&root().join("crates/bumpsim-planar/Cargo.toml")).contains("bumpsim-ident")
    );
}

/// The top-level modules of a crate's `src` (files and folders) and, per
/// module, the sibling modules its code names through `crate::`.
fn module_uses(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let module = |p: &Path| {
        let rel = p.strip_prefix(src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        first.trim_end_matches(".rs").to_string()
    };
    let names: BTreeSet<String> = files
        .iter()
        .map(|p| module(p))
        .filter(|m| m != "lib" && m != "main")
        .collect();
    let mut uses: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in &files {
        let me = module(file);
        if !names.contains(&me) {
            continue;
        }
        let text = code(file);
        for (at, _) in text.match_indices("crate::") {
            let rest = &text[at + 7..];
            let used: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if used != me && names.contains(&used) {
                uses.entry(me.clone()).or_default().insert(used);
            }
        }
    }
    uses
}

/// A circle through `from` in `uses`, if any.
fn circle(uses: &BTreeMap<String, BTreeSet<String>>, from: &str) -> Option<Vec<String>> {
    let mut stack = vec![(from.to_string(), vec![from.to_string()])];
    let mut seen = BTreeSet::new();
    while let Some((at, path)) = stack.pop() {
        for next in uses.get(&at).into_iter().flatten() {
            if next == from {
                return Some([path.clone(), vec![from.to_string()]].concat());
            }
            if seen.insert(next.clone()) {
                stack.push((next.clone(), [path.clone(), vec![next.clone()]].concat()));
            }
        }
    }
    None
}

/// Within a folder module (`src/a/b/`): for each child, the sibling
/// children its code names through `super::x` or `crate::a::b::x`.
fn sibling_uses(src: &Path, folder: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let rel = folder.strip_prefix(src).unwrap();
    let path: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    let prefix = format!("crate::{}::", path.join("::"));
    let children: BTreeMap<String, PathBuf> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir() || p.extension().is_some_and(|e| e == "rs"))
        .map(|p| (p.file_stem().unwrap().to_string_lossy().into_owned(), p))
        .filter(|(name, _)| name != "mod")
        .collect();
    let mut uses: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (child, path) in &children {
        let mut files = Vec::new();
        match path.is_dir() {
            true => rust_files(path, &mut files),
            false => files.push(path.clone()),
        }
        // a grandchild's `super::` is its own parent, so only the child's
        // own file (or its folder's mod.rs) counts for `super::`
        let own = |f: &PathBuf| f == path || f == &path.join("mod.rs");
        for file in &files {
            let text = code(file);
            let mut named = |at: usize| {
                let used: String = text[at..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if &used != child && children.contains_key(&used) {
                    uses.entry(child.clone()).or_default().insert(used);
                }
            };
            for (at, m) in text.match_indices(prefix.as_str()) {
                named(at + m.len());
            }
            if own(file) {
                for (at, m) in text.match_indices("super::") {
                    named(at + m.len());
                }
            }
        }
    }
    uses
}

fn folders(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.push(path.clone());
            folders(&path, out);
        }
    }
}

#[test]
fn no_crate_has_a_module_circle() {
    let mut circles = Vec::new();
    for (name, dir) in crates() {
        let src = dir.join("src");
        let mut graphs = vec![("".to_string(), module_uses(&src))];
        let mut nested = Vec::new();
        folders(&src, &mut nested);
        for folder in nested {
            let label = folder.strip_prefix(&src).unwrap().display().to_string();
            graphs.push((label, sibling_uses(&src, &folder)));
        }
        for (label, uses) in graphs {
            if let Some(c) = uses.keys().find_map(|m| circle(&uses, m)) {
                circles.push(format!("{name} {label}: {}", c.join(" -> ")));
            }
        }
    }
    assert!(circles.is_empty(), "{circles:#?}");
}

/// Each `Result<T, String>` in `code`, whatever generics `T` nests
/// (`Result<Vec<f64>, String>`, `Result<Option<(u8, f64)>, String>`): the
/// type up to its matching `>`, with `String` as its last top-level argument.
fn string_results(code: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (at, m) in code.match_indices("Result<") {
        let body = &code[at + m.len()..];
        let (mut depth, mut last_comma, mut end) = (0usize, None, None);
        let mut previous = ' ';
        for (i, c) in body.char_indices() {
            match c {
                '<' | '(' | '[' => depth += 1,
                // `->` in a `Fn() -> T` argument closes nothing
                '>' if previous == '-' => {}
                '>' | ')' | ']' if depth == 0 => {
                    end = Some(i);
                    break;
                }
                '>' | ')' | ']' => depth -= 1,
                ',' if depth == 0 => last_comma = Some(i),
                ';' | '{' => break,
                _ => {}
            }
            previous = c;
        }
        let (Some(end), Some(comma)) = (end, last_comma) else {
            continue;
        };
        if body[comma + 1..end].trim() == "String" {
            found.push(format!("Result<{}", &body[..=end]));
        }
    }
    found
}

/// The pattern finds a `String` error behind nested generics, where
/// stopping at the first `>` saw `Result<Vec<f64>` and passed it.
#[test]
fn the_typed_error_check_sees_through_nested_generics() {
    let found = |code: &str| string_results(code).len();
    assert_eq!(found("fn a() -> Result<Vec<f64>, String> {"), 1);
    assert_eq!(found("fn a() -> Result<Option<Criterion>, String> {"), 1);
    assert_eq!(
        found("fn a() -> Result<HashMap<u8, Vec<(f64, u8)>>, String>;"),
        1
    );
    assert_eq!(
        found("fn a() -> Result<Box<dyn Fn(u8) -> u8>, String> {"),
        1
    );
    assert_eq!(found("fn a() -> Result<(), String> {"), 1);
    assert_eq!(found("fn a() -> Result<Vec<String>, MyError> {"), 0);
    assert_eq!(found("fn a() -> io::Result<String> {"), 0);
    assert_eq!(found("fn a() -> Result<Vec<f64>, Error<String>> {"), 0);
}

#[test]
fn library_crates_return_typed_errors() {
    let mut found = Vec::new();
    for (name, dir) in crates() {
        if NOT_LIBRARIES.contains(&name.as_str()) {
            continue;
        }
        let mut files = Vec::new();
        rust_files(&dir.join("src"), &mut files);
        for file in files {
            let flat: String = code(&file).split_whitespace().collect::<Vec<_>>().join(" ");
            for result in string_results(&flat) {
                found.push(format!("{}: {result}", file.display()));
            }
            if flat.contains("type Err = String") {
                found.push(format!("{}: type Err = String", file.display()));
            }
        }
    }
    assert!(found.is_empty(), "{found:#?}");
}

#[test]
fn no_source_file_exceeds_800_lines() {
    let mut files = Vec::new();
    rust_files(&root().join("crates"), &mut files);
    rust_files(&root().join("src"), &mut files);
    rust_files(&root().join("tests"), &mut files);
    rust_files(&root().join("examples"), &mut files);
    let long: Vec<String> = files
        .iter()
        .filter(|f| !f.components().any(|c| c.as_os_str() == "target"))
        .map(|f| (f, std::fs::read_to_string(f).unwrap().lines().count()))
        .filter(|(_, n)| *n > 800)
        .map(|(f, n)| format!("{}: {n} lines", f.display()))
        .collect();
    assert!(long.is_empty(), "{long:#?}");
}

#[test]
fn the_facade_re_exports_every_library_crate() {
    let facade = code(&root().join("src/lib.rs"));
    let missing: Vec<String> = crates()
        .into_iter()
        .map(|(name, _)| name)
        .filter(|name| !NOT_LIBRARIES.contains(&name.as_str()))
        .filter(|name| !facade.contains(&format!("pub use {} as ", name.replace('-', "_"))))
        .collect();
    assert!(
        missing.is_empty(),
        "not re-exported by src/lib.rs: {missing:?}"
    );
}

#[test]
fn the_cli_builds_no_bitmap_stack() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = std::process::Command::new(cargo)
        .args([
            "tree",
            "-p",
            "bumpsim-cli",
            "-e",
            "normal",
            "--prefix",
            "none",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("cargo tree runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let tree = String::from_utf8_lossy(&out.stdout);
    let heavy: Vec<&str> = tree
        .lines()
        .filter(|l| {
            let name = l.split_whitespace().next().unwrap_or("");
            ["image", "png", "jpeg-decoder"].contains(&name)
        })
        .collect();
    assert!(heavy.is_empty(), "{heavy:?}");
}

/// The front ends: the command line and the Python module.
const FRONT_ENDS: &[&str] = &["bumpsim-cli", "bumpsim-py"];

/// A front end's source files, comments left out.
fn front_end_code(name: &str) -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    rust_files(&root().join("crates").join(name).join("src"), &mut files);
    files.sort();
    files.into_iter().map(|f| (f.clone(), code(&f))).collect()
}

#[test]
fn no_front_end_sniffs_a_file_to_choose_a_model() {
    // what the legacy detection looks at; it lives in bumpsim_io::kind alone
    const SNIFFS: &[&str] = &[
        "is_planar",
        "[\"body\"]",
        "\"planar_car\"",
        "contains_key(\"planar\")",
        "from_str::<toml::Table>",
        "from_str::<toml::Value>",
        "get(\"body\")",
        "get(\"kind\")",
        "has_links",
        "contains_key(\"links\")",
        "contains(\"[body]\")",
        "contains(\"[[links]]\")",
        "contains(\"[front]\")",
        "contains(\"planar\")",
        "contains(\"kind",
    ];
    let mut found = Vec::new();
    for front in FRONT_ENDS {
        for (file, code) in front_end_code(front) {
            for sniff in SNIFFS {
                if code.contains(sniff) {
                    found.push(format!("{}: {sniff}", file.display()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "a front end reads a file to choose its model (use bumpsim_io::kind::ModelKind::of): {found:#?}"
    );
}

#[test]
fn the_identify_loop_over_model_sizes_exists_once() {
    // the loop continues each size from the last one: only it makes a Sweep
    let mut files = Vec::new();
    rust_files(&root().join("crates"), &mut files);
    rust_files(&root().join("src"), &mut files);
    let loops: Vec<String> = files
        .iter()
        .filter(|f| f.components().any(|c| c.as_os_str() == "src"))
        .filter(|f| !f.ends_with("bumpsim-ident/src/dofs.rs"))
        .filter(|f| code(f).contains("Sweep::new()"))
        .map(|f| f.display().to_string())
        .collect();
    let one = root().join("crates/bumpsim-ident/src/sizes.rs");
    assert_eq!(
        loops,
        vec![one.display().to_string()],
        "the identify loop over model sizes is bumpsim_ident::sizes::identify"
    );
    // and it runs for one request: the engine's identify (a chain study's
    // `IdentifyRequest`), which every front end makes
    let callers: Vec<String> = files
        .iter()
        .filter(|f| f.components().any(|c| c.as_os_str() == "src"))
        .filter(|f| !f.starts_with(root().join("crates/bumpsim-ident")))
        .filter(|f| code(f).contains("sizes::identify("))
        .map(|f| f.display().to_string())
        .collect();
    let request = root().join("crates/bumpsim-engine/src/identify.rs");
    assert_eq!(
        callers,
        vec![request.display().to_string()],
        "the loop over model sizes runs for the engine's identify request alone"
    );
}

#[test]
fn no_front_end_runs_an_identification_or_a_verdict_itself() {
    // what a loop over a study's model sizes, or a verdict's set-up, is
    // made of: a front end that names one runs the command itself instead
    // of making the engine's request (`bumpsim_engine::identify`,
    // `bumpsim_engine::verdict`)
    const RUNS: &[&str] = &[
        // a study identified over its sizes
        "sizes::identify(",
        "bumpsim_ident::sizes",
        "Sweep::",
        "dofs::table",
        ".retarget(",
        ".dofs()",
        "DofSpec",
        "Watch for",
        // a verdict set up and run
        "bumpsim_verdict::verdict(",
        "Setup::new(",
        "CarEnd::",
        "with_bumper(",
        "protocol::select",
        "select_in(",
        "target::search(",
        "probability::propagate(",
        "sensitivity::sensitivity(",
    ];
    let mut found = Vec::new();
    for front in FRONT_ENDS {
        for (file, code) in front_end_code(front) {
            for run in RUNS {
                if code.contains(run) {
                    found.push(format!("{}: {run}", file.display()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "a front end runs what the engine's request runs: {found:#?}"
    );
}

#[test]
fn the_front_ends_name_the_links_chain_at_most_once() {
    // the chain with nonlinear links plugs into the engine (bumpsim-engine's
    // registry): outside its own modules a front end names it on at most
    // one line, its registration
    const NAMES: &[&str] = &[
        "ModelKind::Links",
        "link_car",
        "LinkCar",
        "ChainCar::Links",
        "bumpsim_core::chain",
        "bumpsim_core::link",
        "engine::links",
    ];
    let mut over = Vec::new();
    for front in ["bumpsim-cli", "bumpsim-py"] {
        let lines: Vec<String> = front_end_code(front)
            .iter()
            .flat_map(|(file, code)| {
                code.lines()
                    .filter(|l| NAMES.iter().any(|n| l.contains(n)))
                    .map(|l| format!("{}: {}", file.display(), l.trim()))
                    .collect::<Vec<_>>()
            })
            .collect();
        if lines.len() > 1 {
            over.push(format!(
                "{front} names the links chain on {} lines: {lines:#?}",
                lines.len()
            ));
        }
    }
    assert!(over.is_empty(), "{over:#?}");
    // both front ends run the planar car through the engine alone
    for front in FRONT_ENDS {
        let manifest = root().join("crates").join(front).join("Cargo.toml");
        assert!(
            !dependencies(&manifest).contains("bumpsim-planar"),
            "{front} depends on bumpsim-planar: its commands are the engine's requests"
        );
    }
}

#[test]
fn the_front_ends_name_the_planar_crate_less_and_less() {
    // lines of code naming bumpsim_planar: none in either front end (the
    // ceiling was lowered as the commands became the engine's requests)
    const CEILING: &[(&str, usize)] = &[("bumpsim-cli", 0), ("bumpsim-py", 0)];
    let mut over = Vec::new();
    for &(front, ceiling) in CEILING {
        let lines: usize = front_end_code(front)
            .iter()
            .map(|(_, code)| {
                code.lines()
                    .filter(|l| l.contains("bumpsim_planar"))
                    .count()
            })
            .sum();
        if lines > ceiling {
            over.push(format!(
                "{front}: {lines} lines name bumpsim_planar, at most {ceiling}"
            ));
        }
    }
    assert!(over.is_empty(), "{over:#?}");
    // both front ends run the planar car through the engine alone
    for front in FRONT_ENDS {
        let manifest = root().join("crates").join(front).join("Cargo.toml");
        assert!(
            !dependencies(&manifest).contains("bumpsim-planar"),
            "{front} depends on bumpsim-planar: its commands are the engine's requests"
        );
    }
}
