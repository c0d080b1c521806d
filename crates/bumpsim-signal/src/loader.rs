//! One way from channel references to a signal: open, select, scale, combine.
//!
//! A [`ChannelSource`] names a test file, a selector (number, code with `?`
//! and `*` wildcards, or name substring; see `bumpsim_io::test_data`) and a
//! scale factor. The [`Loader`] opens each test file once, loads every
//! channel each selector picks, multiplies it by its factor and, when
//! several channels result, combines them by sum or mean
//! ([`combine`]: their common time base, linear
//! interpolation where bases differ).
//!
//! Nothing is left out silently: each channel a wildcard or name selection
//! skips (marked invalid by the lab, or its samples absent) and each invalid
//! channel asked for explicitly (and so used) becomes a [`Note`] returned
//! with the signal. Both the pipeline (`bumpsim signal process`) and the
//! study files of identification load through here.
//!
//! ```no_run
//! use bumpsim_signal::loader::{ChannelSource, Loader};
//! use bumpsim_signal::process::Combine;
//! let mut loader = Loader::new();
//! let cells = [ChannelSource::new("v10146.EV5", "0-LC-*-XG", 1.0)];
//! let force = loader.signal(&cells, Some(Combine::Sum), "barrier force")?;
//! for note in &force.notes {
//!     println!("note: {note}");
//! }
//! # Ok::<(), bumpsim_signal::loader::LoadError>(())
//! ```

use crate::process::{Combine, ProcessError, Resampling, Step, combine, resampling};
use bumpsim_core::channel::Channel;
use bumpsim_io::signal_error::SignalFileError;
use bumpsim_io::test_data::{Selection, TestData};
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why channels could not be loaded into a signal.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// A test file, or a selector that matches nothing usable.
    #[error(transparent)]
    Data(#[from] SignalFileError),
    /// Scaling or combining failed.
    #[error(transparent)]
    Process(#[from] ProcessError),
    /// No channel references at all.
    #[error("'channels' is empty")]
    NoChannels,
    /// One channel picked by two references: it would count twice in a
    /// sum or a mean.
    #[error("{path}: channel {number} ({code}) is picked by '{}' and again by '{}': it would count twice; name each channel once", selectors[0], selectors[1])]
    Twice {
        /// The test file.
        path: PathBuf,
        /// Channel number.
        number: usize,
        /// Channel code.
        code: String,
        /// The first selector that picks it and the later one (boxed: the
        /// error stays small).
        selectors: Box<[String; 2]>,
    },
    /// An exact code (no wildcard) that several channels of the test
    /// carry: summing or averaging them was not asked for by the selector.
    #[error(
        "{path}: channel '{selector}' is an exact code that {} channels carry ({}): it is ambiguous; pick one by its number ('#{}'), or match them with a wildcard to combine them",
        channels.len(),
        channels.iter().map(|(n, c)| format!("channel {n} ({c})")).collect::<Vec<_>>().join(", "),
        channels.first().map_or(0, |(n, _)| *n)
    )]
    Ambiguous {
        /// The test file.
        path: PathBuf,
        /// The selector as given.
        selector: String,
        /// The number and code of each channel it matches.
        channels: Vec<(usize, String)>,
    },
    /// Several channels and no way to combine them.
    #[error("{count} channels selected: say combine = \"sum\" or \"mean\"")]
    Combine {
        /// How many channels were selected.
        count: usize,
    },
}

/// Something the selection did that the user should know.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Note {
    /// A wildcard or name selection left out a channel marked invalid.
    Invalid {
        /// The selector.
        selector: String,
        /// Channel number.
        number: usize,
        /// Channel code.
        code: String,
    },
    /// A selection left out matching channels whose samples are absent.
    Absent {
        /// The selector.
        selector: String,
        /// Channel numbers.
        numbers: Vec<usize>,
        /// Their codes, in the same order.
        codes: Vec<String>,
    },
    /// What the test file said about the selection (an invalid channel
    /// asked for by number or exact code, used anyway).
    Selection {
        /// The selector.
        selector: String,
        /// The test file's words.
        message: String,
    },
    /// Channels sampled at different intervals or times, or over different
    /// spans, were put on one time base to be combined or compared.
    Resampled(Resampling),
}

impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Note::Invalid {
                selector,
                number,
                code,
            } => write!(
                f,
                "'{selector}': left out channel {number} ({code}): marked invalid"
            ),
            Note::Absent {
                selector,
                numbers,
                codes,
            } => {
                let named: Vec<String> = numbers
                    .iter()
                    .zip(codes)
                    .map(|(n, c)| format!("{n} ({c})"))
                    .collect();
                match numbers.len() {
                    1 => write!(
                        f,
                        "'{selector}': left out channel {} whose file is missing or unusable",
                        named.join("")
                    ),
                    n => write!(
                        f,
                        "'{selector}': left out {n} matching channels whose files are missing or unusable: {}",
                        named.join(", ")
                    ),
                }
            }
            Note::Selection { message, .. } => f.write_str(message),
            Note::Resampled(resampling) => resampling.fmt(f),
        }
    }
}

/// One channel reference: test file, selector, factor.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelSource {
    /// The test file (ISO-MME folder/.mme/.zip, NHTSA .EV5, CSV).
    pub path: PathBuf,
    /// Channel selector (number, code with wildcards, name).
    pub selector: String,
    /// Factor applied to every selected channel (e.g. −1 to change sign).
    pub scale: f64,
}

impl ChannelSource {
    /// A reference to the channels `selector` picks in `path`, times `scale`.
    pub fn new(path: impl Into<PathBuf>, selector: &str, scale: f64) -> ChannelSource {
        ChannelSource {
            path: path.into(),
            selector: selector.to_string(),
            scale,
        }
    }
}

/// Loaded data with the notes of its selection.
#[derive(Debug, Clone)]
pub struct Loaded<T> {
    /// The data.
    pub data: T,
    /// What the selection left out or used despite a mark.
    pub notes: Vec<Note>,
}

/// Opens each test file once and loads signals from it.
#[derive(Debug, Default)]
pub struct Loader {
    tests: BTreeMap<PathBuf, TestData>,
}

impl Loader {
    /// A loader with no test open yet.
    pub fn new() -> Loader {
        Loader::default()
    }

    /// The test at `path`, opened on first use.
    pub fn open(&mut self, path: &Path) -> Result<&TestData, SignalFileError> {
        if !self.tests.contains_key(path) {
            let test = TestData::open(path)?;
            self.tests.insert(path.to_path_buf(), test);
        }
        Ok(&self.tests[path])
    }

    /// A test opened before, if any.
    pub fn opened(&self, path: &Path) -> Option<&TestData> {
        self.tests.get(path)
    }

    /// Every channel the sources pick, each scaled by its factor.
    pub fn channels(
        &mut self,
        sources: &[ChannelSource],
    ) -> Result<Loaded<Vec<Channel>>, LoadError> {
        let mut channels = Vec::new();
        let mut notes = Vec::new();
        let mut picked: Vec<(PathBuf, usize, &str)> = Vec::new();
        for source in sources {
            let test = self.open(&source.path)?;
            let indices = test.select(&source.selector)?.indices;
            unambiguous(test, &source.selector, &indices)?;
            for i in indices {
                let key = (source.path.clone(), i);
                if let Some((_, _, first)) = picked.iter().find(|(p, j, _)| (p, *j) == (&key.0, i))
                {
                    return Err(LoadError::Twice {
                        path: key.0,
                        number: test.entries[i].number,
                        code: test.entries[i].code.clone(),
                        selectors: Box::new([first.to_string(), source.selector.clone()]),
                    });
                }
                picked.push((key.0, i, &source.selector));
            }
            let loaded = select(test, &source.selector)?;
            notes.extend(loaded.notes);
            for channel in loaded.data {
                channels.push(scale(channel, source.scale)?);
            }
        }
        Ok(Loaded {
            data: channels,
            notes,
        })
    }

