//! The posterior of an identified chain in the report (issue 39): a corner
//! plot (Foreman-Mackey 2016, `corner.py`) of the sampled draws — on the
//! diagonal each free parameter's marginal histogram with its 90 %
//! interval (grey) and the optimum (red), below it each pair's 2-D
//! histogram with the optimum marked — and the posterior's lines
//! ([`bumpsim_ident::posterior::lines`]: medians and 90 % and 95 % intervals next to
//! the local 95 % ones, the diagnostics and any warning).
//!
//! Values are drawn in each parameter's display unit (kg, Ns/mm, N/mm),
//! every axis named `m1 [kg]`. Each axis spans the draws' 0.5 % to 99.5 %
//! quantiles, so a long tail does not squeeze the rest into one bin.
//!
//! ```
//! use bumpsim_ident::posterior::{Diagnostics, Ensemble, Noise, Posterior};
//! let draws: Vec<Vec<f64>> = (0..400)
//!     .map(|k| { let a = (k as f64 * 0.37).sin(); vec![30.0 + a, 900.0 + 20.0 * (k as f64 * 0.71).cos(), 3e3, 6e5 * (1.0 + 0.05 * a)] })
//!     .collect();
//! let post = Posterior {
//!     names: ["m1", "m2", "c1", "k1"].map(String::from).to_vec(),
//!     mean: vec![30.0, 900.0, 3e3, 6e5], median: vec![30.0, 900.0, 3e3, 6e5],
//!     sd: vec![0.7, 14.0, 0.0, 2e4], ci90: vec![Some([29.0, 31.0]), Some([880.0, 920.0]), None, Some([5.7e5, 6.3e5])],
//!     ci95: vec![None; 4], fixed: vec![false, false, true, false], noise: Noise::Effective(50.0),
//!     ensemble: Ensemble { walkers: 16, steps: 100, burn: 25, seed: 1 },
//!     diagnostics: Diagnostics { autocorrelation_time: vec![], time_reliable: vec![], effective_draws: vec![],
//!         r_hat: vec![], acceptance: 0.4, converged: true, warnings: vec![] },
//!     draws,
//! };
//! let svg = bumpsim_report::posterior::corner(&post, 2, &[30.0, 900.0, 3e3, 6e5]).unwrap();
//! assert!(svg.contains("m1 [kg]") && svg.contains("k1 [N/mm]") && !svg.contains("c1 [Ns/mm]"));
//! ```

use crate::html::Html;
use crate::plot::{PlotError, drawable};
use bumpsim_core::model::parameter_kind;
use bumpsim_core::units::Unit;
use bumpsim_ident::estimate::Identification;
use bumpsim_ident::posterior::{Posterior, quantile};
use plotters::prelude::*;

/// Bins of a marginal histogram.
const BINS: usize = 30;
/// Bins along each axis of a pair's 2-D histogram.
const PAIR_BINS: usize = 20;
/// Pixels of one panel.
const PANEL: u32 = 150;
/// Pixels left of the grid (y labels) and below it (x labels).
const LEFT: u32 = 84;
/// Pixels below the grid.
const BOTTOM: u32 = 64;
/// Pixels above the grid (title).
const TOP: u32 = 40;

/// One free parameter of the plot: label, display unit, draws and range
/// in that unit, optimum and 90 % interval in it.
struct Axis {
    label: String,
    values: Vec<f64>,
    range: (f64, f64),
    optimum: f64,
    interval: Option<[f64; 2]>,
}

fn axes(post: &Posterior, dof: usize, optimum: &[f64]) -> Result<Vec<Axis>, PlotError> {
    let title = "posterior corner plot";
    let mut out = Vec::new();
    for i in (0..post.names.len()).filter(|&i| !post.fixed[i]) {
        let unit: Unit = parameter_kind(dof, i).0.dimension().display_unit();
        let values: Vec<f64> = post
            .draws
            .iter()
            .filter_map(|d| d.get(i).map(|&v| unit.from_si(v)))
            .filter(|v| v.is_finite())
            .collect();
        if values.is_empty() {
            return Err(PlotError::Empty {
                title: title.into(),
            });
        }
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        let (lo, hi) = (quantile(&sorted, 0.005), quantile(&sorted, 0.995));
        let pad = match hi > lo {
            true => 0.05 * (hi - lo),
            false => lo.abs().max(1e-9) * 0.01,
        };
        let range = (lo - pad, hi + pad);
        drawable(title, range.0, range.1)?;
        out.push(Axis {
            label: format!("{} [{}]", post.names[i], unit.symbol),
            values,
            range,
            optimum: optimum.get(i).map_or(f64::NAN, |&v| unit.from_si(v)),
            interval: post.ci90[i].map(|[a, b]| [unit.from_si(a), unit.from_si(b)]),
        });
    }
    match out.is_empty() {
        true => Err(PlotError::Empty {
            title: title.into(),
        }),
        false => Ok(out),
    }
}

