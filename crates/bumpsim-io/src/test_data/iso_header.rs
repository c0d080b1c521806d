//! What the ISO-MME writer puts in the headers: the ISO/TS 13499 channel
//! header (RED A 1.6, channel file) filled from the channel and its source,
//! the test header (`Velocity test object 1`, `Mass test object 1`), and the
//! NHTSA → ISO channel-code mapping (table in docs/formats.md).
//!
//! Channel header fields, in the standard's order: the ones bumpsim knows
//! (code, name, dimension letters, `Channel frequency class`, SI `Unit`,
//! time base, sample count, extrema) are computed; the rest (transducer,
//! reference system, data source and status, comments) are carried over
//! from the source header, NHTSA fields renamed to their ISO counterparts
//! (`Comment` → `Comments`, `Sensor` → `Transducer type`, `Prefilter (Hz)` → `Cut off frequency`,
//! `Range` → `Channel amplitude class`, axis `…G`/`…L` → `Reference system`
//! global/local). Source fields that no longer hold (`Unit`, NHTSA `Units`
//! and `Time unit` after the conversion to SI) are replaced, and the
//! conversion is recorded in `Comments`.

use bumpsim_core::channel::{Channel, ChannelCode};

/// The ISO/TS 13499 channel-file fields, in order.
pub const CHANNEL_FIELDS: [&str; 37] = [
    "Test object number",
    "Name of the channel",
    "Laboratory channel code",
    "Customer channel code",
    "Channel code",
    "Location",
    "Direction",
    "Test object",
    "Position",
    "Transducer type",
    "Transducer serial number",
    "Transducer natural frequency",
    "Transducer damping ratio",
    "Transducer sensitivity",
    "Transducer mounting",
    "Dimension",
    "Channel frequency class",
    "Unit",
    "Reference system",
    "Pre-filter type",
    "Cut off frequency",
    "Channel amplitude class",
    "Sampling interval",
    "Bit resolution",
    "Time of first sample",
    "Number of samples",
    "Reference channel",
    "Reference channel name",
    "Data source",
    "Data status",
    "First global maximum value",
    "Time of maximum value",
    "First global minimum value",
    "Time of minimum value",
    "Start offset interval",
    "End offset interval",
    "Comments",
];

/// `Data status` values (ISO/TS 13499 RED A) that mark a channel unusable;
/// read back, such a channel is invalid. An invalid channel is written as
/// [`FAILED`].
pub const FAILED_STATUSES: [&str; 4] = [
    "channel failed",
    "meaningless data",
    "no data",
    "system failed",
];

/// The `Data status` bumpsim writes for a channel its source marks invalid.
pub const FAILED: &str = "channel failed";

/// NHTSA EV5 instrumentation fields carried over under their ISO name.
const NHTSA_RENAMED: [(&str, &str); 4] = [
    ("Comment", "Comments"),
    ("Sensor", "Transducer type"),
    ("Prefilter (Hz)", "Cut off frequency"),
    ("Range", "Channel amplitude class"),
];

/// Source fields that the conversion to SI makes wrong; replaced.
const STALE: [&str; 3] = ["Units", "Time unit", "Unit"];

/// NHTSA sensor locations → ISO main location and fine location 1 (and 2).
const NHTSA_LOCATIONS: [(&str, &str, &str, &str); 16] = [
    ("FLLR", "SECM", "LE", "00"),
    ("FLRR", "SECM", "RI", "00"),
    ("ENGN", "ENGN", "00", "00"),
    ("VECG", "VEHC", "00", "00"),
    ("HDCG", "HEAD", "00", "00"),
    ("CHST", "CHST", "00", "00"),
    ("PVCN", "PELV", "00", "00"),
    ("NEKU", "NECK", "UP", "00"),
    ("FMRL", "FEMR", "LE", "00"),
    ("FMRR", "FEMR", "RI", "00"),
    ("TBLU", "TIBI", "LE", "UP"),
    ("TBLL", "TIBI", "LE", "LO"),
    ("TBRU", "TIBI", "RI", "UP"),
    ("TBRL", "TIBI", "RI", "LO"),
    ("LSBM", "SILB", "LE", "00"),
    ("RSBM", "SILB", "RI", "00"),
];

fn meta<'c>(channel: &'c Channel, key: &str) -> Option<&'c str> {
    channel
        .meta(key)
        .map(str::trim)
        .filter(|v| !v.is_empty() && !v.eq_ignore_ascii_case("NOVALUE"))
}

