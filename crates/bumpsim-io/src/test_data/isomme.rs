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
//! to the same `f64`, so a written test reads back bit-identical, under the
//! full ISO/TS 13499 channel header ([`iso_header`]): codes that follow the
//! processing, NHTSA codes mapped to ISO ones, transducer fields carried
//! over, and the test object's speed and mass in the `.mme` file.

use super::{Entry, Format, Store, TestData, Validity, iso_header};
use crate::signal_error::{SignalFileError, TimeBaseError, decode, parse_number};
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, Unit};
#[cfg(feature = "zip")]
use std::io::Read;
use std::path::{Path, PathBuf};

pub use bumpsim_core::channel::ChannelCode;

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
        let mut values = Vec::new();
        for (i, l) in lines.filter(|(_, l)| !l.trim().is_empty()) {
            super::check_sample_count(values.len(), &self.path, i + 1)?;
            values.push(parse_number(l).ok_or_else(|| {
                let message = format!("'{}' is not a finite number", l.trim());
                SignalFileError::line(&self.path, i + 1, message)
            })?);
        }
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
        // pyisomme writes a dimensionless unit as an empty `Unit :` line
        let blank = self
            .header
            .iter()
            .any(|(k, v, _)| normal_key(k) == "unit" && v.is_empty());
        if blank && lookup(&self.header, "Unit").is_none() {
            return Ok(Unit::si(Dimension::Dimensionless));
        }
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
            return uniform_time_base(&times, count).map_err(time_base_error(&self.path));
        }
        if !explicit {
            let start = self.number("Time of first sample")?;
            let (_, _, line) = self.required("Sampling interval")?;
            let step = self.number("Sampling interval")?;
            let step = super::check_interval(step, &self.path, *line, "'Sampling interval'")?;
            return Ok((start, step));
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
        uniform_time_base(&times, count).map_err(time_base_error(&reference.path))
    }
}

/// Start and interval of explicit sample times, checked to be uniform.
fn uniform_time_base(times: &[f64], count: usize) -> Result<(f64, f64), TimeBaseError> {
    if times.len() != count || count < 2 {
        return Err(TimeBaseError::Count {
            times: times.len(),
            count,
        });
    }
    let step = (times[count - 1] - times[0]) / (count - 1) as f64;
    let bad =
        (0..count).find(|&k| (times[k] - times[0] - k as f64 * step).abs() > 0.01 * step.abs());
    match bad {
        _ if step <= 0.0 => Err(TimeBaseError::NotIncreasing),
        Some(k) => Err(TimeBaseError::Irregular {
            sample: k + 1,
            time: times[k],
            step,
        }),
        None => Ok((times[0], step)),
    }
}

/// A time-base error of the times in `path`.
fn time_base_error(path: &Path) -> impl FnOnce(TimeBaseError) -> SignalFileError + '_ {
    |source| SignalFileError::TimeBase {
        path: path.into(),
        source,
    }
}