    /// One signal from the sources: a single channel as it is, several
    /// combined by `how` (required then) into a channel coded `name`.
    pub fn signal(
        &mut self,
        sources: &[ChannelSource],
        how: Option<Combine>,
        name: &str,
    ) -> Result<Loaded<Channel>, LoadError> {
        let Loaded { data, mut notes } = self.channels(sources)?;
        let channel = match (data.len(), how) {
            (0, _) => return Err(LoadError::NoChannels),
            (1, _) => data.into_iter().next().ok_or(LoadError::NoChannels)?,
            (count, None) => return Err(LoadError::Combine { count }),
            (_, Some(how)) => {
                notes.extend(resampling(&data).map(Note::Resampled));
                combine(&data, how, name)?
            }
        };
        Ok(Loaded {
            data: channel,
            notes,
        })
    }
}

/// Refuses an exact code (neither a number nor a wildcard) that picks
/// several channels: a channel file given twice in an ISO-MME test was
/// summed without a word (issue 48). A wildcard or a name matching several
/// channels combines them by design.
pub(crate) fn unambiguous(
    test: &TestData,
    selector: &str,
    indices: &[usize],
) -> Result<(), LoadError> {
    let text = selector.trim();
    let number = text.strip_prefix('#').unwrap_or(text).parse::<usize>();
    let by_code = |&i: &usize| test.entries[i].code.eq_ignore_ascii_case(text);
    if indices.len() < 2 || number.is_ok() || text.contains(['*', '?']) {
        return Ok(());
    }
    if !indices.iter().all(by_code) {
        return Ok(());
    }
    let channels = indices
        .iter()
        .map(|&i| (test.entries[i].number, test.entries[i].code.clone()))
        .collect();
    Err(LoadError::Ambiguous {
        path: test.path.clone(),
        selector: selector.to_string(),
        channels,
    })
}

fn scale(channel: Channel, factor: f64) -> Result<Channel, ProcessError> {
    if factor == 1.0 {
        return Ok(channel);
    }
    Step::Scale(factor).apply(&channel)
}

/// Loads every channel `selector` picks in `test`, with the notes of the
/// selection.
pub fn select(test: &TestData, selector: &str) -> Result<Loaded<Vec<Channel>>, SignalFileError> {
    let selection = test.select(selector)?;
    Ok(Loaded {
        data: test.load_all(&selection)?,
        notes: notes(test, selector, &selection),
    })
}

/// The notes of one selection, in the order: the file's words, invalid
/// channels left out, absent channels left out.
pub fn notes(test: &TestData, selector: &str, selection: &Selection) -> Vec<Note> {
    let said = selection.warnings.iter().map(|message| Note::Selection {
        selector: selector.to_string(),
        message: message.clone(),
    });
    let invalid = selection.excluded.iter().map(|&i| Note::Invalid {
        selector: selector.to_string(),
        number: test.entries[i].number,
        code: test.entries[i].code.clone(),
    });
    let mut notes: Vec<Note> = said.chain(invalid).collect();
    if !selection.absent.is_empty() {
        notes.push(Note::Absent {
            selector: selector.to_string(),
            numbers: selection
                .absent
                .iter()
                .map(|&i| test.entries[i].number)
                .collect(),
            codes: selection
                .absent
                .iter()
                .map(|&i| test.entries[i].code.clone())
                .collect(),
        });
    }
    notes
}

