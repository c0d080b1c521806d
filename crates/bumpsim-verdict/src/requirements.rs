//! What each protocol requires and what of it the verdict judges (issue 45
//! item 5): per protocol its criteria from the regulation or protocol text,
//! paraphrased, each judged by the model (a criterion bumpsim computes),
//! by a proxy (a criterion standing in for it, and why), or not judged
//! (the engineer must check it on the car).
//!
//! The texts as read here: 49 CFR 581.5(c)(1) and (c)(8) against public
//! copies of the regulation and an NHTSA interpretation (86-6.17); the RCAR
//! barrier's backstop against the barrier specification (Issue 1, 2007,
//! §2.2). The other entries are marked `verified: false`: their wording was
//! not checked against the text, and the engineer should read the clause.

use crate::protocol::Test;
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

/// A criterion the verdict computes ([`crate::criteria`]), by the name it
/// carries in the verdict (`clearance: radiator` is a [`Kind::Clearance`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// `clearance: <item>`: the travel towards each item the car file lists.
    Clearance,
    /// `rail force`: the side members' force against their yield.
    RailForce,
    /// `crash-box stroke`: the first link's compression against its stroke.
    CrashBoxStroke,
    /// `bumper stroke`: the bumper's crush against its depth.
    BumperStroke,
    /// `beam engagement`: the beam's heights against the striker's.
    BeamEngagement,
    /// `deceleration (3 ms clip)`.
    Deceleration,
}

impl Kind {
    /// The criterion's name in the verdict (a clearance: its prefix).
    pub fn criterion(self) -> &'static str {
        match self {
            Kind::Clearance => "clearance",
            Kind::RailForce => "rail force",
            Kind::CrashBoxStroke => "crash-box stroke",
            Kind::BumperStroke => "bumper stroke",
            Kind::BeamEngagement => "beam engagement",
            Kind::Deceleration => "deceleration (3 ms clip)",
        }
    }

    /// Whether a criterion of the verdict, by its name, is of this kind.
    pub fn matches(self, name: &str) -> bool {
        let own = self.criterion();
        name == own
            || name
                .strip_prefix(own)
                .is_some_and(|rest| rest.starts_with(": "))
    }
}

/// How a requirement is judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Judgement {
    /// By the model: a criterion the verdict computes and judges.
    Model {
        /// The criterion.
        criterion: Kind,
        /// What of it judges the requirement.
        what: &'static str,
    },
    /// By a proxy: a criterion standing in for the requirement.
    Proxy {
        /// The criterion that stands in.
        by: Kind,
        /// What of it stands in.
        what: &'static str,
        /// Why it is only a proxy: what it does not tell.
        why: &'static str,
    },
    /// Not judged: the engineer must check it on the car.
    NotJudged {
        /// Why the model cannot judge it.
        why: &'static str,
    },
}

impl Judgement {
    /// `model`, `proxy` or `not judged`.
    pub fn word(&self) -> &'static str {
        match self {
            Judgement::Model { .. } => "model",
            Judgement::Proxy { .. } => "proxy",
            Judgement::NotJudged { .. } => "not judged",
        }
    }

    /// The criterion that judges or stands in (None: not judged).
    pub fn kind(&self) -> Option<Kind> {
        match *self {
            Judgement::Model { criterion, .. } => Some(criterion),
            Judgement::Proxy { by, .. } => Some(by),
            Judgement::NotJudged { .. } => None,
        }
    }

    /// What judges it or stands in (None: not judged).
    pub fn by(&self) -> Option<&'static str> {
        match *self {
            Judgement::Model { what, .. } | Judgement::Proxy { what, .. } => Some(what),
            Judgement::NotJudged { .. } => None,
        }
    }

    /// Why it is a proxy or not judged (None: judged by the model).
    pub fn why(&self) -> Option<&'static str> {
        match *self {
            Judgement::Model { .. } => None,
            Judgement::Proxy { why, .. } | Judgement::NotJudged { why } => Some(why),
        }
    }
}

