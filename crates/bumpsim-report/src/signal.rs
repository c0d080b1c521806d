//! Signal plots: each processed channel over its raw input against time,
//! raw solid and processed dashed; when processing changed the dimension
//! (an integration), the raw signal gets a plot of its own.

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
