//! Line plots of time histories as SVG.
//!
//! Values come in SI and are drawn in the display unit of their dimension
//! (ms, mm, kN, g, ...; `bumpsim_core::units::Dimension::display_unit`), and
//! each axis label states that unit. Measured data are drawn solid,
//! simulated or processed data dashed, as in the thesis figures; a band
//! (a prediction's pointwise interval) is a shaded area between its ends,
//! drawn under the lines. A marked span of x (the window a model was
//! fitted over, [`Span`]) is shaded from the bottom to the top of the
//! axes with a line at each end and its own legend entry, so a reader
//! sees where the fit was taken and where the curves only continue.

use bumpsim_core::units::Dimension;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Why a plot cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// Nothing to draw.
    #[error("plot '{title}': no series with finite points")]
    Empty {
        /// The plot title.
        title: String,
    },
    /// A series has x and y of different lengths.
    #[error("plot '{title}': series '{series}' has {x} x values and {y} y values")]
    Length {
        /// The plot title.
        title: String,
        /// The series.
        series: String,
        /// Number of x values.
        x: usize,
        /// Number of y values.
        y: usize,
    },
    /// The drawing backend failed.
    #[error("plot '{title}': {message}")]
    Draw {
        /// The plot title.
        title: String,
        /// What plotters said.
        message: String,
    },
}

/// Line style of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid line (measured).
    Solid,
    /// Dashed line (simulated, processed).
    Dashed,
    /// Markers only (scatter).
    Points,
}

/// One curve: name (legend), x and y values in SI, style.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// x values, SI.
    pub x: Vec<f64>,
    /// y values, SI.
    pub y: Vec<f64>,
    /// Line style.
    pub style: Style,
}

impl Series {
    /// A series.
    pub fn new(name: &str, x: Vec<f64>, y: Vec<f64>, style: Style) -> Series {
        Series {
            name: name.to_string(),
            x,
            y,
            style,
        }
    }
}

/// A shaded area between two curves over the same x: a prediction's
/// pointwise interval (SI values, as [`Series`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Legend entry.
    pub name: String,
    /// x values, SI.
    pub x: Vec<f64>,
    /// Lower end at each x, SI.
    pub low: Vec<f64>,
    /// Upper end at each x, SI.
    pub high: Vec<f64>,
}

/// A span of x marked on the plot (the fitted window): shaded over the
/// whole height of the axes, a vertical line at each end, named in the
/// legend. Ends in SI, as the x values.
#[derive(Debug, Clone, PartialEq)]
pub struct Span {
    /// Legend entry.
    pub name: String,
    /// First and last x, SI.
    pub ends: [f64; 2],
}

impl Span {
    /// The fitted window `[start, end]` (s) of a time plot: named
    /// `fitted window 12.3–101.5 ms` in the legend (`what` replaces
    /// `fitted` for a window that was only scored).
    ///
    /// ```
    /// use bumpsim_report::plot::Span;
    /// let span = Span::window("fitted", [0.0123, 0.1015]);
    /// assert_eq!(span.name, "fitted window 12.30–101.50 ms");
    /// ```
    pub fn window(what: &str, [start, end]: [f64; 2]) -> Span {
        let ms = |t: f64| format!("{:.2}", t * 1e3);
        Span {
            name: format!("{what} window {}–{} ms", ms(start), ms(end)),
            ends: [start, end],
        }
    }
}

/// The colour of a marked span: amber, light when shaded, dark at its ends.
const SPAN: RGBColor = RGBColor(230, 160, 0);

/// A line plot with a title, two axes of given dimensions and its series.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePlot {
    /// Title.
    pub title: String,
    /// x dimension (label and unit).
    pub x: Dimension,
    /// y dimension (label and unit).
    pub y: Dimension,
    /// The curves.
    pub series: Vec<Series>,
    /// Shaded areas, drawn under the curves.
    pub bands: Vec<Band>,
    /// Marked spans of x (fitted windows), drawn under everything.
    pub spans: Vec<Span>,
    /// Size in pixels.
    pub size: (u32, u32),
    /// Axis labels replacing the dimension's `name [unit]` (x, y).
    pub labels: (Option<String>, Option<String>),
}

