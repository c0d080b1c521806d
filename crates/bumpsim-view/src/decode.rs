//! Channel codes decoded into the words an engineer reads them in.
//!
//! An ISO/TS 13499 (ISO-MME) code has 16 characters, split by
//! [`ChannelCode::parse`]: test object (1), position (1), main location (4),
//! fine locations 1–3 (2 each), physical dimension (2), direction (1),
//! filter class (1), e.g. `10SIMELE0000ACXP` = test object 1, position 0,
//! sill/side member, fine locations LE 00 00, acceleration, X, prefiltered.
//! An NHTSA code (`1-AC-HDCG-XL`) is object, sensor type, location and
//! axis with its frame (`G` global, `L` local). Letters the tables below do
//! not know are shown as they are: decoding never guesses.

use bumpsim_core::channel::ChannelCode;
use serde::Serialize;

/// The fields of a code, each with its meaning where known.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Decoded {
    /// The standard the code follows: `ISO/TS 13499` or `NHTSA`.
    pub standard: &'static str,
    /// (field, code letters, meaning) in the code's order.
    pub fields: Vec<(&'static str, String, String)>,
}

/// Main locations of ISO/TS 13499 (the ones bumper and crash work reads).
const MAIN_LOCATIONS: &[(&str, &str)] = &[
    ("SIME", "sill / side member"),
    ("HEAD", "head"),
    ("NECK", "neck"),
    ("CHST", "chest"),
    ("PELV", "pelvis"),
    ("FEMR", "femur"),
    ("TIBI", "tibia"),
    ("SEBE", "seat belt"),
    ("VEHC", "vehicle"),
    ("IMPA", "impactor"),
    ("BARR", "barrier"),
    ("BPIL", "B-pillar"),
    ("ENGN", "engine"),
    ("STWH", "steering wheel"),
    ("SEAT", "seat"),
    ("TUNL", "tunnel"),
    ("BUMP", "bumper"),
];

/// Physical dimensions of ISO/TS 13499.
const DIMENSIONS: &[(&str, &str)] = &[
    ("AC", "acceleration"),
    ("VE", "velocity"),
    ("DS", "displacement"),
    ("DC", "deflection"),
    ("FO", "force"),
    ("MO", "moment"),
    ("AN", "angle"),
    ("AV", "angular velocity"),
    ("AA", "angular acceleration"),
    ("PR", "pressure"),
    ("TI", "time"),
    ("EN", "energy"),
    ("MA", "mass"),
];

/// NHTSA sensor types.
const NHTSA_SENSORS: &[(&str, &str)] = &[
    ("AC", "accelerometer"),
    ("LC", "load cell"),
    ("DS", "displacement"),
    ("VE", "velocity"),
    ("AV", "angular velocity"),
    ("EV", "event"),
    ("PR", "pressure"),
];

fn lookup(table: &[(&str, &str)], key: &str) -> String {
    table
        .iter()
        .find(|(k, _)| k.eq_ignore_ascii_case(key))
        .map_or_else(
            || "not in the viewer's table".into(),
            |(_, v)| v.to_string(),
        )
}

fn test_object(c: char) -> String {
    match c.to_ascii_uppercase() {
        d @ '0'..='9' => format!("test object {d}"),
        'P' => "pendulum / impactor".into(),
        'B' => "barrier".into(),
        'D' => "dummy".into(),
        _ => "not in the viewer's table".into(),
    }
}

fn position(c: char) -> String {
    match c {
        '0' => "none (not an occupant)".into(),
        d @ '1'..='9' => format!("position {d}"),
        _ => "not in the viewer's table".into(),
    }
}

fn direction(c: char) -> String {
    match c.to_ascii_uppercase() {
        'X' | 'Y' | 'Z' => format!("{c} axis"),
        'R' => "resultant".into(),
        '0' => "none".into(),
        _ => "not in the viewer's table".into(),
    }
}

fn filter_class(code: &ChannelCode) -> String {
    match (code.cfc(), code.filter_class.to_ascii_uppercase()) {
        (Some(cfc), _) => format!("CFC {cfc}"),
        (None, 'P') => "prefiltered".into(),
        (None, 'S') => "special filter".into(),
        (None, '0' | 'X') => "unfiltered".into(),
        _ => "not in the viewer's table".into(),
    }
}

/// Decodes an ISO/TS 13499 or NHTSA code; `None` for other names (CSV columns).
pub fn decode(code: &str) -> Option<Decoded> {
    if let Some(iso) = ChannelCode::parse(code) {
        let fine = iso.fine_locations.join(" ");
        return Some(Decoded {
            standard: "ISO/TS 13499",
            fields: vec![
                (
                    "test object",
                    iso.test_object.to_string(),
                    test_object(iso.test_object),
                ),
                ("position", iso.position.to_string(), position(iso.position)),
                (
                    "main location",
                    iso.main_location.clone(),
                    lookup(MAIN_LOCATIONS, &iso.main_location),
                ),
                ("fine locations", fine.clone(), fine),
                (
                    "dimension",
                    iso.dimension.clone(),
                    lookup(DIMENSIONS, &iso.dimension),
                ),
                (
                    "direction",
                    iso.direction.to_string(),
                    direction(iso.direction),
                ),
                (
                    "filter class",
                    iso.filter_class.to_string(),
                    filter_class(&iso),
                ),
            ],
        });
    }
    nhtsa(code)
}

fn nhtsa(code: &str) -> Option<Decoded> {
    let parts: Vec<&str> = code.split('-').collect();
    let [object, sensor, location, axis, ..] = parts[..] else {
        return None;
    };
    if sensor.len() != 2 || location.is_empty() || axis.is_empty() {
        return None;
    }
    let mut chars = axis.chars();
    let (dir, frame) = (chars.next()?, chars.next());
    let frame = match frame.map(|c| c.to_ascii_uppercase()) {
        Some('G') => "global (vehicle) frame",
        Some('L') => "local (sensor) frame",
        _ => "frame not stated",
    };
    Some(Decoded {
        standard: "NHTSA",
        fields: vec![
            ("object", object.to_string(), format!("object {object}")),
            ("sensor", sensor.to_string(), lookup(NHTSA_SENSORS, sensor)),
            ("location", location.to_string(), location.to_string()),
            (
                "axis",
                axis.to_string(),
                format!("{} · {frame}", direction(dir)),
            ),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_code_fields() {
        let d = decode("10SIMELE0000ACXD").unwrap();
        assert_eq!(d.fields[2].2, "sill / side member");
        assert_eq!(d.fields[4].2, "acceleration");
        assert_eq!(d.fields[6].2, "CFC 60");
        assert_eq!(d.fields[3].1, "LE 00 00");
    }

    #[test]
    fn nhtsa_code_fields() {
        let d = decode("1-AC-HDCG-XL").unwrap();
        assert_eq!(d.fields[1].2, "accelerometer");
        assert!(d.fields[3].2.contains("local"));
        assert!(decode("force").is_none());
    }
}
