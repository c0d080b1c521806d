//! Self-contained HTML reports: one file, inline SVG and CSS, no network
//! and no JavaScript needed to read it.
//!
//! Each figure can name the command that opens its data in the
//! interactive viewer ([`with_viewer`]): a report is a file and cannot
//! start the viewer's local server, so it shows the command line
//! (`bumpsim view FILE...`) under the figure, ready to copy.
//!
//! ```
//! use bumpsim_report::html::Html;
//! let mut page = Html::new("Identification");
//! page.heading("Results");
//! page.table(&["DOF", "fit %"], &[vec!["3".into(), "99.1".into()]]);
//! let text = page.finish();
//! assert!(text.starts_with("<!DOCTYPE html>") && text.contains("bumpsim"));
//! ```

/// Escapes text for HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// An HTML page under construction.
#[derive(Debug, Clone, Default)]
pub struct Html {
    title: String,
    body: String,
    figures: usize,
}

const STYLE: &str = "body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:60em;margin:2em auto;color:#222;line-height:1.4}\
h1{border-bottom:2px solid #1f77b4}h2{margin-top:1.6em;color:#1f4f7b}\
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #bbb;padding:.25em .6em;text-align:right}\
th{background:#eef3f8}td:first-child,th:first-child{text-align:left}\
pre{background:#f6f6f6;padding:.6em;white-space:pre-wrap;overflow-wrap:anywhere}\
figure{margin:1em 0}figcaption{font-size:.9em;color:#555}\
.warning{background:#fff4d6;border-left:4px solid #e0a800;padding:.4em .8em;margin:.4em 0}\
.failure{background:#fde2e1;border-left:4px solid #c0392b;padding:.4em .8em;margin:.4em 0}\
footer{margin-top:3em;font-size:.85em;color:#666}\
.view{font-size:.85em;color:#555;margin:.2em 0 0}.view code{background:#f6f6f6;padding:.1em .3em;overflow-wrap:anywhere}";

/// The end of every figure [`Html::figure`] writes, where [`with_viewer`]
/// puts its command.
const FIGURE_END: &str = "</figcaption>\n</figure>\n";

/// A file name as one shell word: as it is when it holds only letters,
/// digits and `/._-+:,=@%`, else in single quotes (a `'` inside written
/// `'\''`); one starting with `-` led by `./`, so it is not read as an option.
fn shell_word(word: &str) -> String {
    if word.starts_with('-') {
        return shell_word(&format!("./{word}"));
    }
    let plain = |c: char| c.is_ascii_alphanumeric() || "/._-+:,=@%".contains(c);
    match !word.is_empty() && word.chars().all(plain) {
        true => word.to_string(),
        false => format!("'{}'", word.replace('\'', "'\\''")),
    }
}

/// The viewer's command line for `files`: `bumpsim view FILE...`.
///
/// ```
/// use bumpsim_report::html::view_command;
/// let files = ["out/result.json", "my study.toml", "-x.csv", "it's.mme"].map(String::from);
/// assert_eq!(
///     view_command(&files),
///     r"bumpsim view out/result.json 'my study.toml' ./-x.csv 'it'\''s.mme'"
/// );
/// ```
pub fn view_command(files: &[String]) -> String {
    let words: Vec<String> = files.iter().map(|f| shell_word(f)).collect();
    format!("bumpsim view {}", words.join(" "))
}

/// `page` with, under each figure, the command that opens the figure's
/// data in the interactive viewer (`bumpsim view FILE...`, run from the
/// folder the paths are relative to); `page` as it is when `files` is empty.
///
/// ```
/// use bumpsim_report::html::{Html, with_viewer};
/// let mut page = Html::new("Identification");
/// page.figure("<svg></svg>", "flat");
/// let page = with_viewer(&page.finish(), &["result.json".into(), "study.toml".into()]);
/// assert!(page.contains("<code>bumpsim view result.json study.toml</code>"));
/// ```
pub fn with_viewer(page: &str, files: &[String]) -> String {
    if files.is_empty() {
        return page.to_string();
    }
    let line = format!(
        "<p class=\"view\">Open in the viewer: <code>{}</code></p>\n",
        escape(&view_command(files))
    );
    page.replace(FIGURE_END, &format!("</figcaption>\n{line}</figure>\n"))
}

