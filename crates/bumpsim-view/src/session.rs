//! The inputs the viewer was given and the signals it computes from them.
//!
//! A [`Session`] opens each path once through bumpsim-io
//! ([`TestData::open`]: ISO-MME folder, `.mme`, `.zip`, NHTSA EV5, CSV) or
//! as a bumpsim result JSON, and from then on answers only by index: a
//! request names test 0, channel 12, never a path, so nothing outside the
//! given files can be reached. A folder holding a link that leads out of it
//! is refused when it is opened.
//!
//! Signals are processed by bumpsim-signal's own code: without a
//! combination through [`bumpsim_signal::pipeline::export`], the function
//! behind `bumpsim signal export`, with the same steps in the same order
//! (bias, CFC, scale, integrations), so a CFC 60 view equals
//! `bumpsim signal export --cfc 60` sample for sample; sums and means
//! through [`combine`]; the resultant √(Σ xᵢ²) on [`align`]'s common time
//! base.

use crate::error::ViewError;
use crate::query::{Combination, Processing, Query};
use crate::results::ResultFile;
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::Unit;
use bumpsim_io::test_data::TestData;
use bumpsim_signal::process::{Combine, align, combine, run};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A test the viewer opened.
#[derive(Debug)]
pub struct OpenTest {
    /// The test as bumpsim-io read it.
    pub data: TestData,
    /// The path as given on the command line.
    pub given: PathBuf,
}

/// One processed signal, ready to be drawn.
#[derive(Debug, Clone)]
pub struct Signal {
    /// The test it comes from (index).
    pub test: usize,
    /// Legend label: test and channel.
    pub label: String,
    /// The processed channel, SI.
    pub channel: Channel,
    /// The unit it is shown in.
    pub unit: Unit,
}

/// The opened inputs.
#[derive(Debug, Default)]
pub struct Session {
    /// Tests.
    pub tests: Vec<OpenTest>,
    /// Result JSONs.
    pub results: Vec<ResultFile>,
    cache: Vec<(String, Arc<Vec<Signal>>)>,
}

/// How many processed selections are kept (zoom and pan reuse them).
const CACHE: usize = 8;

/// Refuses a folder with a link whose target lies outside it.
fn check_links(root: &Path, dir: &Path, depth: usize) -> Result<(), ViewError> {
    let entries = std::fs::read_dir(dir).map_err(|e| ViewError::Input {
        path: dir.to_path_buf(),
        reason: e.to_string(),
    })?;
    for entry in entries.flatten() {
        let path = entry.path();
        let target = path.canonicalize().unwrap_or_else(|_| path.clone());
        if !target.starts_with(root) {
            return Err(ViewError::Input {
                path,
                reason: format!(
                    "links outside the test folder {} (to {}): the viewer reads only the files it is given",
                    root.display(),
                    target.display()
                ),
            });
        }
        if depth > 0 && target.is_dir() {
            check_links(root, &target, depth - 1)?;
        }
    }
    Ok(())
}

impl Session {
    /// Opens every path: a `.json` as a bumpsim result, anything else as a test.
    pub fn open(paths: &[PathBuf]) -> Result<Session, ViewError> {
        let mut session = Session::default();
        let mut studies = Vec::new();
        for path in paths {
            let canonical = path.canonicalize().map_err(|e| ViewError::Input {
                path: path.clone(),
                reason: format!("cannot open: {e}"),
            })?;
            if canonical.is_dir() {
                check_links(&canonical, &canonical, 3)?;
            }
            let json = canonical
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("json"));
            let toml = canonical
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
            if json {
                session.results.push(ResultFile::read(path)?);
            } else if toml {
                studies.push(path.clone());
            } else {
                let data = TestData::open(path)?;
                session.tests.push(OpenTest {
                    data,
                    given: path.clone(),
                });
            }
        }
        session.model_against_test(&studies)?;
        Ok(session)
    }

    /// Simulates each identification and prediction on the study given
    /// with it (one study).
    fn model_against_test(&mut self, studies: &[PathBuf]) -> Result<(), ViewError> {
        let study = match studies {
            [] => return Ok(()),
            [one] => one,
            [_, second, ..] => {
                return Err(ViewError::Input {
                    path: second.clone(),
                    reason:
                        "one study at a time: its identification results are simulated on its cases"
                            .into(),
                });
            }
        };
        let mut any = false;
        for result in &mut self.results {
            match result.kind {
                "identification" => {
                    result.curves = crate::curves::model_against_test(study, &result.path)?;
                }
                "prediction" => prediction_curves(result, study)?,
                _ => continue,
            }
            any = true;
        }
        if !any {
            return Err(ViewError::Input {
                path: study.clone(),
                reason: "a study needs an identification or prediction result beside it (bumpsim view study.toml result.json)".into(),
            });
        }
        Ok(())
    }

    /// The processed signals of a request's selection (cached).
    pub fn signals(&mut self, q: &Query) -> Result<Arc<Vec<Signal>>, ViewError> {
        let key = format!("{:?}{:?}", q.selected, q.processing);
        if let Some((_, hit)) = self.cache.iter().find(|(k, _)| *k == key) {
            return Ok(hit.clone());
        }
        let mut out = Vec::new();
        for test in self.tests_of(&q.selected)? {
            let indices: Vec<usize> = q
                .selected
                .iter()
                .filter(|(t, _)| *t == test)
                .map(|&(_, c)| c)
                .collect();
            out.extend(self.signals_of(test, &indices, &q.processing)?);
        }
        let signals = Arc::new(out);
        self.cache.push((key, signals.clone()));
        if self.cache.len() > CACHE {
            self.cache.remove(0);
        }
        Ok(signals)
    }

    /// The distinct tests of a selection, in order, each checked.
    fn tests_of(&self, selected: &[(usize, usize)]) -> Result<Vec<usize>, ViewError> {
        let mut tests = Vec::new();
        for &(t, c) in selected {
            let test = self.tests.get(t).ok_or_else(|| {
                ViewError::parameter("sel", format!("no test {t} ({} given)", self.tests.len()))
            })?;
            if c >= test.data.entries.len() {
                return Err(ViewError::parameter(
                    "sel",
                    format!("test {t} has no channel {c}"),
                ));
            }
            if !tests.contains(&t) {
                tests.push(t);
            }
        }
        Ok(tests)
    }

    fn signals_of(
        &self,
        t: usize,
        indices: &[usize],
        processing: &Processing,
    ) -> Result<Vec<Signal>, ViewError> {
        let data = &self.tests[t].data;
        let steps = processing.steps();
        let channels = match processing.combine {
            Combination::None => {
                let selectors: Vec<String> = indices
                    .iter()
                    .map(|&i| format!("#{}", data.entries[i].number))
                    .collect();
                bumpsim_signal::pipeline::export(data, &selectors, &steps, None)?.signals
            }
            how => {
                let raws = indices
                    .iter()
                    .map(|&i| data.load(i))
                    .collect::<Result<Vec<_>, _>>()?;
                let joined = joined(&raws, how)?;
                vec![run(&steps, &joined)?]
            }
        };
        Ok(channels
            .into_iter()
            .map(|channel| Signal {
                test: t,
                label: format!("T{}: {} {}", t + 1, channel.code, channel.name),
                unit: unit_for(&processing.units, &channel),
                channel,
            })
            .collect())
    }
}