/// One requirement of a protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Requirement {
    /// The clause (`581.5(c)(1)`).
    pub clause: &'static str,
    /// What it requires, in short words (paraphrased).
    pub requirement: &'static str,
    /// How the verdict judges it.
    pub judgement: Judgement,
    /// Whether the paraphrase was checked against the text.
    pub verified: bool,
}

/// A protocol's requirements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Requirements {
    /// The protocol (`part581`, [`crate::protocol::PROTOCOLS`]).
    pub protocol: &'static str,
    /// Where the requirements are stated.
    pub source: &'static str,
    /// The requirements.
    pub list: &'static [Requirement],
}

/// What the verdict's JSON carries of one requirement.
#[derive(Debug, Clone, Serialize)]
pub struct Entry {
    /// The clause.
    pub clause: &'static str,
    /// What it requires.
    pub requirement: &'static str,
    /// `model`, `proxy` or `not judged`.
    pub judgement: &'static str,
    /// The criterion that judges it or stands in (None: not judged).
    pub criterion: Option<Kind>,
    /// What judges it or stands in.
    pub by: Option<&'static str>,
    /// Why it is a proxy or not judged.
    pub why: Option<&'static str>,
    /// Whether the paraphrase was checked against the text.
    pub verified: bool,
}

impl Requirement {
    /// The JSON entry.
    pub fn entry(&self) -> Entry {
        let j = &self.judgement;
        Entry {
            clause: self.clause,
            requirement: self.requirement,
            judgement: j.word(),
            criterion: j.kind(),
            by: j.by(),
            why: j.why(),
            verified: self.verified,
        }
    }

    /// One line: `581.5(c)(1) lamps ...: proxy (clearance to the lamps)`.
    pub fn line(&self) -> String {
        let how = match self.judgement.by() {
            Some(by) => format!("{} ({by})", self.judgement.word()),
            None => "NOT JUDGED: the engineer must check it".into(),
        };
        format!("{} {}: {how}{}", self.clause, self.requirement, self.mark())
    }

    /// The requirement with its judgement and why, on two lines.
    pub fn described(&self) -> String {
        let j = &self.judgement;
        let how = match (j.by(), j.why()) {
            (Some(by), None) => format!("judged by the model: {by}"),
            (Some(by), Some(why)) => format!("judged by a proxy: {by}; {why}"),
            (None, why) => format!(
                "not judged: {}; the engineer must check it",
                why.unwrap_or("")
            ),
        };
        format!(
            "{} {}{}\n  {how}",
            self.clause,
            self.requirement,
            self.mark()
        )
    }

    fn mark(&self) -> &'static str {
        match self.verified {
            true => "",
            false => " [wording not checked against the text]",
        }
    }
}

const fn req(clause: &'static str, requirement: &'static str, judgement: Judgement) -> Requirement {
    Requirement {
        clause,
        requirement,
        judgement,
        verified: false,
    }
}

const fn checked(
    clause: &'static str,
    requirement: &'static str,
    judgement: Judgement,
) -> Requirement {
    Requirement {
        verified: true,
        ..req(clause, requirement, judgement)
    }
}

const fn model(criterion: Kind, what: &'static str) -> Judgement {
    Judgement::Model { criterion, what }
}

const fn proxy(by: Kind, what: &'static str, why: &'static str) -> Judgement {
    Judgement::Proxy { by, what, why }
}

const fn not(why: &'static str) -> Judgement {
    Judgement::NotJudged { why }
}

const LAMPS: &str = "the clearances to the lamps the car file lists";
const NO_HEIGHT: &str =
    "the model has no height: pitch, dive and the contact's vertical position are not computed";
const REPAIR: Judgement =
    not("repair costs, parts and labour are not modelled; the criteria bound the damage only");

