//! `identify` of the linear chain as one request (issue 46 item 1): the
//! study read with the model sizes asked over its own, the one loop over
//! the sizes ([`bumpsim_ident::sizes::identify`]) watched through the
//! request's [`Progress`] (a stage per size, each size's text as it is
//! done), the DOF table, the posterior of the identified (or recommended)
//! size, the ±3 % sensitivity, and the outcome assembled once
//! ([`crate::sizes::Identified`]). The front ends convert their arguments
//! into an [`IdentifyRequest`] and print or return what comes back. No
//! equations here.

use crate::model::{IdentifyRequest, Progress};
use crate::sizes::{Asked, Done, Identified, Size};
use crate::{EngineError, Outcome};
use bumpsim_ident::estimate::Identification;
use bumpsim_ident::posterior::{Posterior, Request};
use bumpsim_ident::sizes::{Observer, Order, Overrides, Watch};
use bumpsim_ident::study::{DofSpec, Study};
use bumpsim_ident::text::{case_lines, dof_table, parameter_table};
use std::cell::RefCell;

/// The request's study with the sizes asked (`--dof`) over its own.
fn study(request: &IdentifyRequest<'_>) -> Result<Study, EngineError> {
    let mut study = Study::read(request.study).map_err(Box::new)?;
    // a study of another kind read here (Python's dof_table) is not a
    // chain study to identify as one
    if let Some(kind) = study.kind.as_deref().filter(|k| *k != "chain") {
        return Err(EngineError::Refused {
            path: request.study.into(),
            reason: format!(
                "kind = \"{kind}\": this identification takes chain studies; `bumpsim identify` (and Python's `bumpsim.identify`) runs a {kind} study"
            ),
        });
    }
    if let Some(sizes) = request.sizes {
        study.model.dof = DofSpec::Many(sizes.to_vec());
    }
    Ok(study)
}

/// The model sizes (numbers of masses) the request identifies, in order.
pub fn sizes(request: &IdentifyRequest<'_>) -> Result<Vec<usize>, EngineError> {
    Ok(study(request)?.dofs())
}

/// The posterior run the request asks for, refused before the
/// identification when it cannot be made at one of the sizes.
fn posterior_request(
    request: &IdentifyRequest<'_>,
    study: &Study,
) -> Result<Option<Request>, EngineError> {
    let Some(asked) = request.posterior else {
        return Ok(None);
    };
    let posterior = Request {
        walkers: asked.walkers,
        steps: asked.steps,
        seed: request.seed.unwrap_or(study.model.seed),
    };
    for dof in study.dofs() {
        let settings = study.settings(dof).map_err(Box::new)?;
        posterior
            .ensemble(&settings)
            .map_err(|e| EngineError::Ensemble(Box::new(e)))?;
    }
    Ok(Some(posterior))
}

/// A chain study identified over its sizes as the request asks (the
/// front ends that hold the results: Python's `identify` and
/// `dof_table`); the text goes to the request's progress as it comes.
pub fn identified(request: &IdentifyRequest<'_>) -> Result<Identified, EngineError> {
    let study = study(request)?;
    Ok(run(request, &study, &Said::new(request.progress))?.0)
}

/// The sizes identified and the text and warnings said along.
fn run(
    request: &IdentifyRequest<'_>,
    study: &Study,
    said: &Said<'_>,
) -> Result<(Identified, bool), EngineError> {
    let overrides = Overrides {
        starts: request.starts,
        seed: request.seed,
    };
    let many = study.dofs().len() > 1;
    let watch = Watched { said, many };
    let sizes = bumpsim_ident::sizes::identify(study, &overrides, &watch).map_err(Box::new)?;
    Ok((Identified::of(sizes), many))
}