/// Ten distinguishable colours (matplotlib's tab10 order): a plot of up to
/// ten series (the sensitivity plot draws one per parameter, seven for a
/// 3-DOF chain) never gives two of them the same colour.
const COLOURS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
];

/// The axis label of a dimension: `force [kN]`.
pub fn axis_label(dimension: Dimension) -> String {
    format!("{} [{}]", dimension.name(), dimension.display_unit().symbol)
}

impl LinePlot {
    /// An empty plot.
    pub fn new(title: &str, x: Dimension, y: Dimension) -> LinePlot {
        LinePlot {
            title: title.to_string(),
            x,
            y,
            series: Vec::new(),
            bands: Vec::new(),
            spans: Vec::new(),
            size: (800, 480),
            labels: (None, None),
        }
    }

    /// Names the quantities on the axes (`displacement`, `compression`, ...)
    /// where the dimension's name (`length`) would not say which one: the
    /// labels read `displacement [mm]`, in the dimension's display unit.
    pub fn quantities(self, x: Option<&str>, y: Option<&str>) -> Self {
        let label = |name: &str, d: Dimension| format!("{name} [{}]", d.display_unit().symbol);
        let (dx, dy) = (self.x, self.y);
        let x = x.map(|n| label(n, dx));
        let y = y.map(|n| label(n, dy));
        self.with_labels(x.as_deref(), y.as_deref())
    }

    /// Replaces the axis labels, for quantities without a [`Dimension`]
    /// (values are then drawn as given, in the unit the label states).
    pub fn with_labels(mut self, x: Option<&str>, y: Option<&str>) -> Self {
        self.labels = (x.map(str::to_string), y.map(str::to_string));
        self
    }

    /// Adds a series.
    pub fn add(&mut self, series: Series) -> &mut Self {
        self.series.push(series);
        self
    }

    /// Adds a shaded band between `low` and `high` over `x`.
    ///
    /// ```
    /// use bumpsim_core::units::Dimension;
    /// use bumpsim_report::plot::{Band, LinePlot};
    /// let mut plot = LinePlot::new("force", Dimension::Time, Dimension::Force);
    /// let (x, low, high) = (vec![0.0, 0.01], vec![0.0, 900.0], vec![0.0, 1100.0]);
    /// plot.band(Band { name: "5 % to 95 %".into(), x, low, high });
    /// assert!(plot.svg()?.contains("<polygon opacity=\"0.3\""));
    /// # Ok::<(), bumpsim_report::plot::PlotError>(())
    /// ```
    pub fn band(&mut self, band: Band) -> &mut Self {
        self.bands.push(band);
        self
    }

    /// Marks a span of x (a fitted window, [`Span::window`]).
    pub fn span(&mut self, span: Span) -> &mut Self {
        self.spans.push(span);
        self
    }

    /// Every curve as a series: the lines and both ends of each band.
    fn curves(&self) -> Vec<Series> {
        let ends = self.bands.iter().flat_map(|b| {
            let end = |y: &Vec<f64>| Series::new(&b.name, b.x.clone(), y.clone(), Style::Solid);
            [end(&b.low), end(&b.high)]
        });
        self.series.iter().cloned().chain(ends).collect()
    }

    /// The data range in display units: (x0, x1, y0, y1), padded.
    fn range(&self) -> Result<(f64, f64, f64, f64), PlotError> {
        let (ux, uy) = (self.x.display_unit(), self.y.display_unit());
        let mut r = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for s in &self.curves() {
            if s.x.len() != s.y.len() {
                let (title, series) = (self.title.clone(), s.name.clone());
                return Err(PlotError::Length {
                    title,
                    series,
                    x: s.x.len(),
                    y: s.y.len(),
                });
            }
            for (&x, &y) in
                s.x.iter()
                    .zip(&s.y)
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
            {
                let (x, y) = (ux.from_si(x), uy.from_si(y));
                r = (r.0.min(x), r.1.max(x), r.2.min(y), r.3.max(y));
            }
        }
        if !r.0.is_finite() {
            return Err(PlotError::Empty {
                title: self.title.clone(),
            });
        }
        let pad = |a: f64, b: f64| {
            if b > a {
                0.05 * (b - a)
            } else {
                a.abs().max(1.0) * 0.05
            }
        };
        let (px, py) = (pad(r.0, r.1), pad(r.2, r.3));
        // a time axis starts at its first sample; markers get room on
        // every side, so none at the limits is cut in half
        let scatter = self.series.iter().any(|s| s.style == Style::Points);
        let (left, right) = if scatter {
            (px, px)
        } else {
            (0.0, px * f64::from(r.1 <= r.0))
        };
        let range = (r.0 - left, r.1 + right, r.2 - py, r.3 + py);
        drawable(&self.title, range.0, range.1)?;
        drawable(&self.title, range.2, range.3)?;
        Ok(range)
    }

