//! The top-view picture of a planar impact (car outline, wheels, side
//! members, crushed bumper line and the striker's face) as SVG, drawn to
//! scale (equal x and y scales) in mm.
//!
//! Every part is drawn with one `Ink` and the figure's legend
//! ([`legend`]) names each ink's colour as it looks on the white page, so
//! the caption cannot say one colour while the picture shows another.

use crate::plot::PlotError;
use bumpsim_planar::picture::{FaceShape, TopView};
use plotters::prelude::*;

/// Picture size, px.
const SIZE: (u32, u32) = (900, 560);

/// How one part of the top view is drawn: its colour and opacity on the
/// white page.
#[derive(Debug, Clone, Copy)]
struct Ink {
    /// The part's name in the legend.
    part: &'static str,
    /// Red, green, blue.
    rgb: (u8, u8, u8),
    /// Opacity, 0..=1.
    opacity: f64,
}

const BODY: Ink = Ink::new("body outline", (150, 150, 150), 1.0);
const WHEELS: Ink = Ink::new("wheels", (0, 0, 0), 0.6);
const MEMBERS: Ink = Ink::new("side members", (0, 0, 255), 1.0);
const BUMPER: Ink = Ink::new("crushed bumper line", (255, 0, 0), 1.0);
const BARRIER: Ink = Ink::new("striker", (0, 0, 0), 0.45);
const POLE: Ink = Ink::new("striker", (0, 0, 0), 0.8);

impl Ink {
    const fn new(part: &'static str, rgb: (u8, u8, u8), opacity: f64) -> Ink {
        Ink { part, rgb, opacity }
    }

    fn colour(self) -> RGBAColor {
        RGBColor(self.rgb.0, self.rgb.1, self.rgb.2).mix(self.opacity)
    }

    /// The colour's plain name as it looks on white: black, grey or white
    /// when its channels are near equal, else the strongest channel.
    fn name(self) -> &'static str {
        let seen = |c: u8| 255.0 - self.opacity * (255.0 - f64::from(c));
        let (r, g, b) = (seen(self.rgb.0), seen(self.rgb.1), seen(self.rgb.2));
        let (low, high) = (r.min(g).min(b), r.max(g).max(b));
        match high - low < 30.0 {
            true if high < 80.0 => "black",
            true if high < 215.0 => "grey",
            true => "white",
            false if r >= g && r >= b => "red",
            false if g >= b => "green",
            false => "blue",
        }
    }
}

/// The striker's ink: a rigid face (barrier, pendulum) or a pole.
fn striker_ink(view: &TopView) -> Ink {
    match view.face {
        FaceShape::Segment(..) => BARRIER,
        FaceShape::Circle { .. } => POLE,
    }
}

/// The legend of [`top_view_svg`]'s picture, each part with the colour it
/// is drawn in, e.g. "body outline (grey), side members (blue), ...".
pub fn legend(view: &TopView) -> String {
    [BODY, MEMBERS, BUMPER, WHEELS, striker_ink(view)]
        .map(|ink| format!("{} ({})", ink.part, ink.name()))
        .join(", ")
}

/// The top view as SVG, titled `title`.
pub fn top_view_svg(view: &TopView, title: &str) -> Result<String, PlotError> {
    crate::register_font();
    let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
        title: title.to_string(),
        message: e.to_string(),
    };
    let range = bounds(view).ok_or_else(|| PlotError::Empty {
        title: title.to_string(),
    })?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_error(&e))?;
        draw(&root, view, title, range).map_err(|e| draw_error(&e))?;
        root.present().map_err(|e| draw_error(&e))?;
    }
    Ok(svg)
}

/// The view's extent in mm, padded and widened to the picture's aspect.
fn bounds(view: &TopView) -> Option<(f64, f64, f64, f64)> {
    let mut points: Vec<[f64; 2]> = view.body.clone();
    points.extend(view.bumper.iter().copied());
    match view.face {
        FaceShape::Segment(a, b) => points.extend([a, b]),
        FaceShape::Circle { centre, radius } => points.extend([
            [centre[0] - radius, centre[1] - radius],
            [centre[0] + radius, centre[1] + radius],
        ]),
    }
    let finite = points.iter().all(|p| p[0].is_finite() && p[1].is_finite());
    if !finite || points.is_empty() {
        return None;
    }
    let fold = |i: usize, f: fn(f64, f64) -> f64, start: f64| {
        points.iter().map(|p| p[i] * 1e3).fold(start, f)
    };
    let (x0, x1) = (
        fold(0, f64::min, f64::INFINITY) - 200.0,
        fold(0, f64::max, f64::NEG_INFINITY) + 200.0,
    );
    let (y0, y1) = (
        fold(1, f64::min, f64::INFINITY) - 200.0,
        fold(1, f64::max, f64::NEG_INFINITY) + 200.0,
    );
    // plot area about 800 × 460 px: equal scales
    let aspect = 800.0 / 460.0;
    let (w, h) = (x1 - x0, y1 - y0);
    Some(match w / h > aspect {
        true => {
            let mid = 0.5 * (y0 + y1);
            (x0, x1, mid - 0.5 * w / aspect, mid + 0.5 * w / aspect)
        }
        false => {
            let mid = 0.5 * (x0 + x1);
            (mid - 0.5 * h * aspect, mid + 0.5 * h * aspect, y0, y1)
        }
    })
}

