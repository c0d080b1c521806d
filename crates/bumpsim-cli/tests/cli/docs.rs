//! The docs run (issue 35): every shell block of README.md and docs/*.md
//! marked runnable is run with this very binary as `bumpsim`, and what it
//! prints is compared with the docs, so the docs cannot drift from the tool.
//!
//! Markers (fence info strings; GitHub renders them as plain code):
//!
//! - ```` ```sh runnable ```` — commands, run by `bash -e -o pipefail` with
//!   stdout and stderr together; `runnable exit=2` expects that exit code;
//! - ```` ```text output ```` right after it — what the commands print: its
//!   lines in order, a line `...` standing for any number of lines; every
//!   figure equal to the printed one within 1 % (relative, or 1e-9
//!   absolute), every other character exactly;
//! - ```` ```toml file=PATH ```` (any language) — written to PATH before the
//!   blocks that follow run;
//! - ```` ```text contents=PATH ```` — what the file PATH holds after the
//!   blocks before it ran, compared like an output (`...` for elision);
//! - ```` ```sh runnable needs=ccx ```` — the block needs CalculiX: skipped
//!   with a message when `ccx` is absent, a failure under
//!   `BUMPSIM_REQUIRE_PEERS`.
//!
//! Each docs page runs in its own scratch folder (with `examples`, `docs`,
//! `tests` and `crates` linked to the repository's), blocks in page order,
//! so a page's later blocks see what its earlier blocks wrote under `out/`.

use crate::util::{root, scratch, text};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Figures of the docs and of the run agree within this share.
const TOLERANCE: f64 = 0.01;

#[derive(Debug)]
enum Block {
    Run {
        code: String,
        exit: i32,
        line: usize,
        needs_ccx: bool,
    },
    Output {
        text: String,
    },
    File {
        path: String,
        text: String,
    },
    Contents {
        path: String,
        text: String,
        line: usize,
    },
}

/// The marked blocks of a markdown page, in order.
fn blocks(markdown: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut lines = markdown.lines().enumerate();
    while let Some((number, line)) = lines.next() {
        let Some(info) = line.trim_start().strip_prefix("```") else {
            continue;
        };
        let body: Vec<&str> = lines
            .by_ref()
            .map(|(_, l)| l)
            .take_while(|l| !l.trim_start().starts_with("```"))
            .collect();
        let body = body.join("\n");
        let words: Vec<&str> = info.split_whitespace().collect();
        let word = |key: &str| words.iter().find_map(|w| w.strip_prefix(key));
        if let Some(path) = word("contents=") {
            out.push(Block::Contents {
                path: path.to_string(),
                text: body,
                line: number + 1,
            });
        } else if let Some(path) = word("file=") {
            out.push(Block::File {
                path: path.to_string(),
                text: body + "\n",
            });
        } else if words.contains(&"runnable") {
            let exit = word("exit=").map_or(0, |e| e.parse().expect("exit=N"));
            out.push(Block::Run {
                code: body,
                exit,
                line: number + 1,
                needs_ccx: word("needs=") == Some("ccx"),
            });
        } else if words == ["text", "output"] {
            out.push(Block::Output { text: body });
        }
    }
    out
}

