//! Heat maps of a value over a grid (mass-reduction sweeps), as SVG, with a
//! colour bar. Cells without a value are drawn grey.

use crate::plot::PlotError;
use plotters::prelude::*;

/// A heat map: `values[i][j]` at `(x[i], y[j])`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatMap {
    /// Title.
    pub title: String,
    /// x axis label with unit.
    pub x_label: String,
    /// y axis label with unit.
    pub y_label: String,
    /// Colour-bar label with unit.
    pub value_label: String,
    /// x values (cell centres), in the unit of the label.
    pub x: Vec<f64>,
    /// y values (cell centres).
    pub y: Vec<f64>,
    /// The values.
    pub values: Vec<Vec<Option<f64>>>,
}

/// Viridis-like colour of `t` in [0, 1].
fn colour(t: f64) -> RGBColor {
    const STOPS: [(f64, (f64, f64, f64)); 5] = [
        (0.0, (68.0, 1.0, 84.0)),
        (0.25, (59.0, 82.0, 139.0)),
        (0.5, (33.0, 145.0, 140.0)),
        (0.75, (94.0, 201.0, 98.0)),
        (1.0, (253.0, 231.0, 37.0)),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = STOPS.iter().position(|s| s.0 >= t).unwrap_or(4).max(1);
    let ((t0, a), (t1, b)) = (STOPS[k - 1], STOPS[k]);
    let f = (t - t0) / (t1 - t0);
    let mix = |x: f64, y: f64| (x + f * (y - x)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

fn edges(centres: &[f64]) -> Vec<f64> {
    let n = centres.len();
    if n == 1 {
        return vec![centres[0] - 0.5, centres[0] + 0.5];
    }
    let mut e = vec![centres[0] - 0.5 * (centres[1] - centres[0])];
    e.extend(centres.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    e.push(centres[n - 1] + 0.5 * (centres[n - 1] - centres[n - 2]));
    e
}

impl HeatMap {
    /// The range of the finite values.
    fn range(&self) -> Option<(f64, f64)> {
        let all = self
            .values
            .iter()
            .flatten()
            .flatten()
            .copied()
            .filter(|v| v.is_finite());
        let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        lo.is_finite()
            .then_some((lo, if hi > lo { hi } else { lo + 1e-12 }))
    }

    /// Draws the map as SVG.
    pub fn svg(&self) -> Result<String, PlotError> {
        crate::register_font();
        let empty = || PlotError::Empty {
            title: self.title.clone(),
        };
        let (lo, hi) = self.range().ok_or_else(empty)?;
        if self.x.is_empty() || self.y.is_empty() || self.values.len() != self.x.len() {
            return Err(empty());
        }
        let hi = if hi - lo > 1e-12 * lo.abs() {
            hi
        } else {
            lo + lo.abs().max(1.0) * 1e-6
        };
        crate::plot::drawable(&self.title, lo, hi)?;
        for axis in [&self.x, &self.y] {
            let (a, b) = (axis[0], axis[axis.len() - 1]);
            if !(a.is_finite() && b.is_finite()) {
                return Err(empty());
            }
        }
        let mut svg = String::new();
        let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
            title: self.title.clone(),
            message: e.to_string(),
        };
        {
            let root = SVGBackend::with_string(&mut svg, (860, 520)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| draw_error(&e))?;
            let (main, bar) = root.split_horizontally(760);
            self.draw_cells(&main, lo, hi).map_err(|e| draw_error(&e))?;
            self.draw_bar(&bar, lo, hi).map_err(|e| draw_error(&e))?;
            root.present().map_err(|e| draw_error(&e))?;
        }
        Ok(svg)
    }

    fn draw_cells<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        lo: f64,
        hi: f64,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (xe, ye) = (edges(&self.x), edges(&self.y));
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(("sans-serif", 13))
            .draw()?;
        let cells = (0..self.x.len()).flat_map(|i| (0..self.y.len()).map(move |j| (i, j)));
        chart.draw_series(cells.map(|(i, j)| {
            let fill = match self.values[i].get(j).copied().flatten() {
                Some(v) => colour((v - lo) / (hi - lo)).filled(),
                None => RGBColor(200, 200, 200).filled(),
            };
            Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], fill)
        }))?;
        Ok(())
    }

    fn draw_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        lo: f64,
        hi: f64,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let mut chart = ChartBuilder::on(area)
            .margin_top(44)
            .margin_bottom(56)
            .margin_right(12)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(&self.value_label)
            .label_style(("sans-serif", 12))
            .draw()?;
        let steps = 64;
        chart.draw_series((0..steps).map(|k| {
            let (a, b) = (
                lo + (hi - lo) * k as f64 / steps as f64,
                lo + (hi - lo) * (k + 1) as f64 / steps as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                colour((k as f64 + 0.5) / steps as f64).filled(),
            )
        }))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_labels_and_colour_bar() {
        let map = HeatMap {
            title: "scale factor".into(),
            x_label: "spring k [kN/m]".into(),
            y_label: "mass ratio [-]".into(),
            value_label: "M*/(M1+M2) [-]".into(),
            x: vec![1.0, 2.0, 3.0],
            y: vec![0.5, 0.7],
            values: vec![
                vec![Some(0.7), Some(0.8)],
                vec![Some(0.9), None],
                vec![Some(0.95), Some(1.0)],
            ],
        };
        let svg = map.svg().unwrap();
        assert!(
            svg.contains("spring k [kN/m]")
                && svg.contains("mass ratio [-]")
                && svg.contains("M*/(M1+M2) [-]")
        );
        assert!(
            svg.matches("<rect").count() >= 6 + 64,
            "one rectangle per cell and per colour-bar step"
        );
        assert!(svg.contains("#C8C8C8"), "the missing cell is grey");
        assert_eq!(colour(0.0), RGBColor(68, 1, 84));
        assert_eq!(colour(1.0), RGBColor(253, 231, 37));
    }
}
