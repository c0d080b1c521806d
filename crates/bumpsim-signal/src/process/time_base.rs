//! Channels on one time base: the overlap of their spans at the finest
//! interval, linear interpolation where their samples differ ([`align`],
//! [`combine`]), and the note of what that did to them ([`resampling`]).

use super::error::ProcessError;
use bumpsim_core::channel::{Channel, ChannelCode};
use bumpsim_core::names;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, format_number};
use bumpsim_io::test_data::iso_header;
use serde::Deserialize;

/// Linear interpolation of a series at time `t` (clamped to its ends).
pub fn interpolate(series: &UniformSeries, t: f64) -> f64 {
    series.at(t)
}

/// How channels are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// The arithmetic mean (left and right side members).
    Mean,
    /// The sum (the cells of a load-cell wall).
    Sum,
}

/// Combines channels of one dimension on their common time base (the
/// overlap of their spans, at the finest interval; linear interpolation
/// where bases differ). The result is named `code`, and its name, comments
/// and ISO code say what it combines (see `combined`).
pub fn combine(channels: &[Channel], how: Combine, code: &str) -> Result<Channel, ProcessError> {
    let first = channels.first().ok_or_else(|| ProcessError::Range {
        channel: code.to_string(),
        step: "combine",
        reason: "no channels to combine".into(),
    })?;
    if let Some(odd) = channels.iter().find(|c| c.dimension != first.dimension) {
        return Err(ProcessError::Range {
            channel: code.to_string(),
            step: "combine",
            reason: format!(
                "{} is {} but {} is {}",
                first.code, first.dimension, odd.code, odd.dimension
            ),
        });
    }
    let base = common_base(channels).ok_or_else(|| ProcessError::Range {
        channel: code.to_string(),
        step: "combine",
        reason: "the channels do not overlap in time".into(),
    })?;
    let scale = match how {
        Combine::Mean => 1.0 / channels.len() as f64,
        Combine::Sum => 1.0,
    };
    let values = base
        .times()
        .iter()
        .map(|&t| {
            scale
                * channels
                    .iter()
                    .map(|c| sample_at(&c.series, t))
                    .sum::<f64>()
        })
        .collect();
    let series = UniformSeries::new(base.start(), base.step(), values).map_err(|source| {
        ProcessError::Series {
            channel: code.to_string(),
            step: "combine",
            source,
        }
    })?;
    Ok(combined(channels, how, code, series))
}

/// The identity of a mean or sum: `code`, a name and comment that say what
/// it combines, the source fields every input shares, and the ISO/TS 13499
/// code of the inputs' common fields with `SU` (sum) or `AV` (average) in
/// the first free fine location (RED B: fine location 1 when it is `00`,
/// else 2), e.g. `B0LOMASU0000FOXP` for the cells of a load-cell wall.
fn combined(channels: &[Channel], how: Combine, code: &str, series: UniformSeries) -> Channel {
    let first = &channels[0];
    if channels.len() == 1 {
        let mut out = first.with_series(series);
        out.code = code.to_string();
        return out;
    }
    let (word, letters) = match how {
        Combine::Mean => ("mean", "AV"),
        Combine::Sum => ("sum", "SU"),
    };
    let mut out = first.with_series(series);
    out.code = code.to_string();
    out.name = format!(
        "{word} of {} channels {}",
        channels.len(),
        names::escaped(code)
    );
    out.metadata = shared_fields(channels);
    let codes: Vec<String> = channels.iter().map(iso_header::iso_code).collect();
    if let Some(merged) = merged_code(&codes, letters) {
        out.set_meta("Channel code", &merged);
    }
    let listed = match codes.as_slice() {
        [one] => one.clone(),
        [a, b] => format!("{a} and {b}"),
        [a, .., z] => format!("{a} … {z}"),
        [] => String::new(),
    };
    out.set_meta(
        "Comments",
        &format!("{} of {} channels: {listed}", word, codes.len()),
    );
    out
}

/// The source fields whose value every channel shares.
fn shared_fields(channels: &[Channel]) -> Vec<(String, String)> {
    let first = &channels[0];
    first
        .metadata
        .iter()
        .filter(|(k, v)| channels[1..].iter().all(|c| c.meta(k) == Some(v.as_str())))
        .cloned()
        .collect()
}

/// The ISO code of what `codes` share (differing fields zero), with
/// `letters` in the first fine location that is `00` (fine location 3 when
/// none is).
fn merged_code(codes: &[String], letters: &str) -> Option<String> {
    let parsed: Vec<ChannelCode> = codes.iter().filter_map(|c| ChannelCode::parse(c)).collect();
    let mut merged = parsed.first()?.clone();
    for other in &parsed[1..] {
        merge(&mut merged, other);
    }
    let free = merged
        .fine_locations
        .iter()
        .position(|f| f == "00")
        .unwrap_or(2);
    merged.fine_locations[free] = letters.to_string();
    Some(merged.to_string())
}

