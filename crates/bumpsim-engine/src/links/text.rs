//! The links chain's impact as text, JSON, CSV and report pages (the
//! figures of [`super::Crush`]; no equations beyond the sums of its
//! energy terms: dissipated = viscous + plastic).

use super::struck::StrikerFigures;
use super::{Crush, Energy};
use crate::{EngineError, Outcome, Report};
use bumpsim_core::chain::Chain;
use bumpsim_core::units::{Dimension, format_quantity};
use bumpsim_report::html::Html;
use bumpsim_report::plot::{LinePlot, Series, Style};
use serde::Serialize;

/// A link's figures in the JSON document.
#[derive(Debug, Clone, PartialEq, Serialize)]
struct LinkFigures {
    /// `front` or `link j` (between m_j and m_(j+1)).
    name: String,
    /// Largest compression, m.
    max_compression: f64,
    /// Plastic set at the end, m.
    plastic_set: f64,
}

/// `bumpsim impact --json` of a car with nonlinear links (SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
struct LinksImpact<'a> {
    /// The model kind (`links`).
    kind: &'static str,
    /// The car's name.
    car: &'a str,
    /// What hit what.
    scenario: &'a str,
    /// Impact speed, m/s.
    speed: f64,
    /// Largest |barrier force|, N.
    peak_force: f64,
    /// Its time, s.
    peak_time: f64,
    /// The last time the wall pushes, s.
    contact_time: f64,
    /// The centre of mass's speed at the end, m/s.
    final_speed: f64,
    /// Each link's figures, the front link first.
    links: Vec<LinkFigures>,
    /// The energy balance at the end, J.
    energy: Energy,
    /// Dissipated work (viscous + plastic), J.
    dissipated: f64,
    /// The striker's figures (a pendulum or moving barrier run only).
    #[serde(skip_serializing_if = "Option::is_none")]
    striker: Option<StrikerFigures>,
    /// Sample interval of the histories, s.
    step: f64,
    /// The result's own checks.
    warnings: Vec<String>,
}

fn links(chain: &Chain, crush: &Crush) -> Vec<LinkFigures> {
    let front = crush.front.map(|(reached, set)| LinkFigures {
        name: "front".into(),
        max_compression: reached,
        plastic_set: set,
    });
    let r = &crush.response;
    // an elastic link keeps no history (its δ_max stays 0): its largest
    // compression is read from the samples, x_(j+1) − x_j in the car's frame
    let sampled = |j: usize| {
        r.displacement[j + 1]
            .iter()
            .zip(&r.displacement[j])
            .fold(0.0_f64, |m, (behind, ahead)| m.max(behind - ahead))
    };
    let between = (0..chain.links().len()).map(|j| LinkFigures {
        name: format!("link {}", j + 1),
        max_compression: r.reached[j].max(sampled(j)),
        plastic_set: r.plastic_set[j],
    });
    // the wall links (second path, rebound link): their mass's travel past the gap
    let walls = super::forward::sets(chain, r)
        .into_iter()
        .filter(|s| ["second load path", "rebound link"].contains(&s.name.as_str()))
        .map(|s| LinkFigures {
            name: s.name,
            max_compression: s.max_compression,
            plastic_set: s.plastic_set,
        });
    front.into_iter().chain(between).chain(walls).collect()
}

fn length(x: f64) -> String {
    format_quantity(x, Dimension::Length)
}

fn energy(x: f64) -> String {
    format_quantity(x, Dimension::Energy)
}

/// The summary lines.
fn summary(figures: &[LinkFigures], crush: &Crush) -> String {
    let (peak, at) = crush.peak;
    let what = match crush.striker {
        None => "barrier",
        Some(_) => "contact",
    };
    let mut text = format!(
        "  peak {what} force {} at {}\n",
        format_quantity(peak, Dimension::Force),
        format_quantity(at, Dimension::Time)
    );
    for f in figures {
        let what = match f.name.as_str() {
            "front" => "front link (crush zone)".to_string(),
            other => other.to_string(),
        };
        text += &format!(
            "  {what}: largest compression {}, plastic set {}\n",
            length(f.max_compression),
            length(f.plastic_set)
        );
    }
    let contact = format_quantity(crush.contact_time, Dimension::Time);
    text += &match crush.striker_figures() {
        None => format!(
            "  contact time {contact}; speed of the centre of mass at the end {}\n",
            format_quantity(crush.final_speed, Dimension::Velocity)
        ),
        Some(figures) => super::struck::summary(&contact, &figures),
    };
    let e = crush.energy();
    // the penalty contact's share, only without a front link
    let wall = match e.wall == 0.0 {
        true => String::new(),
        false => format!(" + wall contact {}", energy(e.wall)),
    };
    text += &format!(
        "  energy: initial kinetic {} = kinetic {} + stored {} + dissipated {} (viscous {}, plastic {}){wall}; relative energy balance error {:.2e}\n",
        energy(e.initial),
        energy(e.kinetic),
        energy(e.stored),
        energy(e.viscous + e.plastic),
        energy(e.viscous),
        energy(e.plastic),
        e.relative_error
    );
    text
}