/// Where the files of a test are: a folder or a zip archive in memory.
enum Source {
    Folder(PathBuf),
    #[cfg_attr(not(feature = "zip"), allow(dead_code))]
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
                let bytes = crate::signal_error::read_bytes(&path)?;
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

/// Most channels an ISO-MME test may list (`Number of channels` in the
/// `.chn` file); channel files are numbered with up to four digits.
pub const MAX_CHANNELS: usize = 9_999;
/// Largest inflated size of an ISO-MME zip archive, in bytes.
pub const MAX_ZIP_BYTES: u64 = 1 << 30;
/// Most inflated bytes per byte of the archive (real tests compress ~5-20 ×).
pub const MAX_ZIP_RATIO: u64 = 200;

/// Opens a `.zip` holding an ISO-MME test folder: without this crate's
/// `zip` feature (on by default) a clear error instead.
#[cfg(not(feature = "zip"))]
pub fn open_zip(path: &Path) -> Result<TestData, SignalFileError> {
    Err(SignalFileError::file(
        path,
        "reading a .zip test needs bumpsim-io's `zip` feature (on by default; the CLI has it)",
    ))
}

/// Opens a `.zip` holding an ISO-MME test folder (at any depth); inflating
/// stops at [`MAX_ZIP_BYTES`] or [`MAX_ZIP_RATIO`] times the archive size.
#[cfg(feature = "zip")]
pub fn open_zip(path: &Path) -> Result<TestData, SignalFileError> {
    if let Some(kind) = bumpsim_core::files::not_a_file(path)? {
        let path = path.into();
        return Err(bumpsim_core::files::ReadError::NotAFile { path, kind }.into());
    }
    let file = std::fs::File::open(path).map_err(|e| SignalFileError::read(path, e))?;
    let zip_error = |e: zip::result::ZipError| {
        SignalFileError::file(path, format!("not a readable zip archive: {e}"))
    };
    let archive_size = file.metadata().map_or(0, |m| m.len());
    let mut archive = zip::ZipArchive::new(file).map_err(zip_error)?;
    let mut members = Vec::new();
    // inflate at most the limit (never trusting the declared sizes)
    let limit = MAX_ZIP_BYTES.min(archive_size.saturating_mul(MAX_ZIP_RATIO).max(1 << 20));
    let mut total = 0u64;
    for i in 0..archive.len() {
        let member = archive.by_index(i).map_err(zip_error)?;
        let name = member.name().map_err(zip_error)?.to_string();
        let mut bytes = Vec::new();
        member
            .take(limit - total + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| SignalFileError::read(path, e))?;
        total += bytes.len() as u64;
        if total > limit {
            return Err(SignalFileError::file(
                path,
                format!(
                    "the archive inflates beyond {limit} bytes (limits: {MAX_ZIP_BYTES} bytes, {MAX_ZIP_RATIO} × the archive size): refused as a possible zip bomb"
                ),
            ));
        }
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
    let read = (1..=count).map(|i| source.read(&format!("Channel/{stem}.{i:03}")));
    let (mut entries, raws): (Vec<Entry>, Vec<RawChannel>) = read
        .enumerate()
        .map(|(i, file)| channel_file(i + 1, file, &chn_header))
        .unzip();
    mark_unreadable(&mut entries, &raws);
    let title = lookup(&mme_header, "Title").map_or(stem.clone(), |(_, v, _)| v.clone());
    let (speed, mass) = moving_object(&mme_header);
    Ok(TestData {
        path: opened.to_path_buf(),
        format: Format::IsoMme,
        title,
        speed,
        mass,
        metadata: mme_header.into_iter().map(|(k, v, _)| (k, v)).collect(),
        entries,
        store: Store::IsoMme(raws),
    })
}

/// The impact speed (m/s) and mass (kg): test object 1's, unless it stands
/// still and another test object moves (a pendulum striking a parked car
/// that is test object 1), then the first moving object's.
fn moving_object(header: &[HeaderLine]) -> (Option<f64>, Option<f64>) {
    let number = |key: String| lookup(header, &key).and_then(|(_, v, _)| parse_number(v));
    let objects =
        number("Number of test objects".into()).map_or(1, |n| n.clamp(1.0, 99.0) as usize);
    let moving = (1..=objects)
        .find(|n| number(format!("Velocity test object {n}")).is_some_and(|v| v != 0.0))
        .unwrap_or(1);
    (
        number(format!("Velocity test object {moving}")),
        number(format!("Mass test object {moving}")),
    )
}

fn channel_count(header: &[HeaderLine], path: &Path) -> Result<usize, SignalFileError> {
    let (_, value, line) = lookup(header, "Number of channels")
        .ok_or_else(|| SignalFileError::file(path, "'Number of channels' is missing"))?;
    let count: usize = value.parse().map_err(|_| {
        SignalFileError::line(
            path,
            *line,
            format!("'Number of channels' is '{value}', expected a count"),
        )
    })?;
    if count > MAX_CHANNELS {
        return Err(SignalFileError::line(
            path,
            *line,
            format!("'Number of channels' is {count}, above the limit of {MAX_CHANNELS}"),
        ));
    }
    Ok(count)
}

/// The entry of channel `number` and its file; the entry is absent (with
/// the reason) when the file is missing, empty or truncated. A missing file
/// is kept as an empty placeholder so that channels stay numbered.
fn channel_file(
    number: usize,
    file: Result<(PathBuf, String), SignalFileError>,
    chn: &[HeaderLine],
) -> (Entry, RawChannel) {
    let (raw, why) = match file {
        Ok((path, text)) => (RawChannel::new(path, text), None),
        Err(e) => (RawChannel::new(PathBuf::new(), String::new()), Some(e)),
    };
    let why = why.or_else(|| match raw.text.trim().is_empty() {
        true => Some(SignalFileError::file(&raw.path, "empty channel file")),
        false => raw.values().err(),
    });
    let mut entry = entry(number, &raw, chn);
    entry.present = why.is_none();
    entry.absence = why.map(|e| e.to_string());
    (entry, raw)
}

/// Marks absent, with the reason, every present channel whose unit or time
/// base cannot be read (no `Sampling interval`, a missing reference
/// channel...), so that it is reported and left out like a missing file
/// instead of failing the whole test when loaded.
fn mark_unreadable(entries: &mut [Entry], raws: &[RawChannel]) {
    for (entry, raw) in entries.iter_mut().zip(raws).filter(|(e, _)| e.present) {
        let readable = raw
            .unit()
            .and_then(|_| raw.values())
            .and_then(|values| raw.time_base(raws, values.len()));
        if let Err(why) = readable {
            entry.present = false;
            entry.absence = Some(why.to_string());
        }
    }
}

fn entry(number: usize, raw: &RawChannel, chn: &[HeaderLine]) -> Entry {
    let listed = lookup(chn, &format!("Name of channel {number:03}")).map(|(_, v, _)| v.as_str());
    let (listed_code, listed_name) = listed
        .and_then(|v| v.split_once('/'))
        .unwrap_or((listed.unwrap_or(""), ""));
    let value = |key: &str| raw.value(key);
    let code = value("Channel code")
        .unwrap_or(listed_code.trim())
        .to_string();
    let name = value("Name of the channel")
        .unwrap_or(listed_name.trim())
        .to_string();
    Entry {
        number,
        code,
        name,
        unit: value("Unit").unwrap_or("?").to_string(),
        validity: validity(raw),
        present: true,
        absence: None,
        metadata: raw
            .header
            .iter()
            .map(|(k, v, _)| (k.clone(), v.clone()))
            .collect(),
    }
}

/// Invalid when `Data status` says the channel failed
/// ([`iso_header::FAILED_STATUSES`]), with the status and the comments.
fn validity(raw: &RawChannel) -> Validity {
    let status = raw.value("Data status").unwrap_or("");
    let failed = iso_header::FAILED_STATUSES
        .iter()
        .any(|f| f.eq_ignore_ascii_case(status.trim()));
    match (failed, raw.value("Comments")) {
        (false, _) => Validity::Valid,
        (true, Some(comments)) => Validity::Invalid(format!("Data status {status}: {comments}")),
        (true, None) => Validity::Invalid(format!("Data status {status}")),
    }
}

fn header_line(key: &str, value: &str) -> String {
    format!("{key:<28}:{value}\r\n")
}

/// The files of an ISO-MME test `name` (relative path, text): `<name>.mme`,
/// `Channel/<name>.chn` and `Channel/<name>.001`... Test metadata lines go
/// to the `.mme` file in order (see [`test_header`]); each channel gets the
/// full ISO/TS 13499 header ([`iso_header::channel_header`]) and its SI
/// values in the shortest text that reads back to the same `f64`.
pub fn files(
    name: &str,
    metadata: &[(String, String)],
    channels: &[Channel],
) -> Vec<(String, String)> {
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
    let mut out = vec![(format!("{name}.mme"), mme)];
    let mut chn = header_line("Number of channels", &channels.len().to_string());
    let headers = iso_header::distinct_codes(channels.iter().map(iso_header::channel_header));
    for (i, (c, header)) in channels.iter().zip(headers).enumerate() {
        let mut text: String = header.iter().map(|(k, v)| header_line(k, v)).collect();
        for v in c.series.values() {
            text += &iso_header::number(*v);
            text += "\r\n";
        }
        let code = iso_header::field(&header, "Channel code").unwrap_or_default();
        chn += &header_line(
            &format!("Name of channel {:03}", i + 1),
            &format!("{code} / {}", c.name),
        );
        out.push((format!("Channel/{name}.{:03}", i + 1), text));
    }
    out.push((format!("Channel/{name}.chn"), chn));
    out
}

/// Writes channels (SI values) as an ISO-MME test `folder/<name>.mme`,
/// `folder/Channel/<name>.chn` and `.001`... (the texts of [`files`]).
/// Returns the `.mme` path. The test is staged and moved into place
/// complete ([`crate::output`]); `name` must be a plain file name.
pub fn write(
    folder: &Path,
    name: &str,
    metadata: &[(String, String)],
    channels: &[Channel],
) -> Result<PathBuf, SignalFileError> {
    crate::output::plain_name(name)?;
    let staged = crate::output::stage_folder(folder)?;
    let channel_dir = staged.path().join("Channel");
    std::fs::create_dir_all(&channel_dir).map_err(|e| SignalFileError::write(&channel_dir, e))?;
    for (relative, text) in files(name, metadata, channels) {
        crate::output::write_atomic(&staged.path().join(relative), text.as_bytes())?;
    }
    crate::output::commit(staged)?;
    Ok(folder.join(format!("{name}.mme")))
}

/// The `.mme` lines bumpsim writes for a test it read: title, impact speed
/// (`Velocity test object 1`, m/s) and mass (`Mass test object 1`, kg).
pub fn test_header(test: &TestData) -> Vec<(String, String)> {
    iso_header::test_header(&test.title, test.speed, test.mass)
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::series::UniformSeries;

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
    fn an_empty_unit_line_is_dimensionless_and_a_missing_one_an_error() {
        let raw = |t: &str| RawChannel::new(PathBuf::from("T.001"), t.to_string());
        let blank = raw("Unit :\r\nNumber of samples :1\r\n1\r\n");
        assert_eq!(blank.unit().unwrap().dimension, Dimension::Dimensionless);
        assert!(raw("Number of samples :1\r\n1\r\n").unit().is_err());
        assert!(raw("Unit :NOVALUE\r\n1\r\n").unit().is_err());
    }

    #[test]
    fn samples_beyond_the_limit_are_refused_while_read() {
        let limit = bumpsim_core::files::MAX_INPUT_SAMPLES;
        let text = |n: usize| format!("Number of samples :{n}\r\n{}", "1\r\n".repeat(n));
        let raw = |n| RawChannel::new(PathBuf::from("T.001"), text(n));
        assert_eq!(raw(limit).values().unwrap().len(), limit);
        let e = raw(limit + 1).values().unwrap_err().to_string();
        assert!(
            e.contains(&format!("T.001:{}: more than {limit} samples", limit + 2)),
            "{e}"
        );
    }

    #[test]
    fn a_huge_channel_count_is_refused_before_reading() {
        let (header, _) = parse_header("Number of channels :18446744073709551615\r\n");
        let e = channel_count(&header, Path::new("T.chn")).unwrap_err();
        assert!(e.to_string().contains("above the limit of 9999"), "{e}");
        let (header, _) = parse_header("Number of channels :3\r\n");
        assert_eq!(channel_count(&header, Path::new("T.chn")).unwrap(), 3);
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

    fn written(name: &str, channels: &[Channel], header: &[(String, String)]) -> TestData {
        let dir =
            std::env::temp_dir().join(format!("bumpsim-isomme-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        write(&dir, "T", header, channels).unwrap();
        TestData::open(&dir).unwrap()
    }

    fn channel(code: &str, meta: &[(&str, &str)]) -> Channel {
        let series = UniformSeries::new(-1e-4, 1e-4, vec![0.0, 1.0, 3.0]).unwrap();
        let mut c = Channel::new(code, "x", Dimension::Acceleration, series);
        meta.iter().for_each(|(k, v)| c.set_meta(k, v));
        c
    }

    #[test]
    fn a_failed_channel_reads_back_invalid() {
        let test = written(
            "status",
            &[
                channel("10SIMELE0000ACXP", &[("Data status", "channel failed")]),
                channel("10SIMERI0000ACXP", &[("Data status", "ok")]),
            ],
            &[],
        );
        assert!(
            matches!(test.entries[0].validity, Validity::Invalid(ref why) if why.contains("channel failed"))
        );
        assert_eq!(test.entries[1].validity, Validity::Valid);
        assert_eq!(test.select("10SIME*").unwrap().excluded, vec![0]);
    }

    #[test]
    fn the_moving_test_object_gives_speed_and_mass() {
        use iso_header::{TestObject, test_objects_header};
        let object = |name: &str, speed: f64, mass: f64| TestObject {
            name: name.into(),
            speed: Some(speed),
            mass: Some(mass),
        };
        let header = test_objects_header(
            "T",
            &[object("car", 0.0, 1200.0), object("pendulum", 2.5, 900.0)],
        );
        let test = written(
            "objects",
            &[
                channel("10SIMELE0000ACXP", &[]),
                channel("P0IMPA000000ACXP", &[]),
            ],
            &header,
        );
        assert_eq!((test.speed, test.mass), (Some(2.5), Some(900.0)));
    }

    #[test]
    fn a_channel_without_a_time_base_is_absent_not_fatal() {
        let dir =
            std::env::temp_dir().join(format!("bumpsim-isomme-{}-timeless", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        write(
            &dir,
            "T",
            &[],
            &[
                channel("10SIMELE0000ACXP", &[]),
                channel("10SIMERI0000ACXP", &[]),
            ],
        )
        .unwrap();
        let file = dir.join("Channel/T.002");
        let text = std::fs::read_to_string(&file).unwrap();
        let spoiled: String = text
            .lines()
            .filter(|l| !l.starts_with("Sampling interval"))
            .map(|l| format!("{l}\r\n"))
            .collect();
        std::fs::write(&file, spoiled).unwrap();
        let test = TestData::open(&dir).unwrap();
        assert!(test.entries[0].present);
        assert!(!test.entries[1].present);
        assert!(
            test.entries[1]
                .absence
                .as_deref()
                .unwrap()
                .contains("Sampling interval")
        );
        assert_eq!(test.select("*").unwrap().absent, vec![1]);
    }
}