/// Zeroes the fields of `code` that `other` does not share.
fn merge(code: &mut ChannelCode, other: &ChannelCode) {
    if code.test_object != other.test_object {
        code.test_object = '0';
    }
    if code.position != other.position {
        code.position = '0';
    }
    if code.main_location != other.main_location {
        code.main_location = "0000".into();
    }
    for (mine, theirs) in code.fine_locations.iter_mut().zip(&other.fine_locations) {
        if mine != theirs {
            *mine = "00".into();
        }
    }
    if code.direction != other.direction {
        code.direction = '0';
    }
}

/// Samples every channel on their common time base (see [`combine`]):
/// returns the times, s, and one value column per channel.
pub fn align(channels: &[Channel]) -> Result<(Vec<f64>, Vec<Vec<f64>>), ProcessError> {
    let base = common_base(channels).ok_or_else(|| ProcessError::Range {
        channel: channels
            .iter()
            .map(|c| c.code.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        step: "align",
        reason: "the channels do not overlap in time".into(),
    })?;
    let times = base.times();
    let columns = channels
        .iter()
        .map(|c| times.iter().map(|&t| sample_at(&c.series, t)).collect())
        .collect();
    Ok((times, columns))
}

/// What sampling channels on their common time base ([`align`],
/// [`combine`]) does to them: which are interpolated and which lose
/// samples outside the overlap. Nothing of it is silent: the study and the
/// loader turn it into a note.
#[derive(Debug, Clone, PartialEq)]
pub struct Resampling {
    /// The common sample interval, s (the finest of the channels').
    pub step: f64,
    /// The common span's first and last time, s (the channels' overlap).
    pub span: [f64; 2],
    /// Each channel's code, in the order given.
    pub codes: Vec<String>,
    /// Each channel's role in the note (`force`); its code unless
    /// [`Resampling::with_roles`] names them.
    pub roles: Vec<String>,
    /// Channels whose samples do not fall on the common base and are
    /// interpolated linearly: index into `codes` and own interval, s.
    pub interpolated: Vec<(usize, f64)>,
    /// Channels with samples outside the overlap, left out: index into
    /// `codes` and count.
    pub trimmed: Vec<(usize, usize)>,
}

impl std::fmt::Display for Resampling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let own: Vec<f64> = self.interpolated.iter().map(|&(_, step)| step).collect();
        let times = distinct_times(&[&[self.step, self.span[0], self.span[1]], &own[..]].concat());
        let all = match self.codes.len() {
            n if n > 3 => format!("{n} channels"),
            n => (0..n)
                .map(|i| self.named(i))
                .collect::<Vec<_>>()
                .join(" and "),
        };
        write!(
            f,
            "{all} put on one time base, every {} from {} to {}",
            times[0], times[1], times[2]
        )?;
        // channels with the same own interval, or losing as many samples,
        // are named together
        let steps: Vec<(usize, &String)> = self
            .interpolated
            .iter()
            .map(|e| e.0)
            .zip(&times[3..])
            .collect();
        for (every, group) in grouped(&steps) {
            write!(
                f,
                "; {} (every {every}) interpolated linearly",
                self.roles_of(&group)
            )?;
        }
        for (&count, group) in grouped(&self.trimmed) {
            let each = if group.len() > 1 { " each" } else { "" };
            let samples = plural(count, "sample");
            let roles = self.roles_of(&group);
            write!(
                f,
                "; {roles}: {count} {samples}{each} outside that span left out"
            )?;
        }
        Ok(())
    }
}

/// `(index, value)` pairs grouped by equal value, in order of first
/// appearance.
fn grouped<T: PartialEq>(pairs: &[(usize, T)]) -> Vec<(&T, Vec<usize>)> {
    let mut groups: Vec<(&T, Vec<usize>)> = Vec::new();
    for (i, value) in pairs {
        match groups.iter_mut().find(|(v, _)| *v == value) {
            Some((_, members)) => members.push(*i),
            None => groups.push((value, vec![*i])),
        }
    }
    groups
}

impl Resampling {
    /// The same, with the channels named by their roles (`force`,
    /// `displacement`) in the order given; the note then shows both.
    pub fn with_roles(self, roles: &[&str]) -> Resampling {
        let roles = roles.iter().map(ToString::to_string).collect();
        Resampling { roles, ..self }
    }

    /// The roles of channels `group`, escaped, joined by commas.
    fn roles_of(&self, group: &[usize]) -> String {
        let roles: Vec<String> = group
            .iter()
            .map(|&i| names::escaped(&self.roles[i]))
            .collect();
        roles.join(", ")
    }

    /// Channel `i` as first named: its code, or its role and code.
    fn named(&self, i: usize) -> String {
        let code = names::escaped(&self.codes[i]);
        match self.roles[i] == self.codes[i] {
            true => code,
            false => format!("{} '{code}'", names::escaped(&self.roles[i])),
        }
    }
}

fn plural(count: usize, noun: &str) -> String {
    match count {
        1 => noun.to_string(),
        _ => format!("{noun}s"),
    }
}