fn mm(points: &[[f64; 2]]) -> Vec<(f64, f64)> {
    points.iter().map(|p| (p[0] * 1e3, p[1] * 1e3)).collect()
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    view: &TopView,
    title: &str,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc("x, forward [mm]")
        .y_desc("y, left [mm]")
        .disable_mesh()
        .draw()?;
    chart.draw_series(std::iter::once(PathElement::new(
        mm(&view.body),
        BODY.colour().stroke_width(2),
    )))?;
    chart.draw_series(
        view.wheels
            .iter()
            .map(|w| Polygon::new(mm(w), WHEELS.colour().filled())),
    )?;
    let members = view
        .side_members
        .iter()
        .map(|m| PathElement::new(mm(m), MEMBERS.colour().stroke_width(3)));
    chart.draw_series(members)?;
    match view.face {
        FaceShape::Segment(a, b) => {
            chart.draw_series(std::iter::once(PathElement::new(
                mm(&[a, b]),
                BARRIER.colour().stroke_width(10),
            )))?;
        }
        FaceShape::Circle { centre, radius } => {
            let ring: Vec<[f64; 2]> = (0..=48)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / 48.0;
                    [centre[0] + radius * a.cos(), centre[1] + radius * a.sin()]
                })
                .collect();
            chart.draw_series(std::iter::once(Polygon::new(
                mm(&ring),
                POLE.colour().filled(),
            )))?;
        }
    }
    chart.draw_series(std::iter::once(PathElement::new(
        mm(&view.bumper),
        BUMPER.colour().stroke_width(4),
    )))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_planar::picture::TopView;

    fn view(face: FaceShape) -> TopView {
        TopView {
            time: 0.01,
            body: vec![
                [0.0, -0.9],
                [0.0, 0.9],
                [-4.5, 0.9],
                [-4.5, -0.9],
                [0.0, -0.9],
            ],
            wheels: vec![],
            side_members: vec![[[-0.2, 0.5], [-1.2, 0.5]]],
            bumper: vec![[0.05, -0.8], [0.05, 0.8]],
            face,
        }
    }

    #[test]
    fn plain_names_follow_the_colour_seen_on_white() {
        assert_eq!(BODY.name(), "grey");
        assert_eq!(WHEELS.name(), "grey");
        assert_eq!(MEMBERS.name(), "blue");
        assert_eq!(BUMPER.name(), "red");
        assert_eq!(BARRIER.name(), "grey");
        assert_eq!(POLE.name(), "black");
        assert_eq!(Ink::new("x", (0, 160, 0), 1.0).name(), "green");
        assert_eq!(Ink::new("x", (0, 0, 0), 0.05).name(), "white");
    }

    /// The caption once said "striker (black)" under a grey barrier face
    /// (issue 35): the legend now names the ink the picture is drawn with.
    #[test]
    fn the_legend_names_the_striker_as_drawn() {
        let barrier = view(FaceShape::Segment([0.1, -1.0], [0.1, 1.0]));
        let pole = view(FaceShape::Circle {
            centre: [0.3, 0.0],
            radius: 0.127,
        });
        assert!(
            legend(&barrier).ends_with("striker (grey)"),
            "{}",
            legend(&barrier)
        );
        assert!(
            legend(&pole).ends_with("striker (black)"),
            "{}",
            legend(&pole)
        );
        let barrier_svg = top_view_svg(&barrier, "t").unwrap();
        assert!(drawn(&barrier_svg, r##"opacity="0.45" stroke="#000000""##));
        let pole_svg = top_view_svg(&pole, "t").unwrap();
        assert!(drawn(&pole_svg, r##"opacity="0.8" fill="#000000""##));
    }

    /// Whether an SVG element is drawn with these attributes.
    fn drawn(svg: &str, attributes: &str) -> bool {
        svg.lines()
            .any(|l| (l.contains("<polyline") || l.contains("<polygon")) && l.contains(attributes))
    }
}
