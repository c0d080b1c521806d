//! Bar charts with error bars (DOE coefficient plots, MODDE style): one bar
//! per term from zero to its value, the 95 % interval as a whisker.

use crate::plot::PlotError;
use plotters::prelude::*;

/// A bar chart.
#[derive(Debug, Clone, PartialEq)]
pub struct BarPlot {
    /// Title.
    pub title: String,
    /// y axis label with unit.
    pub y_label: String,
    /// Bar labels.
    pub labels: Vec<String>,
    /// Bar values.
    pub values: Vec<f64>,
    /// Error bars `[low, high]` per bar.
    pub errors: Vec<Option<[f64; 2]>>,
}

impl BarPlot {
    /// Draws the chart as SVG.
    pub fn svg(&self) -> Result<String, PlotError> {
        crate::register_font();
        if self.values.is_empty() || self.values.iter().any(|v| !v.is_finite()) {
            return Err(PlotError::Empty {
                title: self.title.clone(),
            });
        }
        let ends = self
            .values
            .iter()
            .copied()
            .chain(self.errors.iter().flatten().flatten().copied())
            .chain([0.0]);
        let (lo, hi) = ends.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        let pad = 0.08 * (hi - lo).max(1e-12);
        crate::plot::drawable(&self.title, lo - pad, hi + pad)?;
        let mut svg = String::new();
        let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
            title: self.title.clone(),
            message: e.to_string(),
        };
        {
            let root = SVGBackend::with_string(&mut svg, (800, 440)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| draw_error(&e))?;
            self.draw(&root, lo - pad, hi + pad)
                .map_err(|e| draw_error(&e))?;
            root.present().map_err(|e| draw_error(&e))?;
        }
        Ok(svg)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        lo: f64,
        hi: f64,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let n = self.values.len();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.5..(n as f64 - 0.5), lo..hi)?;
        let labels = self.labels.clone();
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n)
            .x_label_formatter(&move |x| {
                labels.get(x.round() as usize).cloned().unwrap_or_default()
            })
            .y_desc(&self.y_label)
            .label_style(("sans-serif", 13))
            .draw()?;
        let blue = RGBColor(31, 119, 180);
        chart.draw_series(self.values.iter().enumerate().map(|(i, &v)| {
            Rectangle::new([(i as f64 - 0.3, 0.0), (i as f64 + 0.3, v)], blue.filled())
        }))?;
        chart.draw_series(self.errors.iter().enumerate().filter_map(|(i, e)| {
            e.map(|[a, b]| {
                ErrorBar::new_vertical(i as f64, a, 0.5 * (a + b), b, BLACK.stroke_width(2), 10)
            })
        }))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_bar_and_one_whisker_per_term() {
        let plot = BarPlot {
            title: "m2 [kg]: coded coefficients".into(),
            y_label: "coefficient [kg]".into(),
            labels: vec!["Kax".into(), "Kbnd".into(), "M".into()],
            values: vec![-52.38, 16.63, 215.63],
            errors: vec![Some([-60.0, -45.0]), Some([10.0, 23.0]), None],
        };
        let svg = plot.svg().unwrap();
        assert!(svg.contains("coefficient [kg]") && svg.contains(">Kbnd<") || svg.contains("Kbnd"));
        assert!(
            svg.matches("<rect").count() >= 4,
            "background and three bars"
        );
        assert!(plot.clone().svg().is_ok());
        let empty = BarPlot {
            values: vec![],
            ..plot
        };
        assert!(empty.svg().is_err());
    }
}
