//! A study's sensor kinds, recognised from their channels (issue 44): the
//! ISO/TS 13499 code's physical dimension (characters 13–14) and direction
//! (15), or for a channel without an ISO code its unit's dimension and the
//! study's `axis`.
//!
//! | dimension | direction | place        | sensor                                  |
//! |-----------|-----------|--------------|-----------------------------------------|
//! | `AC`      | `X`       | body / chain | [`Sensor::Body`] / [`Sensor::Chain`]    |
//! | `AC`      | `Y`       | body         | [`Sensor::Lateral`]                     |
//! | `AV`      | `Z`       | none         | [`Sensor::YawRate`]                     |
//! | `DS`      | `X`       | body / chain | [`Sensor::Film`] / [`Sensor::Crush`]    |
//!
//! The planar rigid body's kinematics give each its model reading
//! ([`crate::drive::Driven::sensor_reading`]): at body point r = (ξ, η),
//! `a = A + ψ̈ k × r − ψ̇² r`, so along the body axes
//! `a_x = A_x − ψ̈ η − ψ̇² ξ` and `a_y = A_y + ψ̈ ξ − ψ̇² η`; the angular
//! velocity is ψ̇ everywhere on the body.

use crate::drive::Sensor;
use bumpsim_core::channel::{Channel, ChannelCode};
use bumpsim_core::units::{Dimension, parse_quantity};

/// Why a sensor's kind or noise cannot be taken from the study.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SensingError {
    /// A dimension and direction no planar sensor measures.
    #[error(
        "a {dimension} channel along {axis}: a planar study takes accelerations along x or y (AC X, AC Y), the yaw rate (AV Z) and displacements along x (DS X)"
    )]
    Kind {
        /// The channel's dimension, in words.
        dimension: &'static str,
        /// Its direction as given.
        axis: String,
    },
    /// An axis word other than x, y, z.
    #[error("axis = {0:?}: expected \"x\", \"y\" or \"z\"")]
    Axis(String),
    /// The study's axis contradicts the ISO code's direction.
    #[error("axis = {given:?}, but the ISO code's direction is {code}")]
    Contradiction {
        /// The study's axis.
        given: String,
        /// The code's direction letter.
        code: char,
    },
    /// The place keys do not fit the kind.
    #[error("{0}")]
    Place(&'static str),
    /// A noise that is no positive finite quantity of the channel's dimension.
    #[error(
        "{0}: expected the rms noise, positive, as text with a unit of the channel's dimension (\"0.05 g\", \"0.2 deg/s\") or an SI number from 1e-12 to 1e15"
    )]
    Noise(String),
}

/// The sensor a channel is, placed by the study's `body` or `chain`.
pub fn kind(
    channel: &Channel,
    axis: Option<&str>,
    body: Option<[f64; 2]>,
    chain: Option<usize>,
) -> Result<Sensor, SensingError> {
    let axis = direction(channel, axis)?;
    let wrong = || SensingError::Kind {
        dimension: channel.dimension.name(),
        axis: axis.to_string(),
    };
    let place = |on_body: fn([f64; 2]) -> Sensor, on_chain: Option<fn(usize) -> Sensor>| match (
        body, chain, on_chain,
    ) {
        (Some(p), None, _) => Ok(on_body(p)),
        (None, Some(i), Some(f)) => Ok(f(i)),
        (None, Some(_), None) => Err(SensingError::Place(
            "a lateral accelerometer sits on the body: give body = [ξ, η] (m), not chain",
        )),
        _ => Err(SensingError::Place(
            "give either body = [ξ, η] (m) or chain = index",
        )),
    };
    match (channel.dimension, axis) {
        (Dimension::Acceleration, 'X') => place(Sensor::Body, Some(Sensor::Chain)),
        (Dimension::Acceleration, 'Y') => place(Sensor::Lateral, None),
        (Dimension::Length, 'X') => place(Sensor::Film, Some(Sensor::Crush)),
        // a place given is refused, not dropped: the user may have meant
        // another channel (an accelerometer at that place)
        (Dimension::AngularVelocity, 'Z') => match (body, chain) {
            (None, None) => Ok(Sensor::YawRate),
            (Some(_), _) => Err(SensingError::Place(
                "a yaw-rate channel takes no `body`: a yaw-rate sensor reads the body's rotation, the same everywhere (remove body = [ξ, η], or name the accelerometer meant)",
            )),
            (None, Some(_)) => Err(SensingError::Place(
                "a yaw-rate sensor reads the body's rotation, the same everywhere: it takes no chain",
            )),
        },
        _ => Err(wrong()),
    }
}

/// The channel's direction letter: the ISO code's, checked against the
/// study's `axis`, or the axis (default x; z for an angular velocity).
fn direction(channel: &Channel, axis: Option<&str>) -> Result<char, SensingError> {
    let given = axis
        .map(|a| match a.trim().to_ascii_uppercase().as_str() {
            "X" => Ok('X'),
            "Y" => Ok('Y'),
            "Z" => Ok('Z'),
            _ => Err(SensingError::Axis(a.to_string())),
        })
        .transpose()?;
    let code = ChannelCode::parse(&channel.code).map(|c| c.direction.to_ascii_uppercase());
    match (code, given) {
        (Some(c), Some(g)) if c != g => Err(SensingError::Contradiction {
            given: axis.unwrap_or_default().to_string(),
            code: c,
        }),
        (Some(c), _) => Ok(c),
        (None, Some(g)) => Ok(g),
        (None, None) if channel.dimension == Dimension::AngularVelocity => Ok('Z'),
        (None, None) => Ok('X'),
    }
}