/// The filter-class letter a channel's processing stands for: the letter of
/// its `Channel frequency class`, else `P` (prefiltered raw data).
fn filter_letter(channel: &Channel) -> char {
    meta(channel, "Channel frequency class")
        .and_then(|v| v.parse::<f64>().ok())
        .map_or('P', ChannelCode::filter_letter)
}

/// The ISO/TS 13499 code of a channel: its own code when it is one, else
/// the code its `Channel code` field records (a combined channel's), the
/// mapped code of an NHTSA channel, or an undefined-location code; the last
/// three with the channel's dimension and filter class.
pub fn iso_code(channel: &Channel) -> String {
    if ChannelCode::parse(&channel.code).is_some() {
        return channel.code.clone();
    }
    let letters = ChannelCode::dimension_letters(channel.dimension).unwrap_or("00");
    let recorded = meta(channel, "Channel code").and_then(ChannelCode::parse);
    let code = match (recorded, meta(channel, "Sensor location")) {
        (Some(code), _) => Some(code),
        (None, Some(location)) => nhtsa_code(channel, location),
        (None, None) => ChannelCode::parse(&format!("000000000000{letters}00")),
    };
    let mut code = code
        .unwrap_or_else(|| ChannelCode::parse("000000000000000P").expect("a valid constant code"));
    code.dimension = letters.to_string();
    code.filter_class = match (
        recorded_letter(channel),
        meta(channel, "Channel frequency class"),
    ) {
        (Some(letter), None) => letter,
        _ => filter_letter(channel),
    };
    code.to_string()
}

/// The filter letter of the code a channel's `Channel code` field records.
fn recorded_letter(channel: &Channel) -> Option<char> {
    meta(channel, "Channel code")
        .and_then(ChannelCode::parse)
        .map(|c| c.filter_class)
}

/// Maps an NHTSA curve (vehicle, occupant, location, axis, primary or
/// redundant) to an ISO code; see docs/formats.md for the table.
fn nhtsa_code(channel: &Channel, location: &str) -> Option<ChannelCode> {
    let vehicle = meta(channel, "Vehicle number").unwrap_or("1");
    let test_object = match vehicle {
        "0" => 'B',
        v if v.len() == 1 && v.chars().all(|c| c.is_ascii_digit()) => v.chars().next()?,
        _ => '0',
    };
    let position = match meta(channel, "Occupant location") {
        Some("01") => '1',
        Some("02") => '3',
        _ => '0',
    };
    let (main, fine1, mut fine2) = match location.strip_prefix("LC") {
        Some(cell) if cell.len() == 4 && cell.chars().all(|c| c.is_ascii_digit()) => {
            ("LOMA", cell[..2].to_string(), cell[2..].to_string())
        }
        _ => NHTSA_LOCATIONS
            .iter()
            .find(|(n, ..)| n.eq_ignore_ascii_case(location))
            .map_or(("0000", "00".into(), "00".into()), |&(_, m, f1, f2)| {
                (m, f1.to_string(), f2.to_string())
            }),
    };
    if meta(channel, "Primary/redundant").is_some_and(|p| p.eq_ignore_ascii_case("R")) {
        fine2 = "RD".into();
    }
    let axis = meta(channel, "Axis").unwrap_or("");
    let direction = axis
        .chars()
        .next()
        .map(|c| c.to_ascii_uppercase())
        .filter(|c| "XYZR".contains(*c))
        .unwrap_or('0');
    ChannelCode::parse(&format!(
        "{test_object}{position}{main}{fine1}{fine2}00AA{direction}P"
    ))
}

/// Renders a number as the writer does: the shortest text that reads back
/// to the same `f64`.
pub fn number(value: f64) -> String {
    format!("{value:e}")
}

