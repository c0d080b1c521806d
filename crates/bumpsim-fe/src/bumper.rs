//! The parametric FE bumper: a bumper beam of box section across the car,
//! two crash boxes behind it, both meshed with CalculiX `B32R` beams (spec
//! §8: "the mesh of the bumper system is coupled to a simplified model of
//! the car"), and the contact stiffness towards the striker.
//!
//! Equivalent characteristic against a flat, full-width face: the beam
//! translates, both crash boxes shorten axially, and the contact springs
//! act in series with them, so the initial stiffness is
//! `k = 1 / (1 / (2 E A_box / L_box) + 1 / k_contact)`; with a yield stress
//! σ_y the crash boxes carry at most `2 σ_y A_box` (the plateau). The
//! box-section area is `A = a b − (a − 2t)(b − 2t)` from the outer
//! dimensions, as CalculiX's `SECTION=BOX` takes them.
//!
//! SI throughout: m, kg, Pa, N/m.

use crate::FeError;
use bumpsim_impact::bumper::Bumper;
use serde::Deserialize;
use std::path::Path;

/// An isotropic material; `yield_curve` makes it elastic–plastic.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν.
    #[serde(default = "steel_poisson")]
    pub poisson: f64,
    /// Density ρ, kg/m³.
    pub density: f64,
    /// (true stress Pa, plastic strain) pairs, strain from 0 increasing;
    /// none: elastic.
    #[serde(default, deserialize_with = "bumpsim_io::numbers::list")]
    pub yield_curve: Vec<[f64; 2]>,
}

fn steel_poisson() -> f64 {
    0.3
}

/// A thin-walled box section, outer dimensions.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSection {
    /// Outer size along the car's axis (beam) or across it (crash box), m.
    pub depth: f64,
    /// Outer height (vertical), m.
    pub height: f64,
    /// Wall thickness, m.
    pub wall: f64,
}

impl BoxSection {
    /// Cross-section area, m².
    pub fn area(&self) -> f64 {
        self.depth * self.height - (self.depth - 2.0 * self.wall) * (self.height - 2.0 * self.wall)
    }
}

/// The bumper beam.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Beam {
    /// Length across the car, m.
    pub width: f64,
    /// Number of B32R elements.
    pub elements: usize,
    /// Section.
    pub section: BoxSection,
    /// Material.
    pub material: Material,
}

/// The two crash boxes at ±`offset` behind the beam.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrashBoxes {
    /// Lateral position of each box, m (snapped to the beam's nearest node).
    pub offset: f64,
    /// Length along the car's axis, m.
    pub length: f64,
    /// Number of B32R elements per box.
    pub elements: usize,
    /// Section.
    pub section: BoxSection,
    /// Material.
    pub material: Material,
}

/// The parametric bumper (TOML file).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BumperMesh {
    /// A name for reports.
    #[serde(default)]
    pub name: Option<String>,
    /// The beam.
    pub beam: Beam,
    /// The crash boxes.
    pub crash_boxes: CrashBoxes,
    /// Total contact stiffness of the beam's face, N/m, spread evenly over
    /// the beam's nodes; default 50 × the crash boxes' axial stiffness.
    #[serde(default)]
    pub contact_stiffness: Option<f64>,
}

/// Most elements of the beam or of one crash box.
pub const MAX_ELEMENTS: usize = 400;

fn check(name: &str, value: f64, ok: bool, expected: &str) -> Result<(), FeError> {
    match ok && value.is_finite() {
        true => Ok(()),
        false => Err(FeError::Parameter {
            name: name.to_string(),
            value,
            expected: expected.to_string(),
        }),
    }
}

/// A positive value at most `max` (a plausibility bound that also keeps
/// every derived coordinate and deck value finite).
fn bounded(name: &str, value: f64, max: f64) -> Result<(), FeError> {
    check(
        name,
        value,
        value > 0.0 && value <= max,
        &format!("positive, at most {max:e}"),
    )
}

