//! `identify` of a links study (issue 46 items 2 and 3): the linear chain
//! identified at the study's size ([`bumpsim_ident::identify`]) is the
//! staged start; the car with nonlinear links is identified as it ran
//! into the barrier ([`bumpsim_ident::links::into_wall`]: the wall force
//! and the output together, the test sheet's mass as a prior, the
//! settings of the study's `[links]`, [`bumpsim_ident::links::study`]);
//! the two are compared on the linear chain's residuals
//! ([`bumpsim_ident::links::verdict::compare_outputs`], BIC with the
//! reasons); and the identified car alone runs into a rigid wall at each
//! case's speed. Figures of that forward run over the case's window
//! `[a, b]` (h the sample interval, v0 the case's speed, y the output):
//!
//! ```text
//! force fit = 100 (1 − ‖F_sim − F_meas‖ / ‖F_meas − mean‖)
//! ΔV_meas = (y_b − y_(b−1)) / h − v0,  ΔV_sim = v_out(b) − v0
//! ΔV error = |ΔV_sim − ΔV_meas| / |ΔV_meas|
//! ```
//!
//! Each link's plastic set carries its 95 % interval (delta method,
//! [`bumpsim_ident::links::PlasticSet`]). No other equations here.

use super::forward::{self, Forward};
use crate::model::{IdentifyRequest, Progress};
use crate::{EngineError, Outcome};
use bumpsim_core::units::{Dimension, format_number, format_quantity};
use bumpsim_ident::Study;
use bumpsim_ident::links::study::LinksStudy;
use bumpsim_ident::links::verdict::{Verdict, compare_outputs};
use bumpsim_ident::links::{LinkIdentification, PlasticSet, into_wall};
use bumpsim_ident::study::DofSpec;
use bumpsim_io::link_car::LinkCar;
use serde::Serialize;

/// `identify` on a links study.
pub(super) fn identify(request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
    refuse(request)?;
    let study = Study::read(request.study).map_err(Box::new)?;
    let path = request.study;
    let spec = LinksStudy::of(study.links.as_ref()).map_err(|source| EngineError::LinksStudy {
        path: path.into(),
        source,
    })?;
    let dof = size(request, &study)?;
    let sheet = study.sheet_mass().map_err(Box::new)?;
    spec.check(dof, sheet)
        .map_err(|source| EngineError::LinksStudy {
            path: path.into(),
            source,
        })?;
    let loaded = study.load(dof).map_err(Box::new)?;
    let cases = &loaded.cases;
    let said = Said::new(request.progress);
    let notes: String = loaded
        .notes
        .iter()
        .map(|n| format!("note: {n}\n"))
        .collect();
    said.say(notes);
    let (starts, seed) = (
        request.starts.unwrap_or(study.model.starts),
        request.seed.unwrap_or(study.model.seed),
    );
    let mut settings = study.settings(dof).map_err(Box::new)?;
    (settings.starts, settings.seed) = (spec.linear_starts, seed);
    let progress = request.progress;
    let observer = || progress.start_finished();
    progress.stage(
        &format!("linear {dof}-DOF"),
        settings.starts as u64,
        "starts",
    );
    let linear = bumpsim_ident::identify(cases, &settings, &observer);
    progress.end();
    let linear = linear.map_err(|e| EngineError::Size {
        dof,
        source: Box::new(e),
    })?;
    said.say(linear_lines(&linear));
    let barrier = spec
        .settings(dof, (starts, seed), sheet, cases, &linear.model)
        .map_err(|source| EngineError::LinksStudy {
            path: path.into(),
            source,
        })?;
    progress.stage(&format!("links {dof}-DOF"), starts as u64, "starts");
    let found = into_wall::identify(cases, &barrier, &observer);
    progress.end();
    let found = found.map_err(|e| EngineError::LinkIdent(Box::new(e)))?;
    let whole = car_of(&found)?;
    let forward = cases
        .iter()
        .map(|case| Forward::run(case, &whole, path))
        .collect::<Result<Vec<_>, _>>()?;
    said.say(found_lines(&found, &forward, sheet, &spec));
    let verdict =
        compare_outputs(&linear, &found, cases).map_err(|e| EngineError::LinkIdent(Box::new(e)))?;
    said.say(format!(
        "which links the data want (on the linear chain's residuals of the output):\n{}",
        verdict
            .reasons
            .iter()
            .map(|r| format!("  {r}\n"))
            .collect::<String>()
    ));
    let name = format!("identified from {}", path.display());
    let car = LinkCar {
        name: Some(name.clone()),
        chain: whole,
    };
    let mut warnings = loaded.warnings.clone();
    warnings.extend(forward.iter().flat_map(|f| f.warnings.iter().cloned()));
    let document = Document::of(&name, &linear, &found, &forward, &verdict, sheet, &warnings);
    let json = serde_json::to_string_pretty(&document)?;
    let report = match request.report {
        true => Some(forward::report(&name, &said.text(), &forward)?),
        false => None,
    };
    Ok(Outcome {
        text: said.text(),
        warnings,
        json,
        report,
        car: request.car.then(|| car.to_toml()),
        ..Outcome::default()
    })
}