/// The full channel header of a channel in SI, ISO field order first, then
/// every other source field.
pub fn channel_header(channel: &Channel) -> Vec<(String, String)> {
    let s = &channel.series;
    let values = s.values();
    let (max_at, min_at) = extrema(values);
    let unit = channel.dimension.si_symbol().replace('^', "**");
    let code = iso_code(channel);
    let computed = |key: &str| -> Option<String> {
        Some(match key {
            "Name of the channel" => channel.name.clone(),
            "Channel code" => code.clone(),
            "Test object number" => meta(channel, key)
                .map(str::to_string)
                .or_else(|| test_object_number(&code))?,
            "Test object" if meta(channel, key).is_none() => code[..1].to_string(),
            "Position" if meta(channel, key).is_none() => code[1..2].to_string(),
            "Location" if meta(channel, key).is_none() => code[2..12].to_string(),
            "Laboratory channel code" if code != channel.code => channel.code.clone(),
            "Dimension" => code[12..14].to_string(),
            "Unit" => unit.clone(),
            "Direction" if meta(channel, key).is_none() => code[14..15].to_string(),
            "Reference system" => meta(channel, key)
                .map(str::to_string)
                .or_else(|| nhtsa_reference_system(channel))?,
            "Sampling interval" => number(s.step()),
            "Time of first sample" => number(s.start()),
            "Number of samples" => s.len().to_string(),
            "Reference channel" => "implicit".into(),
            "Reference channel name" => "NOVALUE".into(),
            "First global maximum value" => number(values[max_at]),
            "Time of maximum value" => number(s.time(max_at)),
            "First global minimum value" => number(values[min_at]),
            "Time of minimum value" => number(s.time(min_at)),
            "Comments" => comments(channel, &unit)?,
            _ => return None,
        })
    };
    let carried = |key: &str| {
        let renamed = NHTSA_RENAMED.iter().find(|(_, iso)| *iso == key);
        meta(channel, key)
            .or_else(|| renamed.and_then(|(nhtsa, _)| meta(channel, nhtsa)))
            .map(str::to_string)
    };
    let mut header: Vec<(String, String)> = CHANNEL_FIELDS
        .iter()
        .map(|&key| {
            let value = computed(key).or_else(|| carried(key));
            (key.to_string(), value.unwrap_or_else(|| "NOVALUE".into()))
        })
        .collect();
    let known = |k: &str| {
        CHANNEL_FIELDS.iter().any(|f| f.eq_ignore_ascii_case(k))
            || NHTSA_RENAMED.iter().any(|(n, _)| *n == k)
            || STALE.iter().any(|f| f.eq_ignore_ascii_case(k))
    };
    header.extend(
        channel
            .metadata
            .iter()
            .filter(|(k, _)| !known(k.trim()))
            .map(|(k, v)| (k.trim().to_string(), v.trim().to_string())),
    );
    header
}

/// The test object number a code's first character gives: `1` … `9` for
/// vehicles 1 … 9; none for a barrier, pendulum, dummy...
fn test_object_number(code: &str) -> Option<String> {
    code.chars()
        .next()
        .filter(|c| ('1'..='9').contains(c))
        .map(String::from)
}

/// The value of `key` in a header.
pub fn field(header: &[(String, String)], key: &str) -> Option<String> {
    header
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.clone())
}

/// Channel headers of one test with distinct `Channel code`s: channels that
/// would share a code (two sensors at one location, as NHTSA's top and
/// bottom of the engine) are numbered `01`, `02`, ... in fine location 3,
/// which `Comments` records.
pub fn distinct_codes(
    headers: impl Iterator<Item = Vec<(String, String)>>,
) -> Vec<Vec<(String, String)>> {
    let mut headers: Vec<Vec<(String, String)>> = headers.collect();
    let codes: Vec<String> = headers
        .iter()
        .map(|h| field(h, "Channel code").unwrap_or_default())
        .collect();
    for (i, header) in headers.iter_mut().enumerate() {
        let same: Vec<usize> = (0..codes.len()).filter(|&j| codes[j] == codes[i]).collect();
        if same.len() > 1 {
            let rank = same.iter().position(|&j| j == i).unwrap_or(0) + 1;
            renumber(header, &codes[i], rank, same.len());
        }
    }
    headers
}

/// Puts `rank` (of `count` channels sharing `code`) into fine location 3.
fn renumber(header: &mut [(String, String)], code: &str, rank: usize, count: usize) {
    let Some(mut parsed) = ChannelCode::parse(code) else {
        return;
    };
    parsed.fine_locations[2] = format!("{:02}", rank.min(99));
    let note = format!("fine location 3 numbers {count} channels that share the code {code}");
    for (key, value) in header.iter_mut() {
        match key.as_str() {
            "Channel code" => *value = parsed.to_string(),
            "Location" if *value == code[2..12] => *value = parsed.to_string()[2..12].to_string(),
            "Comments" if value == "NOVALUE" => *value = note.clone(),
            "Comments" => *value = format!("{value}; {note}"),
            _ => {}
        }
    }
}