const LAB: &[Requirement] = &[
    req(
        "lab tests (no regulation)",
        "the car's own damageability limits: parts behind the bumper, rails, crash boxes",
        model(Kind::Clearance, "clearance to each item the car file lists"),
    ),
    req(
        "lab tests (no regulation)",
        "the rails not deformed",
        model(Kind::RailForce, "rail force below the rails' yield"),
    ),
];

const PART581: &[Requirement] = &[
    checked(
        "581.5(c)(1)",
        "each lamp and reflective device (but licence-plate lamps) free of cracks and visible as FMVSS 108 asks; headlamp aim adjustable within the inspection limits",
        proxy(
            Kind::Clearance,
            LAMPS,
            "a lamp nothing reaches is taken as undamaged; cracks, visibility and aim are not computed, and a lamp the car file does not list is not judged",
        ),
    ),
    req(
        "581.5(c)(2)",
        "hood, trunk and doors operate in the normal manner",
        proxy(
            Kind::Clearance,
            "the clearances to the latches, hinges and panels the car file lists (e.g. the bonnet latch)",
            "a closure nothing reaches is taken as operable; body distortion and door fit are not computed",
        ),
    ),
    req(
        "581.5(c)(3)",
        "fuel and cooling systems free of leaks and constricted flow, their closures operating normally",
        proxy(
            Kind::Clearance,
            "the clearance to the radiator (and any fuel or coolant part the car file lists)",
            "a part nothing reaches is taken as tight; leaks and flow are not computed, and the fuel system is judged only if listed",
        ),
    ),
    req(
        "581.5(c)(4)",
        "exhaust system free of leaks and constriction",
        not("the exhaust is not modelled (at the rear a clearance to it may be listed as a proxy)"),
    ),
    req(
        "581.5(c)(5)",
        "propulsion, suspension, steering and braking systems in adjustment and operating normally",
        proxy(
            Kind::RailForce,
            "the side members' force below their yield",
            "rails that do not yield are taken as keeping the subframe and steering mounts in place; adjustment and function are not computed",
        ),
    ),
    req(
        "581.5(c)(6)",
        "a pressure vessel absorbing impact energy (gas or hydraulic) loses no gas or fluid with fragments separating",
        not(
            "energy absorbers are a spring-damper link; the crash-box stroke is reported (not judged in this test) and a bottomed absorber is a warning sign",
        ),
    ),
    req(
        "581.5(c)(7)",
        "the vehicle touches the pendulum only on its impact ridge (a force limit on its other planes)",
        proxy(
            Kind::BeamEngagement,
            "the beam covering the ridge's height range (with damageability.beam_height)",
            "the pendulum's face is flat in the model: the force off the ridge is not computed",
        ),
    ),
    checked(
        "581.5(c)(8)",
        "exterior surfaces (but the bumper face bar and its attachments) without separated paint or coverings and without permanent deviation from their contour 30 minutes after each impact",
        proxy(
            Kind::Clearance,
            "the clearances from the front surface to the panels and lamps the car file lists",
            "a panel the bumper does not reach is taken as undamaged; paint and permanent set are not computed",
        ),
    ),
    req(
        "581.5(c)(9)",
        "no breakage or release of fasteners or joints (but as (c)(8) allows)",
        not(
            "fasteners and joints are not modelled; the rail force and crash-box stroke are the nearest figures",
        ),
    ),
];

const R42: &[Requirement] = &[
    req(
        "R42 §6",
        "lighting and light-signalling devices function and stay correctly fitted after the tests",
        proxy(
            Kind::Clearance,
            LAMPS,
            "a lamp nothing reaches is taken as working; its function and fitting are not computed",
        ),
    ),
    req(
        "R42 §6",
        "bonnet, boot lid and doors open and close normally; side doors do not open in the impact",
        proxy(
            Kind::Clearance,
            "the clearances to the latches and panels the car file lists",
            "a closure nothing reaches is taken as operable; door opening in the impact is not computed",
        ),
    ),
    req(
        "R42 §6",
        "fuel and cooling systems neither leak nor are obstructed",
        proxy(
            Kind::Clearance,
            "the clearance to the radiator (and any fuel part the car file lists)",
            "leaks and flow are not computed",
        ),
    ),
    req(
        "R42 §6",
        "exhaust, propulsion, suspension, steering and braking systems function normally",
        not("these systems are not modelled; the rail force below yield is the nearest figure"),
    ),
    req(
        "R42 annex 3 §2",
        "the impactor strikes the protective device at its reference line (445 mm)",
        model(
            Kind::BeamEngagement,
            "the beam covering the reference line (with damageability.beam_height)",
        ),
    ),
];

