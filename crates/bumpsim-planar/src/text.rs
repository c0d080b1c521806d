//! Human-readable and CSV text of planar impacts, shared by the terminal,
//! the reports and the bindings: the striker in test terms (degrees,
//! percent, km/h), the summary with units and the time histories (SI).
//!
//! Units and signs follow [`crate::result`]: forces are the striker's on the
//! car in the world frame (N), side-member forces are compressive (N), yaw is
//! counter-clockwise seen from above (shown in degrees).

use crate::result::PlanarResult;
use crate::striker::{Face, Motion, Side, Striker};
use bumpsim_core::units::{Dimension, format_quantity, format_time_at};

/// The striker in the words of a test protocol.
///
/// ```
/// use bumpsim_planar::striker::{Face, Side, Striker};
/// let face = Face::plane_in_degrees(10.0, 40.0, Side::Left);
/// let text = bumpsim_planar::text::striker(&Striker::barrier(face, 15.0 / 3.6));
/// assert_eq!(text, "the car at 15 km/h into a rigid plane at 10°, 40 % overlap from the left");
/// ```
pub fn striker(s: &Striker) -> String {
    let face = match s.face {
        Face::Plane { angle, overlap, .. } if overlap >= 1.0 && angle == 0.0 => {
            "a full-width flat rigid face".to_string()
        }
        Face::Plane {
            angle,
            overlap,
            side,
        } => format!(
            "a rigid plane at {}°, {} % overlap from the {}",
            short(angle.to_degrees()),
            short(overlap * 100.0),
            side_name(side)
        ),
        Face::Pole { radius, lateral } => format!(
            "a pole of diameter {} mm at y = {} mm",
            short(2e3 * radius),
            short(1e3 * lateral)
        ),
        Face::Barrier(b) => format!(
            "a {} mm wide barrier curved to {} mm{} at {}°, {} % overlap from the {}",
            short(1e3 * b.width),
            short(1e3 * b.radius),
            b.absorber.map_or(String::new(), |a| format!(
                " with a {} mm absorber",
                short(1e3 * a.depth)
            )),
            short(b.angle.to_degrees()),
            short(b.overlap * 100.0),
            side_name(b.side)
        ),
    };
    let kmh = |v: f64| format!("{} km/h", short(v * 3.6));
    match s.motion {
        Motion::Fixed { speed } => format!("the car at {} into {face}", kmh(speed)),
        Motion::Pendulum { mass, speed } => format!(
            "a {} kg pendulum at {} carrying {face} into the car at rest",
            short(mass),
            kmh(speed)
        ),
    }
}

/// A test-protocol figure: at most three decimals, no trailing zeros.
fn short(value: f64) -> String {
    // beyond 1e12 the decimals are meaningless and `value * 1e3` can overflow
    // (a 1e308 kg pendulum printed as "inf kg")
    if value.abs() >= 1e12 {
        return format!("{value:.3e}");
    }
    let rounded = (value * 1e3).round() / 1e3;
    match rounded == 0.0 {
        true => "0".to_string(),
        false => format!("{rounded}"),
    }
}

fn side_name(side: Side) -> &'static str {
    match side {
        Side::Left => "left",
        Side::Right => "right",
    }
}

/// The largest value of `values` and the time it occurs.
fn peak(time: &[f64], values: &[f64]) -> (f64, f64) {
    time.iter().zip(values).fold((0.0, 0.0), |best, (&t, &v)| {
        if v.abs() > best.1.abs() { (t, v) } else { best }
    })
}

/// The summary: forces, crush, contact, yaw, energies and balances.
pub fn summary(r: &PlanarResult) -> String {
    let q = format_quantity;
    let (t_peak, _) = peak(&r.time, &r.force);
    let (_, left) = peak(&r.time, &r.side_force_left);
    let (_, right) = peak(&r.time, &r.side_force_right);
    let deepest = (0..r.max_crush.len()).max_by(|&a, &b| r.max_crush[a].total_cmp(&r.max_crush[b]));
    let remaining = r.remaining_crush.iter().copied().fold(0.0, f64::max);
    let mut text = format!(
        "  peak force {} at {}; side members: left {}, right {}\n",
        q(r.peak_force, Dimension::Force),
        q(t_peak, Dimension::Time),
        q(left, Dimension::Force),
        q(right, Dimension::Force)
    );
    if let Some(j) = deepest {
        text += &format!(
            "  maximum crush {} (segment {} of {}, at y = {}), largest remaining {}\n",
            q(r.max_compression, Dimension::Length),
            j + 1,
            r.max_crush.len(),
            q(
                r.segment_centres.get(j).copied().unwrap_or(0.0),
                Dimension::Length
            ),
            q(remaining, Dimension::Length)
        );
    }
    text += &contact(r);
    text += &motion(r);
    text += &energy(r);
    text += &side_members(r);
    text
}

