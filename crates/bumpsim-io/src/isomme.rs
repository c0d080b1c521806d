//! ISO/TS 13499 "ISO-MME" test folders (spec §4): reading and writing.
//!
//! A test is a folder with `<test>.mme` (test header, `Key :value` lines),
//! `Channel/<test>.chn` (`Number of channels`, `Name of channel 001 :CODE / name`)
//! and one file per channel, `Channel/<test>.001`, `.002`, ...: header lines
//! `Key :value` (any order; `NOVALUE` means empty) followed by one value per
//! line. Accepted: the folder, its `.mme` file, or a `.zip` of the folder;
//! CRLF or LF; UTF-8 or Latin-1; numbers such as `1.0E-4` or
//! `9.999999999999999e-05`. File names are matched case-insensitively.
//!
//! Time base: implicit (`Time of first sample`, `Sampling interval`, s) or
//! explicit (`Reference channel :explicit` with `Reference channel name`
//! naming the channel code whose samples are the times, s). Values are
//! converted from `Unit` (`g`, `kN`, `mm`, `m/s**2`, ...) to SI. Test speed is
//! `Velocity test object 1` (m/s) and test mass `Mass test object 1` (kg).
//!
//! The writer writes SI values with the shortest decimal form that reads back
//! to the same `f64`, so a written test reads back bit-identical.

use crate::signal_error::{SignalFileError, decode, parse_number};
use crate::test_data::{Entry, Format, Store, TestData, Validity};
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, Unit};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The fields of a 16-character ISO/TS 13499 channel code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChannelCode {
    /// Test object: `0`..`9` vehicles, `P` pendulum / impactor, `B` barrier, `D` dummy...
    pub test_object: char,
    /// Position (seat or side).
    pub position: char,
    /// Main location, 4 characters (`SIME` sill/side member, `HEAD`, `IMPA` impactor).
    pub main_location: String,
    /// Fine locations 1, 2 and 3, 2 characters each.
    pub fine_locations: [String; 3],
    /// Physical dimension, 2 characters (`AC`, `FO`, `DS`, `VE`).
    pub dimension: String,
    /// Direction (`X`, `Y`, `Z`, `R`, `0`).
    pub direction: char,
    /// Filter class (`A` CFC 1000, `B` 600, `C` 180, `D` 60, `P` prefiltered, `0`/`X` none).
    pub filter_class: char,
}

impl ChannelCode {
    /// Splits a 16-character code; `None` for other lengths.
    pub fn parse(code: &str) -> Option<ChannelCode> {
        let c: Vec<char> = code.trim().chars().collect();
        if c.len() != 16 {
            return None;
        }
        let s = |a: usize, b: usize| c[a..b].iter().collect::<String>();
        Some(ChannelCode {
            test_object: c[0],
            position: c[1],
            main_location: s(2, 6),
            fine_locations: [s(6, 8), s(8, 10), s(10, 12)],
            dimension: s(12, 14),
            direction: c[14],
            filter_class: c[15],
        })
    }

    /// The CFC the filter-class letter stands for, if any.
    pub fn cfc(&self) -> Option<f64> {
        match self.filter_class.to_ascii_uppercase() {
            'A' => Some(1000.0),
            'B' => Some(600.0),
            'C' => Some(180.0),
            'D' => Some(60.0),
            _ => None,
        }
    }
}

/// A header line: key, value, 1-based line.
type HeaderLine = (String, String, usize);

/// A channel file, read but not yet converted.
#[derive(Debug)]
pub(crate) struct RawChannel {
    path: PathBuf,
    text: String,
    header: Vec<HeaderLine>,
}

fn normal_key(key: &str) -> String {
    key.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase()
}

/// Parses the leading `Key :value` lines; returns them and the index of the first data line.
fn parse_header(text: &str) -> (Vec<HeaderLine>, usize) {
    let mut header = Vec::new();
    for (i, line) in text.lines().enumerate() {
        match line.split_once(':') {
            Some((key, value)) if parse_number(line).is_none() => {
                header.push((key.trim().to_string(), value.trim().to_string(), i + 1))
            }
            _ if line.trim().is_empty() => {}
            _ => return (header, i),
        }
    }
    let count = text.lines().count();
    (header, count)
}

