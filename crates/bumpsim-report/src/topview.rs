//! The top-view picture of a planar impact (car outline, wheels, side
//! members, crushed bumper line and the striker's face) as SVG, drawn to
//! scale (equal x and y scales) in mm.

use crate::plot::PlotError;
use bumpsim_planar::picture::{FaceShape, TopView};
use plotters::prelude::*;

/// Picture size, px.
const SIZE: (u32, u32) = (900, 560);

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
    let grey = RGBColor(150, 150, 150);
    chart.draw_series(std::iter::once(PathElement::new(
        mm(&view.body),
        grey.stroke_width(2),
    )))?;
    chart.draw_series(
        view.wheels
            .iter()
            .map(|w| Polygon::new(mm(w), BLACK.mix(0.6).filled())),
    )?;
    let members = view
        .side_members
        .iter()
        .map(|m| PathElement::new(mm(m), BLUE.stroke_width(3)));
    chart.draw_series(members)?;
    match view.face {
        FaceShape::Segment(a, b) => {
            chart.draw_series(std::iter::once(PathElement::new(
                mm(&[a, b]),
                BLACK.mix(0.45).stroke_width(10),
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
                BLACK.mix(0.8).filled(),
            )))?;
        }
    }
    chart.draw_series(std::iter::once(PathElement::new(
        mm(&view.bumper),
        RED.stroke_width(4),
    )))?;
    Ok(())
}
