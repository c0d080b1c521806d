//! Loading one case of a study: its force and displacement channels
//! (summed, averaged, bias removed, CFC filtered, accelerations integrated
//! twice), the alignment of their samples and the fit window (the force's
//! contact window, 5 % rise and 2 % fall, or the study's `[t0, t1]`).

use super::error::{DefinitionError, StudyError, StudyValueError};
use super::file::{CaseSpec, ChannelRef, OutputDof, Study, WindowSpec};
use crate::case::{Comparison, Domain, LoadCase, Walk};
use bumpsim_core::channel::{Channel, ChannelCode};
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, format_number, short};
use bumpsim_signal::filter::CfcStandard;
use bumpsim_signal::loader::{ChannelSource, LoadError, Loader, Note};
use bumpsim_signal::process::{Combine, ProcessError, Resampling, Step, align, resampling, run};
use bumpsim_signal::window::ContactThreshold;
use std::fmt;

/// A note on the channels of one case (left out, or used despite a mark).
#[derive(Debug, Clone, PartialEq)]
pub struct CaseNote {
    /// The case.
    pub case: String,
    /// The note of its channel selection.
    pub note: Note,
}

impl fmt::Display for CaseNote {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "case '{}': {}", self.case, self.note)
    }
}

/// The load cases of a study and the notes of their channel selections.
#[derive(Debug, Clone)]
pub struct LoadedCases {
    /// The cases, processed.
    pub cases: Vec<LoadCase>,
    /// What the channel selections left out or used despite a mark.
    pub notes: Vec<CaseNote>,
    /// Cases whose measured motion goes against their force (a sign
    /// convention mixed up: [`LoadCase::direction_warning`]).
    pub warnings: Vec<String>,
}

/// One case being loaded: its study, definition, the channel loader and
/// the notes on what the selections left out.
pub(super) struct CaseContext<'a> {
    pub(super) study: &'a Study,
    pub(super) spec: &'a CaseSpec,
    pub(super) loader: &'a mut Loader,
    pub(super) notes: Vec<CaseNote>,
}