fn lookup<'h>(header: &'h [HeaderLine], key: &str) -> Option<&'h HeaderLine> {
    let key = normal_key(key);
    header.iter().find(|(k, v, _)| {
        normal_key(k) == key && !v.eq_ignore_ascii_case("NOVALUE") && !v.is_empty()
    })
}

impl RawChannel {
    fn new(path: PathBuf, text: String) -> RawChannel {
        let (header, _) = parse_header(&text);
        RawChannel { path, text, header }
    }

    fn value(&self, key: &str) -> Option<&str> {
        lookup(&self.header, key).map(|(_, v, _)| v.as_str())
    }

    fn required(&self, key: &str) -> Result<&HeaderLine, SignalFileError> {
        lookup(&self.header, key).ok_or_else(|| {
            SignalFileError::file(
                &self.path,
                format!("header field '{key}' is missing or NOVALUE"),
            )
        })
    }

    fn number(&self, key: &str) -> Result<f64, SignalFileError> {
        let (_, value, line) = self.required(key)?;
        parse_number(value).ok_or_else(|| {
            SignalFileError::line(
                &self.path,
                *line,
                format!("'{key}' is '{value}', expected a number"),
            )
        })
    }

    fn values(&self) -> Result<Vec<f64>, SignalFileError> {
        let (_, first) = parse_header(&self.text);
        let lines = self.text.lines().enumerate().skip(first);
        let values = lines
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| {
                parse_number(l).ok_or_else(|| {
                    SignalFileError::line(
                        &self.path,
                        i + 1,
                        format!("'{}' is not a finite number", l.trim()),
                    )
                })
            })
            .collect::<Result<Vec<f64>, _>>()?;
        let (_, declared, line) = self.required("Number of samples")?;
        let declared_count = declared.parse::<usize>().map_err(|_| {
            SignalFileError::line(
                &self.path,
                *line,
                format!("'Number of samples' is '{declared}', expected a count"),
            )
        })?;
        if declared_count != values.len() {
            let end = self.text.lines().count();
            return Err(SignalFileError::line(
                &self.path,
                end,
                format!(
                    "the header (line {line}) declares {declared_count} samples but the file holds {} (truncated or sample count mismatch)",
                    values.len()
                ),
            ));
        }
        Ok(values)
    }

    fn unit(&self) -> Result<Unit, SignalFileError> {
        let (_, text, line) = self.required("Unit")?;
        Unit::parse(text).map_err(|e| SignalFileError::line(&self.path, *line, e.to_string()))
    }

    /// Converts to a channel in SI units.
    pub(crate) fn to_channel(
        &self,
        entry: &Entry,
        all: &[RawChannel],
    ) -> Result<Channel, SignalFileError> {
        let unit = self.unit()?;
        let values: Vec<f64> = self.values()?.into_iter().map(|v| unit.to_si(v)).collect();
        let (start, step) = self.time_base(all, values.len())?;
        let series = UniformSeries::new(start, step, values)
            .map_err(|e| SignalFileError::file(&self.path, e.to_string()))?;
        let mut channel = Channel::new(&entry.code, &entry.name, unit.dimension, series);
        channel.source_unit = unit.symbol.to_string();
        channel.metadata = entry.metadata.clone();
        Ok(channel)
    }

    fn time_base(&self, all: &[RawChannel], count: usize) -> Result<(f64, f64), SignalFileError> {
        let explicit = self
            .value("Reference channel")
            .is_some_and(|v| v.to_lowercase().starts_with("explicit"));
        let own_times = self.unit().is_ok_and(|u| u.dimension == Dimension::Time);
        if !explicit && own_times && self.value("Sampling interval").is_none() {
            let times = self.values()?;
            return uniform_time_base(&times, count)
                .map_err(|m| SignalFileError::file(&self.path, m));
        }
        if !explicit {
            return Ok((
                self.number("Time of first sample")?,
                self.number("Sampling interval")?,
            ));
        }
        let (_, name, line) = self.required("Reference channel name")?;
        let reference = all
            .iter()
            .find(|r| {
                r.value("Channel code")
                    .is_some_and(|c| c.eq_ignore_ascii_case(name))
            })
            .ok_or_else(|| {
                SignalFileError::line(
                    &self.path,
                    *line,
                    format!("reference channel '{name}' is not in the test"),
                )
            })?;
        let times = reference.values()?;
        uniform_time_base(&times, count).map_err(|m| SignalFileError::file(&reference.path, m))
    }
}

