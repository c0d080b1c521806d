//! `bumpsim view`: tests and results in the browser (bumpsim-view). Opens
//! the inputs, then serves them on 127.0.0.1 behind a random token and
//! opens the browser, or writes the self-contained page with `--html`.

use anyhow::{Context, Result};
use bumpsim_view::{Session, Viewer};
use std::path::PathBuf;

/// Arguments of `view`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Tests (ISO-MME folder, .mme or .zip; NHTSA .EV5; .csv) and bumpsim result JSONs.
    #[arg(required = true)]
    paths: Vec<PathBuf>,
    /// Print the address but do not open a browser.
    #[arg(long)]
    no_open: bool,
    /// Write the page self-contained (data embedded, no server) to this file and stop.
    #[arg(long)]
    html: Option<PathBuf>,
    /// Folder the page's "ISO-MME" export writes new test folders into (default: the current folder).
    #[arg(long)]
    export_dir: Option<PathBuf>,
}

/// Runs `view`.
pub fn run(args: &Args) -> Result<()> {
    let session = Session::open(&args.paths)?;
    if let Some(out) = &args.html {
        let page = bumpsim_view::server::standalone(&session)?;
        return crate::write(out, &page);
    }
    let folder = match &args.export_dir {
        Some(dir) => dir.clone(),
        None => std::env::current_dir().context("the current folder (for exports)")?,
    };
    let viewer = Viewer::bind(session, folder)?;
    let url = viewer.url();
    println!("bumpsim view: {url}");
    println!("(read-only; the address holds the key: share it with no one; Ctrl-C ends it)");
    use std::io::Write;
    let _ = std::io::stdout().flush();
    if !args.no_open {
        open_browser(&url);
    }
    Ok(viewer.serve()?)
}

/// Asks the desktop to open `url`; says so when it cannot.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    if std::process::Command::new(opener).arg(url).spawn().is_err() {
        eprintln!("note: could not start {opener}: open the address above in a browser");
    }
}
