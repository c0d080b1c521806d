//! The sign check of a load case: force and motion must agree.
//!
//! bumpsim takes the force on m1 positive in the direction it pushes the
//! car and every acceleration and displacement positive in that same
//! direction (one axis, along the impact). Whatever the initial velocity,
//! the force drives the car's velocity away from it in the force's
//! direction (momentum balance, `Σ m_i Δv_i = ∫ F dt`, spec §3); a light
//! m1 may swing back before the contact ends, so the check weighs each
//! sample's velocity change by the force then acting:
//! `S = Σ F_k (v_k − v_0) / (Σ |F_k| · max_k |v_k − v_0|)`, 1 for motion
//! all along the force, −1 for motion all against it. A clearly negative
//! `S` (below −0.2) is the fingerprint of an
//! accelerometer recorded in another axis convention (the ISO vehicle
//! frame, X forward, reads negative in a front impact), so the case gets a
//! warning that says so instead of a fit that silently fails.

use super::LoadCase;
use bumpsim_core::units::format_number;

/// How far below zero the force-weighted velocity change `S` must be to be
/// reported (noise and drift give small values of either sign).
const CLEAR: f64 = 0.2;

impl LoadCase {
    /// A warning when the measured motion moves against the force over the
    /// fit window (velocity change and impulse of opposite signs, clearly
    /// beyond noise), naming both and the fix; `None` otherwise.
    ///
    /// ```
    /// use bumpsim_ident::LoadCase;
    /// // a push of 1 kN for 10 ms while the measured mass moves backwards
    /// let n = 101;
    /// let case = LoadCase {
    ///     name: "flat".into(),
    ///     start: 0.0,
    ///     step: 1e-4,
    ///     force: vec![1e3; n],
    ///     measured: (0..n).map(|i| -0.5 * (i as f64 * 1e-4).powi(2) * 10.0).collect(),
    ///     output_dof: 1,
    ///     initial_velocity: 0.0,
    ///     window: (0, n - 1),
    ///     compare: Default::default(),
    /// };
    /// assert!(case.direction_warning().unwrap().contains("scale = -1.0"));
    /// ```
    pub fn direction_warning(&self) -> Option<String> {
        self.direction_warning_given(&[])
    }

    /// [`LoadCase::direction_warning`] for a case whose study already gives
    /// the channels `flipped` (their selectors) a negative scale: the fix it
    /// names is then to remove that scale, not to add one.
    ///
    /// ```
    /// use bumpsim_ident::LoadCase;
    /// let n = 101;
    /// let case = LoadCase {
    ///     name: "flat".into(),
    ///     start: 0.0,
    ///     step: 1e-4,
    ///     force: vec![1e3; n],
    ///     measured: (0..n).map(|i| -0.5 * (i as f64 * 1e-4).powi(2) * 10.0).collect(),
    ///     output_dof: 1,
    ///     initial_velocity: 0.0,
    ///     window: (0, n - 1),
    ///     compare: Default::default(),
    /// };
    /// let warning = case.direction_warning_given(&["10SIME*ACXP".into()]).unwrap();
    /// assert!(warning.contains("remove"), "{warning}");
    /// ```
    pub fn direction_warning_given(&self, flipped: &[String]) -> Option<String> {
        let (first, last) = self.window;
        if last < first + 4 || last >= self.measured.len() || self.step <= 0.0 {
            return None;
        }
        let velocity = |i: usize| (self.measured[i + 1] - self.measured[i - 1]) / (2.0 * self.step);
        let v0 = velocity(first + 1);
        let (mut weighted, mut force, mut largest) = (0.0, 0.0, 0.0_f64);
        for i in first + 1..last {
            let change = velocity(i) - v0;
            weighted += self.force[i] * change;
            force += self.force[i].abs();
            largest = if change.abs() > largest.abs() {
                change
            } else {
                largest
            };
        }
        let agreement = weighted / (force * largest.abs());
        let impulse: f64 = self.force[first..=last].iter().sum::<f64>() * self.step;
        (agreement < -CLEAR).then(|| self.against(largest, impulse, flipped))
    }

    fn against(&self, change: f64, impulse: f64, flipped: &[String]) -> String {
        format!(
            "case '{}': the measured motion goes against the force: its largest velocity change in the fit window is {} m/s while the force's impulse is {} N·s. bumpsim takes force, accelerations and displacements positive in the direction the force pushes the car; {} (docs/your-own-tests.md, signs)",
            self.name,
            format_number(change, 4),
            format_number(impulse, 4),
            sign_fix(flipped)
        )
    }
}

/// The fix a sign warning names: add a negative scale, or remove the one
/// the study already gives (a channel turned that needed no turning).
fn sign_fix(flipped: &[String]) -> String {
    if flipped.is_empty() {
        return "an accelerometer in the vehicle frame (X forward) reads negative in a front impact: give its channel scale = -1.0".into();
    }
    let names: Vec<String> = flipped.iter().map(|c| format!("'{c}'")).collect();
    format!(
        "the study already gives {} a negative scale: remove it (the channel may already read along the force)",
        names.join(" and ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pendulum push: force a half sine, the measured mass a free body
    /// of 100 kg under it (x'' = F/m), from `v0`.
    fn case(sign: f64, v0: f64) -> LoadCase {
        let (n, step, mass) = (201, 1e-4, 100.0);
        let force: Vec<f64> = (0..n)
            .map(|i| 1e4 * (std::f64::consts::PI * i as f64 / (n - 1) as f64).sin())
            .collect();
        let (mut x, mut v, mut measured) = (0.0, v0, Vec::new());
        for f in &force {
            measured.push(sign * x);
            v += f / mass * step;
            x += v * step;
        }
        LoadCase {
            name: "flat".into(),
            start: 0.0,
            step,
            force,
            measured,
            output_dof: 1,
            initial_velocity: sign * v0,
            window: (0, n - 1),
            compare: Default::default(),
        }
    }

    #[test]
    fn motion_along_the_force_passes_at_any_initial_velocity() {
        for v0 in [0.0, -2.0, 3.0] {
            assert_eq!(case(1.0, v0).direction_warning(), None, "v0 {v0}");
        }
    }

    #[test]
    fn motion_against_the_force_is_named_with_its_fix() {
        for v0 in [0.0, -2.0] {
            let w = case(-1.0, v0).direction_warning().expect("a warning");
            assert!(
                w.contains("case 'flat'") && w.contains("scale = -1.0"),
                "{w}"
            );
            // Δv = ∫F dt / m = (2/π · 1e4 N · 20 ms) / 100 kg ≈ 1.27 m/s
            assert!(w.contains("is -1.27"), "{w}");
        }
    }

    #[test]
    fn a_channel_already_turned_is_named_with_the_fix_to_remove_its_scale() {
        let w = case(-1.0, 0.0)
            .direction_warning_given(&["10SIME*ACXP".into()])
            .expect("a warning");
        assert!(
            w.contains("already gives '10SIME*ACXP' a negative scale: remove it"),
            "{w}"
        );
        assert!(!w.contains("give its channel scale = -1.0"), "{w}");
    }
}
