//! `verdict` of a car with nonlinear links: one links car file per end
//! with its `[damageability]` table (or a limits file merged in, as the
//! planar car's), each selected test run along the car's centre line by
//! this model ([`super::Crush::of_scenario`]: the rigid barrier, or a
//! pendulum or moving barrier of the test's mass; UN R42's laden runs
//! carry their load on the body, the last mass, the impactor keeping the
//! unladen mass) and judged by [`bumpsim_verdict::line`] on the planar
//! car's criteria. From a run, in the car's frame (x towards the struck
//! end, compressions positive):
//!
//! ```text
//! beam travel      = x_n − x_1                       (Σ link compressions)
//! crash box        = x_2 − x_1                       (link 1)
//! force into body  = s_(n−1) + c_(n−1) (v_n − v_(n−1))   (the last link)
//! bumper energy    = the front link's plastic work
//! structure        = W_viscous + (W_plastic − bumper) + E_stored(end)
//! ```
//!
//! with the bumper's crush the front link's (`x_1 − x_s`). The bumper
//! target region, sequences, the car's uncertainty and a replacement
//! bumper are the planar car's: refused by name.

use super::Crush;
use crate::EngineError;
use crate::model::{End, Judged, VerdictRequest};
use bumpsim_core::chain::Chain;
use bumpsim_core::link::LinkState;
use bumpsim_io::link_car::LinkCar;
use bumpsim_verdict::criteria::Energies;
use bumpsim_verdict::limits::{Damageability, End as Side};
use bumpsim_verdict::line::{self, Judging, LineRun};
use bumpsim_verdict::prelude::{Test, TestVerdict, VerdictError};
use std::path::Path;

/// One end of a links car: its file, the car and its limits.
struct LineEnd {
    path: std::path::PathBuf,
    name: Option<String>,
    chain: Chain,
    limits: Damageability,
}

/// `verdict` of links cars: the ends judged in the tests.
pub(super) fn verdict(request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
    refuse_options(request)?;
    let names: Vec<&str> = request.protocols.iter().map(String::as_str).collect();
    let tests = bumpsim_verdict::protocol::select_in(&names, request.market).map_err(|source| {
        EngineError::VerdictIn {
            context: "--protocol".into(),
            source: Box::new(source),
        }
    })?;
    let ends = request
        .ends
        .iter()
        .map(read_end)
        .collect::<Result<Vec<_>, _>>()?;
    let mut slots: [Option<&LineEnd>; 2] = [None, None];
    for end in &ends {
        let slot = &mut slots[matches!(end.limits.end, Side::Rear) as usize];
        if slot.is_some() {
            return Err(VerdictError::two_cars_for(end.limits.end.name()).into());
        }
        *slot = Some(end);
    }
    let margin = request.margin;
    let expected = "a margin is a share of each limit, 0 ≤ margin < 1 (0.1: keep 10 % inside every limit); a negative margin would pass what fails";
    if !(0.0..1.0).contains(&margin) {
        return Err(VerdictError::Value {
            key: "margin".into(),
            value: margin,
            unit: "(a share of each limit)",
            expected: expected.into(),
        }
        .into());
    }
    let mut judged = Vec::with_capacity(tests.len());
    for test in &tests {
        judged.push(match slots[matches!(test.end, Side::Rear) as usize] {
            None => line::not_assessed(test),
            Some(end) => judge(end, test, request)?,
        });
    }
    let car = ends
        .iter()
        .find_map(|e| e.name.clone())
        .unwrap_or_else(|| "car".into());
    Ok(Judged {
        verdict: line::verdict(car, margin, &tests, judged),
        region: None,
        indices: None,
    })
}

/// The options only the planar car's verdict has, refused by name.
fn refuse_options(request: &VerdictRequest<'_>) -> Result<(), EngineError> {
    let refused = [
        (request.target, "--target"),
        (request.sequence, "--sequence"),
        (request.uncertainty.is_some(), "--uncertainty"),
        (request.bumper.is_some(), "bumper"),
    ];
    match refused.iter().find(|(given, _)| *given) {
        Some((_, option)) => Err(EngineError::Unsupported {
            option: (*option).into(),
            reason: "a car with nonlinear links is judged test by test on its own crush zone: the bumper target region, sequences, the car's uncertainty and a replacement bumper are the planar car's (docs/verdict.md)".into(),
        }),
        None => Ok(()),
    }
}

