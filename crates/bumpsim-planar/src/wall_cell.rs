//! Where a wall cell's measured force acts on the bumper line: the line of
//! action of a replayed load cell ([`crate::drive::Load::cell`]), the same
//! on `f64` ([`crate::drive`]) and on dual numbers ([`crate::sensitivity`]).
//!
//! The bumper line is straight (the beam's displacement is the lever rule
//! between the side-member tips), so along it, at lateral position η (body
//! frame, left positive), both its penetration into the wall face and its
//! position along the face are affine: `d(η) = d₀ + d′ η` and
//! `s(η) = s₀ + s′ η` (s from the cell's centre). The cell carries the
//! part of the line with `|s(η)| ≤ c/2` (c the cell's width), crushed where
//! `d(η) > 0`, and only the beam itself, `|η| ≤ w/2` (w the bumper's width,
//! to its ends, not to its outermost segment centres). Segment j, of width
//! `w/n`, pushes back with the force per unit length `L_j(d(η))·n/w`, its
//! loading curve spread over its width. The cell's resultant acts at
//!
//! `η_c = ∫ η L(d(η)) dη / ∫ L(d(η)) dη` over the crushed part of the band,
//!
//! integrated piece by piece (each segment's part of the interval) by the
//! 2-point Gauss–Legendre rule: exact where the loading curve is linear over
//! the piece (then η·L is quadratic in η), otherwise in error by O(h²) of the
//! curve's change of slope at a knee, h the piece's width, so it converges
//! as the segments are refined and does not depend on where their centres
//! fall (a rigid, flat, full contact acts at the band's centre; an angled
//! wall first loads the bumper at its end, not at its last segment centre).
//! Nothing crushed in the band: the band's point deepest into the face;
//! no part of the beam in the band: none.

use bumpsim_core::dual::Real;
use bumpsim_impact::bumper::Bumper;

/// An affine profile along the bumper line: `at_zero + slope · η`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Affine<T> {
    /// The value at η = 0.
    pub at_zero: T,
    /// Its change per metre of η.
    pub slope: T,
}

/// The 2-point Gauss–Legendre rule on [−1, 1]: nodes ±1/√3, weights 1.
const NODES: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// The smaller of `a` and `b`, by value.
fn lesser<T: Real>(a: T, b: T) -> T {
    match b.value() < a.value() {
        true => b,
        false => a,
    }
}

/// The larger of `a` and `b`, by value.
fn greater<T: Real>(a: T, b: T) -> T {
    match b.value() > a.value() {
        true => b,
        false => a,
    }
}

/// The interval of η where `|along(η)| ≤ half_cell`, within the beam
/// `|η| ≤ half_beam`; `None` when it is empty.
fn band<T: Real>(along: Affine<T>, half_cell: f64, half_beam: f64) -> Option<(T, T)> {
    let (lo, hi) = match along.slope.value() != 0.0 {
        true => {
            let a = (-along.at_zero - half_cell) / along.slope;
            let b = (-along.at_zero + half_cell) / along.slope;
            (lesser(a, b), greater(a, b))
        }
        false if along.at_zero.value().abs() <= half_cell => {
            (T::constant(-half_beam), T::constant(half_beam))
        }
        false => return None,
    };
    let lo = greater(lo, T::constant(-half_beam));
    let hi = lesser(hi, T::constant(half_beam));
    (lo.value() < hi.value()).then_some((lo, hi))
}