/// `identify` on a chain study: every size identified, the DOF table,
/// the posterior when asked, and the document, sensitivity and report.
pub fn identify(request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
    if request.car {
        return Err(EngineError::Unsupported {
            option: "--car".into(),
            reason: "only a planar study identifies a planar car (docs/planar.md)".into(),
        });
    }
    let study = study(request)?;
    let posterior = posterior_request(request, &study)?;
    let said = Said::new(request.progress);
    let (identified, many) = run(request, &study, &said)?;
    if let (false, Some(Size::Failed { dof, error })) = (many, identified.sizes.first()) {
        return Err(EngineError::Size {
            dof: *dof,
            source: Box::new(error.clone()),
        });
    }
    let results = identified.results();
    if results.len() > 1 {
        said.say(format!("\n{}\n", dof_table(&results)));
    }
    let posterior = match &posterior {
        Some(asked) => sample(&said, &identified.done(), asked)?,
        None => None,
    };
    // the ±3 % sweep (91 simulations per case) only when it is written
    let sweeps = match request.sensitivity || request.report {
        true => identified.sweeps()?,
        false => None,
    };
    let asked = Asked {
        study: request.study,
        starts: request.starts.unwrap_or(study.model.starts),
        seed: request.seed.unwrap_or(study.model.seed),
        report: request.report,
    };
    let posterior = posterior.as_ref().map(|(p, r)| (p, *r));
    let outcome = identified.outcome(&asked, sweeps.as_deref(), posterior)?;
    let failed: Vec<String> = identified
        .failed()
        .iter()
        .map(|f| f.dof.to_string())
        .collect();
    let failure = (!failed.is_empty()).then(|| {
        format!(
            "{} of the {} models failed (DOF {}, see above); the others are reported",
            failed.len(),
            identified.sizes.len(),
            failed.join(", ")
        )
    });
    let (text, warnings, printed_warnings) = said.into_parts();
    Ok(Outcome {
        text,
        warnings,
        printed_warnings,
        failure,
        ..outcome
    })
}

/// The posterior of the identified size (or of the DOF table's
/// recommendation), said; `None` when no size was identified.
fn sample<'a>(
    said: &Said<'_>,
    done: &[&'a Done],
    request: &Request,
) -> Result<Option<(Posterior, &'a Identification)>, EngineError> {
    let results: Vec<Identification> = done.iter().map(|d| d.result.clone()).collect();
    let dof = match results.as_slice() {
        [one] => Some(one.dof),
        _ => bumpsim_ident::text::recommended_dof(&results),
    };
    let Some(Done {
        result,
        cases,
        settings,
    }) = done.iter().copied().find(|d| Some(d.result.dof) == dof)
    else {
        return Ok(None);
    };
    let ensemble = request
        .ensemble(settings)
        .map_err(|e| EngineError::Ensemble(Box::new(e)))?;
    let progress = said.progress;
    let name = format!("posterior {}-DOF", result.dof);
    progress.stage(&name, ensemble.steps as u64, "steps");
    let post = bumpsim_ident::posterior::run(cases, settings, result, request, &|| {
        progress.start_finished()
    });
    progress.end();
    let post = post.map_err(|source| EngineError::Posterior {
        dof: result.dof,
        source: Box::new(source),
    })?;
    said.say(format!(
        "\n{}-DOF {}\n",
        result.dof,
        bumpsim_ident::posterior::lines(&post, result)
    ));
    said.printed(post.diagnostics.warnings.len());
    Ok(Some((post, result)))
}

/// The text, warnings and printed warnings of a run, each part told to
/// the progress as it comes.
struct Said<'a> {
    progress: &'a dyn Progress,
    text: RefCell<String>,
    warnings: RefCell<Vec<String>>,
    printed: RefCell<usize>,
}

impl<'a> Said<'a> {
    fn new(progress: &'a dyn Progress) -> Said<'a> {
        Said {
            progress,
            text: RefCell::new(String::new()),
            warnings: RefCell::new(Vec::new()),
            printed: RefCell::new(0),
        }
    }

    /// Text of the outcome, told at once.
    fn say(&self, text: String) {
        self.progress.text(&text);
        self.text.borrow_mut().push_str(&text);
    }

    /// Warnings the text has printed.
    fn printed(&self, n: usize) {
        *self.printed.borrow_mut() += n;
    }

    fn into_parts(self) -> (String, Vec<String>, usize) {
        (
            self.text.into_inner(),
            self.warnings.into_inner(),
            self.printed.into_inner(),
        )
    }
}

/// The one loop's watch: a stage per size, each size said when done.
struct Watched<'a, 'b> {
    said: &'a Said<'b>,
    many: bool,
}

impl Watch for Watched<'_, '_> {
    fn loaded(&self, notes: &[String], warnings: &[String]) {
        let notes: String = notes.iter().map(|n| format!("note: {n}\n")).collect();
        if !notes.is_empty() {
            self.said.say(notes);
        }
        self.said.warnings.borrow_mut().extend_from_slice(warnings);
    }

