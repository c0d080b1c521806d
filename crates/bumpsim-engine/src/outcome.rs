//! What a request gives its front end: the text to print (standard output,
//! in order), the warnings about the result (the front end prints and
//! counts them for `--strict`), the JSON document, the CSV histories and
//! the report's pages. Nothing here is written: writing (whole, never onto
//! an input) is the front end's (no equations here).

/// The answer of one request.
#[derive(Debug, Clone, PartialEq, Default)]
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
}

/// A report: its index page and its figures and further pages.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// `index.html`.
    pub html: String,
    /// Further files of the folder: (file name, content).
    pub figures: Vec<(String, String)>,
}