const RCAR_BUMPER: &[Requirement] = &[
    req(
        "RCAR Bumper Test §5.1.2",
        "the bumper beam reaches the qualifying height against the barrier face (455-555 mm or 405-505 mm by market, --market)",
        proxy(
            Kind::BeamEngagement,
            "the beam overlapping half the barrier face's 100 mm height",
            "RCAR's qualifying-height rule was not available here: half the face is bumpsim's choice",
        ),
    ),
    req(
        "RCAR Bumper Test §5.1.3-5.1.5",
        "the beam's height measured across its width, pedestrian-protection elements apart",
        not("bumpsim takes one beam height for the whole width"),
    ),
    req(
        "RCAR Bumper Test §6",
        "the bumper stays engaged in the dynamic tests: no override or underride",
        proxy(
            Kind::BeamEngagement,
            "the static overlap of beam and face",
            NO_HEIGHT,
        ),
    ),
    checked(
        "RCAR barrier spec. §2.2",
        "the barrier carries a rigid backstop, 200 ± 2 mm tall, 25 ± 1 mm behind its steel face, on top of the barrier: bonnet, grille or lamps that reach it are damaged",
        not(
            "the backstop is not modelled: contact of the bonnet, grille or lamps with it is not computed",
        ),
    ),
    req(
        "RCAR Bumper Test §6",
        "the crash boxes take the impact without the rails deforming",
        model(
            Kind::CrashBoxStroke,
            "crash-box stroke within its usable stroke",
        ),
    ),
    req(
        "RCAR Bumper Test §6",
        "the rails (side members) are not damaged",
        model(Kind::RailForce, "rail force below the rails' yield"),
    ),
    req(
        "RCAR Bumper Test §6",
        "parts behind the bumper (radiator, lamps, bonnet) undamaged",
        model(Kind::Clearance, "clearance to each item the car file lists"),
    ),
    req("RCAR Bumper Test §6", "the damage's repair cost", REPAIR),
];

const RCAR_STRUCTURAL: &[Requirement] = &[
    req(
        "RCAR structural test",
        "damage kept to the crash boxes, the rails repairable",
        model(
            Kind::CrashBoxStroke,
            "crash-box stroke within its usable stroke",
        ),
    ),
    req(
        "RCAR structural test",
        "the rails not deformed",
        model(Kind::RailForce, "rail force below the rails' yield"),
    ),
    req(
        "RCAR structural test",
        "parts behind the bumper undamaged",
        model(Kind::Clearance, "clearance to each item the car file lists"),
    ),
    req(
        "RCAR structural test",
        "the airbags do not deploy",
        proxy(
            Kind::Deceleration,
            "the 3 ms clip deceleration against damageability.deceleration, if given",
            "the airbag's firing algorithm is not modelled",
        ),
    ),
    req("RCAR structural test", "the damage's repair cost", REPAIR),
];

const IIHS_1990S: &[Requirement] = &[
    req(
        "IIHS low-speed tests",
        "the damage's repair cost in each test (the rating)",
        REPAIR,
    ),
    req(
        "IIHS low-speed tests",
        "damage kept to the bumper system",
        model(
            Kind::BumperStroke,
            "bumper stroke within the bumper's crushable depth",
        ),
    ),
    req(
        "IIHS low-speed tests",
        "the structure behind the bumper undamaged",
        model(Kind::RailForce, "rail force below the rails' yield"),
    ),
    req(
        "IIHS low-speed tests",
        "parts behind the bumper undamaged",
        model(Kind::Clearance, "clearance to each item the car file lists"),
    ),
];