/// A sensor's given noise: text with a unit of `dimension` or an SI number,
/// positive and finite, within [`bumpsim_estimate::domain::NOISE_RANGE`]
/// (1e-300 rad/s left no start that could be evaluated).
pub fn noise(value: &toml::Value, dimension: Dimension) -> Result<f64, SensingError> {
    let sigma = match value {
        toml::Value::Float(v) => Some(*v),
        toml::Value::Integer(v) => Some(*v as f64),
        toml::Value::String(s) => parse_quantity(s, dimension).ok(),
        _ => None,
    };
    sigma
        .filter(|s| bumpsim_estimate::domain::NOISE_RANGE.contains(s))
        .ok_or_else(|| {
            // (TOML prints 1e-300 with all its 300 digits)
            let shown = match value {
                toml::Value::Float(v) => bumpsim_core::units::short(*v),
                other => other.to_string(),
            };
            SensingError::Noise(shown)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::series::UniformSeries;

    fn channel(code: &str, dimension: Dimension) -> Channel {
        let series = UniformSeries::new(0.0, 1e-4, vec![0.0; 4]).unwrap();
        Channel::new(code, code, dimension, series)
    }

    #[test]
    fn iso_codes_name_the_kinds() {
        let acc = Dimension::Acceleration;
        let body = Some([0.6, 0.7]);
        assert_eq!(
            kind(&channel("10SILBLE0000ACXP", acc), None, body, None),
            Ok(Sensor::Body([0.6, 0.7]))
        );
        assert_eq!(
            kind(&channel("10SIMELE0000ACXP", acc), None, None, Some(0)),
            Ok(Sensor::Chain(0))
        );
        assert_eq!(
            kind(&channel("10SILBLE0000ACYP", acc), None, body, None),
            Ok(Sensor::Lateral([0.6, 0.7]))
        );
        let av = channel("10VEHC0000CGAVZP", Dimension::AngularVelocity);
        assert_eq!(kind(&av, None, None, None), Ok(Sensor::YawRate));
        let ds = Dimension::Length;
        assert_eq!(
            kind(&channel("10CRBXLE0000DSXP", ds), None, None, Some(1)),
            Ok(Sensor::Crush(1))
        );
        assert_eq!(
            kind(&channel("10BPILLE0000DSXP", ds), None, body, None),
            Ok(Sensor::Film([0.6, 0.7]))
        );
        // a CSV column: its unit's dimension and the axis
        assert_eq!(
            kind(&channel("lat", acc), Some("y"), body, None),
            Ok(Sensor::Lateral([0.6, 0.7]))
        );
        assert_eq!(
            kind(
                &channel("yaw", Dimension::AngularVelocity),
                None,
                None,
                None
            ),
            Ok(Sensor::YawRate)
        );
    }

    #[test]
    fn hostile_kinds_are_refused_with_the_reason() {
        let body = Some([0.6, 0.7]);
        let acc = Dimension::Acceleration;
        let e = |r: Result<Sensor, SensingError>| r.unwrap_err().to_string();
        // unknown direction: a resultant, a z acceleration, a roll rate
        assert!(e(kind(&channel("10SILBLE0000ACRP", acc), None, body, None)).contains("along R"));
        assert!(e(kind(&channel("10SILBLE0000ACZP", acc), None, body, None)).contains("along Z"));
        let roll = channel("10VEHC0000CGAVXP", Dimension::AngularVelocity);
        assert!(e(kind(&roll, None, None, None)).contains("AV Z"));
        assert!(e(kind(&channel("x", acc), Some("w"), body, None)).starts_with("axis = \"w\""));
        assert!(
            e(kind(
                &channel("10SILBLE0000ACXP", acc),
                Some("y"),
                body,
                None
            ))
            .contains("ISO code's direction is X")
        );
        assert!(e(kind(&channel("10SILBLE0000ACYP", acc), None, None, Some(0))).contains("body"));
        let av = channel("10VEHC0000CGAVZP", Dimension::AngularVelocity);
        assert!(e(kind(&av, None, None, Some(0))).contains("no chain"));
        // a place on a yaw-rate sensor was dropped without a word
        assert!(e(kind(&av, None, body, None)).starts_with("a yaw-rate channel takes no `body`"));
        assert!(e(kind(&channel("f", Dimension::Force), None, body, None)).contains("force"));
        assert!(e(kind(&channel("10SILBLE0000ACXP", acc), None, None, None)).contains("either"));
        for bad in [
            "\"-1 deg/s\"",
            "\"nan deg/s\"",
            "\"2 m\"",
            "0.0",
            "true",
            "1e-300",
            "1e300",
        ] {
            let v: toml::Value =
                toml::from_str::<toml::Table>(&format!("n = {bad}")).unwrap()["n"].clone();
            assert!(noise(&v, Dimension::AngularVelocity).is_err(), "{bad}");
        }
        let v = toml::Value::String("0.2 deg/s".into());
        let sigma = noise(&v, Dimension::AngularVelocity).unwrap();
        assert!((sigma - 0.2f64.to_radians()).abs() < 1e-12);
    }
}