/// Start and interval of explicit sample times, checked to be uniform.
fn uniform_time_base(times: &[f64], count: usize) -> Result<(f64, f64), String> {
    if times.len() != count || count < 2 {
        return Err(format!(
            "the time channel has {} samples, the channel {count}",
            times.len()
        ));
    }
    let step = (times[count - 1] - times[0]) / (count - 1) as f64;
    let bad =
        (0..count).find(|&k| (times[k] - times[0] - k as f64 * step).abs() > 0.01 * step.abs());
    match bad {
        _ if step <= 0.0 => Err("time does not increase".into()),
        Some(k) => Err(format!(
            "sample {} at {} s breaks the uniform interval {step} s",
            k + 1,
            times[k]
        )),
        None => Ok((times[0], step)),
    }
}

/// Where the files of a test are: a folder or a zip archive in memory.
enum Source {
    Folder(PathBuf),
    Zip {
        archive: PathBuf,
        base: String,
        members: Vec<(String, Vec<u8>)>,
    },
}

impl Source {
    /// Reads `relative` (e.g. `Channel/T1.chn`), matching names case-insensitively.
    fn read(&self, relative: &str) -> Result<(PathBuf, String), SignalFileError> {
        match self {
            Source::Folder(root) => {
                let path = find_case_insensitive(root, relative);
                let bytes = std::fs::read(&path).map_err(|e| SignalFileError::read(&path, e))?;
                Ok((path, decode(&bytes)))
            }
            Source::Zip {
                archive,
                base,
                members,
            } => {
                let wanted = format!("{base}{relative}").to_lowercase();
                let display = PathBuf::from(format!("{}!{base}{relative}", archive.display()));
                let member = members.iter().find(|(n, _)| n.to_lowercase() == wanted);
                member
                    .map(|(_, b)| (display.clone(), decode(b)))
                    .ok_or_else(|| SignalFileError::file(display, "missing from the archive"))
            }
        }
    }
}

/// `root/relative` with each component matched case-insensitively when the exact name is absent.
fn find_case_insensitive(root: &Path, relative: &str) -> PathBuf {
    relative.split('/').fold(root.to_path_buf(), |dir, part| {
        let exact = dir.join(part);
        if exact.exists() {
            return exact;
        }
        let found = std::fs::read_dir(&dir).ok().and_then(|entries| {
            entries.flatten().map(|e| e.path()).find(|p| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().eq_ignore_ascii_case(part))
            })
        });
        found.unwrap_or(exact)
    })
}

/// Opens the test in `folder` (the folder holding exactly one `.mme` file).
pub fn open_folder(folder: &Path) -> Result<TestData, SignalFileError> {
    let entries = std::fs::read_dir(folder).map_err(|e| SignalFileError::read(folder, e))?;
    let mme: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("mme")))
        .collect();
    match mme.as_slice() {
        [one] => open_mme(one),
        [] => Err(SignalFileError::file(
            folder,
            "no .mme file: not an ISO-MME test folder",
        )),
        _ => Err(SignalFileError::file(
            folder,
            format!("{} .mme files; name the one to open", mme.len()),
        )),
    }
}

/// Opens the test whose `.mme` file is `path`.
pub fn open_mme(path: &Path) -> Result<TestData, SignalFileError> {
    let root = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    build(Source::Folder(root), &name, path)
}