/// Loads every channel the selectors pick in `test`; returns them and the
/// notes of the selections.
pub fn select_all(
    test: &TestData,
    selectors: &[String],
) -> Result<(Vec<Channel>, Vec<Note>), SignalFileError> {
    let mut channels = Vec::new();
    let mut notes = Vec::new();
    for selector in selectors {
        let loaded = select(test, selector)?;
        channels.extend(loaded.data);
        notes.extend(loaded.notes);
    }
    Ok((channels, notes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::units::Dimension;
    use std::fmt::Write;

    /// An EV5 test with three accelerometers: two valid, one marked
    /// invalid, and one more listed whose file is missing or unusable.
    fn ev5(dir: &Path) -> PathBuf {
        std::fs::create_dir_all(dir).unwrap();
        let row = |curve: usize, location: &str, comment: &str| {
            format!(
                "1|{curve}|AC|00|{location}|XG|SEC|G'S|0|S|01/JAN/2020|100|1|0|0|3|100|AM|P|{comment}\n"
            )
        };
        let mut text = String::from("----- TEST -----\nV5|loader test|||||||||||||0||||4\n");
        text += "----- INSTRUMENTATION -----\n";
        text += &row(1, "SIMELE", "LEFT");
        text += &row(2, "SIMERI", "RIGHT");
        text += &row(3, "SIMEXX", "No valid data");
        text += &row(4, "SIMEYY", "NEVER WRITTEN");
        let path = dir.join("t.EV5");
        std::fs::write(&path, text).unwrap();
        for (curve, g) in [(1, 1.0), (2, 3.0), (3, 100.0)] {
            let mut samples = String::new();
            for k in 0..4 {
                writeln!(samples, "{}\t{g}", k as f64 * 1e-4).unwrap();
            }
            std::fs::write(dir.join(format!("t.{curve:03}")), samples).unwrap();
        }
        path
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("bumpsim-loader-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn a_wildcard_leaves_out_invalid_and_absent_channels_and_says_so() {
        let path = ev5(&scratch("wildcard"));
        let mut loader = Loader::new();
        let sources = [ChannelSource::new(&path, "1-AC-SIME*", -2.0)];
        let mean = loader
            .signal(&sources, Some(Combine::Mean), "sides")
            .unwrap();
        let g = 9.80665;
        assert_eq!(mean.data.dimension, Dimension::Acceleration);
        for v in mean.data.series.values() {
            approx::assert_relative_eq!(*v, -2.0 * 2.0 * g, max_relative = 1e-12);
        }
        let texts: Vec<String> = mean.notes.iter().map(ToString::to_string).collect();
        assert_eq!(
            texts,
            [
                "'1-AC-SIME*': left out channel 3 (1-AC-SIMEXX-XG): marked invalid",
                "'1-AC-SIME*': left out channel 4 (1-AC-SIMEYY-XG) whose file is missing or unusable"
            ]
        );
        assert!(matches!(&mean.notes[1], Note::Absent { numbers, .. } if numbers == &[4]));
    }

    #[test]
    fn an_invalid_channel_asked_for_by_number_is_used_with_a_note() {
        let path = ev5(&scratch("explicit"));
        let mut loader = Loader::new();
        let one = loader
            .signal(&[ChannelSource::new(&path, "3", 1.0)], None, "x")
            .unwrap();
        assert_eq!(one.data.code, "1-AC-SIMEXX-XG");
        assert!(
            matches!(&one.notes[..], [Note::Selection { message, .. }] if message.contains("marked invalid"))
        );
        assert!(loader.opened(&path).is_some());
    }

    #[test]
    fn several_channels_need_a_combination_and_none_is_an_error() {
        let path = ev5(&scratch("combine"));
        let mut loader = Loader::new();
        let both = [ChannelSource::new(&path, "1-AC-SIME*", 1.0)];
        let err = loader.signal(&both, None, "x").unwrap_err();
        assert!(matches!(err, LoadError::Combine { count: 2 }), "{err}");
        assert!(matches!(
            loader.signal(&[], Some(Combine::Sum), "x"),
            Err(LoadError::NoChannels)
        ));
        let missing = [ChannelSource::new(
            path.with_file_name("none.EV5"),
            "1",
            1.0,
        )];
        assert!(matches!(
            loader.signal(&missing, None, "x"),
            Err(LoadError::Data(_))
        ));
        let huge = [ChannelSource::new(&path, "1", f64::MAX)];
        assert!(matches!(
            loader.signal(&huge, None, "x"),
            Err(LoadError::Process(_))
        ));
    }
}