/// The bin of `v` among `n` over `range`, if inside.
fn bin(v: f64, (lo, hi): (f64, f64), n: usize) -> Option<usize> {
    let t = (v - lo) / (hi - lo);
    (0.0..1.0)
        .contains(&t)
        .then(|| ((t * n as f64) as usize).min(n - 1))
}

/// The corner plot of `post` (a `dof`-mass chain's posterior; `optimum`
/// the identified parameters, SI, every parameter) as SVG.
pub fn corner(post: &Posterior, dof: usize, optimum: &[f64]) -> Result<String, PlotError> {
    crate::register_font();
    let axes = axes(post, dof, optimum)?;
    let d = axes.len() as u32;
    let size = (LEFT + d * PANEL + 16, TOP + d * PANEL + BOTTOM);
    let title = format!(
        "Posterior of the {dof}-DOF model ({} draws)",
        post.draws.len()
    );
    let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
        title: title.clone(),
        message: e.to_string(),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_error(&e))?;
        let grid = root
            .titled(&title, ("sans-serif", 20))
            .map_err(|e| draw_error(&e))?;
        let xs: Vec<u32> = (1..d).map(|c| LEFT + c * PANEL).collect();
        let ys: Vec<u32> = (1..d).map(|r| r * PANEL).collect();
        let panels = grid.split_by_breakpoints(xs, ys);
        for (k, area) in panels.iter().enumerate() {
            let (r, c) = (k / d as usize, k % d as usize);
            let last = r + 1 == d as usize;
            panel(area, &axes, (r, c), last).map_err(|e| draw_error(&e))?;
        }
        root.present().map_err(|e| draw_error(&e))?;
    }
    Ok(svg)
}

/// Panel (row `r`, column `c`): a marginal on the diagonal, a pair below
/// it, nothing above.
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    axes: &[Axis],
    (r, c): (usize, usize),
    last: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let label_areas = (if last { BOTTOM } else { 0 }, if c == 0 { LEFT } else { 0 });
    match c.cmp(&r) {
        std::cmp::Ordering::Equal => marginal(area, &axes[c], label_areas),
        std::cmp::Ordering::Less => pair(area, (&axes[c], &axes[r]), label_areas),
        std::cmp::Ordering::Greater => Ok(()),
    }
}

fn tick(v: &f64) -> String {
    bumpsim_core::units::format_number(*v, 3)
}

/// The marginal histogram of `axis`, its 90 % interval and the optimum.
fn marginal<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    axis: &Axis,
    (bottom, left): (u32, u32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut counts = [0usize; BINS];
    axis.values
        .iter()
        .filter_map(|&v| bin(v, axis.range, BINS))
        .for_each(|b| counts[b] += 1);
    let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64 * 1.1;
    let mut chart = ChartBuilder::on(area)
        .margin(4)
        .x_label_area_size(bottom)
        .y_label_area_size(left)
        .build_cartesian_2d(axis.range.0..axis.range.1, 0.0..top)?;
    let mut mesh = chart.configure_mesh();
    mesh.disable_mesh()
        .x_labels(3)
        .y_labels(0)
        .x_label_formatter(&tick)
        .label_style(("sans-serif", 11));
    if bottom > 0 {
        mesh.x_desc(axis.label.clone());
    }
    if left > 0 {
        mesh.y_desc("draws");
    }
    mesh.draw()?;
    let width = (axis.range.1 - axis.range.0) / BINS as f64;
    let fill = RGBColor(31, 119, 180);
    chart.draw_series(counts.iter().enumerate().map(|(k, &n)| {
        let x = axis.range.0 + k as f64 * width;
        Rectangle::new([(x, 0.0), (x + width, n as f64)], fill.mix(0.6).filled())
    }))?;
    let grey = RGBColor(110, 110, 110).stroke_width(1);
    for x in axis.interval.into_iter().flatten() {
        chart.draw_series([PathElement::new(vec![(x, 0.0), (x, top)], grey)])?;
    }
    let red = RGBColor(214, 39, 40).stroke_width(2);
    chart.draw_series([PathElement::new(
        vec![(axis.optimum, 0.0), (axis.optimum, top)],
        red,
    )])?;
    Ok(())
}