/// Opens a `.zip` holding an ISO-MME test folder (at any depth).
pub fn open_zip(path: &Path) -> Result<TestData, SignalFileError> {
    let file = std::fs::File::open(path).map_err(|e| SignalFileError::read(path, e))?;
    let zip_error = |e: zip::result::ZipError| {
        SignalFileError::file(path, format!("not a readable zip archive: {e}"))
    };
    let mut archive = zip::ZipArchive::new(file).map_err(zip_error)?;
    let mut members = Vec::new();
    for i in 0..archive.len() {
        let mut member = archive.by_index(i).map_err(zip_error)?;
        let mut bytes = Vec::new();
        member
            .read_to_end(&mut bytes)
            .map_err(|e| SignalFileError::read(path, e))?;
        let name = member.name().map_err(zip_error)?.to_string();
        members.push((name, bytes));
    }
    let mme = members
        .iter()
        .map(|(n, _)| n.clone())
        .find(|n| n.to_lowercase().ends_with(".mme"))
        .ok_or_else(|| SignalFileError::file(path, "the archive holds no .mme file"))?;
    let (base, name) = match mme.rfind('/') {
        Some(i) => (mme[..=i].to_string(), mme[i + 1..].to_string()),
        None => (String::new(), mme.clone()),
    };
    build(
        Source::Zip {
            archive: path.to_path_buf(),
            base,
            members,
        },
        &name,
        path,
    )
}

