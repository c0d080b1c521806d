//! What a request gives its front end: the text to print (standard output,
//! in order), the warnings about the result (the front end prints and
//! counts them for `--strict`), the JSON document, the CSV histories and
//! the report's pages. Nothing here is written: writing (whole, never onto
//! an input) is the front end's (no equations here).

/// The answer of one request; it serialises whole (the Python module
/// pickles its results as their outcome).
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Outcome {
    /// Standard output, in order, each line ending in `\n`.
    pub text: String,
    /// Warnings about the result (without the `warning:` prefix).
    pub warnings: Vec<String>,
    /// The JSON document (`--json`, and beside the report).
    pub json: String,
    /// The time histories as CSV (SI; `--csv`).
    pub csv: String,
    /// The report, when the request asked for it.
    pub report: Option<Report>,
    /// Warnings already printed in `text` (counted for `--strict`, not
    /// printed again).
    pub printed_warnings: usize,
    /// The identified car as a car file (`identify --car`), when made.
    pub car: Option<String>,
    /// Plots (`predict --plot`): file name, SVG.
    pub plots: Vec<(String, String)>,
    /// Part of the request failed (a model size of several): why; the
    /// rest is delivered whole, then the command fails with this.
    #[serde(default)]
    pub failure: Option<String>,
}

/// A report: its index page and its figures and further pages.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Report {
    /// `index.html`.
    pub html: String,
    /// Further files of the folder: (file name, content).
    pub figures: Vec<(String, String)>,
    /// The inputs the report's viewer also needs (a study's tests).
    pub inputs: Vec<std::path::PathBuf>,
}