    /// Draws the plot as a PNG image (bitmap backend, bundled font; no
    /// system libraries), written to `path` atomically and never over an
    /// input ([`bumpsim_io::output`]). Needs the crate's `png` feature.
    #[cfg(any(test, feature = "png"))]
    pub fn png(&self, path: &std::path::Path) -> Result<(), PlotError> {
        crate::register_font();
        let range = self.range()?;
        let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
            title: self.title.clone(),
            message: e.to_string(),
        };
        bumpsim_io::output::write_rendered(path, |temp| {
            let root = BitMapBackend::new(temp, self.size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| draw_error(&e))?;
            self.draw(&root, range).map_err(|e| draw_error(&e))?;
            root.present().map_err(|e| draw_error(&e))
        })
        .map_err(|e| draw_error(&e))
    }

    /// Draws the plot as an SVG document.
    pub fn svg(&self) -> Result<String, PlotError> {
        crate::register_font();
        let range = self.range()?;
        let mut svg = String::new();
        let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
            title: self.title.clone(),
            message: e.to_string(),
        };
        {
            let root = SVGBackend::with_string(&mut svg, self.size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| draw_error(&e))?;
            self.draw(&root, range).map_err(|e| draw_error(&e))?;
            root.present().map_err(|e| draw_error(&e))?;
        }
        Ok(self.dash(svg))
    }

    /// Gives the polylines of dashed series a `stroke-dasharray`, so each
    /// series stays one path (plotters' own dashed series draws one path per dash).
    fn dash(&self, svg: String) -> String {
        let mut svg = svg;
        for (i, _) in self
            .series
            .iter()
            .enumerate()
            .filter(|(_, s)| s.style == Style::Dashed)
        {
            let RGBColor(r, g, b) = COLOURS[i % COLOURS.len()];
            let stroke = format!("stroke=\"#{r:02X}{g:02X}{b:02X}\" stroke-width=\"2\"");
            svg = svg.replace(&stroke, &format!("{stroke} stroke-dasharray=\"8 5\""));
        }
        svg
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        (x0, x1, y0, y1): (f64, f64, f64, f64),
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(self.labels.0.clone().unwrap_or_else(|| axis_label(self.x)))
            .y_desc(self.labels.1.clone().unwrap_or_else(|| axis_label(self.y)))
            .label_style(("sans-serif", 13))
            .draw()?;
        let (ux, uy) = (self.x.display_unit(), self.y.display_unit());
        for span in &self.spans {
            Self::mark(&mut chart, span, ux, (x0, x1, y0, y1))?;
        }
        for band in &self.bands {
            self.shade(&mut chart, band)?;
        }
        for (i, s) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let points: Vec<(f64, f64)> =
                s.x.iter()
                    .zip(&s.y)
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .map(|(&x, &y)| (ux.from_si(x), uy.from_si(y)))
                    .collect();
            let style = colour.stroke_width(2);
            // each legend sample is the series' own mark: a marker for a
            // scatter, a line (dashed in the SVG, see `dash`) otherwise
            match s.style {
                Style::Points => {
                    let marker = colour.filled();
                    chart
                        .draw_series(points.iter().map(|&p| Circle::new(p, 3, marker)))?
                        .label(s.name.clone())
                        .legend(move |(x, y)| Circle::new((x + 10, y), 3, marker));
                }
                _ => {
                    chart
                        .draw_series(LineSeries::new(points, style))?
                        .label(s.name.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .draw()
    }
}

impl LinePlot {
    /// Draws `band` as a translucent polygon (its lower end forward, its
    /// upper end back) with a filled legend mark; points where an end is
    /// not finite are left out.
    fn shade<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        band: &Band,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (ux, uy) = (self.x.display_unit(), self.y.display_unit());
        let finite = |(&x, (&l, &h)): (&f64, (&f64, &f64))| {
            (x.is_finite() && l.is_finite() && h.is_finite()).then_some((x, l, h))
        };
        let points: Vec<(f64, f64, f64)> = (band.x.iter().zip(band.low.iter().zip(&band.high)))
            .filter_map(finite)
            .map(|(x, l, h)| (ux.from_si(x), uy.from_si(l), uy.from_si(h)))
            .collect();
        let outline = (points.iter().map(|&(x, l, _)| (x, l)))
            .chain(points.iter().rev().map(|&(x, _, h)| (x, h)))
            .collect::<Vec<_>>();
        let fill = BAND.mix(0.3).filled();
        chart
            .draw_series(std::iter::once(Polygon::new(outline, fill)))?
            .label(band.name.clone())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], fill));
        Ok(())
    }
}