fn build(source: Source, mme_name: &str, opened: &Path) -> Result<TestData, SignalFileError> {
    let stem = mme_name
        .rsplit_once('.')
        .map_or(mme_name, |(s, _)| s)
        .to_string();
    let (_, mme_text) = source.read(mme_name)?;
    let (mme_header, _) = parse_header(&mme_text);
    let (chn_path, chn_text) =
        source
            .read(&format!("Channel/{stem}.chn"))
            .map_err(|e| match e {
                SignalFileError::Io { path, .. } | SignalFileError::File { path, .. } => {
                    SignalFileError::file(
                        path,
                        "missing: an ISO-MME test lists its channels in Channel/<test>.chn",
                    )
                }
                other => other,
            })?;
    let (chn_header, _) = parse_header(&chn_text);
    let count = channel_count(&chn_header, &chn_path)?;
    let raws = (1..=count)
        .map(|i| {
            source
                .read(&format!("Channel/{stem}.{i:03}"))
                .map(|(p, t)| RawChannel::new(p, t))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let entries = raws
        .iter()
        .enumerate()
        .map(|(i, r)| entry(i + 1, r, &chn_header))
        .collect();
    let number = |key: &str| lookup(&mme_header, key).and_then(|(_, v, _)| parse_number(v));
    let title = lookup(&mme_header, "Title").map_or(stem.clone(), |(_, v, _)| v.clone());
    Ok(TestData {
        path: opened.to_path_buf(),
        format: Format::IsoMme,
        title,
        speed: number("Velocity test object 1"),
        mass: number("Mass test object 1"),
        metadata: mme_header.into_iter().map(|(k, v, _)| (k, v)).collect(),
        entries,
        store: Store::IsoMme(raws),
    })
}

fn channel_count(header: &[HeaderLine], path: &Path) -> Result<usize, SignalFileError> {
    let (_, value, line) = lookup(header, "Number of channels")
        .ok_or_else(|| SignalFileError::file(path, "'Number of channels' is missing"))?;
    value.parse().map_err(|_| {
        SignalFileError::line(
            path,
            *line,
            format!("'Number of channels' is '{value}', expected a count"),
        )
    })
}

fn entry(number: usize, raw: &RawChannel, chn: &[HeaderLine]) -> Entry {
    let listed = lookup(chn, &format!("Name of channel {number:03}")).map(|(_, v, _)| v.as_str());
    let (listed_code, listed_name) = listed
        .and_then(|v| v.split_once('/'))
        .unwrap_or((listed.unwrap_or(""), ""));
    let code = raw
        .value("Channel code")
        .unwrap_or(listed_code.trim())
        .to_string();
    let name = raw
        .value("Name of the channel")
        .unwrap_or(listed_name.trim())
        .to_string();
    Entry {
        number,
        code,
        name,
        unit: raw.value("Unit").unwrap_or("?").to_string(),
        validity: Validity::Valid,
        present: true,
        metadata: raw
            .header
            .iter()
            .map(|(k, v, _)| (k.clone(), v.clone()))
            .collect(),
    }
}

/// The keys the writer sets itself; metadata under these keys is replaced.
const OWN_KEYS: [&str; 7] = [
    "Name of the channel",
    "Channel code",
    "Unit",
    "Time of first sample",
    "Sampling interval",
    "Number of samples",
    "Reference channel",
];

fn header_line(key: &str, value: &str) -> String {
    format!("{key:<28}:{value}\r\n")
}

/// Writes channels (SI values) as an ISO-MME test `folder/<name>.mme`,
/// `folder/Channel/<name>.chn` and `.001`... Test metadata lines are
/// written to the `.mme` file in order. Returns the `.mme` path.
pub fn write(
    folder: &Path,
    name: &str,
    metadata: &[(String, String)],
    channels: &[Channel],
) -> Result<PathBuf, SignalFileError> {
    let channel_dir = folder.join("Channel");
    std::fs::create_dir_all(&channel_dir).map_err(|e| SignalFileError::write(&channel_dir, e))?;
    let mut mme = String::new();
    if !metadata
        .iter()
        .any(|(k, _)| normal_key(k) == "data format edition number")
    {
        mme += &header_line("Data format edition number", "1.6");
    }
    for (key, value) in metadata {
        mme += &header_line(key, value);
    }
    let mme_path = folder.join(format!("{name}.mme"));
    write_file(&mme_path, &mme)?;
    let mut chn = header_line("Number of channels", &channels.len().to_string());
    for (i, c) in channels.iter().enumerate() {
        chn += &header_line(
            &format!("Name of channel {:03}", i + 1),
            &format!("{} / {}", c.code, c.name),
        );
        write_file(
            &channel_dir.join(format!("{name}.{:03}", i + 1)),
            &channel_text(c),
        )?;
    }
    write_file(&channel_dir.join(format!("{name}.chn")), &chn)?;
    Ok(mme_path)
}

fn channel_text(channel: &Channel) -> String {
    let s = &channel.series;
    let own = [
        channel.name.clone(),
        channel.code.clone(),
        channel.dimension.si_symbol().replace('^', "**"),
        format!("{:e}", s.start()),
        format!("{:e}", s.step()),
        s.len().to_string(),
        "implicit".to_string(),
    ];
    let mut text: String = OWN_KEYS
        .iter()
        .zip(&own)
        .map(|(k, v)| header_line(k, v))
        .collect();
    let own_keys: Vec<String> = OWN_KEYS.iter().map(|k| normal_key(k)).collect();
    for (key, value) in channel
        .metadata
        .iter()
        .filter(|(k, _)| !own_keys.contains(&normal_key(k)))
    {
        text += &header_line(key, value);
    }
    for v in s.values() {
        text += &format!("{v:e}\r\n");
    }
    text
}

fn write_file(path: &Path, text: &str) -> Result<(), SignalFileError> {
    std::fs::write(path, text).map_err(|e| SignalFileError::write(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn channel_code_fields() {
        let code = ChannelCode::parse("10SIMELE0000ACXD").unwrap();
        assert_eq!(code.test_object, '1');
        assert_eq!(code.main_location, "SIME");
        assert_eq!(code.fine_locations[0], "LE");
        assert_eq!(code.dimension, "AC");
        assert_eq!(code.direction, 'X');
        assert_eq!(code.cfc(), Some(60.0));
        assert!(ChannelCode::parse("short").is_none());
    }

    #[test]
    fn header_stops_at_the_first_value() {
        let (h, first) = parse_header("Unit :g\r\nTime of first sample :-1.0E-4\r\n1.5\r\n2\r\n");
        assert_eq!(h.len(), 2);
        assert_eq!(first, 2);
        assert_eq!(h[1].1, "-1.0E-4");
    }

    #[test]
    fn explicit_time_must_be_uniform() {
        assert_eq!(uniform_time_base(&[0.0, 0.1, 0.2], 3), Ok((0.0, 0.1)));
        assert!(uniform_time_base(&[0.0, 0.1, 0.5], 3).is_err());
        assert!(uniform_time_base(&[0.0, 0.1], 3).is_err());
    }
}