/// The side members' nonlinear links (issue 46): their plastic work and
/// each link's largest compression and plastic set; nothing for linear ones.
fn side_members(r: &PlanarResult) -> String {
    if r.link_set.is_empty() {
        return String::new();
    }
    let q = |v, d| format_quantity(v, d);
    let links: Vec<String> = r
        .link_set
        .iter()
        .zip(&r.link_reached)
        .map(|(set, most)| {
            format!(
                "{} ({})",
                q(*most, Dimension::Length),
                q(*set, Dimension::Length)
            )
        })
        .collect();
    format!(
        "  side-member links: plastic work {}; largest compression (plastic set), left chain then right, front to back: {}\n",
        q(r.energy.plastic, Dimension::Energy),
        links.join(", ")
    )
}

fn contact(r: &PlanarResult) -> String {
    let start = r.time.first().copied().unwrap_or(0.0);
    let free = match start < 0.0 {
        true => format!(
            "  time zero at the first touch; the striker started {} before it (the gap)\n",
            format_quantity(-start, Dimension::Time)
        ),
        false => String::new(),
    };
    // times of samples, printed to the sample (0.03333 ms read as noise)
    let step = match r.time.as_slice() {
        [first, second, ..] => second - first,
        _ => f64::NAN,
    };
    let at = |t| format_time_at(t, step);
    free + &match (r.contact_start, r.contact_end) {
        (Some(a), Some(b)) => format!("  contact from {} to {} ({})\n", at(a), at(b), at(b - a)),
        (Some(a), None) => format!(
            "  contact from {}, not ended within the simulated time\n",
            at(a)
        ),
        _ => "  no contact\n".to_string(),
    }
}

fn motion(r: &PlanarResult) -> String {
    let last = |v: &[f64]| v.last().copied().unwrap_or(0.0);
    format!(
        "  peak yaw rate {}, yaw at the end {}; CG velocity at the end {} along x, {} along y\n",
        format_quantity(r.peak_yaw_rate, Dimension::AngularVelocity),
        format_quantity(last(&r.yaw), Dimension::Angle),
        format_quantity(last(&r.velocity_x), Dimension::Velocity),
        format_quantity(last(&r.velocity_y), Dimension::Velocity)
    )
}

fn energy(r: &PlanarResult) -> String {
    let e = &r.energy;
    let q = |v| format_quantity(v, Dimension::Energy);
    format!(
        "  energy {} at the start: bumper {}, dampers {}, tyres {}, springs and beam {}, kinetic at the end {}\n  relative energy balance error {:.2e} of the initial energy (largest {:.2e}), integration step {}\n  relative momentum residuals {:.2e} linear, {:.2e} angular (of the initial momentum)\n",
        q(e.initial),
        q(e.crush),
        q(e.dampers),
        q(e.friction),
        q(e.springs + e.bending),
        q(e.kinetic),
        e.relative_error,
        e.max_relative_error,
        format_quantity(r.step, Dimension::Time),
        r.momentum.linear_residual,
        r.momentum.angular_residual
    )
}

