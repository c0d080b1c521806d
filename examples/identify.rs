//! The main job from Rust: read the bundled study (three synthetic pendulum
//! tests, see `examples/identify/README.md`), identify one MSD car model per
//! model order of the study, print the parameters and the per-case fit, and
//! write the self-contained HTML report with its SVG figures.
//!
//! ```sh
//! cargo run --example identify [OUT_DIR]
//! ```
//!
//! OUT_DIR defaults to `bumpsim-identify-example` in the system's temporary
//! folder.

use bumpsim::ident::explore::predict;
use bumpsim::ident::text::{case_lines, parameter_table};
use bumpsim::io::output;
use bumpsim::prelude::*;
use bumpsim::report::identification::{DofOutcome, report};
use std::error::Error;
use std::path::{Path, PathBuf};

fn main() -> Result<(), Box<dyn Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/identify/study.toml");
    let out = std::env::args_os().nth(1).map_or_else(
        || std::env::temp_dir().join("bumpsim-identify-example"),
        PathBuf::from,
    );
    let study = Study::read(&path)?;
    let dofs = study.dofs();
    let loaded = study.load(dofs.iter().copied().max().unwrap_or(1))?;
    let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
    for note in &notes {
        println!("note: {note}");
    }
    let mut outcomes = Vec::new();
    for dof in dofs {
        let settings = study.settings(dof)?;
        let cases = study.retarget(&loaded.cases, dof);
        let result = identify(&cases, &settings, &|| {})?;
        println!("{dof}-DOF model: fit {:.2} %", result.fit_percent);
        print!("{}{}", parameter_table(&result), case_lines(&result));
        let predictions = predict(&cases, &result.model)?;
        outcomes.push(DofOutcome::Done {
            result: Box::new(result),
            predictions,
        });
    }
    let inputs = std::fs::read_to_string(&path)?;
    let settings = format!("Study {}; the study's starts and seed.", path.display());
    let (html, figures) = report(
        "bumpsim identification",
        &inputs,
        &settings,
        &notes,
        &outcomes,
        None,
    )?;
    // the study is an input: the report folder may not land on it; the
    // files are staged and appear together
    output::register_input(&path);
    let folder = output::stage_folder(&out)?;
    for (name, svg) in figures {
        folder.write(&name, svg.as_bytes())?;
    }
    folder.write("index.html", html.as_bytes())?;
    output::commit(folder)?;
    println!("wrote {}", out.join("index.html").display());
    Ok(())
}