/// Indices of the first global maximum and minimum.
fn extrema(values: &[f64]) -> (usize, usize) {
    let mut at = (0, 0);
    for (i, &v) in values.iter().enumerate() {
        if v > values[at.0] {
            at.0 = i;
        }
        if v < values[at.1] {
            at.1 = i;
        }
    }
    at
}

/// `global` / `local` from an NHTSA axis code (`XG`, `ZL`).
fn nhtsa_reference_system(channel: &Channel) -> Option<String> {
    let axis = meta(channel, "Axis")?;
    match axis.chars().nth(1).map(|c| c.to_ascii_uppercase()) {
        Some('G') => Some("global".into()),
        Some('L') => Some("local".into()),
        _ => None,
    }
}

/// The source comments, plus a note when the source header's unit (`Unit`,
/// NHTSA `Units`) is not the SI unit written now.
fn comments(channel: &Channel, unit: &str) -> Option<String> {
    let old = meta(channel, "Comments")
        .or_else(|| meta(channel, "Comment"))
        .map(str::to_string);
    let source = meta(channel, "Unit").or_else(|| meta(channel, "Units"));
    let note = source.and_then(|source| {
        let parsed = bumpsim_core::units::Unit::parse(source).ok()?;
        let converted = parsed.dimension == channel.dimension && parsed.factor != 1.0;
        converted.then(|| format!("converted from {source} to {unit}"))
    });
    match (old, note) {
        (Some(o), Some(n)) => Some(format!("{o}; {n}")),
        (o, n) => o.or(n),
    }
}

/// A test object of an ISO-MME test header: its name, speed (m/s) and mass
/// (kg) where known. Objects are numbered from 1 in the order given, the
/// number a vehicle's channel codes carry first (`1…` for test object 1).
#[derive(Debug, Clone, PartialEq)]
pub struct TestObject {
    /// `Name of test object N`.
    pub name: String,
    /// `Velocity test object N`, m/s.
    pub speed: Option<f64>,
    /// `Mass test object N`, kg.
    pub mass: Option<f64>,
}

/// The test header lines for a test's title and its test objects:
/// `Title`, `Number of test objects`, then per object N `Name of test
/// object N`, `Velocity test object N` (m/s) and `Mass test object N` (kg).
pub fn test_objects_header(title: &str, objects: &[TestObject]) -> Vec<(String, String)> {
    let mut header = vec![
        ("Title".to_string(), title.to_string()),
        (
            "Number of test objects".to_string(),
            objects.len().to_string(),
        ),
    ];
    for (i, object) in objects.iter().enumerate() {
        let n = i + 1;
        header.push((format!("Name of test object {n}"), object.name.clone()));
        if let Some(v) = object.speed {
            header.push((format!("Velocity test object {n}"), number(v)));
        }
        if let Some(m) = object.mass {
            header.push((format!("Mass test object {n}"), number(m)));
        }
    }
    header
}

