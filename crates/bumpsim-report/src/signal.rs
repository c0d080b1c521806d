//! Signal plots: each processed channel over its raw input against time,
//! raw solid and processed dashed; when processing changed the dimension
//! (an integration), the raw signal gets a plot of its own. The signal
//! report ([`report`]) opens with the signals found (peaks, the momentum
//! balance) and the warnings, then the plots, and ends with the pipeline.

use crate::html::Html;
use crate::plot::{LinePlot, PlotError, Series, Style};
use bumpsim_core::channel::Channel;
use bumpsim_core::units::Dimension;

/// The raw-vs-processed plots of channels paired in order: (file name, SVG),
/// the file named after the processed channel's code (`-raw` for a raw
/// signal plotted alone).
pub fn raw_and_processed(
    raw: &[Channel],
    processed: &[Channel],
) -> Result<Vec<(String, String)>, PlotError> {
    let mut written = Vec::new();
    for (raw, processed) in raw.iter().zip(processed) {
        for (i, plot) in plots(raw, processed).iter().enumerate() {
            let suffix = if i == 0 { "" } else { "-raw" };
            let name = format!("{}{suffix}.svg", crate::file_name(&processed.code));
            written.push((name, plot.svg()?));
        }
    }
    Ok(written)
}

fn curve(c: &Channel, name: &str, style: Style) -> Series {
    Series::new(name, c.series.times(), c.series.values().to_vec(), style)
}

fn plots(raw: &Channel, processed: &Channel) -> Vec<LinePlot> {
    let mut plots = vec![LinePlot::new(
        &processed.code,
        Dimension::Time,
        processed.dimension,
    )];
    if raw.dimension == processed.dimension {
        plots[0].add(curve(raw, "raw", Style::Solid));
    } else {
        let mut raw_plot = LinePlot::new(
            &format!("{} (raw)", processed.code),
            Dimension::Time,
            raw.dimension,
        );
        raw_plot.add(curve(raw, "raw", Style::Solid));
        plots.push(raw_plot);
    }
    plots[0].add(curve(processed, "processed", Style::Dashed));
    plots
}

/// What a signal report shows: the pipeline's path and text (the inputs),
/// the summary of the signals (peaks and the momentum balance), the
/// warnings and the plots (file name, SVG).
#[derive(Debug, Clone, Copy)]
pub struct SignalPage<'a> {
    /// The pipeline file, as given.
    pub pipeline: &'a str,
    /// The pipeline file's text.
    pub inputs: &'a str,
    /// One line per signal and the momentum balance, with units.
    pub summary: &'a str,
    /// What the run warned about.
    pub warnings: &'a [String],
    /// The plots (file name, SVG).
    pub plots: &'a [(String, String)],
}

/// The signal report: the signals and warnings first, the plots, the
/// pipeline last.
///
/// ```
/// use bumpsim_report::signal::{SignalPage, report};
/// let page = report(&SignalPage { pipeline: "p.toml", inputs: "[[signal]]", summary: "F: peak 5 kN",
///     warnings: &[], plots: &[("F.svg".into(), "<svg></svg>".into())] });
/// assert!(page.find("peak 5 kN") < page.find("[[signal]]"));
/// ```
pub fn report(p: &SignalPage) -> String {
    let mut page = Html::new(&format!("bumpsim signal processing: {}", p.pipeline));
    page.heading("Signals");
    page.preformatted(p.summary);
    match p.warnings.is_empty() {
        true => page.paragraph("No warnings."),
        false => page.warnings(p.warnings),
    }
    for (name, svg) in p.plots {
        page.figure(svg, name);
    }
    page.heading("Inputs");
    page.paragraph(&format!("Pipeline {}:", p.pipeline));
    page.preformatted(p.inputs);
    page.finish()
}