/// The unit a channel is shown in: the one asked for its dimension, else
/// bumpsim's display unit (g, kN, mm).
fn unit_for(asked: &[Unit], channel: &Channel) -> Unit {
    asked
        .iter()
        .find(|u| u.dimension == channel.dimension)
        .copied()
        .unwrap_or(channel.dimension.display_unit())
}

/// The sum, mean or resultant of raw channels.
fn joined(raws: &[Channel], how: Combination) -> Result<Channel, ViewError> {
    let codes: Vec<&str> = raws.iter().map(|c| c.code.as_str()).collect();
    match how {
        Combination::Sum => Ok(combine(
            raws,
            Combine::Sum,
            &format!("SUM({})", codes.join("+")),
        )?),
        Combination::Mean => Ok(combine(
            raws,
            Combine::Mean,
            &format!("MEAN({})", codes.join(",")),
        )?),
        _ => resultant(raws, &codes),
    }
}

/// √(Σ xᵢ²) of channels of one dimension on their common time base.
fn resultant(raws: &[Channel], codes: &[&str]) -> Result<Channel, ViewError> {
    let first = raws
        .first()
        .ok_or_else(|| ViewError::parameter("sel", "select channels to combine"))?;
    if let Some(odd) = raws.iter().find(|c| c.dimension != first.dimension) {
        return Err(ViewError::parameter(
            "combine",
            format!(
                "a resultant of {} ({}) and {} ({})",
                first.code, first.dimension, odd.code, odd.dimension
            ),
        ));
    }
    let (times, columns) = align(raws)?;
    if times.is_empty() {
        return Err(ViewError::parameter(
            "combine",
            "the channels share no samples in time",
        ));
    }
    let values: Vec<f64> = (0..times.len())
        .map(|k| columns.iter().map(|c| c[k] * c[k]).sum::<f64>().sqrt())
        .collect();
    // align's common base: the finest interval of the channels
    let step = raws
        .iter()
        .map(|c| c.series.step())
        .fold(f64::INFINITY, f64::min);
    let series = UniformSeries::new(times[0], step, values)
        .map_err(|e| ViewError::parameter("combine", e.to_string()))?;
    let code = format!("RESULTANT({})", codes.join(","));
    Ok(Channel::new(
        &code,
        &format!("resultant of {}", codes.join(", ")),
        first.dimension,
        series,
    ))
}

/// A prediction's curves: the model file its JSON names simulated on
/// `study`'s cases (those the prediction holds), or a note saying why not.
fn prediction_curves(result: &mut ResultFile, study: &Path) -> Result<(), ViewError> {
    let Some(model) = result.model_file.clone() else {
        result.note = Some(format!(
            "{}; its model is not a file here",
            crate::results::PREDICTION_NOTE
        ));
        return Ok(());
    };
    let predicted: Vec<&str> = result.cases.iter().map(|c| c.name.as_str()).collect();
    let mut curves = crate::curves::model_against_test(study, &model)?;
    curves.retain(|c| predicted.contains(&c.name.as_str()));
    result.note = Some(format!(
        "curves: {} simulated on {} by bumpsim-ident's predict, as bumpsim predict does",
        model.display(),
        study.display()
    ));
    result.curves = curves;
    Ok(())
}