    fn starting(&self, dof: usize, starts: usize) -> Box<dyn Observer + '_> {
        let progress = self.said.progress;
        progress.stage(&format!("{dof}-DOF"), starts as u64, "starts");
        Box::new(move || progress.start_finished())
    }

    fn done(&self, order: &Order) {
        self.said.progress.end();
        match &order.result {
            Ok(result) => self.result(result),
            Err(e) if self.many => self.said.progress.part_failed(&format!(
                "{}-DOF model: {e} (the other models go on)",
                order.dof
            )),
            Err(_) => {}
        }
    }
}

impl Watched<'_, '_> {
    /// One identified size as `identify` prints it.
    fn result(&self, r: &Identification) {
        if !(r.objective.is_finite() && r.fit_percent.is_finite()) {
            self.said.warnings.borrow_mut().push(format!(
                "{}-DOF model: objective {} {}, fit {} %: the measured data do not determine the model",
                r.dof,
                r.objective,
                r.objective_unit(),
                r.fit_percent
            ));
        }
        let phrase = r.objective_phrase();
        let compared = match phrase.is_empty() {
            true => String::new(),
            false => format!(" ({phrase})"),
        };
        let unit = r.objective_unit();
        let mut text = format!(
            "\n{}-DOF model: objective {} {unit}{compared}, fit {} %\n",
            r.dof,
            bumpsim_core::units::format_number(r.objective, 5),
            bumpsim_core::units::format_number(r.fit_percent, 4)
        );
        text += &parameter_table(r);
        text += &case_lines(r);
        if let Some(line) = bumpsim_ident::text::residuals_line(r) {
            text += &format!("  {line}\n");
        }
        text += &bumpsim_ident::text::prior_lines(r);
        text += &format!("  {}\n", bumpsim_ident::text::starts_line(r));
        for w in &r.warnings {
            text += &format!("  warning: {w}\n");
        }
        self.said.say(text);
        self.said.printed(r.warnings.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// A progress that keeps what it hears.
    #[derive(Default)]
    struct Heard {
        stages: Mutex<Vec<String>>,
        starts: Mutex<usize>,
        text: Mutex<String>,
    }

    impl Progress for Heard {
        fn stage(&self, name: &str, count: u64, unit: &str) {
            let stage = format!("{name}: {count} {unit}");
            self.stages.lock().unwrap().push(stage);
        }
        fn start_finished(&self) {
            *self.starts.lock().unwrap() += 1;
        }
        fn text(&self, text: &str) {
            self.text.lock().unwrap().push_str(text);
        }
    }

    #[test]
    fn a_chain_study_is_one_request_whose_progress_hears_each_size_and_its_text() {
        let study = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/identify/study.toml");
        let heard = Heard::default();
        let sizes = [1, 2];
        let request = IdentifyRequest {
            study: &study,
            starts: Some(2),
            seed: None,
            report: false,
            posterior: None,
            sizes: Some(&sizes),
            sensitivity: false,
            car: false,
            progress: &heard,
        };
        let outcome = identify(&request).expect("the bundled study identifies");
        assert_eq!(
            *heard.stages.lock().unwrap(),
            vec!["1-DOF: 2 starts", "2-DOF: 2 starts"]
        );
        assert!(*heard.starts.lock().unwrap() >= 4);
        // the text heard as it came is the outcome's, in order
        assert_eq!(*heard.text.lock().unwrap(), outcome.text);
        let one = outcome.text.find("\n1-DOF model: objective").unwrap();
        let two = outcome.text.find("\n2-DOF model: objective").unwrap();
        let table = outcome.text.find(" DOF ").unwrap();
        assert!(one < two && two < table, "{}", outcome.text);
        assert!(outcome.failure.is_none() && outcome.json.contains("\"dof\": 2"));
        // the same request through Python's door: the sizes as results
        let identified = identified(&request).unwrap();
        assert_eq!(identified.results().len(), 2);
        // a chain study does not identify a planar car
        let refused = identify(&IdentifyRequest {
            car: true,
            ..request
        })
        .unwrap_err();
        assert!(
            refused
                .to_string()
                .starts_with("--car: only a planar study")
        );
    }
}