impl Material {
    fn validate(&self, part: &str) -> Result<(), FeError> {
        bounded(
            &format!("{part}.material.youngs_modulus (Pa)"),
            self.youngs_modulus,
            1e13,
        )?;
        bounded(
            &format!("{part}.material.density (kg/m³)"),
            self.density,
            1e5,
        )?;
        let nu = self.poisson;
        check(
            &format!("{part}.material.poisson"),
            nu,
            (0.0..0.5).contains(&nu),
            "in [0, 0.5)",
        )?;
        let name = format!("{part}.material.yield_curve");
        for (i, w) in self.yield_curve.iter().enumerate() {
            bounded(&format!("{name}[{i}] stress (Pa)"), w[0], 1e12)?;
            check(
                &format!("{name}[{i}] plastic strain"),
                w[1],
                w[1] >= 0.0,
                "not negative",
            )?;
        }
        if let Some(first) = self.yield_curve.first() {
            check(
                &format!("{name}[0] plastic strain"),
                first[1],
                first[1] == 0.0,
                "0 (the initial yield stress)",
            )?;
        }
        for (i, w) in self.yield_curve.windows(2).enumerate() {
            check(
                &format!("{name}[{}] plastic strain", i + 1),
                w[1][1],
                w[1][1] > w[0][1],
                "increasing",
            )?;
        }
        Ok(())
    }

    /// Initial yield stress, Pa (none: elastic).
    pub fn yield_stress(&self) -> Option<f64> {
        self.yield_curve.first().map(|p| p[0])
    }
}

impl BoxSection {
    fn validate(&self, part: &str) -> Result<(), FeError> {
        bounded(&format!("{part}.section.depth (m)"), self.depth, 1.0)?;
        bounded(&format!("{part}.section.height (m)"), self.height, 1.0)?;
        let inner = self.depth.min(self.height) / 2.0;
        check(
            &format!("{part}.section.wall (m)"),
            self.wall,
            self.wall > 0.0 && self.wall < inner,
            "positive and below half the smaller outer dimension",
        )
    }
}

/// An element count from `least` to [`MAX_ELEMENTS`].
fn elements(name: &str, count: usize, least: usize) -> Result<(), FeError> {
    let ok = (least..=MAX_ELEMENTS).contains(&count);
    check(
        name,
        count as f64,
        ok,
        &format!("{least} to {MAX_ELEMENTS}"),
    )
}

impl BumperMesh {
    /// Checks every parameter, naming the one out of range.
    pub fn validate(&self) -> Result<(), FeError> {
        let b = &self.beam;
        bounded("beam.width (m)", b.width, 10.0)?;
        elements("beam.elements", b.elements, 2)?;
        b.section.validate("beam")?;
        b.material.validate("beam")?;
        let c = &self.crash_boxes;
        check(
            "crash_boxes.offset (m)",
            c.offset,
            c.offset > 0.0 && c.offset <= b.width / 2.0,
            "positive and within half the beam width",
        )?;
        bounded("crash_boxes.length (m)", c.length, 10.0)?;
        elements("crash_boxes.elements", c.elements, 1)?;
        c.section.validate("crash_boxes")?;
        c.material.validate("crash_boxes")?;
        if let Some(k) = self.contact_stiffness {
            bounded("contact_stiffness (N/m)", k, 1e15)?;
        }
        Ok(())
    }