/// A line split into its figures and the text between them.
fn figures(line: &str) -> (String, Vec<f64>) {
    let (mut skeleton, mut numbers) = (String::new(), Vec::new());
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let start = i;
        let signed = chars[i] == '-' && chars.get(i + 1).is_some_and(char::is_ascii_digit);
        if chars[i].is_ascii_digit() || signed {
            i += 1;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i + 1 < chars.len() && chars[i] == 'e' {
                let sign = usize::from(matches!(chars[i + 1], '-' | '+'));
                if chars.get(i + 1 + sign).is_some_and(char::is_ascii_digit) {
                    i += 1 + sign;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let number: String = chars[start..i].iter().collect();
            let number = number.trim_end_matches('.');
            if let Ok(value) = number.parse() {
                numbers.push(value);
                skeleton.push('#');
                i = start + number.chars().count();
                continue;
            }
        }
        skeleton.push(chars[start]);
        i = start + 1;
    }
    (skeleton, numbers)
}

fn same_line(expected: &str, actual: &str) -> bool {
    let (a, b) = (figures(expected.trim_end()), figures(actual.trim_end()));
    a.0 == b.0
        && a.1
            .iter()
            .zip(&b.1)
            .all(|(e, x)| (e - x).abs() <= TOLERANCE * e.abs() || (e - x).abs() <= 1e-9)
}

/// Whether `actual` is `expected` with `...` lines standing for any lines.
fn matches(expected: &[&str], actual: &[&str]) -> bool {
    match expected.split_first() {
        None => actual.is_empty(),
        Some((first, rest)) if first.trim() == "..." => {
            (0..=actual.len()).any(|skip| matches(rest, &actual[skip..]))
        }
        Some((first, rest)) => actual
            .split_first()
            .is_some_and(|(a, more)| same_line(first, a) && matches(rest, more)),
    }
}

/// The scratch folder of a page: the repository's inputs linked in.
fn workspace(page: &str) -> PathBuf {
    let dir = scratch(&format!("docs-{}", page.replace('/', "-")));
    for entry in ["examples", "docs", "tests", "crates"] {
        std::os::unix::fs::symlink(root().join(entry), dir.join(entry)).unwrap();
    }
    dir
}

fn run(dir: &Path, code: &str) -> (i32, String) {
    let bin = Path::new(env!("CARGO_BIN_EXE_bumpsim"));
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("bash")
        .args([
            "-e",
            "-o",
            "pipefail",
            "-c",
            &format!("{{\n{code}\n}} 2>&1"),
        ])
        .current_dir(dir)
        .env("PATH", path)
        .output()
        .unwrap();
    (out.status.code().unwrap_or(-1), text(&out.stdout))
}

/// Runs one page's marked blocks; the failures, each with its line.
fn check_page(page: &str) -> Vec<String> {
    let markdown = std::fs::read_to_string(root().join(page)).unwrap();
    let dir = workspace(page);
    let mut failures = Vec::new();
    let mut last: Option<(usize, String)> = None;
    for block in blocks(&markdown) {
        match block {
            Block::File { path, text } => {
                let file = dir.join(&path);
                std::fs::create_dir_all(file.parent().unwrap()).unwrap();
                std::fs::write(file, text).unwrap();
            }
            Block::Run {
                needs_ccx: true, ..
            } if !crate::export::ccx_available() => {
                eprintln!("{page}: skipped from here on: it runs CalculiX (ccx), not installed");
                break;
            }
            Block::Run {
                code, exit, line, ..
            } => {
                let (status, printed) = run(&dir, &code);
                if status != exit {
                    failures.push(format!(
                        "{page}:{line}: exit {status}, not {exit}:\n{printed}"
                    ));
                }
                last = Some((line, printed));
            }
            Block::Output { text } => {
                let Some((line, printed)) = last.take() else {
                    failures.push(format!("{page}: an output block with no command before it"));
                    continue;
                };
                let expected: Vec<&str> = text.lines().collect();
                let actual: Vec<&str> = printed.lines().collect();
                if !matches(&expected, &actual) {
                    failures.push(format!(
                        "{page}:{line}: the docs show\n{text}\n--- the command printed\n{printed}"
                    ));
                }
            }
            Block::Contents { path, text, line } => {
                let held = std::fs::read_to_string(dir.join(&path)).unwrap_or_default();
                let expected: Vec<&str> = text.lines().collect();
                if !matches(&expected, &held.lines().collect::<Vec<_>>()) {
                    failures.push(format!(
                        "{page}:{line}: the docs show {path} as\n{text}\n--- it holds\n{held}"
                    ));
                }
            }
        }
    }
    failures
}

/// Every page with runnable blocks (while writing docs,
/// `BUMPSIM_DOCS_PAGE=verdict` checks only the pages whose path holds it).
fn pages() -> Vec<String> {
    let mut pages = vec!["README.md".to_string()];
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    docs.sort();
    pages.extend(docs);
    match std::env::var("BUMPSIM_DOCS_PAGE") {
        Ok(only) => pages.into_iter().filter(|p| p.contains(&only)).collect(),
        Err(_) => pages,
    }
}

#[test]
fn every_runnable_block_of_the_docs_prints_what_the_docs_show() {
    let mut runnable = 0;
    let mut failures = Vec::new();
    for page in pages() {
        let markdown = std::fs::read_to_string(root().join(&page)).unwrap();
        let blocks = blocks(&markdown);
        runnable += blocks
            .iter()
            .filter(|b| matches!(b, Block::Run { .. }))
            .count();
        if !blocks.is_empty() {
            failures.extend(check_page(&page));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // the walkthrough alone has 6; a marker typo must not empty the check
    let whole = std::env::var("BUMPSIM_DOCS_PAGE").is_err();
    assert!(
        runnable >= 7 || !whole,
        "only {runnable} runnable blocks found"
    );
}

#[test]
fn the_comparison_catches_drift_and_allows_elision() {
    let docs = ["fit 99.42 %", "...", "wrote out/r.json"];
    assert!(matches(
        &docs,
        &["fit 99.43 %", "x", "y", "wrote out/r.json"]
    ));
    assert!(matches(&docs, &["fit 99.42 %", "wrote out/r.json"]));
    // a figure off by more than 1 %, a changed word, a missing line
    assert!(!matches(&docs, &["fit 97.1 %", "wrote out/r.json"]));
    assert!(!matches(&docs, &["fit 99.42 percent", "wrote out/r.json"]));
    assert!(!matches(&docs, &["fit 99.42 %"]));
    assert!(!matches(&["a", "b"], &["a", "b", "c"]));
    // codes keep their digits; exponents and signs are figures
    assert!(same_line(
        "P0IMPA000000FOXP 1.797e-5 m²",
        "P0IMPA000000FOXP 1.79e-5 m²"
    ));
    assert!(!same_line("-0.2962 m/s", "0.2962 m/s"));
    assert!(!same_line("10SIMELE0000ACXP", "11SIMELE0000ACXP"));
}