/// The identified car whole: its chain, front zone, second path and
/// rebound link.
pub(super) fn car_of(
    found: &LinkIdentification,
) -> Result<bumpsim_core::chain::Chain, EngineError> {
    let mut chain = found.chain.clone();
    if let Some(front) = &found.front {
        chain = chain.with_front(front.clone());
    }
    let walls = [(&found.path, false), (&found.rebound, true)];
    for (wall, rebound) in walls {
        if let Some(w) = wall {
            let link = w.link.clone();
            chain = match rebound {
                false => chain.with_path(w.mass, w.gap, link),
                true => chain.with_rebound(w.mass, w.gap, link),
            }
            .map_err(|e| EngineError::LinkIdent(Box::new(e.into())))?;
        }
    }
    Ok(chain)
}

/// The options a links identification has no use for, refused by name.
fn refuse(request: &IdentifyRequest<'_>) -> Result<(), EngineError> {
    let refuse = |option: &str, reason: &str| {
        Err(EngineError::Unsupported {
            option: option.into(),
            reason: format!("a links study {reason}"),
        })
    };
    if request.posterior.is_some() {
        return refuse(
            "--posterior",
            "has no posterior sampling yet (its plastic sets carry 95 % intervals by the delta method); leave --posterior out",
        );
    }
    if request.sensitivity {
        return refuse(
            "--sensitivity",
            "has no ±3 % sensitivity sweep yet; leave --sensitivity out",
        );
    }
    Ok(())
}

/// The one model size identified: `--dof`'s, else the study's (one).
fn size(request: &IdentifyRequest<'_>, study: &Study) -> Result<usize, EngineError> {
    let sizes = match request.sizes {
        Some(sizes) => sizes.to_vec(),
        None => match &study.model.dof {
            DofSpec::One(n) => vec![*n],
            DofSpec::Many(list) => list.clone(),
        },
    };
    match sizes.as_slice() {
        [dof] if *dof >= 2 => Ok(*dof),
        _ => Err(EngineError::Refused {
            path: request.study.into(),
            reason: format!(
                "[model] dof (or --dof) = {sizes:?}: a links study identifies one model size of 2 masses or more (dof = 2)"
            ),
        }),
    }
}

/// The text said as it comes: to the progress and kept.
struct Said<'a> {
    progress: &'a dyn Progress,
    text: std::cell::RefCell<String>,
}

