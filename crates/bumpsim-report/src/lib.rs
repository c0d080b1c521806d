//! bumpsim-report: pictures of results, for people who would rather look.
//!
//! - [`bar`]: bar charts with error bars;
//! - [`doe`]: DOE coefficient, observed-vs-predicted and residual plots;
//! - [`heatmap`]: heat maps of sweeps with a colour bar;
//! - [`html`]: self-contained HTML reports;
//! - [`impact`]: impact pages and mass-reduction heat maps;
//! - [`identification`]: the identification report;
//! - [`planar`]: planar impact pages (forces, yaw, crush per segment, top view) and the planar identification;
//! - [`posterior`]: the corner plot of an identified chain's posterior;
//! - [`signal`]: raw against processed crash-test signals;
//! - [`topview`]: the top-view picture of a planar impact;
//! - [`verdict`](mod@verdict): the verdict report (tests × criteria, top views, forces, crush, the target corridor);
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
pub mod posterior;
pub mod signal;
pub mod topview;
pub mod verdict;

pub use bar::BarPlot;
pub use heatmap::HeatMap;
pub use html::Html;
pub use plot::{LinePlot, PlotError, Series, Span, Style};

/// The main types, for `use bumpsim_report::prelude::*` (the facade's
/// prelude globs it).
pub mod prelude {
    pub use crate::bar::BarPlot;
    pub use crate::heatmap::HeatMap;
    pub use crate::html::Html;
    pub use crate::plot::{LinePlot, PlotError, Series, Span, Style};
}

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

/// File names from users' names: the one rule lives in
/// [`bumpsim_core::names`] (kept here under their old paths for the pages
/// and the CLI).
pub use bumpsim_core::names::{FILE_NAME_CHARS, file_name, unique_name};