/// The time histories as CSV (SI units in the headers, one column per segment crush).
pub fn histories(r: &PlanarResult) -> String {
    let mut csv = String::from(
        "time [s],force x [N],force y [N],force [N],side member left [N],side member right [N],x [m],y [m],yaw [rad],yaw rate [rad/s],velocity x [m/s],velocity y [m/s],pendulum travel [m]",
    );
    for j in 0..r.crush.len() {
        csv += &format!(",crush segment {} [m]", j + 1);
    }
    csv.push('\n');
    for k in 0..r.time.len() {
        let row = [
            r.time[k],
            r.force_x[k],
            r.force_y[k],
            r.force[k],
            r.side_force_left[k],
            r.side_force_right[k],
            r.x[k],
            r.y[k],
            r.yaw[k],
            r.yaw_rate[k],
            r.velocity_x[k],
            r.velocity_y[k],
            r.pendulum_travel[k],
        ];
        let crush = r.crush.iter().map(|c| c[k]);
        let cells: Vec<String> = row
            .into_iter()
            .chain(crush)
            .map(|v| v.to_string())
            .collect();
        csv += &cells.join(",");
        csv.push('\n');
    }
    csv
}

/// The summary of a planar identification, every number with its unit;
/// `validation` holds the fits of cases predicted but not fitted. The
/// parameter table and the start statistics are the estimation layer's, as
/// the 1-D identification prints them.
pub fn identification_summary(
    result: &crate::identify::PlanarIdentification,
    validation: &[crate::identify::CaseFit],
) -> String {
    let parameters = crate::identify::parameters_of(result);
    let theta: Vec<f64> = result.parameters.iter().map(|p| p.value).collect();
    let mut s = String::from("planar identification\n");
    for line in
        bumpsim_estimate::text::parameter_table(&parameters, &theta, &result.uncertainty).lines()
    {
        s += &format!("  {line}\n");
    }
    let u = &result.uncertainty;
    s += &format!(
        "  objective {} {}; variance inflation {} (the residuals' integrated autocorrelation time; lag-1 correlation ρ = {})\n",
        bumpsim_core::units::format_number(result.objective, 5),
        result.domain.squared_unit(),
        bumpsim_core::units::format_number(result.inflation, 3),
        bumpsim_core::units::format_number(u.residual_correlation, 4),
    );
    s += &format!(
        "  {}\n",
        bumpsim_estimate::text::starts_line(&result.starts, result.iterations, result.run_time)
    );
    s += &search_noise_line(result);
    s += &prior_lines(result, &parameters);
    let fits: Vec<_> = result
        .fits
        .iter()
        .map(|f| (f, "fitted"))
        .chain(validation.iter().map(|f| (f, "validation")))
        .collect();
    s += &format!(
        "  case fits (x: mean of the sills{}; {}; each replayed from its time zero, in its files' time)\n",
        match fits.iter().any(|(f, _)| f.bias_x.is_some()) {
            true => ", less their bias read after the contact (given per case)",
            false => "",
        },
        match fits.iter().any(|(f, _)| f.yaw_rate_sensor) {
            true =>
                "yaw: the yaw-rate sensor integrated where a case has one (marked), else the sills' difference",
            false => "yaw from their difference",
        }
    );
    for (f, kind) in fits {
        s += &format!(
            "    {:<16} {:<10}  x {:6.2} %   yaw {:6.2} %   peak yaw {:.3} deg   ISO/TS 18571 x {}, yaw {}   from {}{}{}\n",
            f.name,
            kind,
            f.fit_x,
            f.fit_yaw,
            f.peak_yaw.to_degrees(),
            rating(&f.rating_x),
            rating(&f.rating_yaw),
            format_quantity(f.time_zero, Dimension::Time),
            if f.yaw_rate_sensor {
                "   (yaw-rate sensor)"
            } else {
                ""
            },
            f.bias_x.map_or_else(String::new, |b| format!(
                "   (x bias {})",
                format_quantity(b, Dimension::Acceleration)
            ))
        );
    }
    for w in identification_warnings(result, validation) {
        s += &format!("  warning: {w}\n");
    }
    s
}

