//! A links car run forward into a rigid wall at a study case's speed
//! (`identify` and `predict` of a links study): the wall force and the
//! output against the case's measurements over its window `[a, b]` (h the
//! sample interval, v0 the case's speed):
//!
//! ```text
//! fit = 100 (1 − ‖s_sim − s_meas‖ / ‖s_meas − mean‖)     (force; output y)
//! ΔV_meas = (y_b − y_(b−1)) / h − v0,  ΔV_sim = v_out(b) − v0
//! ΔV error = |ΔV_sim − ΔV_meas| / |ΔV_meas|
//! ```
//!
//! and each link's plastic set at the end of the run, `δ_p = δ_max −
//! F(δ_max)/k_u` ([`bumpsim_core::link::LinkState::plastic_set`]): the
//! front zone's δ_max is m1's largest travel into the wall, a wall link's
//! (second path, rebound link) its mass's largest travel past its gap.
//! The report draws the measured and forward wall force and output.

use crate::model::PredictRequest;
use crate::{EngineError, Outcome, Report};
use bumpsim_core::chain::{Chain, ChainResponse, Drive};
use bumpsim_core::link::LinkState;
use bumpsim_core::units::{Dimension, format_number, format_quantity};
use bumpsim_ident::case::LoadCase;
use bumpsim_io::link_car::LinkCar;
use bumpsim_report::html::Html;
use bumpsim_report::plot::{LinePlot, Series, Style};
use serde::Serialize;
use std::path::Path;

/// A link's plastic set after a run, m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Set {
    /// `front crush zone`, `link j`, `second load path`, `rebound link`.
    pub name: String,
    /// Largest compression, m.
    pub max_compression: f64,
    /// Plastic set, m.
    pub plastic_set: f64,
}

/// Every link's set after the run `r` of `chain` into the wall (the
/// module's rule), the front zone first, the wall links last.
pub fn sets(chain: &Chain, r: &ChainResponse) -> Vec<Set> {
    let most = |x: &mut dyn Iterator<Item = f64>| x.fold(0.0_f64, f64::max);
    let mut out = Vec::new();
    if let Some(front) = chain.front() {
        let reached = most(&mut r.displacement[0].iter().copied());
        out.push(Set {
            name: "front crush zone".into(),
            max_compression: reached,
            plastic_set: LinkState { reached }.plastic_set(front),
        });
    }
    for j in 0..chain.links().len() {
        out.push(Set {
            name: format!("link {}", j + 1),
            max_compression: r.reached[j],
            plastic_set: r.plastic_set[j],
        });
    }
    let walls = [
        ("second load path", chain.path()),
        ("rebound link", chain.rebound()),
    ];
    for (name, wall) in walls {
        if let Some(w) = wall {
            let reached = most(&mut r.displacement[w.mass].iter().map(|x| x - w.gap));
            out.push(Set {
                name: name.into(),
                max_compression: reached,
                plastic_set: LinkState { reached }.plastic_set(&w.link),
            });
        }
    }
    out
}

/// A link's name in a sentence: `the front crush zone`, `link 1`.
pub fn the(name: &str) -> String {
    match name.starts_with("link") {
        true => name.to_string(),
        false => format!("the {name}"),
    }
}

/// One case's forward run and its figures.
#[derive(Debug, Clone, Serialize)]
pub struct Forward {
    /// The case.
    pub case: String,
    /// The impact speed, m/s.
    pub speed: f64,
    /// Fit of the wall force over the window, %.
    pub force_fit: f64,
    /// Fit of the output over the window, %.
    pub output_fit: f64,
    /// The output's ΔV at the window's end, m/s.
    pub delta_v: f64,
    /// The measured ΔV, m/s.
    pub measured_delta_v: f64,
    /// |ΔV − measured| / |measured|.
    pub delta_v_error: f64,
    /// Largest |wall force|, N.
    pub peak_force: f64,
    /// Each link's plastic set at the end of the run.
    pub sets: Vec<Set>,
    /// The run's own checks.
    pub warnings: Vec<String>,
    /// Time, s, the measured and forward wall force, N, the measured and
    /// forward output, m, over the window (the report's).
    #[serde(skip)]
    histories: [Vec<f64>; 5],
}

impl Forward {
    /// `chain` (read from `path`) into the wall at `case`'s speed over its
    /// samples.
    pub fn run(case: &LoadCase, chain: &Chain, path: &Path) -> Result<Forward, EngineError> {
        let drive = Drive::Barrier {
            speed: case.initial_velocity,
            step: case.step,
            samples: case.window.1 + 1,
        };
        let r = chain.run(&drive).map_err(|source| EngineError::Run {
            path: path.into(),
            source,
        })?;
        let (a, b) = case.window;
        let Some(y) = r.displacement.get(case.output_dof.wrapping_sub(1)) else {
            return Err(EngineError::Refused {
                path: path.into(),
                reason: format!(
                    "case '{}' measures mass {}; the car has {}",
                    case.name,
                    case.output_dof,
                    chain.dof()
                ),
            });
        };
        let v = &r.velocity[case.output_dof - 1];
        let (h, v0) = (case.step, case.initial_velocity);
        let measured_delta_v = (case.measured[b] - case.measured[b.saturating_sub(1)]) / h - v0;
        let delta_v = v[b] - v0;
        let mut warnings = Vec::new();
        let energy = r.energy_error();
        if energy.is_nan() || energy >= super::ENERGY_TOLERANCE {
            warnings.push(format!(
                "case '{}': the forward run's energy balance error {energy:.3} exceeds {}",
                case.name,
                super::ENERGY_TOLERANCE
            ));
        }
        let time = (a..=b).map(|k| k as f64 * h).collect();
        Ok(Forward {
            case: case.name.clone(),
            speed: v0,
            force_fit: bumpsim_estimate::fit::percent(&r.force[a..=b], &case.force[a..=b]),
            output_fit: case.fit(y).1,
            delta_v,
            measured_delta_v,
            delta_v_error: (delta_v - measured_delta_v).abs() / measured_delta_v.abs(),
            peak_force: r.force.iter().fold(0.0_f64, |m, f| m.max(f.abs())),
            sets: sets(chain, &r),
            warnings,
            histories: [
                time,
                case.force[a..=b].to_vec(),
                r.force[a..=b].to_vec(),
                case.measured[a..=b].to_vec(),
                y[a..=b].to_vec(),
            ],
        })
    }