impl CaseContext<'_> {
    pub(super) fn load_case(&mut self, dof: usize) -> Result<LoadCase, StudyError> {
        let spec = self.spec;
        let force = self.force()?;
        let output = match (&spec.displacement, spec.acceleration.is_empty()) {
            (Some(d), true) => {
                let displacement = std::slice::from_ref(d);
                self.along_the_impact(displacement, "displacement channel")?;
                self.channels(displacement, Combine::Mean)?
            }
            (None, false) => self.displacement_from_acceleration()?,
            _ => return Err(self.case(DefinitionError::Output)),
        };
        self.expect(
            &output,
            Dimension::Length,
            "displacement channel",
            "a length",
        )?;
        self.build(force, output, dof)
    }

    fn case(&self, source: impl Into<DefinitionError>) -> StudyError {
        StudyError::Case {
            case: self.spec.name.clone(),
            source: source.into(),
        }
    }

    fn process(&self, result: Result<Channel, ProcessError>) -> Result<Channel, StudyError> {
        result.map_err(|source| StudyError::Process {
            case: self.spec.name.clone(),
            source,
        })
    }

    fn expect(
        &self,
        channel: &Channel,
        dimension: Dimension,
        signal: &'static str,
        expected: &'static str,
    ) -> Result<(), StudyError> {
        if channel.dimension == dimension {
            return Ok(());
        }
        Err(self.case(DefinitionError::Dimension {
            signal,
            found: channel.dimension,
            expected,
        }))
    }

    /// Loads, scales and combines channel references; keeps their notes.
    fn channels(&mut self, refs: &[ChannelRef], how: Combine) -> Result<Channel, StudyError> {
        let sources: Vec<ChannelSource> = refs
            .iter()
            .map(|r| ChannelSource::new(self.study.base.join(&r.path), &r.channel, r.scale))
            .collect();
        let name = &self.spec.name;
        let loaded = self
            .loader
            .signal(&sources, Some(how), name)
            .map_err(|e| match e {
                LoadError::Data(source) => StudyError::Data {
                    case: name.clone(),
                    source,
                },
                LoadError::Process(source) => StudyError::Process {
                    case: name.clone(),
                    source,
                },
                other => self.case(DefinitionError::Load(other)),
            })?;
        let notes = loaded.notes.into_iter().map(|note| CaseNote {
            case: name.clone(),
            note,
        });
        self.notes.extend(notes);
        Ok(loaded.data)
    }

    /// Bias removal and the CFC filter.
    fn conditioning(&self, channel: &Channel) -> Result<Vec<Step>, StudyError> {
        let mut steps = Vec::new();
        match self.spec.bias {
            Some(window) => steps.push(Step::Bias(window)),
            None if channel.series.start() < 0.0 => steps.push(Step::PretriggerBias(true)),
            None => {}
        }
        if let Some(class) = self.spec.cfc {
            self.check_cfc(class, channel.series.step())?;
            steps.push(Step::Cfc(class));
        }
        Ok(steps)
    }

    /// The case's CFC class within what the channel's sample interval
    /// `step` allows ([`CfcStandard::classes`]), named by the study file
    /// and key.
    fn check_cfc(&self, class: f64, step: f64) -> Result<(), StudyError> {
        let (low, high) = CfcStandard::SaeJ211.classes(step);
        if class >= low && class < high {
            return Ok(());
        }
        Err(StudyError::Value {
            path: self.study.path.clone(),
            source: StudyValueError::CaseValue {
                case: self.spec.name.clone(),
                key: "cfc",
                value: short(class),
                expected: format!(
                    "a class from {} to below {} for channels sampled at {} Hz (its design frequency must lie from 1e-6 of the sample rate to below the Nyquist frequency)",
                    format_number(low, 4),
                    format_number(high, 4),
                    format_number(1.0 / step, 4)
                ),
            },
        })
    }

    fn force(&mut self) -> Result<Channel, StudyError> {
        let raw = self.channels(std::slice::from_ref(&self.spec.force), Combine::Sum)?;
        self.expect(&raw, Dimension::Force, "force channel", "a force")?;
        self.process(run(&self.conditioning(&raw)?, &raw))
    }

    /// Refuses a channel of `refs` whose ISO code measures across the
    /// impact (direction other than X; a code-less column is taken as
    /// along it).
    fn along_the_impact(
        &mut self,
        refs: &[ChannelRef],
        signal: &'static str,
    ) -> Result<(), StudyError> {
        let sources: Vec<ChannelSource> = refs
            .iter()
            .map(|r| ChannelSource::new(self.study.base.join(&r.path), &r.channel, r.scale))
            .collect();
        // a selection that fails is reported by the loading that follows
        let Ok(loaded) = self.loader.channels(&sources) else {
            return Ok(());
        };
        let across = loaded.data.iter().find_map(|c| {
            let direction = ChannelCode::parse(&c.code)?.direction.to_ascii_uppercase();
            (direction != 'X').then(|| (c.code.clone(), direction))
        });
        match across {
            Some((channel, direction)) => Err(self.case(DefinitionError::Across {
                signal,
                channel,
                direction,
            })),
            None => Ok(()),
        }
    }

    fn displacement_from_acceleration(&mut self) -> Result<Channel, StudyError> {
        let (what, spec) = ("acceleration channel", self.spec);
        self.along_the_impact(&spec.acceleration, what)?;
        let raw = self.channels(&spec.acceleration, Combine::Mean)?;
        self.expect(&raw, Dimension::Acceleration, what, "an acceleration")?;
        let mut steps = self.conditioning(&raw)?;
        steps.extend([
            Step::Integrate(self.spec.initial_velocity),
            Step::Integrate(0.0),
        ]);
        self.process(run(&steps, &raw))
    }

    /// Aligns force and displacement, starts at t = 0 and sets the window.
    /// A case that fails after its channels were put on one time base
    /// says how they were (the overlap may be what left too little).
    fn build(
        &mut self,
        force: Channel,
        output: Channel,
        dof: usize,
    ) -> Result<LoadCase, StudyError> {
        let pair = [force, output];
        let resampled = resampling(&pair).map(|r| Resampling {
            codes: self.selectors(),
            ..r.with_roles(&["force", "displacement"])
        });
        let case = self
            .assemble(&pair, dof)
            .map_err(|e| match (&resampled, e) {
                (Some(r), StudyError::Case { case, source }) => StudyError::Case {
                    case,
                    source: DefinitionError::Resampled {
                        note: r.to_string(),
                        error: Box::new(source),
                    },
                },
                (_, e) => e,
            })?;
        if let Some(resampled) = resampled {
            self.notes.push(CaseNote {
                case: self.spec.name.clone(),
                note: Note::Resampled(resampled),
            });
        }
        Ok(case)
    }

    /// The force's and the displacement's channels as the study names
    /// them (a processed channel's code may differ: CFC sets its
    /// filter-class letter).
    fn selectors(&self) -> Vec<String> {
        let spec = self.spec;
        let output: Vec<&str> = match &spec.displacement {
            Some(d) => vec![d.channel.as_str()],
            None => spec
                .acceleration
                .iter()
                .map(|a| a.channel.as_str())
                .collect(),
        };
        vec![spec.force.channel.clone(), output.join(", ")]
    }

    fn assemble(&self, pair: &[Channel; 2], dof: usize) -> Result<LoadCase, StudyError> {
        let (time, columns) = align(pair).map_err(|source| StudyError::Process {
            case: self.spec.name.clone(),
            source,
        })?;
        let step = if time.len() > 1 {
            time[1] - time[0]
        } else {
            1.0
        };
        let name = &self.spec.name;
        let aligned = UniformSeries::new(time[0], step, columns[0].clone()).map_err(|source| {
            let source = ProcessError::Series {
                channel: name.clone(),
                step: "align",
                source,
            };
            StudyError::Process {
                case: name.clone(),
                source,
            }
        })?;
        let first = *aligned
            .window(0.0, f64::INFINITY)
            .ok_or_else(|| self.case(DefinitionError::NoSamples))?
            .start();
        let (force, measured) = (columns[0][first..].to_vec(), columns[1][first..].to_vec());
        let start = time[first];
        let window = self.window(&aligned, first)?;
        let output_dof = match &self.spec.output_dof {
            None => 1,
            Some(OutputDof::Number(n)) => *n,
            Some(OutputDof::Named(s)) if s.eq_ignore_ascii_case("last") => dof,
            Some(OutputDof::Named(s)) => {
                return Err(self.case(DefinitionError::OutputDof(s.clone())));
            }
        };
        if output_dof == 0 || output_dof > dof {
            return Err(self.case(DefinitionError::OutputDofRange { output_dof, dof }));
        }
        let step = if time.len() > 1 { step } else { 0.0 };
        let mut compare = self.comparison(&columns[1][..first], step);
        if self.spec.displacement.is_none() {
            compare = compare.integrated(self.walk(&aligned, first));
        }
        let case = LoadCase {
            name: self.spec.name.clone(),
            start,
            step,
            force,
            measured,
            output_dof,
            initial_velocity: self.spec.initial_velocity,
            window,
            compare,
        };
        case.validate().map_err(|e| self.case(e))?;
        Ok(case)
    }

    /// The case's comparison: the study's domain, and the noise the case
    /// gives or, beyond displacement, the spread of the processed
    /// measurement's `pretrigger` (the samples before t = 0) in that
    /// domain (none without a pre-trigger: not weighted).
    fn comparison(&self, pretrigger: &[f64], step: f64) -> Comparison {
        let domain = self.study.objective().unwrap_or_default();
        let noise = match (self.spec.noise, domain) {
            (Some(given), _) => Some(given),
            (None, Domain::Displacement) => None,
            (None, _) => domain.noise(pretrigger, step),
        };
        Comparison::new(domain, noise)
    }

    /// The random walk of a displacement integrated from accelerations
    /// from the first aligned sample: `first` samples before t = 0, the
    /// bias removed over the `bias` window or the pre-trigger.
    fn walk(&self, aligned: &UniformSeries, first: usize) -> Walk {
        let bias = match self.spec.bias {
            Some([t0, t1]) => aligned
                .window(t0, t1)
                .map(|w| (*w.start(), w.end() + 1 - w.start())),
            None => (first > 0).then_some((0, first)),
        };
        Walk { lead: first, bias }
    }

    /// The fit window as sample indices counted from `first` (the sample at
    /// t = 0) in the aligned force.
    fn window(&self, aligned: &UniformSeries, first: usize) -> Result<(usize, usize), StudyError> {
        let force = &aligned.values()[first..];
        match &self.spec.window {
            None => self.contact(force),
            Some(WindowSpec::Named(s)) if s.eq_ignore_ascii_case("contact") => self.contact(force),
            Some(WindowSpec::Named(s)) => Err(self.case(DefinitionError::WindowName(s.clone()))),
            Some(WindowSpec::Times(bumpsim_io::numbers::Numbers([t0, t1]))) => {
                self.within_record(aligned, [*t0, *t1])?;
                let empty = || self.case(DefinitionError::EmptyWindow { t0: *t0, t1: *t1 });
                let inside = aligned.window(*t0, *t1).ok_or_else(empty)?;
                let (a, b) = (*inside.start().max(&first), *inside.end());
                if a >= b {
                    return Err(empty());
                }
                Ok((a - first, b - first))
            }
        }
    }

    /// A fit window `[t0, t1]` s lies within the record of the case's
    /// aligned channels (half a sample's slack at each end), as a `bias`
    /// window must: one reaching past it was cut to the record without a
    /// word (`window = [0, 1e300]` fitted the record's 0.16 s), so the fit
    /// %, SSE and rating were taken over another window than the one given.
    /// A start within the pre-trigger (before t = 0) is the replay's start,
    /// t = 0 (docs/identify.md).
    fn within_record(&self, aligned: &UniformSeries, [t0, t1]: [f64; 2]) -> Result<(), StudyError> {
        let (first, last) = (aligned.start(), aligned.end());
        if crate::case::within_record(aligned, [t0, t1]) {
            return Ok(());
        }
        Err(StudyError::Value {
            path: self.study.path.clone(),
            source: StudyValueError::CaseValue {
                case: self.spec.name.clone(),
                key: "window",
                value: format!("[{}, {}]", short(t0), short(t1)),
                expected: format!(
                    "times within the record of the case's channels, {} s to {} s ({} s long; a bias window must lie within it too)",
                    format_number(first, 4),
                    format_number(last, 4),
                    format_number(last - first, 4)
                ),
            },
        })
    }

    fn contact(&self, force: &[f64]) -> Result<(usize, usize), StudyError> {
        let w = ContactThreshold::default()
            .detect(force)
            .map_err(|e| self.case(e))?;
        Ok((w.first, w.last))
    }
}