/// The histories as CSV (SI): time, the wall's force, each mass's x and
/// v, each link's force, the energy terms.
fn histories(chain: &Chain, crush: &Crush) -> String {
    let r = &crush.response;
    let mut csv = String::from("time [s],force [N]");
    for i in 1..=chain.dof() {
        csv += &format!(",x m{i} [m],v m{i} [m/s]");
    }
    for j in 1..=chain.links().len() {
        csv += &format!(",link {j} force [N]");
    }
    csv += ",kinetic [J],stored [J],viscous [J],plastic [J]\n";
    for k in 0..r.force.len() {
        csv += &format!("{},{}", k as f64 * r.step, r.force[k]);
        for (x, v) in r.displacement.iter().zip(&r.velocity) {
            csv += &format!(",{},{}", x[k], v[k]);
        }
        for s in &r.link_force {
            csv += &format!(",{}", s[k]);
        }
        csv += &format!(
            ",{},{},{},{}\n",
            r.kinetic[k], r.stored[k], r.viscous[k], r.plastic[k]
        );
    }
    csv
}

/// The report: the summary, the wall's force and the energy terms over time.
fn report(title: &str, summary: &str, crush: &Crush) -> Result<Report, EngineError> {
    let r = &crush.response;
    let time: Vec<f64> = (0..r.force.len()).map(|k| k as f64 * r.step).collect();
    let mut force = LinePlot::new("barrier force", Dimension::Time, Dimension::Force);
    let pushed: Vec<f64> = r.force.iter().map(|f| -f).collect();
    force.add(Series::new(
        "wall on car (pushing back)",
        time.clone(),
        pushed,
        Style::Solid,
    ));
    let mut energies = LinePlot::new("energy balance", Dimension::Time, Dimension::Energy);
    for (name, values, style) in [
        ("kinetic", &r.kinetic, Style::Solid),
        ("stored", &r.stored, Style::Dashed),
        ("viscous", &r.viscous, Style::Dashed),
        ("plastic", &r.plastic, Style::Solid),
    ] {
        energies.add(Series::new(name, time.clone(), values.clone(), style));
    }
    let (force, energies) = (force.svg()?, energies.svg()?);
    let mut page = Html::new(title);
    page.heading("Result");
    page.preformatted(summary);
    page.figure(&force, "the barrier's force on the car over time");
    page.figure(
        &energies,
        "kinetic, stored, viscous and plastic energy over time",
    );
    Ok(Report {
        html: page.finish(),
        figures: vec![("force.svg".into(), force), ("energy.svg".into(), energies)],
        inputs: Vec::new(),
    })
}

/// The outcome of an impact of the car `name` (`label`: what hit what).
pub(super) fn outcome(
    name: &str,
    label: &str,
    chain: &Chain,
    crush: &Crush,
    with_report: bool,
) -> Result<Outcome, EngineError> {
    let figures = links(chain, crush);
    let summary = summary(&figures, crush);
    let mut warnings = crush.warnings();
    warnings.extend(super::unloading::replaced(chain, crush));
    let heading = format!("{name}: {label}");
    let e = crush.energy();
    let document = LinksImpact {
        kind: "links",
        car: name,
        scenario: label,
        speed: crush.speed,
        peak_force: crush.peak.0,
        peak_time: crush.peak.1,
        contact_time: crush.contact_time,
        final_speed: crush.final_speed,
        links: figures,
        energy: e,
        dissipated: e.viscous + e.plastic,
        striker: crush.striker_figures(),
        step: crush.response.step,
        warnings: warnings.clone(),
    };
    let report = match with_report {
        true => Some(report(&heading, &summary, crush)?),
        false => None,
    };
    Ok(Outcome {
        text: format!("{heading}\n{summary}"),
        warnings,
        json: serde_json::to_string_pretty(&document)?,
        csv: histories(chain, crush),
        report,
        ..Outcome::default()
    })
}