/// `values` (s) in the display unit with the fewest significant digits,
/// from 4 to 12, that keep different values apart (a 1 ns span at 10 ms
/// must not read "from 10.00 ms to 10.00 ms").
fn distinct_times(values: &[f64]) -> Vec<String> {
    let unit = Dimension::Time.display_unit();
    let texts = |digits: usize| -> Vec<String> {
        let text = |v: &f64| {
            format!(
                "{} {}",
                format_number(unit.from_si(*v), digits),
                unit.symbol
            )
        };
        values.iter().map(text).collect()
    };
    let apart = |t: &[String]| {
        (0..values.len()).all(|i| (0..i).all(|j| values[i] == values[j] || t[i] != t[j]))
    };
    (4..=12)
        .map(texts)
        .find(|t| apart(t))
        .unwrap_or_else(|| texts(17))
}

/// What [`align`] or [`combine`] would change in `channels`; `None` when
/// every sample of every channel is used as it is.
///
/// ```
/// use bumpsim_core::prelude::*;
/// use bumpsim_signal::process::resampling;
/// let at = |step: f64, n: usize| UniformSeries::new(0.0, step, vec![1.0; n]).unwrap();
/// let force = Channel::new("F", "force", Dimension::Force, at(2e-4, 500));
/// let x = Channel::new("X", "x", Dimension::Length, at(1e-4, 1000));
/// let r = resampling(&[force, x]).unwrap();
/// assert_eq!(r.interpolated.len(), 1);
/// assert_eq!(r.interpolated[0].0, 0); // F
/// assert_eq!(r.trimmed, vec![(1, 1)]); // X: one sample after the force's last
/// let note = r.with_roles(&["force", "displacement"]).to_string();
/// assert!(note.starts_with("force 'F' and displacement 'X' put on one time base"));
/// ```
pub fn resampling(channels: &[Channel]) -> Option<Resampling> {
    let base = common_base(channels)?;
    let (start, step) = (base.start(), base.step());
    let end = start + step * (base.len() - 1) as f64;
    let on_base = |s: &UniformSeries| {
        let phase = (s.start() - start) / step;
        (s.step() / step - 1.0).abs() < 1e-9 && (phase - phase.round()).abs() < 1e-6
    };
    // samples before the span and after it, counted, not visited
    let outside = |s: &UniformSeries| {
        let slack = 1e-6 * step;
        let index = |t: f64| (t - s.start()) / s.step();
        let before = index(start - slack).ceil().clamp(0.0, s.len() as f64) as usize;
        let through = (index(end + slack).floor() + 1.0).clamp(0.0, s.len() as f64) as usize;
        s.len() - through + before
    };
    let series = || channels.iter().map(|c| &c.series).enumerate();
    let interpolated: Vec<(usize, f64)> = series()
        .filter(|(_, s)| !on_base(s))
        .map(|(i, s)| (i, s.step()))
        .collect();
    let trimmed: Vec<(usize, usize)> = series()
        .map(|(i, s)| (i, outside(s)))
        .filter(|&(_, n)| n > 0)
        .collect();
    let codes: Vec<String> = channels.iter().map(|c| c.code.clone()).collect();
    let changed = !(interpolated.is_empty() && trimmed.is_empty());
    changed.then(|| Resampling {
        step,
        span: [start, end],
        roles: codes.clone(),
        codes,
        interpolated,
        trimmed,
    })
}

/// The value at `t`, exact when `t` falls on a sample.
fn sample_at(series: &UniformSeries, t: f64) -> f64 {
    let x = (t - series.start()) / series.step();
    let k = x.round();
    if (x - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < series.len() {
        return series.values()[k as usize];
    }
    interpolate(series, t)
}

/// The overlap of the channels' spans sampled at the finest interval.
fn common_base(channels: &[Channel]) -> Option<UniformSeries> {
    if channels.is_empty() {
        return None;
    }
    let start = channels
        .iter()
        .map(|c| c.series.start())
        .fold(f64::NEG_INFINITY, f64::max);
    let end = channels
        .iter()
        .map(|c| c.series.end())
        .fold(f64::INFINITY, f64::min);
    let step = channels
        .iter()
        .map(|c| c.series.step())
        .fold(f64::INFINITY, f64::min);
    if end < start {
        return None;
    }
    let count = ((end - start) / step + 1e-6).floor() as usize + 1;
    UniformSeries::new(start, step, vec![0.0; count]).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resampled_times_get_the_digits_that_tell_them_apart() {
        assert_eq!(
            distinct_times(&[1e-4, 0.01, 0.01 + 1e-9]),
            ["0.10000000 ms", "10.000000 ms", "10.000001 ms"]
        );
        assert_eq!(
            distinct_times(&[1e-4, 1.00000001e-4]),
            ["0.100000000 ms", "0.100000001 ms"]
        );
        assert_eq!(distinct_times(&[0.0, 0.0998]), ["0 ms", "99.80 ms"]);
    }
}