    /// Reads and validates a bumper mesh TOML file.
    pub fn read(path: &Path) -> Result<BumperMesh, FeError> {
        let file = |message: String| FeError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| file(format!("cannot read: {e}")))?;
        let mesh: BumperMesh = toml::from_str(&text).map_err(|e| file(e.to_string()))?;
        mesh.validate().map_err(|e| file(e.to_string()))?;
        Ok(mesh)
    }

    /// Lateral positions of the beam's 2n + 1 nodes (quadratic elements), m.
    pub fn beam_node_y(&self) -> Vec<f64> {
        let (w, n) = (self.beam.width, 2 * self.beam.elements);
        (0..=n)
            .map(|i| -w / 2.0 + w * i as f64 / n as f64)
            .collect()
    }

    /// The beam node each crash box (left, right) starts at: the one
    /// nearest ±offset.
    pub fn crash_box_nodes(&self) -> [usize; 2] {
        let y = self.beam_node_y();
        [-1.0, 1.0].map(|sign| {
            let target = sign * self.crash_boxes.offset;
            (0..y.len())
                .min_by(|&a, &b| (y[a] - target).abs().total_cmp(&(y[b] - target).abs()))
                .unwrap_or(0)
        })
    }

    /// Axial stiffness of both crash boxes, N/m.
    pub fn crash_box_stiffness(&self) -> f64 {
        let c = &self.crash_boxes;
        2.0 * c.material.youngs_modulus * c.section.area() / c.length
    }

    /// Total contact stiffness, N/m.
    pub fn contact(&self) -> f64 {
        self.contact_stiffness
            .unwrap_or(50.0 * self.crash_box_stiffness())
    }

    /// Mass of the beam and both crash boxes, kg.
    pub fn mass(&self) -> f64 {
        let (b, c) = (&self.beam, &self.crash_boxes);
        b.section.area() * b.width * b.material.density
            + 2.0 * c.section.area() * c.length * c.material.density
    }

    /// The equivalent characteristic against a flat full-width face (see
    /// the module overview): ramp and unloading at the series stiffness, the
    /// plateau at the crash boxes' yield force (elastic: 1e12 N).
    pub fn equivalent_bumper(&self) -> Result<Bumper, FeError> {
        let k = 1.0 / (1.0 / self.crash_box_stiffness() + 1.0 / self.contact());
        let c = &self.crash_boxes;
        let plateau = c
            .material
            .yield_stress()
            .map_or(1e12, |s| 2.0 * s * c.section.area());
        Bumper::three_part(k, plateau, k).map_err(|e| FeError::Parameter {
            name: "equivalent bumper".into(),
            value: k,
            expected: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn elastic() -> BumperMesh {
        toml::from_str(
            r#"
            [beam]
            width = 1.2
            elements = 6
            section = { depth = 0.05, height = 0.1, wall = 0.002 }
            material = { youngs_modulus = 210e9, density = 7850 }
            [crash_boxes]
            offset = 0.4
            length = 0.15
            elements = 1
            section = { depth = 0.08, height = 0.08, wall = 0.0015 }
            material = { youngs_modulus = 3.2e8, density = 7850 }
            "#,
        )
        .unwrap()
    }

    #[test]
    fn the_equivalent_stiffness_is_the_boxes_in_series_with_the_contact() {
        let mesh = elastic();
        mesh.validate().unwrap();
        let area = 0.08 * 0.08 - 0.077 * 0.077;
        let boxes = 2.0 * 3.2e8 * area / 0.15;
        approx::assert_relative_eq!(mesh.crash_box_stiffness(), boxes, max_relative = 1e-12);
        let b = mesh.equivalent_bumper().unwrap();
        approx::assert_relative_eq!(
            b.loading_force(1e-3),
            1e-3 * boxes * 50.0 / 51.0,
            max_relative = 1e-12
        );
    }

    #[test]
    fn parameters_out_of_range_are_named() {
        let mut mesh = elastic();
        mesh.crash_boxes.section.wall = 0.05;
        let e = mesh.validate().unwrap_err().to_string();
        assert!(e.contains("crash_boxes.section.wall"), "{e}");
        let mut mesh = elastic();
        mesh.beam.material.yield_curve = vec![[3e8, 0.0], [2e8, 0.0]];
        let e = mesh.validate().unwrap_err().to_string();
        assert!(e.contains("yield_curve[1] plastic strain"), "{e}");
        let mut mesh = elastic();
        mesh.crash_boxes.offset = 0.9;
        assert!(mesh.validate().unwrap_err().to_string().contains("offset"));
        let mut mesh = elastic();
        mesh.beam.elements = usize::MAX;
        assert!(mesh.validate().is_err());
    }
}