/// The lateral position η (body frame, m) where a wall cell's force acts
/// on a bumper of `segments` (right to left) over `width` (m): the cell is
/// `cell` wide, `along` its position along the face from the cell's centre
/// and `depth` the penetration into the face, both along the bumper line
/// (module doc). `None` when no part of the beam lies in the cell's band.
pub(crate) fn line_of_action<T: Real>(
    segments: &[Bumper],
    width: f64,
    cell: f64,
    along: Affine<T>,
    depth: Affine<T>,
) -> Option<T> {
    let half_beam = 0.5 * width;
    let (lo, hi) = band(along, 0.5 * cell, half_beam)?;
    let deepest = match depth.slope.value() {
        s if s > 0.0 => hi,
        s if s < 0.0 => lo,
        _ => (lo + hi) * 0.5,
    };
    // the crushed part of the band: d(η) > 0
    let (a, b) = match depth.slope.value() {
        s if s > 0.0 => (greater(lo, -depth.at_zero / depth.slope), hi),
        s if s < 0.0 => (lo, lesser(hi, -depth.at_zero / depth.slope)),
        _ if depth.at_zero.value() > 0.0 => (lo, hi),
        _ => return Some(deepest),
    };
    if a.value() >= b.value() {
        return Some(deepest);
    }
    let n = segments.len();
    let piece = width / n as f64;
    let index = |eta: f64| {
        ((eta + half_beam) / piece)
            .floor()
            .clamp(0.0, (n - 1) as f64) as usize
    };
    let zero = T::constant(0.0);
    let (mut sum, mut moment) = (zero, zero);
    for (j, segment) in segments
        .iter()
        .enumerate()
        .take(index(b.value()) + 1)
        .skip(index(a.value()))
    {
        let left = -half_beam + j as f64 * piece;
        let from = greater(a, T::constant(left));
        let to = lesser(b, T::constant(left + piece));
        if to.value() <= from.value() {
            continue;
        }
        let (mid, half) = ((from + to) * 0.5, (to - from) * 0.5);
        for node in NODES {
            let eta = mid + half * node;
            let f = loading(segment, depth.at_zero + depth.slope * eta) * half;
            sum += f;
            moment += f * eta;
        }
    }
    match sum.value() > 0.0 {
        true => Some(moment / sum),
        false => Some(deepest),
    }
}