    /// The forward run's line (speed, force fit, ΔV).
    pub fn line(&self) -> String {
        format!(
            "{}: into a rigid wall at {} km/h: wall force fit {} %, output fit {} %, output ΔV {} (measured {}, {} % off)\n",
            self.case,
            format_number(3.6 * self.speed, 4),
            format_number(self.force_fit, 4),
            format_number(self.output_fit, 4),
            format_quantity(self.delta_v, Dimension::Velocity),
            format_quantity(self.measured_delta_v, Dimension::Velocity),
            format_number(100.0 * self.delta_v_error, 3)
        )
    }

    /// The two plots of the case: wall force and output, measured and
    /// forward.
    pub fn plots(&self) -> Result<[String; 2], EngineError> {
        let [t, f_meas, f_sim, y_meas, y_sim] = &self.histories;
        let mut force = LinePlot::new(
            &format!("{}: wall force", self.case),
            Dimension::Time,
            Dimension::Force,
        );
        force.add(Series::new(
            "measured",
            t.clone(),
            f_meas.clone(),
            Style::Solid,
        ));
        force.add(Series::new(
            "forward",
            t.clone(),
            f_sim.clone(),
            Style::Dashed,
        ));
        let mut output = LinePlot::new(
            &format!("{}: output displacement", self.case),
            Dimension::Time,
            Dimension::Length,
        );
        output.add(Series::new(
            "measured",
            t.clone(),
            y_meas.clone(),
            Style::Solid,
        ));
        output.add(Series::new(
            "forward",
            t.clone(),
            y_sim.clone(),
            Style::Dashed,
        ));
        Ok([force.svg()?, output.svg()?])
    }
}

/// The report: the text, then each case's measured and forward force and
/// output.
pub fn report(title: &str, text: &str, forward: &[Forward]) -> Result<Report, EngineError> {
    let mut page = Html::new(title);
    page.heading("Result");
    page.preformatted(text);
    let mut figures = Vec::new();
    for f in forward {
        let [force, output] = f.plots()?;
        let name = bumpsim_report::file_name(&f.case);
        page.figure(&force, "measured and forward wall force");
        page.figure(&output, "measured and forward output");
        figures.push((format!("force-{name}.svg"), force));
        figures.push((format!("output-{name}.svg"), output));
    }
    Ok(Report {
        html: page.finish(),
        figures,
        inputs: Vec::new(),
    })
}

/// `predict` as a request asks it: the links car file and the study's
/// cases (those named, or all) read, then [`predict`].
pub fn requested(request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
    let text =
        bumpsim_core::files::read_car_text(request.car).map_err(bumpsim_io::car::CarError::from)?;
    let car = LinkCar::parse(&text, request.car)?;
    let study = bumpsim_ident::Study::read(request.study).map_err(Box::new)?;
    let loaded = study
        .load_named(car.chain.dof(), request.cases)
        .map_err(Box::new)?;
    let name = car
        .name
        .clone()
        .unwrap_or_else(|| request.car.display().to_string());
    let mut outcome = predict(&name, &car.chain, request.car, &loaded.cases, request.plot)?;
    outcome.warnings.splice(0..0, loaded.warnings);
    Ok(outcome)
}

/// `predict` of a links car on the cases of a links study: each case run
/// into the wall at its speed.
pub fn predict(
    name: &str,
    chain: &Chain,
    path: &Path,
    cases: &[LoadCase],
    plot: bool,
) -> Result<Outcome, EngineError> {
    let forward = cases
        .iter()
        .map(|case| Forward::run(case, chain, path))
        .collect::<Result<Vec<_>, _>>()?;
    let mut text = String::new();
    for f in &forward {
        text += &f.line();
        for set in &f.sets {
            text += &format!(
                "  plastic set of {}: {} (largest compression {})\n",
                the(&set.name),
                format_quantity(set.plastic_set, Dimension::Length),
                format_quantity(set.max_compression, Dimension::Length)
            );
        }
    }
    let warnings: Vec<String> = forward.iter().flat_map(|f| f.warnings.clone()).collect();
    let mut plots = Vec::new();
    if plot {
        for f in &forward {
            let [force, output] = f.plots()?;
            let file = bumpsim_report::file_name(&f.case);
            plots.push((format!("predict-{file}-force.svg"), force));
            plots.push((format!("predict-{file}-output.svg"), output));
        }
    }
    #[derive(Serialize)]
    struct Predicted<'a> {
        kind: &'static str,
        car: &'a str,
        cases: &'a [Forward],
        warnings: &'a [String],
    }
    let document = Predicted {
        kind: "links",
        car: name,
        cases: &forward,
        warnings: &warnings,
    };
    let json = serde_json::to_string_pretty(&document)?;
    Ok(Outcome {
        text: format!("{name}\n{text}"),
        warnings,
        json,
        plots,
        ..Outcome::default()
    })
}