const IIHS_BUMPER: &[Requirement] = &[
    req(
        "IIHS bumper tests",
        "the damage's repair cost in each test (the rating)",
        REPAIR,
    ),
    req(
        "IIHS bumper tests",
        "the bumper engages the barrier: no override or underride",
        proxy(
            Kind::BeamEngagement,
            "the static overlap of beam and face",
            NO_HEIGHT,
        ),
    ),
    req(
        "IIHS bumper tests",
        "the crash boxes take the impact without the rails deforming",
        model(
            Kind::CrashBoxStroke,
            "crash-box stroke within its usable stroke",
        ),
    ),
    req(
        "IIHS bumper tests",
        "the rails not deformed",
        model(Kind::RailForce, "rail force below the rails' yield"),
    ),
    req(
        "IIHS bumper tests",
        "parts behind the bumper undamaged",
        model(Kind::Clearance, "clearance to each item the car file lists"),
    ),
];

/// Every protocol's requirements, in the order of
/// [`crate::protocol::PROTOCOLS`].
pub const REQUIREMENTS: &[Requirements] = &[
    Requirements {
        protocol: "lab",
        source: "the thesis and papers A-C: no regulation; the car file's limits",
        list: LAB,
    },
    Requirements {
        protocol: "part581",
        source: "49 CFR 581.5(c), the protective criteria after every impact",
        list: PART581,
    },
    Requirements {
        protocol: "cmvss215",
        source: "CMVSS 215 by its 49 CFR 581 route: 581.5(c) as of October 2006 (the R42 route: see r42)",
        list: PART581,
    },
    Requirements {
        protocol: "r42",
        source: "UN R42 paragraph 6 (the checks after the tests) and annex 3",
        list: R42,
    },
    Requirements {
        protocol: "rcar-bumper",
        source: "RCAR Bumper Test Issue 2.0 (2010) and the barrier specification Issue 1 (2007)",
        list: RCAR_BUMPER,
    },
    Requirements {
        protocol: "rcar-structural",
        source: "RCAR low-speed structural crash test, Issue 2.2 (2011)",
        list: RCAR_STRUCTURAL,
    },
    Requirements {
        protocol: "iihs-1990s",
        source: "IIHS low-speed crash tests (1990s to 2006): rated by repair cost",
        list: IIHS_1990S,
    },
    Requirements {
        protocol: "iihs-bumper",
        source: "IIHS bumper tests (2006): rated by repair cost",
        list: IIHS_BUMPER,
    },
];

/// The requirements of the protocol of this name.
pub fn of(protocol: &str) -> Option<&'static Requirements> {
    REQUIREMENTS.iter().find(|r| r.protocol == protocol)
}

/// The requirements of every protocol with a test among `tests`.
pub fn run(tests: &[&Test]) -> Vec<&'static Requirements> {
    crate::protocol::PROTOCOLS
        .iter()
        .filter(|p| p.tests.iter().any(|t| tests.iter().any(|r| r.name == *t)))
        .filter_map(|p| of(p.name))
        .collect()
}