/// One end read: the links car and its limits (its own `[damageability]`
/// or the limits file, not both).
fn read_end(end: &End<'_>) -> Result<LineEnd, EngineError> {
    let (path, text, limits_file) = match end {
        End::File(path, limits) => {
            let text = bumpsim_core::files::read_car_text(path)
                .map_err(bumpsim_io::car::CarError::from)?;
            (*path, text, *limits)
        }
        End::Held { path, text, .. } => (*path, text.to_string(), None),
    };
    let car = LinkCar::parse(&text, path)?;
    let own = limits_file.map(|file| Damageability::given(path).map(|own| (own, file)));
    let limits = match own.transpose() {
        Err(e) => Err(e),
        Ok(None) => Damageability::parse(&text, path),
        Ok(Some((true, file))) => Err(VerdictError::Contradiction {
            first: format!("{} [damageability]", path.display()),
            second: file.display().to_string(),
            reason: "both give the car's clearances and limits: an end has one set; drop the table from the car file or the damageability file".into(),
        }),
        Ok(Some((false, file))) => Damageability::read(file),
    }
    .and_then(|limits| line::check(&limits).map(|()| limits))
    .map_err(|source| EngineError::VerdictIn {
        context: path.display().to_string(),
        source: Box::new(source),
    })?;
    Ok(LineEnd {
        path: path.into(),
        name: car.name,
        chain: car.chain,
        limits,
    })
}

/// The chain with `load` kg added to its body (the last mass).
fn laden(chain: &Chain, load: f64) -> Result<Chain, EngineError> {
    if load == 0.0 {
        return Ok(chain.clone());
    }
    let mut masses = chain.masses().to_vec();
    if let Some(body) = masses.last_mut() {
        *body += load;
    }
    let car =
        Chain::new(masses, chain.dampers().to_vec(), chain.links().to_vec()).map_err(|source| {
            bumpsim_io::car::CarError::Model {
                path: "laden car".into(),
                source,
            }
        })?;
    Ok(match chain.front() {
        Some(front) => car.with_front(front.clone()),
        None => car,
    })
}

/// One test run on `end` and judged.
fn judge(
    end: &LineEnd,
    test: &'static Test,
    request: &VerdictRequest<'_>,
) -> Result<TestVerdict, EngineError> {
    let unladen: f64 = end.chain.masses().iter().sum();
    let chain = laden(&end.chain, test.entry.load)?;
    let scenario = bumpsim_impact::presets::scenario_of(test.entry, unladen, None);
    let crush = Crush::of_scenario(&chain, scenario, &end.path)?;
    let nominal = test.nominal(unladen)?;
    let striker = bumpsim_planar::text::striker(&nominal);
    let judging = Judging {
        test,
        limits: &end.limits,
        striker: &striker,
        margin: request.margin,
        asi_method: request.asi_method,
    };
    Ok(line::judge(&judging, &line_run(&chain, &crush)))
}

/// A run's histories as the line verdict reads them (see the module).
fn line_run(chain: &Chain, crush: &Crush) -> LineRun {
    let r = &crush.response;
    let n = chain.dof();
    let samples = r.force.len();
    let x = &r.displacement;
    let relative = |a: usize, b: usize| (0..samples).map(|k| x[b][k] - x[a][k]).collect();
    let body_force = match n {
        1 => r.force.iter().map(|f| -f).collect(),
        _ => {
            let (j, c) = (n - 2, chain.dampers()[n - 2]);
            (0..samples)
                .map(|k| r.link_force[j][k] + c * (r.velocity[j + 1][k] - r.velocity[j][k]))
                .collect()
        }
    };
    let bumper_work = match (chain.front(), crush.front) {
        (Some(link), Some((reached, _))) => LinkState { reached }.dissipated(link),
        _ => 0.0,
    };
    let e = crush.energy();
    let structure = e.viscous + (e.plastic - bumper_work) + e.stored;
    LineRun {
        time: (0..samples).map(|k| k as f64 * r.step).collect(),
        force: r.force.iter().map(|f| -f).collect(),
        bumper: chain
            .front()
            .map(|_| super::struck::front_crush(r).collect()),
        beam_travel: relative(0, n - 1),
        crash_box: (n > 1).then(|| relative(0, 1)),
        body_force,
        body_velocity: r.velocity[n - 1].clone(),
        energies: Energies {
            initial: e.initial,
            bumper: bumper_work,
            absorber: 0.0,
            structure,
            kinetic: e.kinetic,
            tyres: 0.0,
            bumper_share: bumper_work / (bumper_work + structure).max(f64::MIN_POSITIVE),
        },
        warnings: crush.warnings(),
    }
}

/// One end of a held links car: not a planar car end, so refused.
pub(super) fn end(path: &Path) -> EngineError {
    EngineError::Refused {
        path: path.into(),
        reason: "a car with nonlinear links is judged from its file (verdict --car FILE), not as a held planar end".into(),
    }
}