/// A segment's loading force at the crush `depth`, N, with its slope (on
/// dual numbers) by a central difference of the loading curve (piecewise
/// linear: exact away from its knees).
pub(crate) fn loading<T: Real>(segment: &Bumper, depth: T) -> T {
    let d = depth.value();
    let h = 1e-9_f64.max(1e-7 * d.abs());
    let slope = (segment.loading_force(d + h) - segment.loading_force(d - h)) / (2.0 * h);
    (depth - d) * slope + segment.loading_force(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// A plain crush: ramp 1.5 MN/m up to a plateau of 60 kN a segment.
    fn segments(n: usize, plateau: f64) -> Vec<Bumper> {
        vec![Bumper::three_part(1.5e6, plateau, 6e6).unwrap(); n]
    }

    fn affine(at_zero: f64, slope: f64) -> Affine<f64> {
        Affine { at_zero, slope }
    }

    /// A rigid wall parallel to the bumper, crushing it evenly across a
    /// cell whose band ends inside segments: its force acts at the band's
    /// centre, whatever the segment count (the segment centres in the band
    /// would put it elsewhere).
    #[test]
    fn a_flat_full_contact_acts_at_the_band_s_centre() {
        // the band: along(η) = η − 0.23, the cell 0.37 m wide: η in 0.045..0.415 m
        for n in [7, 16, 31, 32, 64] {
            let eta = line_of_action(
                &segments(n, 6e4),
                1.6,
                0.37,
                affine(-0.23, 1.0),
                affine(0.02, 0.0),
            )
            .unwrap();
            assert_relative_eq!(eta, 0.23, epsilon = 1e-12);
        }
        // a band beyond the beam's end: only its part on the beam
        let eta = line_of_action(
            &segments(32, 6e4),
            1.6,
            0.4,
            affine(-0.75, 1.0),
            affine(0.02, 0.0),
        )
        .unwrap();
        assert_relative_eq!(eta, 0.5 * (0.55 + 0.8), epsilon = 1e-12);
        // and none when the band misses the beam
        let none = line_of_action(
            &segments(32, 6e4),
            1.6,
            0.4,
            affine(-1.5, 1.0),
            affine(0.02, 0.0),
        );
        assert!(none.is_none());
    }

    /// A wall at an angle: the crush grows linearly from η₀ = 0.8 − 0.03/0.176
    /// towards the beam's left end (tan 10° ≈ 0.176). On the ramp alone
    /// (plateau never reached) the force per length is ∝ (η − η₀), so over
    /// the band [η₀, 0.8] the resultant is at η₀ + ⅔ (0.8 − η₀), exactly,
    /// for any segment count, although η₀ lies inside a segment.
    #[test]
    fn an_angled_wedge_acts_where_the_integral_puts_it() {
        let slope = 10f64.to_radians().tan();
        let start = 0.8 - 0.03 / slope;
        for n in [16, 31, 32, 64] {
            let eta = line_of_action(
                &segments(n, 1e9),
                1.6,
                0.8,
                affine(-0.4, 1.0),
                affine(-slope * start, slope),
            )
            .unwrap();
            assert_relative_eq!(eta, start + 2.0 / 3.0 * (0.8 - start), epsilon = 1e-12);
        }
        // with the plateau: force per length min(k s (η − η₀), P), the knee
        // at η_k = η₀ + P/(k s); the exact centroid of that trapezoid
        let (k, p) = (1.5e6, 2e4);
        let knee = start + p / (k * slope);
        let (ramp, flat) = (0.5 * p * (knee - start), p * (0.8 - knee));
        let exact = (ramp * (start + 2.0 / 3.0 * (knee - start)) + flat * 0.5 * (knee + 0.8))
            / (ramp + flat);
        let at = |n: usize| {
            line_of_action(
                &segments(n, p),
                1.6,
                0.8,
                affine(-0.4, 1.0),
                affine(-slope * start, slope),
            )
            .unwrap()
        };
        let errors: Vec<f64> = [16, 32, 64, 128]
            .iter()
            .map(|&n| (at(n) - exact).abs())
            .collect();
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
        eprintln!("wedge with a knee: |η − exact| for 16, 32, 64, 128 segments: {shown:?} m");
        // converges: within 0.5 mm at 16 segments, and each refinement closer
        assert!(errors[0] < 5e-4, "{errors:?}");
        assert!(errors.windows(2).all(|e| e[1] <= e[0]), "{errors:?}");
    }

    /// The old rule (the crushed segment centres, weighted) against this
    /// one on the first millimetres of an angled wall: the segment centres
    /// put the load up to half a segment inboard, and differently for each
    /// count; the line gives nearly the same point for 16, 32 and 64.
    #[test]
    fn the_line_of_action_hardly_depends_on_the_segment_count() {
        let slope = 10f64.to_radians().tan();
        for crush in [0.002, 0.01, 0.05] {
            let start = 0.8 - crush / slope;
            let at = |n: usize| {
                line_of_action(
                    &segments(n, 6e4),
                    1.6,
                    0.8,
                    affine(-0.4, 1.0),
                    affine(-slope * start, slope),
                )
                .unwrap()
            };
            // the old rule: the crushed centres in the band, weighted
            let centres = |n: usize| {
                let (mut sum, mut moment) = (0.0, 0.0);
                for j in 0..n {
                    let eta = -0.8 + (j as f64 + 0.5) * 1.6 / n as f64;
                    let depth = slope * (eta - start);
                    if eta >= 0.0 && depth > 0.0 {
                        let f = segments(1, 6e4)[0].loading_force(depth);
                        (sum, moment) = (sum + f, moment + f * eta);
                    }
                }
                match sum > 0.0 {
                    true => moment / sum,
                    false => 0.8 - 0.8 / n as f64, // none crushed: the deepest centre
                }
            };
            let spread = |v: [f64; 3]| v[0].max(v[1]).max(v[2]) - v[0].min(v[1]).min(v[2]);
            let (line, old) = (
                [at(16), at(32), at(64)],
                [centres(16), centres(32), centres(64)],
            );
            eprintln!(
                "crush {crush} m: η at 16, 32, 64 segments: line {line:.5?} m, segment centres {old:.5?} m"
            );
            // the line: within 0.5 mm (a knee inside a piece); the centres
            // spread at least 5 times as far (3 to 30 mm here)
            assert!(spread(line) < 5e-4, "crush {crush}: {line:?}");
            assert!(
                spread(old) > 5.0 * spread(line).max(5e-4),
                "crush {crush}: {old:?}"
            );
        }
    }

    /// On dual numbers the line of action's derivative is that of the
    /// value: a central difference in the depth's offset agrees.
    #[test]
    fn the_derivative_follows_the_value() {
        use bumpsim_core::dual::Dual;
        let slope = 10f64.to_radians().tan();
        let segs = segments(32, 6e4);
        let value = |d0: f64| {
            line_of_action(&segs, 1.6, 0.8, affine(-0.4, 1.0), affine(d0, slope)).unwrap()
        };
        let d0 = -slope * 0.6;
        let dual = line_of_action(
            &segs,
            1.6,
            0.8,
            Affine {
                at_zero: Dual::<1>::constant(-0.4),
                slope: Dual::constant(1.0),
            },
            Affine {
                at_zero: Dual::seeded(d0, 0, 1.0),
                slope: Dual::constant(slope),
            },
        )
        .unwrap();
        let h = 1e-6;
        let fd = (value(d0 + h) - value(d0 - h)) / (2.0 * h);
        assert_relative_eq!(dual.value(), value(d0), epsilon = 1e-15);
        assert_relative_eq!(dual.tangent[0], fd, max_relative = 1e-5);
    }
}