/// The 2-D histogram of the pair (`x`, `y`) and the optimum.
fn pair<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (x, y): (&Axis, &Axis),
    (bottom, left): (u32, u32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut counts = vec![0usize; PAIR_BINS * PAIR_BINS];
    for (&a, &b) in x.values.iter().zip(&y.values) {
        if let (Some(i), Some(j)) = (bin(a, x.range, PAIR_BINS), bin(b, y.range, PAIR_BINS)) {
            counts[i * PAIR_BINS + j] += 1;
        }
    }
    let most = counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    let mut chart = ChartBuilder::on(area)
        .margin(4)
        .x_label_area_size(bottom)
        .y_label_area_size(left)
        .build_cartesian_2d(x.range.0..x.range.1, y.range.0..y.range.1)?;
    let mut mesh = chart.configure_mesh();
    mesh.disable_mesh()
        .x_labels(3)
        .y_labels(3)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style(("sans-serif", 11));
    if bottom > 0 {
        mesh.x_desc(x.label.clone());
    }
    if left > 0 {
        mesh.y_desc(y.label.clone());
    }
    mesh.draw()?;
    let (wx, wy) = (
        (x.range.1 - x.range.0) / PAIR_BINS as f64,
        (y.range.1 - y.range.0) / PAIR_BINS as f64,
    );
    let cells = (0..PAIR_BINS * PAIR_BINS).filter(|&k| counts[k] > 0);
    chart.draw_series(cells.map(|k| {
        let (i, j) = (k / PAIR_BINS, k % PAIR_BINS);
        let (x0, y0) = (x.range.0 + i as f64 * wx, y.range.0 + j as f64 * wy);
        let shade = 0.15 + 0.85 * counts[k] as f64 / most;
        Rectangle::new(
            [(x0, y0), (x0 + wx, y0 + wy)],
            RGBColor(31, 119, 180).mix(shade).filled(),
        )
    }))?;
    let red = RGBColor(214, 39, 40).stroke_width(2);
    chart.draw_series([Cross::new((x.optimum, y.optimum), 5, red)])?;
    Ok(())
}

/// The report's posterior section of `result`: a heading, the lines, the
/// warnings and the corner plot (returned as the figure's file name,
/// `posterior-<dof>dof.svg`, and its SVG).
pub fn section(
    page: &mut Html,
    post: &Posterior,
    result: &Identification,
) -> Result<(String, String), PlotError> {
    page.heading(&format!("Posterior of the {}-DOF model", result.dof));
    page.preformatted(&bumpsim_ident::posterior::lines(post, result));
    page.warnings(&post.diagnostics.warnings);
    let svg = corner(post, result.dof, &result.model.parameters())?;
    page.figure(
        &svg,
        "corner plot: each free parameter's posterior histogram (grey: 90 % interval; red: the optimum) and each pair's 2-D histogram (red cross: the optimum); axes span the draws' 0.5–99.5 % quantiles",
    );
    Ok((format!("posterior-{}dof.svg", result.dof), svg))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_ident::posterior::{Diagnostics, Ensemble, Noise};

    fn posterior(draws: Vec<Vec<f64>>) -> Posterior {
        Posterior {
            names: ["m1", "m2", "c1", "k1"].map(String::from).to_vec(),
            mean: vec![30.0, 900.0, 3e3, 6e5],
            median: vec![30.0, 900.0, 3e3, 6e5],
            sd: vec![1.0; 4],
            ci90: vec![Some([29.0, 31.0]), Some([880.0, 920.0]), None, None],
            ci95: vec![None; 4],
            fixed: vec![false, false, false, false],
            noise: Noise::Effective(50.0),
            ensemble: Ensemble {
                walkers: 16,
                steps: 100,
                burn: 25,
                seed: 1,
            },
            diagnostics: Diagnostics {
                autocorrelation_time: vec![],
                time_reliable: vec![],
                effective_draws: vec![],
                r_hat: vec![],
                acceptance: 0.4,
                converged: true,
                warnings: vec![],
            },
            draws,
        }
    }

    #[test]
    fn every_pair_below_the_diagonal_and_every_marginal_is_drawn_with_units() {
        let draws = (0..500)
            .map(|k| {
                let (a, b) = ((k as f64 * 0.37).sin(), (k as f64 * 0.71).cos());
                vec![
                    30.0 + a,
                    900.0 + 20.0 * b,
                    3e3 * (1.0 + 0.1 * a * b),
                    6e5 + 1e4 * a,
                ]
            })
            .collect();
        let svg = corner(&posterior(draws), 2, &[30.0, 900.0, 3e3, 6e5]).unwrap();
        for label in ["m1 [kg]", "m2 [kg]", "c1 [Ns/mm]", "k1 [N/mm]"] {
            assert!(svg.contains(label), "{label}");
        }
        // 4 marginals of 30 bins at most, 6 pairs of at most 400 cells
        let rects = svg.matches("<rect").count();
        assert!(
            rects > 4 * 10 + 6 * 20 && rects < 1 + 4 * 30 + 6 * 400,
            "{rects}"
        );
        // the optimum: a red line per marginal and a red cross per pair
        assert!(svg.matches("#D62728").count() >= 4 + 6 * 2, "optimum marks");
        assert!(svg.contains("Posterior of the 2-DOF model (500 draws)"));
    }

    #[test]
    fn a_posterior_without_draws_is_an_error_not_a_panic() {
        let empty = corner(&posterior(vec![]), 2, &[1.0; 4]);
        assert!(matches!(empty, Err(PlotError::Empty { .. })), "{empty:?}");
        let nan = corner(&posterior(vec![vec![f64::NAN; 4]; 10]), 2, &[1.0; 4]);
        assert!(matches!(nan, Err(PlotError::Empty { .. })), "{nan:?}");
    }
}
