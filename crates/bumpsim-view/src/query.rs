//! A request's query string read into checked values: the selected
//! channels (`sel=TEST:INDEX`, repeatable), the processing (`cfc`, `iso`,
//! `bias`, `scale`, `integrate` (repeatable), `combine`, `unit`
//! (repeatable)), the visible window (`t0`, `t1` s, `px` pixels) and the
//! cursors (`ta`, `tb` s).
//!
//! Every number must be finite and within its range; anything else is a
//! [`ViewError::Parameter`] naming the parameter (a 400 answer). Files are
//! named by their index in the command line's list, never by a path.

use crate::error::ViewError;
use bumpsim_core::units::Unit;
use bumpsim_signal::process::Step;

/// The most channels one request may select.
pub const MAX_SELECTED: usize = 64;
/// The most pixels a plot may ask samples for.
pub const MAX_PIXELS: usize = 16_384;
/// The longest query string read.
pub const MAX_QUERY: usize = 16_384;

/// How the selected channels of one test are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Combination {
    /// Each channel on its own.
    None,
    /// Sum (`signal export --combine sum`).
    Sum,
    /// Mean (`signal export --combine mean`).
    Mean,
    /// √(Σ xᵢ²) on the common time base.
    Resultant,
}

/// The processing of the selected channels, in `signal export`'s order:
/// bias, CFC, scale, integrations.
#[derive(Debug, Clone, PartialEq)]
pub struct Processing {
    /// CFC class.
    pub cfc: Option<f64>,
    /// ISO 6487 constant instead of SAE J211-1's.
    pub iso_6487: bool,
    /// Remove the mean before t = 0.
    pub bias: bool,
    /// Factor.
    pub scale: Option<f64>,
    /// Initial values of the integrations (SI).
    pub integrate: Vec<f64>,
    /// Differentiate once.
    pub derivative: bool,
    /// Combination.
    pub combine: Combination,
    /// Display units asked for (one per dimension).
    pub units: Vec<Unit>,
}

/// A checked request.
#[derive(Debug, Clone, PartialEq)]
pub struct Query {
    /// (test, channel entry index) pairs.
    pub selected: Vec<(usize, usize)>,
    /// Processing.
    pub processing: Processing,
    /// Visible window, s.
    pub window: Option<(f64, f64)>,
    /// Plot width, pixels.
    pub pixels: usize,
    /// Cursors, s.
    pub cursors: (Option<f64>, Option<f64>),
    /// Export name (ISO-MME folder, CSV file name).
    pub name: Option<String>,
}

impl Processing {
    /// The steps of bumpsim-signal, in `signal export`'s order.
    pub fn steps(&self) -> Vec<Step> {
        let mut steps = Vec::new();
        if self.bias {
            steps.push(Step::PretriggerBias(true));
        }
        if let Some(class) = self.cfc {
            steps.push(if self.iso_6487 {
                Step::CfcIso(class)
            } else {
                Step::Cfc(class)
            });
        }
        if let Some(factor) = self.scale {
            steps.push(Step::Scale(factor));
        }
        steps.extend(self.integrate.iter().map(|&v| Step::Integrate(v)));
        if self.derivative {
            steps.push(Step::Derivative(true));
        }
        steps
    }
}

/// Decodes `%XX` and `+` of a query component.
pub fn percent_decode(text: &str) -> Result<String, ViewError> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' => {
                let hex = text.get(i + 1..i + 3).unwrap_or("");
                let byte = u8::from_str_radix(hex, 16)
                    .map_err(|_| ViewError::parameter("query", "a bad %-escape"))?;
                out.push(byte);
                i += 2;
            }
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8(out).map_err(|_| ViewError::parameter("query", "not UTF-8"))
}

/// The (key, value) pairs of a query string.
pub fn pairs(query: &str) -> Result<Vec<(String, String)>, ViewError> {
    if query.len() > MAX_QUERY {
        return Err(ViewError::parameter(
            "query",
            format!("longer than {MAX_QUERY} characters"),
        ));
    }
    query
        .split('&')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let (k, v) = p.split_once('=').unwrap_or((p, ""));
            Ok((percent_decode(k)?, percent_decode(v)?))
        })
        .collect()
}

/// A finite number.
pub fn number(key: &str, value: &str) -> Result<f64, ViewError> {
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| ViewError::parameter(key, format!("'{value}' is not a number")))?;
    if !v.is_finite() || v.abs() > 1e12 {
        return Err(ViewError::parameter(
            key,
            format!("{value} is not a finite number of magnitude below 1e12"),
        ));
    }
    Ok(v)
}