impl LinePlot {
    /// Draws `span` (clipped to the axes) as a light rectangle over the
    /// axes' height with a line at each end inside them, and its legend
    /// entry; a span wholly outside the axes or not finite is left out.
    fn mark<DB: DrawingBackend>(
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        span: &Span,
        ux: bumpsim_core::units::Unit,
        (x0, x1, y0, y1): (f64, f64, f64, f64),
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let [a, b] = span.ends.map(|e| ux.from_si(e));
        if !(a.is_finite() && b.is_finite()) || a.max(b) < x0 || a.min(b) > x1 {
            return Ok(());
        }
        let (a, b) = (a.min(b).max(x0), a.max(b).min(x1));
        let fill = SPAN.mix(0.15).filled();
        chart
            .draw_series(std::iter::once(Rectangle::new([(a, y0), (b, y1)], fill)))?
            .label(span.name.clone())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], fill));
        let edge = SPAN.stroke_width(1);
        let edges = [a, b].map(|x| PathElement::new(vec![(x, y0), (x, y1)], edge));
        chart.draw_series(edges)?;
        Ok(())
    }
}

/// The colour of a band's shading: the first series' (a band is drawn
/// around the nominal curve, which comes first).
const BAND: RGBColor = COLOURS[0];

/// Refuses an axis range plotters cannot draw (it asserts on non-finite or
/// empty ranges): values near f64::MAX make the span overflow, and a span
/// below the resolution of its ends is empty.
pub(crate) fn drawable(title: &str, lo: f64, hi: f64) -> Result<(), PlotError> {
    let span = hi - lo;
    if span.is_finite() && span > 0.0 && span > 1e-12 * lo.abs().max(hi.abs()) {
        return Ok(());
    }
    Err(PlotError::Draw {
        title: title.into(),
        message: format!("an axis spans [{lo}, {hi}]: too wide or too narrow to draw"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn demo() -> LinePlot {
        let t: Vec<f64> = (0..50).map(|k| k as f64 * 1e-3).collect();
        let f: Vec<f64> = t.iter().map(|t| 2e4 * (60.0 * t).sin()).collect();
        let mut p = LinePlot::new("Pendulum force", Dimension::Time, Dimension::Force);
        p.add(Series::new("measured", t.clone(), f.clone(), Style::Solid));
        p.add(Series::new("filtered", t, f, Style::Dashed));
        p
    }

    /// The nominal curve of `demo` with a band from 0.8 of it to 5 kN above
    /// it, a NaN at the third point.
    fn banded() -> LinePlot {
        let mut p = demo();
        let nominal = p.series[0].clone();
        let mut low: Vec<f64> = nominal.y.iter().map(|f| 0.8 * f).collect();
        let high = nominal.y.iter().map(|f| f + 5e3).collect();
        low[2] = f64::NAN;
        let name = "5 % to 95 %".into();
        p.band(Band {
            name,
            x: nominal.x,
            low,
            high,
        });
        p
    }

    #[test]
    fn a_band_is_one_shaded_polygon_under_the_lines_within_the_axes() {
        let plot = banded();
        let svg = plot.svg().unwrap();
        let polygon = svg
            .find("<polygon opacity=\"0.3\"")
            .expect("the band's polygon");
        let nominal = svg.find("stroke=\"#1F77B4\" stroke-width=\"2\"").unwrap();
        assert!(polygon < nominal, "the band is drawn under the lines");
        assert!(svg.contains("5 % to 95 %"));
        // 49 finite points forward and back: 98 vertices
        let vertices = svg[polygon..].split("points=\"").nth(1).unwrap();
        let vertices = vertices
            .split('"')
            .next()
            .unwrap()
            .split_whitespace()
            .count();
        assert_eq!(vertices, 98);
        // the y axis reaches the band's top (25 kN), above the nominal's 20 kN
        let (_, _, _, top) = plot.range().unwrap();
        assert!(top >= 25.0 && demo().range().unwrap().3 < 25.0, "{top} kN");
    }

    /// Numbers inside `points="..."` or `d="..."` attributes of path-like elements.
    fn coordinates(svg: &str) -> Vec<f64> {
        svg.split("points=\"")
            .skip(1)
            .flat_map(|rest| rest.split('"').next().unwrap_or("").split([' ', ',']))
            .filter(|s| !s.is_empty())
            .map(|s| s.parse::<f64>().unwrap_or(f64::NAN))
            .collect()
    }

    #[test]
    fn axis_labels_carry_units_and_each_series_is_drawn() {
        let svg = demo().svg().unwrap();
        assert!(svg.contains("time [ms]"), "x label with unit");
        assert!(svg.contains("force [kN]"), "y label with unit");
        let texts: Vec<&str> = svg
            .split("<text")
            .skip(1)
            .map(|t| {
                t.split('>')
                    .nth(1)
                    .unwrap_or("")
                    .split('<')
                    .next()
                    .unwrap_or("")
                    .trim()
            })
            .collect();
        assert!(
            texts.contains(&"measured") && texts.contains(&"filtered"),
            "legend: {texts:?}"
        );
        let long_paths = svg
            .split("<polyline")
            .filter(|p| p.split("/>").next().unwrap_or("").matches(',').count() > 40)
            .count();
        assert_eq!(long_paths, 2, "one path per series");
        let dashed = svg.matches("stroke-dasharray").count();
        assert_eq!(dashed, 2, "the dashed series and its legend sample");
        let coords = coordinates(&svg);
        assert!(!coords.is_empty() && coords.iter().all(|c| c.is_finite()));
    }

    #[test]
    fn scatter_draws_one_marker_per_point() {
        let mut p = LinePlot::new(
            "observed vs predicted",
            Dimension::Dimensionless,
            Dimension::Dimensionless,
        )
        .with_labels(Some("predicted m2 [kg]"), Some("observed m2 [kg]"));
        p.add(Series::new(
            "runs",
            vec![1.0, 2.0, 3.0, 4.0],
            vec![1.1, 1.9, 3.2, 3.9],
            Style::Points,
        ));
        let svg = p.svg().unwrap();
        assert!(svg.contains("predicted m2 [kg]") && svg.contains("observed m2 [kg]"));
        assert_eq!(
            svg.matches("<circle").count(),
            5,
            "one marker per point and the legend's marker"
        );
        // the legend shows the scatter's mark, not a line
        let legend_lines = svg
            .split("<polyline")
            .skip(1)
            .filter(|p| p.split("/>").next().unwrap_or("").contains("#1F77B4"))
            .count();
        assert_eq!(legend_lines, 0, "no line sample for a scatter");
        // markers at the limits are inside the plotting area, which
        // starts at margin + y label area = 82 px: none is cut in half
        let left = svg
            .split("<circle cx=\"")
            .skip(1)
            .filter_map(|c| c.split('"').next()?.parse::<f64>().ok())
            .fold(f64::INFINITY, f64::min);
        assert!(left > 82.0 + 3.0, "a marker at x = {left} px");
    }

    #[test]
    fn seven_series_get_seven_colours_and_named_quantities() {
        let mut p = LinePlot::new("objective", Dimension::Time, Dimension::Length)
            .quantities(None, Some("displacement"));
        for i in 0..7 {
            let y = vec![i as f64, i as f64 + 1.0];
            p.add(Series::new(
                &format!("s{i}"),
                vec![0.0, 1.0],
                y,
                Style::Solid,
            ));
        }
        let svg = p.svg().unwrap();
        assert!(svg.contains("displacement [mm]") && !svg.contains("length [mm]"));
        let colours: std::collections::BTreeSet<&str> = svg
            .split("<polyline")
            .skip(1)
            .filter_map(|p| {
                p.split("/>")
                    .next()?
                    .split("stroke=\"")
                    .nth(1)?
                    .split('"')
                    .next()
            })
            .collect();
        assert!(colours.len() >= 7, "{colours:?}");
    }

    /// The x pixels of the amber rectangles (shaded spans and their legend
    /// marks), largest first: (x, width).
    fn shaded(svg: &str) -> Vec<(f64, f64)> {
        let mut found: Vec<(f64, f64, f64)> = svg
            .split("<rect ")
            .skip(1)
            .map(|r| format!(" {}", r.split("/>").next().unwrap_or("")))
            .filter(|r| r.contains("fill=\"#E6A000\""))
            .map(|r| {
                let get = |k: &str| -> f64 {
                    let v = r.split(&format!(" {k}=\"")).nth(1).unwrap_or("");
                    v.split('"')
                        .next()
                        .unwrap_or("")
                        .parse()
                        .unwrap_or(f64::NAN)
                };
                (get("x"), get("width"), get("height"))
            })
            .collect();
        found.sort_by(|a, b| b.2.total_cmp(&a.2));
        found.into_iter().map(|(x, w, _)| (x, w)).collect()
    }

    #[test]
    fn a_fitted_window_is_shaded_over_its_times_with_a_legend_entry() {
        let mut plot = demo();
        let plain = plot.svg().unwrap();
        // the nominal curve runs from 0 to 49 ms: the ends of the axes
        let curve: Vec<f64> = plain
            .split("<polyline")
            .map(|p| p.split("/>").next().unwrap_or(""))
            .find(|p| p.contains("#1F77B4") && p.matches(',').count() > 40)
            .map(coordinates)
            .unwrap()
            .iter()
            .step_by(2)
            .copied()
            .collect();
        let (left, right) = (curve[0], curve[curve.len() - 1]);
        plot.span(Span::window("fitted", [0.010, 0.030]));
        let svg = plot.svg().unwrap();
        assert!(svg.contains("fitted window 10.00–30.00 ms"), "legend entry");
        let (x, width) = shaded(&svg)[0];
        let px = |ms: f64| left + (right - left) * ms / 49.0;
        assert!(
            (x - px(10.0)).abs() <= 1.0,
            "{x} px for 10 ms at {}",
            px(10.0)
        );
        assert!(
            (x + width - px(30.0)).abs() <= 1.0,
            "end at {} px",
            x + width
        );
        assert_eq!(shaded(&svg).len(), 2, "the span and its legend mark");
        // clipped to the axes; not drawn when outside them or not finite
        let mut wide = demo();
        wide.span(Span::window("fitted", [-1.0, 1.0]));
        let (x, width) = shaded(&wide.svg().unwrap())[0];
        assert!((x - left).abs() <= 1.0 && (x + width - right).abs() <= 1.0);
        for ends in [[0.5, 0.6], [f64::NAN, 0.01]] {
            let mut outside = demo();
            outside.span(Span::window("fitted", ends));
            assert!(shaded(&outside.svg().unwrap()).is_empty(), "{ends:?}");
        }
    }

    #[test]
    fn png_renders() {
        let path = std::env::temp_dir().join(format!("bumpsim-plot-{}.png", std::process::id()));
        demo().png(&path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(
            bytes.starts_with(b"\x89PNG") && bytes.len() > 5000,
            "a PNG with content"
        );
    }

    #[test]
    fn empty_and_ragged_plots_are_errors() {
        let p = LinePlot::new("nothing", Dimension::Time, Dimension::Force);
        assert!(matches!(p.svg(), Err(PlotError::Empty { .. })));
        let mut q = LinePlot::new("ragged", Dimension::Time, Dimension::Force);
        q.add(Series::new("s", vec![0.0], vec![], Style::Solid));
        assert!(matches!(q.svg(), Err(PlotError::Length { .. })));
    }
}