/// Serialises requirements as protocol → list of [`Entry`] (the verdict's
/// JSON).
pub fn as_map<S: Serializer>(
    requirements: &[&'static Requirements],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let mut map = serializer.serialize_map(Some(requirements.len()))?;
    for r in requirements {
        let list: Vec<Entry> = r.list.iter().map(Requirement::entry).collect();
        map.serialize_entry(r.protocol, &list)?;
    }
    map.end()
}

/// What the protocols run require, a line each, for under the verdict
/// table (empty when none).
pub fn lines(requirements: &[&'static Requirements]) -> String {
    if requirements.is_empty() {
        return String::new();
    }
    let mut out =
        "what the regulations require: judged by the model / by a proxy / NOT JUDGED\n".to_string();
    for r in requirements {
        out += &format!("  {} ({}):\n", r.protocol, r.source);
        for q in r.list {
            out += &format!("    {}\n", q.line());
        }
    }
    out
}

/// A protocol's requirements with why each is a proxy or not judged
/// (`bumpsim verdict --list`), indented by `indent`.
pub fn described(r: &Requirements, indent: &str) -> String {
    let mut out = format!("{indent}requires ({}):\n", r.source);
    for q in r.list {
        for line in q.described().lines() {
            out += &format!("{indent}  {line}\n");
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;
    use crate::protocol::{PROTOCOLS, select};

    #[test]
    fn every_protocol_lists_its_requirements() {
        for p in PROTOCOLS {
            let r = of(p.name).unwrap_or_else(|| panic!("{} has no requirements", p.name));
            assert!(!r.list.is_empty(), "{}", p.name);
        }
        assert_eq!(REQUIREMENTS.len(), PROTOCOLS.len());
    }

    #[test]
    fn part581_lists_each_protective_criterion_once() {
        for name in ["part581", "cmvss215"] {
            let clauses: Vec<&str> = of(name).unwrap().list.iter().map(|r| r.clause).collect();
            let expected: Vec<String> = (1..=9).map(|i| format!("581.5(c)({i})")).collect();
            assert_eq!(clauses, expected, "{name}");
        }
    }

    /// The names of every criterion a verdict computes when every limit is
    /// given, over a test of each height kind.
    fn computed() -> Vec<String> {
        use bumpsim_core::model::MsdModel;
        use bumpsim_impact::bumper::Bumper;
        use bumpsim_planar::car::{Layout, PlanarCar};
        let chain = MsdModel::new(vec![16.0, 1300.0], vec![4e3], vec![6e6]).unwrap();
        let bumper = Bumper::three_part(3e6, 200e3, 2e7).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let limits = Damageability::parse(
            "[damageability]\nrail_yield = 300e3\ncrash_box_stroke = 0.05\n\
             bumper_stroke = 0.08\nbeam_height = [0.40, 0.54]\ndeceleration = 300.0\n\
             [[damageability.clearance]]\nname = \"radiator\"\ngap = 0.08\nfrom = \"beam\"\n",
            "car.toml".as_ref(),
        )
        .unwrap();
        let tests = select(&["rcar-bumper-front", "part581-pendulum-front"]).unwrap();
        let setup = Setup::new(vec![CarEnd::new(car, limits).unwrap()], tests, 0.0).unwrap();
        let v = verdict(&setup).unwrap();
        v.tests
            .iter()
            .flat_map(|t| t.criteria.iter().map(|c| c.name.clone()))
            .collect()
    }

    #[test]
    fn every_judging_criterion_is_one_the_verdict_computes() {
        let names = computed();
        for r in REQUIREMENTS {
            for q in r.list {
                if let Some(kind) = q.judgement.kind() {
                    assert!(
                        names.iter().any(|n| kind.matches(n)),
                        "{} {}: {kind:?} is not among {names:?}",
                        r.protocol,
                        q.clause
                    );
                }
            }
        }
        assert!(Kind::Clearance.matches("clearance: radiator"));
        assert!(!Kind::Clearance.matches("clearances"));
    }

    #[test]
    fn a_verdict_carries_the_requirements_of_the_protocols_run() {
        let tests = select(&["r42-corner-front-left"]).unwrap();
        let names: Vec<&str> = run(&tests).iter().map(|r| r.protocol).collect();
        assert_eq!(names, ["r42"]);
        let text = lines(&run(&tests));
        assert!(
            text.contains("R42 annex 3 §2") && text.contains("NOT JUDGED"),
            "{text}"
        );
        let both = select(&["part581"]).unwrap();
        let names: Vec<&str> = run(&both).iter().map(|r| r.protocol).collect();
        assert_eq!(names, ["part581", "cmvss215"]);
    }
}