fn index(key: &str, value: &str) -> Result<usize, ViewError> {
    value
        .parse()
        .map_err(|_| ViewError::parameter(key, format!("'{value}' is not an index")))
}

fn flag(key: &str, value: &str) -> Result<bool, ViewError> {
    match value {
        "1" | "true" | "" => Ok(true),
        "0" | "false" => Ok(false),
        _ => Err(ViewError::parameter(
            key,
            format!("'{value}': expected 1 or 0"),
        )),
    }
}

impl Query {
    /// Reads and checks a query string.
    pub fn parse(text: &str) -> Result<Query, ViewError> {
        let mut q = Query {
            selected: Vec::new(),
            processing: Processing {
                cfc: None,
                iso_6487: false,
                bias: false,
                scale: None,
                integrate: Vec::new(),
                derivative: false,
                combine: Combination::None,
                units: Vec::new(),
            },
            window: None,
            pixels: 1000,
            cursors: (None, None),
            name: None,
        };
        let (mut t0, mut t1) = (None, None);
        for (key, value) in pairs(text)? {
            let k = key.as_str();
            let p = &mut q.processing;
            match k {
                "sel" => {
                    let (t, c) = value
                        .split_once(':')
                        .ok_or_else(|| ViewError::parameter(k, "expected TEST:CHANNEL"))?;
                    q.selected.push((index(k, t)?, index(k, c)?));
                }
                "cfc" if value.is_empty() => {}
                "cfc" => p.cfc = Some(number(k, &value)?),
                "iso" => p.iso_6487 = flag(k, &value)?,
                "bias" => p.bias = flag(k, &value)?,
                "derivative" => p.derivative = flag(k, &value)?,
                "scale" if value.is_empty() => {}
                "scale" => p.scale = Some(number(k, &value)?),
                "integrate" if p.integrate.len() >= 2 => {
                    return Err(ViewError::parameter(k, "at most two integrations"));
                }
                "integrate" => p.integrate.push(number(k, &value)?),
                "combine" => p.combine = combination(&value)?,
                "unit" if value.is_empty() => {}
                "unit" => p
                    .units
                    .push(Unit::parse(&value).map_err(|e| ViewError::parameter(k, e.to_string()))?),
                "t0" => t0 = Some(number(k, &value)?),
                "t1" => t1 = Some(number(k, &value)?),
                "ta" => q.cursors.0 = Some(number(k, &value)?),
                "tb" => q.cursors.1 = Some(number(k, &value)?),
                "px" => q.pixels = pixels(&value)?,
                "name" => q.name = Some(value),
                _ => return Err(ViewError::parameter(k, "not a parameter of the viewer")),
            }
        }
        if q.selected.len() > MAX_SELECTED {
            return Err(ViewError::parameter(
                "sel",
                format!("more than {MAX_SELECTED} channels"),
            ));
        }
        q.window = match (t0, t1) {
            (Some(a), Some(b)) if a < b => Some((a, b)),
            (Some(_), Some(_)) => return Err(ViewError::parameter("t1", "must exceed t0")),
            (None, None) => None,
            _ => return Err(ViewError::parameter("t0", "give both t0 and t1")),
        };
        Ok(q)
    }
}

fn combination(value: &str) -> Result<Combination, ViewError> {
    Ok(match value {
        "" | "none" => Combination::None,
        "sum" => Combination::Sum,
        "mean" => Combination::Mean,
        "resultant" => Combination::Resultant,
        _ => {
            return Err(ViewError::parameter(
                "combine",
                format!("'{value}': expected none, sum, mean or resultant"),
            ));
        }
    })
}

fn pixels(value: &str) -> Result<usize, ViewError> {
    match value.parse::<usize>() {
        Ok(n) if (1..=MAX_PIXELS).contains(&n) => Ok(n),
        _ => Err(ViewError::parameter(
            "px",
            format!("'{value}': expected a width of 1 to {MAX_PIXELS} pixels"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hostile_numbers_are_refused() {
        for bad in [
            "cfc=NaN",
            "t0=1e400&t1=2",
            "px=0",
            "px=99999999999",
            "scale=inf",
        ] {
            assert!(Query::parse(bad).is_err(), "{bad}");
        }
        let q = Query::parse("sel=0:3&cfc=60&bias=1&integrate=15.86&unit=g").unwrap();
        assert_eq!(q.selected, vec![(0, 3)]);
        assert_eq!(q.processing.steps().len(), 3);
        assert!(Query::parse("sel=0:3&t0=2&t1=1").is_err());
        assert!(Query::parse("path=%2Fetc%2Fpasswd").is_err());
    }
}