impl Html {
    /// A page with a title.
    pub fn new(title: &str) -> Html {
        Html {
            title: title.to_string(),
            ..Html::default()
        }
    }

    /// A section heading.
    pub fn heading(&mut self, text: &str) {
        self.body += &format!("<h2>{}</h2>\n", escape(text));
    }

    /// A paragraph of plain text.
    pub fn paragraph(&mut self, text: &str) {
        self.body += &format!("<p>{}</p>\n", escape(text));
    }

    /// Preformatted text (settings, terminal tables).
    pub fn preformatted(&mut self, text: &str) {
        self.body += &format!("<pre>{}</pre>\n", escape(text));
    }

    /// A table with a header row.
    pub fn table(&mut self, headers: &[&str], rows: &[Vec<String>]) {
        let head: String = headers
            .iter()
            .map(|h| format!("<th>{}</th>", escape(h)))
            .collect();
        let body: String = rows
            .iter()
            .map(|r| {
                format!(
                    "<tr>{}</tr>\n",
                    r.iter()
                        .map(|c| format!("<td>{}</td>", escape(c)))
                        .collect::<String>()
                )
            })
            .collect();
        self.body += &format!("<table>\n<tr>{head}</tr>\n{body}</table>\n");
    }

    /// An inline SVG figure with a caption.
    pub fn figure(&mut self, svg: &str, caption: &str) {
        self.figures += 1;
        let svg = svg.trim_start_matches(|c| c != '<');
        let svg = match svg.starts_with("<?xml") {
            true => svg
                .split_once("?>")
                .map_or(svg, |(_, rest)| rest.trim_start()),
            false => svg,
        };
        self.body += &format!(
            "<figure class=\"plot\" id=\"figure-{}\">\n{svg}\n<figcaption>Figure {}: {}</figcaption>\n</figure>\n",
            self.figures,
            self.figures,
            escape(caption)
        );
    }

    /// Warnings, each in a highlighted box.
    pub fn warnings(&mut self, warnings: &[String]) {
        for w in warnings {
            self.body += &format!("<div class=\"warning\">Warning: {}</div>\n", escape(w));
        }
    }

    /// Notes: what the user should know that is not a warning.
    pub fn notes(&mut self, notes: &[String]) {
        if notes.is_empty() {
            return;
        }
        self.body += "<ul>\n";
        for n in notes {
            self.body += &format!("<li>Note: {}</li>\n", escape(n));
        }
        self.body += "</ul>\n";
    }

    /// A failure notice.
    pub fn failure(&mut self, text: &str) {
        self.body += &format!("<div class=\"failure\">Failed: {}</div>\n", escape(text));
    }

    /// Number of figures so far.
    pub fn figure_count(&self) -> usize {
        self.figures
    }

    /// The finished document.
    pub fn finish(self) -> String {
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n{}<footer>Written by bumpsim {} — every number is computed by the run that wrote this file.</footer>\n</body>\n</html>\n",
            self.body,
            env!("CARGO_PKG_VERSION"),
            title = escape(&self.title)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_counts_figures() {
        let mut page = Html::new("a < b");
        page.figure("<?xml version=\"1.0\"?>\n<svg></svg>", "x & y");
        page.failure("case 'pole' diverged");
        let text = page.finish();
        assert!(text.contains("<title>a &lt; b</title>"));
        assert!(text.contains("<svg></svg>") && !text.contains("<?xml"));
        assert!(text.contains("Figure 1: x &amp; y"));
        assert!(text.contains("class=\"failure\""));
    }
}