/// The test header lines for a test's title, impact speed (m/s) and mass
/// (kg) of its one test object: `Title`, `Number of test objects`,
/// `Velocity test object 1`, `Mass test object 1`.
pub fn test_header(title: &str, speed: Option<f64>, mass: Option<f64>) -> Vec<(String, String)> {
    let mut header = vec![
        ("Title".to_string(), title.to_string()),
        ("Number of test objects".to_string(), "1".to_string()),
    ];
    if let Some(v) = speed {
        header.push(("Velocity test object 1".into(), number(v)));
    }
    if let Some(m) = mass {
        header.push(("Mass test object 1".into(), number(m)));
    }
    header
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::series::UniformSeries;
    use bumpsim_core::units::Dimension;

    fn nhtsa(fields: &[(&str, &str)], dimension: Dimension) -> Channel {
        let series = UniformSeries::new(0.0, 1e-4, vec![1.0, 3.0, -2.0]).unwrap();
        let mut c = Channel::new("1-AC-FLLR-XG", "x", dimension, series);
        c.metadata = fields
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        c
    }

    #[test]
    fn nhtsa_codes_map_to_iso() {
        let fields = [
            ("Vehicle number", "1"),
            ("Sensor location", "FLLR"),
            ("Axis", "XG"),
            ("Primary/redundant", "P"),
        ];
        let accel = nhtsa(&fields, Dimension::Acceleration);
        assert_eq!(iso_code(&accel), "10SECMLE0000ACXP");
        assert_eq!(iso_code(&accel.clone().filtered(60.0)), "10SECMLE0000ACXD");
        let velocity = accel.with_dimension(Dimension::Velocity);
        assert_eq!(iso_code(&velocity), "10SECMLE0000VEXP");
        let cell = [
            ("Vehicle number", "0"),
            ("Sensor location", "LC0601"),
            ("Axis", "XG"),
            ("Primary/redundant", "R"),
        ];
        assert_eq!(
            iso_code(&nhtsa(&cell, Dimension::Force)),
            "B0LOMA06RD00FOXP"
        );
    }

    #[test]
    fn header_replaces_stale_units_and_carries_transducers() {
        let c = nhtsa(
            &[
                ("Units", "G'S"),
                ("Sensor", "Endevco 7264"),
                ("Axis", "XG"),
                ("Sensor location", "FLLR"),
            ],
            Dimension::Acceleration,
        );
        let header = channel_header(&c);
        let get = |k: &str| {
            header
                .iter()
                .find(|(key, _)| key == k)
                .map(|(_, v)| v.as_str())
        };
        assert_eq!(get("Unit"), Some("m/s**2"));
        assert_eq!(get("Units"), None);
        assert_eq!(get("Transducer type"), Some("Endevco 7264"));
        assert_eq!(get("Reference system"), Some("global"));
        assert_eq!(get("Laboratory channel code"), Some("1-AC-FLLR-XG"));
        assert!(
            get("Comments")
                .unwrap()
                .contains("converted from G'S to m/s**2")
        );
        assert_eq!(get("First global minimum value"), Some("-2e0"));
        assert_eq!(get("Time of maximum value"), Some("1e-4"));
    }

    #[test]
    fn the_code_fills_test_object_position_and_location() {
        let c = nhtsa(
            &[("Sensor location", "FLLR"), ("Axis", "XG")],
            Dimension::Acceleration,
        );
        let header = channel_header(&c);
        let keys: Vec<&str> = header.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys[..CHANNEL_FIELDS.len()], CHANNEL_FIELDS);
        let get = |k: &str| field(&header, k);
        assert_eq!(get("Channel code").as_deref(), Some("10SECMLE0000ACXP"));
        assert_eq!(get("Test object number").as_deref(), Some("1"));
        assert_eq!(get("Test object").as_deref(), Some("1"));
        assert_eq!(get("Position").as_deref(), Some("0"));
        assert_eq!(get("Location").as_deref(), Some("SECMLE0000"));
        assert_eq!(get("Start offset interval").as_deref(), Some("NOVALUE"));
        let barrier = nhtsa(
            &[("Vehicle number", "0"), ("Sensor location", "LC0101")],
            Dimension::Force,
        );
        assert_eq!(
            field(&channel_header(&barrier), "Test object number").as_deref(),
            Some("NOVALUE")
        );
    }

    #[test]
    fn channels_that_would_share_a_code_are_numbered_in_fine_location_3() {
        let top = nhtsa(
            &[("Sensor location", "ENGN"), ("Axis", "XG")],
            Dimension::Acceleration,
        );
        let headers = distinct_codes(
            [&top, &top, &top.clone().filtered(60.0)]
                .into_iter()
                .map(channel_header),
        );
        let codes: Vec<String> = headers
            .iter()
            .map(|h| field(h, "Channel code").unwrap())
            .collect();
        assert_eq!(
            codes,
            ["10ENGN000001ACXP", "10ENGN000002ACXP", "10ENGN000000ACXD"]
        );
        assert!(
            field(&headers[1], "Comments")
                .unwrap()
                .contains("numbers 2 channels")
        );
        assert_eq!(
            field(&headers[1], "Location").as_deref(),
            Some("ENGN000002")
        );
    }

    #[test]
    fn test_objects_are_numbered_in_order() {
        let objects = [
            TestObject {
                name: "car".into(),
                speed: Some(0.0),
                mass: Some(1200.0),
            },
            TestObject {
                name: "pendulum".into(),
                speed: Some(2.5),
                mass: None,
            },
        ];
        let header = test_objects_header("T", &objects);
        assert_eq!(
            field(&header, "Number of test objects").as_deref(),
            Some("2")
        );
        assert_eq!(
            field(&header, "Name of test object 2").as_deref(),
            Some("pendulum")
        );
        assert_eq!(
            field(&header, "Mass test object 1").as_deref(),
            Some("1.2e3")
        );
        assert_eq!(field(&header, "Mass test object 2"), None);
    }
}