impl<'a> Said<'a> {
    fn new(progress: &'a dyn Progress) -> Said<'a> {
        Said {
            progress,
            text: std::cell::RefCell::new(String::new()),
        }
    }

    fn say(&self, text: String) {
        if !text.is_empty() {
            self.progress.text(&text);
            self.text.borrow_mut().push_str(&text);
        }
    }

    fn text(&self) -> String {
        self.text.borrow().clone()
    }
}

fn percent(x: f64) -> String {
    format!("{} %", format_number(x, 4))
}

fn mm(x: f64) -> String {
    format!("{} mm", format_number(1e3 * x, 4))
}

/// The linear chain's lines.
fn linear_lines(linear: &bumpsim_ident::estimate::Identification) -> String {
    let mut out = format!(
        "linear chain, {}-DOF (the staged start): objective {} {}\n",
        linear.dof,
        format_number(linear.objective, 5),
        linear.objective_unit()
    );
    for case in &linear.cases {
        out += &format!("  fit {}: {}\n", case.name, percent(case.fit_percent));
    }
    out
}

/// What a plastic set belongs to.
pub(super) fn link_name(found: &LinkIdentification, link: usize) -> String {
    let dof = found.layout.dof;
    match link {
        0 => "front crush zone".into(),
        j if found.path.is_some() && j == dof => "second load path".into(),
        j if found.rebound.is_some() && j == dof + usize::from(found.path.is_some()) => {
            "rebound link".into()
        }
        j => format!("link {j}"),
    }
}

/// The identified car's lines: per case the fits, the forward run, the
/// plastic sets; the parameters; the total mass against the sheet's.
fn found_lines(
    found: &LinkIdentification,
    forward: &[Forward],
    sheet: Option<f64>,
    spec: &LinksStudy,
) -> String {
    let path = match spec.path_knots {
        0 => "no second path".to_string(),
        j => format!("a {j}-knot second path"),
    };
    let rebound = found
        .rebound
        .as_ref()
        .map_or("no rebound link".into(), |r| {
            format!("a rebound link on m{}", r.mass + 1)
        });
    let mut out = format!(
        "\nchain with nonlinear links into the barrier, {} masses ({}-knot front crush zone, {path}, {rebound}):\n",
        found.layout.dof, spec.knots
    );
    for ((case, fit), f) in found.fits.iter().zip(forward) {
        let force = found
            .force_fits
            .iter()
            .find(|(c, _)| c == case)
            .map_or(f64::NAN, |c| c.1);
        out += &format!(
            "  {case}: fit {} (output), {} (wall force)\n",
            percent(*fit),
            percent(force)
        );
        out += &format!(
            "  {case}: forward into a rigid wall at {} from the identified car alone: wall force fit {}, output ΔV {} (measured {}, {} off)\n",
            format_number(3.6 * f.speed, 4) + " km/h",
            percent(f.force_fit),
            format_quantity(f.delta_v, Dimension::Velocity),
            format_quantity(f.measured_delta_v, Dimension::Velocity),
            percent(100.0 * f.delta_v_error)
        );
    }
    for set in &found.plastic_sets {
        let interval = set.ci95.map_or("no interval".into(), |[a, b]| {
            format!("[{}, {}]", mm(a), mm(b))
        });
        out += &format!(
            "  plastic set of {} after {}: {}  95 % {interval}\n",
            forward::the(&link_name(found, set.link)),
            set.case,
            mm(set.value)
        );
    }
    out += "  parameters (95 % intervals):\n";
    let u = &found.uncertainty;
    for (i, p) in found.parameters.iter().enumerate() {
        let interval = match u.ci95[i] {
            Some([a, b]) => format!("[{}, {}]", p.format(a), p.format(b)),
            None if u.fixed[i] => "fixed".into(),
            None if u.at_bound[i] => "at a bound".into(),
            None => "no interval".into(),
        };
        out += &format!(
            "    {:<4} {:>14}  {interval}\n",
            p.name,
            p.format(found.theta[i])
        );
    }
    let total: f64 = found.chain.masses().iter().sum();
    out += &format!("  total mass {}", format_quantity(total, Dimension::Mass));
    out += &match (sheet, found.moved.first()) {
        (Some(m), Some(moved)) => format!(
            ", test sheet {} ({:+.1} %, {:+.1} sd of its ±{:.2} % prior)\n",
            format_quantity(m, Dimension::Mass),
            100.0 * (total / m - 1.0),
            moved.z,
            100.0 * spec.mass_spread
        ),
        (Some(m), None) => format!(", test sheet {}\n", format_quantity(m, Dimension::Mass)),
        (None, _) => " (no test sheet mass: [model] mass)\n".into(),
    };
    out
}

/// One parameter in the JSON document (SI).
#[derive(Debug, Serialize)]
struct ParameterFigure {
    name: String,
    /// SI unit.
    unit: &'static str,
    value: f64,
    ci95: Option<[f64; 2]>,
}

/// One plastic set in the JSON document, m.
#[derive(Debug, Serialize)]
struct SetFigure<'a> {
    /// What it belongs to (`front crush zone`, `link 1`, ...).
    name: String,
    #[serde(flatten)]
    set: &'a PlasticSet,
}