/// The line saying that the starts ran with the priors weighed at a noise
/// more than [`crate::identify::CONFIRMED`] times the final one (identify
/// module `staged`): each start then reached the data along the
/// continuation in the priors' weight, where the tally counts them; empty
/// otherwise.
fn search_noise_line(result: &crate::identify::PlanarIdentification) -> String {
    let ratio = result.search_noise / result.prior_noise;
    if result.priors.is_empty() || !ratio.is_finite() || ratio <= crate::identify::CONFIRMED {
        return String::new();
    }
    let unit = result.domain.unit();
    format!(
        "    the starts weighed the priors at a noise of {} {unit}, {}× the final {} {unit}: they searched near the priors' centres, each start that ended on its own was then carried along the polishing's continuation to the data (those merged into it with it), and the tally counts where they ended ([model] confirm = true searches again at the final noise)\n",
        bumpsim_core::units::format_number(result.search_noise, 4),
        bumpsim_core::units::format_number(ratio, 3),
        bumpsim_core::units::format_number(result.prior_noise, 4),
    )
}

/// The stated priors, a line each, with how far the data moved them
/// ([`bumpsim_estimate::prior::text`]); empty without any.
fn prior_lines(
    result: &crate::identify::PlanarIdentification,
    parameters: &[bumpsim_estimate::uncertainty::Parameter],
) -> String {
    bumpsim_estimate::prior::indented_text(&result.priors, parameters)
}

/// The forward predictions' lines: each test's fit per channel and the
/// simulation's time zero in the test's time; empty without any.
pub fn forward_lines(forward: &[crate::forward::Forward]) -> String {
    if forward.is_empty() {
        return String::new();
    }
    let mut s = String::from("  forward prediction (car, bumper and striker; no measured force)\n");
    for f in forward {
        let fits: Vec<String> = f
            .channels
            .iter()
            .map(|c| {
                format!(
                    "{} {:6.2} % (ISO {})",
                    c.name,
                    c.fit_percent,
                    rating(&c.rating)
                )
            })
            .collect();
        s += &format!(
            "    {:<16} {}   (onsets aligned: simulation shifted {} ms)\n",
            f.case,
            fits.join("   "),
            bumpsim_core::units::format_number(1e3 * f.shift, 3)
        );
    }
    s
}

/// An ISO/TS 18571 overall rating with three decimals, `-` without one.
fn rating(r: &Option<bumpsim_signal::rating::Rating>) -> String {
    r.as_ref()
        .map_or("-".into(), |r| format!("{:.3}", r.overall))
}

/// Every warning of a planar identification: the result's, then the
/// negative fits of the validation cases.
pub fn identification_warnings(
    result: &crate::identify::PlanarIdentification,
    validation: &[crate::identify::CaseFit],
) -> Vec<String> {
    let mut out = result.warnings.clone();
    out.extend(
        validation
            .iter()
            .flat_map(crate::identify::CaseFit::warnings),
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Layout, PlanarCar};
    use crate::simulate::{Settings, simulate};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn result(face: Face) -> PlanarResult {
        let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        simulate(
            &car,
            &Striker::barrier(face, 15.0 / 3.6),
            &Settings::default(),
        )
        .unwrap()
    }

    #[test]
    fn the_summary_carries_units_and_no_nan() {
        let r = result(Face::plane_in_degrees(10.0, 40.0, Side::Left));
        let s = summary(&r);
        for part in ["kN", "mm", "ms", "deg/s", " J", "segment"] {
            assert!(s.contains(part), "{part} missing in\n{s}");
        }
        assert!(!s.to_lowercase().contains("nan"), "{s}");
    }

    #[test]
    fn histories_have_one_row_per_sample_and_a_column_per_segment() {
        let r = result(Face::pole_of_diameter(0.178, 0.0));
        let csv = histories(&r);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), r.time.len() + 1);
        let columns = 13 + r.crush.len();
        assert!(lines.iter().all(|l| l.split(',').count() == columns));
    }

    #[test]
    fn strikers_read_as_in_the_protocols() {
        let pole = Striker::pendulum(Face::pole_of_diameter(0.178, 0.0), 1400.0, 8.0 / 3.6);
        assert_eq!(
            striker(&pole),
            "a 1400 kg pendulum at 8 km/h carrying a pole of diameter 178 mm at y = 0 mm into the car at rest"
        );
        assert!(striker(&Striker::barrier(Face::flat(), 1.0)).contains("full-width")); // 1e308 kg: `value * 1e3` overflowed and printed "inf kg"
        let heavy = striker(&Striker::pendulum(Face::flat(), 1e308, 2.0));
        assert!(heavy.contains("1.000e308 kg"), "{heavy}");
    }
}
