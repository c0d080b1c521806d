//! bumpsim-report: pictures of results, for people who would rather look.
//!
//! - [`bar`]: bar charts with error bars;
//! - [`doe`]: DOE coefficient, observed-vs-predicted and residual plots;
//! - [`heatmap`]: heat maps of sweeps with a colour bar;
//! - [`html`]: self-contained HTML reports;
//! - [`impact`]: impact pages and mass-reduction heat maps;
//! - [`identification`]: the identification report;
//! - [`planar`]: planar impact pages (forces, yaw, crush per segment, top view) and the planar identification;
//! - [`signal`]: raw against processed crash-test signals;
//! - [`topview`]: the top-view picture of a planar impact;
//! - [`plot`]: line plots of time histories (measured solid, simulated
//!   dashed, as in the thesis figures) with units on both axes, as SVG.
//!
//! Text is laid out with the bundled DejaVu Sans font (free licence, see
//! `fonts/DejaVuSans-LICENSE.txt`), so no system font library is needed.
//!
//! ```
//! use bumpsim_core::units::Dimension;
//! use bumpsim_report::plot::{LinePlot, Series, Style};
//! let mut plot = LinePlot::new("Force", Dimension::Time, Dimension::Force);
//! plot.add(Series::new("F", vec![0.0, 0.01, 0.02], vec![0.0, 5e3, 0.0], Style::Solid));
//! let svg = plot.svg().unwrap();
//! assert!(svg.contains("<svg") && svg.contains("kN"));
//! ```

pub mod bar;
pub mod doe;
pub mod heatmap;
pub mod html;
pub mod identification;
pub mod impact;
pub mod planar;
pub mod plot;
pub mod signal;
pub mod topview;

pub use bar::BarPlot;
pub use heatmap::HeatMap;
pub use html::Html;
pub use plot::{LinePlot, PlotError, Series, Style};

use std::sync::Once;

static FONT: Once = Once::new();

/// Registers the bundled font with plotters (once per process).
pub(crate) fn register_font() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../fonts/DejaVuSans.ttf");
        // The font is compiled in and known to parse; a failure would only
        // lose text measurement, which plotters then reports when drawing.
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, bytes);
    });
}

/// Longest part of a file name made from a user's name, in characters
/// (file systems allow 255 bytes; prefixes and suffixes are added).
pub const FILE_NAME_CHARS: usize = 64;

/// A file name from a signal or case name: ASCII letters, digits, `-` and
/// `_` kept, anything else `_`, at most [`FILE_NAME_CHARS`] characters.
/// Different names can give the same file name; a report makes its own
/// names unique ([`unique_name`]).
pub fn file_name(name: &str) -> String {
    name.chars()
        .take(FILE_NAME_CHARS)
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `name` itself when `taken` does not hold it, otherwise `name` with `-2`,
/// `-3`, ... before its extension: two cases `a/b` and `a_b` get two plots.
pub fn unique_name(name: &str, taken: impl Fn(&str) -> bool) -> String {
    if !taken(name) {
        return name.to_string();
    }
    let (stem, extension) = match name.rsplit_once('.') {
        Some((stem, extension)) => (stem, format!(".{extension}")),
        None => (name, String::new()),
    };
    (2..)
        .map(|n| format!("{stem}-{n}{extension}"))
        .find(|candidate| !taken(candidate))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_are_short_and_unique_names_count_up() {
        assert_eq!(file_name("a/b c"), "a_b_c");
        assert_eq!(file_name(&"x".repeat(5000)).len(), FILE_NAME_CHARS);
        let taken = ["fit-a_b.svg", "fit-a_b-2.svg"];
        let is_taken = |n: &str| taken.contains(&n);
        assert_eq!(unique_name("fit-c.svg", is_taken), "fit-c.svg");
        assert_eq!(unique_name("fit-a_b.svg", is_taken), "fit-a_b-3.svg");
        assert_eq!(unique_name("README", |n| n == "README"), "README-2");
    }
}