/// The linear chain in the JSON document.
#[derive(Debug, Serialize)]
struct LinearFigures {
    dof: usize,
    /// Σ r², the linear chain's objective.
    objective: f64,
    /// Each case's fit, %.
    fits: Vec<(String, f64)>,
}

/// The comparison in the JSON document.
#[derive(Debug, Serialize)]
struct VerdictFigures<'a> {
    /// Whether the data want the nonlinear links.
    yielding: bool,
    /// BIC of the linear and the nonlinear chain.
    bic: [f64; 2],
    reasons: &'a [String],
}

/// `identify --json` of a links study (SI).
#[derive(Debug, Serialize)]
struct Document<'a> {
    kind: &'static str,
    car: &'a str,
    dof: usize,
    linear: LinearFigures,
    /// Each case's fit (output) and wall force fit, %.
    fits: &'a [(String, f64)],
    force_fits: &'a [(String, f64)],
    forward: &'a [Forward],
    plastic_sets: Vec<SetFigure<'a>>,
    parameters: Vec<ParameterFigure>,
    /// Σ m, kg.
    total_mass: f64,
    /// The test sheet's, kg.
    sheet_mass: Option<f64>,
    verdict: VerdictFigures<'a>,
    warnings: &'a [String],
}

impl<'a> Document<'a> {
    fn of(
        name: &'a str,
        linear: &bumpsim_ident::estimate::Identification,
        found: &'a LinkIdentification,
        forward: &'a [Forward],
        verdict: &'a Verdict,
        sheet_mass: Option<f64>,
        warnings: &'a [String],
    ) -> Document<'a> {
        use bumpsim_estimate::uncertainty::ParameterUnit;
        let parameters = found
            .parameters
            .iter()
            .enumerate()
            .map(|(i, p)| ParameterFigure {
                name: p.name.clone(),
                unit: match p.unit {
                    ParameterUnit::Dimension(d) => d.si_symbol(),
                    ParameterUnit::Symbol(s) => s,
                },
                value: found.theta[i],
                ci95: found.uncertainty.ci95[i],
            })
            .collect();
        Document {
            kind: "links",
            car: name,
            dof: found.layout.dof,
            linear: LinearFigures {
                dof: linear.dof,
                objective: linear.objective,
                fits: linear
                    .cases
                    .iter()
                    .map(|c| (c.name.clone(), c.fit_percent))
                    .collect(),
            },
            fits: &found.fits,
            force_fits: &found.force_fits,
            forward,
            plastic_sets: found
                .plastic_sets
                .iter()
                .map(|set| SetFigure {
                    name: link_name(found, set.link),
                    set,
                })
                .collect(),
            parameters,
            total_mass: found.chain.masses().iter().sum(),
            sheet_mass,
            verdict: VerdictFigures {
                yielding: verdict.yielding,
                bic: verdict.bic,
                reasons: &verdict.reasons,
            },
            warnings,
        }
    }
}
