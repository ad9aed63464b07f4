//! The speed axis: every axis of speed the page draws shows the
//! dimensionless Ω (the default) or the input member's speed in rpm (the
//! small sun s1, or the pinion of the gear pair), as the one view option
//! `axis` chooses. Values are always kept as Ω; this module holds the one
//! conversion ([`SpeedScale`]) that every axis, range field, readout and
//! export uses, and the words and tick labels of an axis in rpm.
//!
//! The conversion is the solver's ([`solver::rpm::RpmScale`], also
//! behind `solver::campbell`): the mesh frequency is `Ω ω_ref / 2π` and
//! the input speed that mesh frequency over the mesh frequency per rpm.
//! Both directions are a product of the same two factors, so rpm to Ω and
//! back gives the value to a few ulps (the link tests check 1e-12).

use solver::model::Model;
use solver::params::MeshKind;
use solver::rpm::RpmScale;

/// What the speed axes show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisUnit {
    /// The dimensionless mesh frequency Ω.
    #[default]
    Omega,
    /// The input member's speed in rpm.
    Rpm,
}

impl AxisUnit {
    /// The link word.
    pub fn name(self) -> &'static str {
        match self {
            AxisUnit::Omega => "omega",
            AxisUnit::Rpm => "rpm",
        }
    }

    /// The unit of a link word, if it is one.
    pub fn from_name(word: &str) -> Option<Self> {
        match word {
            "omega" => Some(AxisUnit::Omega),
            "rpm" => Some(AxisUnit::Rpm),
            _ => None,
        }
    }
}

/// The conversion between Ω and the input member's speed of one model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedScale {
    /// The model's conversion.
    scale: RpmScale,
    /// Whether the model is the gear pair (its input is the pinion).
    pair: bool,
}

impl SpeedScale {
    /// The scale of `model`.
    pub fn of(model: &Model) -> Self {
        SpeedScale {
            scale: model.system.rpm_scale(),
            pair: model
                .system
                .meshes
                .first()
                .is_some_and(|m| m.kind == MeshKind::Pair),
        }
    }

    /// The mesh frequency (Hz) at `omega`.
    pub fn mesh_hz(&self, omega: f64) -> f64 {
        self.scale.mesh_hz(omega)
    }

    /// The input member's speed (rpm) at `omega`.
    pub fn rpm(&self, omega: f64) -> f64 {
        self.scale.rpm(omega)
    }

    /// Ω at the input member's speed `rpm` (the inverse of [`Self::rpm`]).
    pub fn omega(&self, rpm: f64) -> f64 {
        self.scale.omega(rpm)
    }

    /// The input member in words: "sun s1" or "pinion".
    pub fn input(&self) -> &'static str {
        if self.pair {
            "pinion"
        } else {
            "sun s1"
        }
    }

    /// The column name of the input speed in a CSV: `s1_rpm` or `pinion_rpm`.
    pub fn csv_column(&self) -> &'static str {
        if self.pair {
            "pinion_rpm"
        } else {
            "s1_rpm"
        }
    }
}

/// What a speed axis shows: Ω, or rpm through a model's scale. Without a
/// scale (a model that cannot be built) the axes show Ω.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpeedAxis {
    /// The chosen unit.
    pub unit: AxisUnit,
    /// The current model's conversion, if it has one.
    pub scale: Option<SpeedScale>,
}

/// The description of a speed axis in Ω.
pub const OMEGA_AXIS: &str = "Ω = ω / ω_ref (dimensionless mesh frequency)";

impl SpeedAxis {
    /// The axis of `unit` on `model` (Ω if there is no model).
    pub fn new(unit: AxisUnit, model: Option<&Model>) -> Self {
        SpeedAxis {
            unit,
            scale: model.map(SpeedScale::of),
        }
    }

    /// The scale, when the axes show rpm.
    pub fn rpm_scale(&self) -> Option<&SpeedScale> {
        self.scale.as_ref().filter(|_| self.unit == AxisUnit::Rpm)
    }

    /// The axis's description with its unit.
    pub fn label(&self) -> String {
        match self.rpm_scale() {
            Some(s) => format!("{} speed (rpm)", capital(s.input())),
            None => OMEGA_AXIS.to_string(),
        }
    }

    /// The axis's short name, for a small panel: "Ω" or "s1 (rpm)".
    pub fn short_label(&self) -> String {
        match self.rpm_scale() {
            Some(s) => format!("{} (rpm)", s.input()),
            None => "Ω".to_string(),
        }
    }

    /// A speed for the reader: "Ω = 0.350" or "1 234 rpm (Ω 0.350)".
    pub fn text(&self, omega: f64) -> String {
        match self.rpm_scale() {
            Some(s) => format!("{} rpm (Ω {omega:.3})", grouped_fine(s.rpm(omega))),
            None => format!("Ω = {omega:.3}"),
        }
    }

    /// The selected speed in both units with the mesh frequency, for the
    /// readout: "Selected speed: Ω 0.3500, sun s1 at 1 807 rpm, mesh
    /// frequency 1 898 Hz".
    pub fn readout(&self, omega: f64) -> String {
        match &self.scale {
            Some(s) => format!(
                "Selected speed: Ω {omega:.4}, {} at {} rpm, mesh frequency {} Hz",
                s.input(),
                grouped_fine(s.rpm(omega)),
                grouped(s.mesh_hz(omega))
            ),
            None => format!("Selected speed: Ω {omega:.4}"),
        }
    }

    /// The value a field shows for the Ω `omega`: Ω as it is, or the rpm
    /// rounded to 1e-6 (so that a typed 3000 reads back 3000).
    pub fn field_value(&self, omega: f64) -> f64 {
        match self.rpm_scale() {
            Some(s) => (s.rpm(omega) * 1e6).round() / 1e6,
            None => omega,
        }
    }
}

/// `s` with its first letter in upper case ("Sun s1").
pub fn capital(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
}

/// `x` rounded to a whole number, its thousands set apart by a no-break
/// space as people write them ("1 257"): a speed in rpm, a frequency in Hz.
pub fn grouped(x: f64) -> String {
    let n = x.round();
    if !n.is_finite() {
        return format!("{x}");
    }
    let digits = format!("{}", n.abs() as u64);
    let mut out = String::new();
    for (i, ch) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push('\u{a0}');
        }
        out.push(ch);
    }
    if n < 0.0 {
        format!("-{out}")
    } else {
        out
    }
}

/// `x` as [`grouped`], with the decimals of a speed selected to a decimal
/// step (a click on a narrow range: "3 004.37"): the fewest decimals, up
/// to three, that give `x` to 1e-9 of itself. Any other value (an rpm
/// converted from an Ω such as 0.35) is written whole, as [`grouped`].
pub fn grouped_fine(x: f64) -> String {
    let close = |y: f64| (x - y).abs() <= 1e-9 * x.abs().max(1.0);
    let Some(places) = (0..=3).find(|&k| {
        let p = 10f64.powi(k);
        close((x * p).round() / p)
    }) else {
        return grouped(x);
    };
    let p = 10f64.powi(places);
    let units = (x.abs() * p).round();
    let whole = (units / p).trunc();
    if places == 0 || !units.is_finite() {
        return grouped(x);
    }
    let frac = format!(
        "{:0width$}",
        (units - whole * p) as u64,
        width = places as usize
    );
    let sign = if x < 0.0 { "-" } else { "" };
    format!("{sign}{}.{frac}", grouped(whole))
}

/// A CSV with an `omega` column as the rpm axis exports it: a column of
/// the input speed (`s1_rpm`) after it. A CSV without one, or with its
/// own speed column already, is returned as it is.
pub fn csv_with_rpm(csv: &str, scale: &SpeedScale) -> String {
    let mut lines = csv.lines();
    let Some(header) = lines.next() else {
        return csv.to_string();
    };
    let cols: Vec<&str> = header.split(',').collect();
    let Some(at) = cols.iter().position(|c| *c == "omega") else {
        return csv.to_string();
    };
    if cols.iter().any(|c| c.ends_with("rpm")) {
        return csv.to_string();
    }
    let with = |line: &str, extra: &str| {
        let mut cells: Vec<String> = line.split(',').map(str::to_string).collect();
        if cells.len() > at {
            cells.insert(at + 1, extra.to_string());
        }
        cells.join(",")
    };
    let mut out = with(header, scale.csv_column());
    out.push('\n');
    for line in lines {
        let cell = line.split(',').nth(at).unwrap_or("");
        let rpm = cell
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .map_or(String::new(), |o| format!("{}", scale.rpm(o)));
        out.push_str(&with(line, &rpm));
        out.push('\n');
    }
    out
}

/// The speed axis as an export's JSON says it: the unit shown, the input
/// member, and the factor from Ω to its rpm.
pub fn axis_json(axis: &SpeedAxis) -> serde_json::Value {
    match &axis.scale {
        Some(s) => serde_json::json!({
            "unit": axis.unit.name(),
            "input": s.input(),
            "rpm_per_omega": s.rpm(1.0),
            "mesh_hz_per_omega": s.mesh_hz(1.0),
        }),
        None => serde_json::json!({ "unit": AxisUnit::Omega.name() }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::params::{ModelKind, ModelParams};
    use std::f64::consts::PI;

    fn model(kind: ModelKind) -> Model {
        Model::new(&ModelParams::defaults(kind)).unwrap()
    }

    /// The scale is the solver's conversion, bit for bit.
    #[test]
    fn the_scale_is_the_solvers_conversion() {
        for kind in [ModelKind::Ravigneaux, ModelKind::GearPair] {
            let m = model(kind);
            let s = SpeedScale::of(&m);
            for o in [0.01, 0.35, 1.0, 2.0, 20.0] {
                assert_eq!(s.rpm(o), solver::campbell::rpm_at(&m, o));
            }
            for r in [1.0, 3000.0, 12_345.678] {
                assert_eq!(s.omega(r), solver::campbell::omega_at(&m, r));
            }
            // The mesh frequency is Ω ω_ref / 2π, by hand.
            let hz = 0.5 * m.system.omega_ref_rad_s / (2.0 * PI);
            assert!((s.mesh_hz(0.5) - hz).abs() <= 1e-12 * hz);
        }
    }

    #[test]
    fn the_input_member_is_named_per_model() {
        assert_eq!(
            SpeedScale::of(&model(ModelKind::Ravigneaux)).input(),
            "sun s1"
        );
        assert_eq!(
            SpeedScale::of(&model(ModelKind::GearPair)).input(),
            "pinion"
        );
        let axis = SpeedAxis::new(AxisUnit::Rpm, Some(&model(ModelKind::Ravigneaux)));
        assert_eq!(axis.label(), "Sun s1 speed (rpm)");
        assert_eq!(SpeedAxis::default().label(), OMEGA_AXIS);
    }

    #[test]
    fn speeds_are_written_with_their_thousands_apart() {
        assert_eq!(grouped(12_345.4), "12\u{a0}345");
        assert_eq!(grouped(999.6), "1\u{a0}000");
        assert_eq!(grouped(3000.0), "3\u{a0}000");
        assert_eq!(grouped(0.0), "0");
        assert_eq!(grouped_fine(3004.37), "3\u{a0}004.37");
        assert_eq!(grouped_fine(2999.9999999), "3\u{a0}000");
        assert_eq!(grouped_fine(12.0005), "12");
        assert_eq!(grouped_fine(0.25), "0.25");
        assert_eq!(grouped_fine(-1234.5), "-1\u{a0}234.5");
        assert_eq!(grouped_fine(1_806.934_567), "1\u{a0}807");
    }

    /// The rpm column is Ω times rpm per Ω, computed here by hand from the
    /// tooth count and the relative speed.
    #[test]
    fn a_csv_gets_the_input_speed_beside_omega() {
        let m = model(ModelKind::Ravigneaux);
        let s = SpeedScale::of(&m);
        let csv = "branch,omega,x\nhbm,0.5,1\nhbm,,2\n";
        let out = csv_with_rpm(csv, &s);
        let mut lines = out.lines();
        assert_eq!(lines.next(), Some("branch,omega,s1_rpm,x"));
        let row: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rpm: f64 = row[2].parse().unwrap();
        let sp = m.system.speed;
        let per_rpm = f64::from(sp.input_teeth) * sp.relative_per_input.abs() / 60.0;
        let want = 0.5 * m.system.omega_ref_rad_s / (2.0 * PI) / per_rpm;
        assert!((rpm - want).abs() <= 1e-12 * want, "{rpm} {want}");
        assert_eq!(lines.next(), Some("hbm,,,2"));
        // A CSV with its own rpm column is left alone.
        let c = "order,rpm,omega\n1,2,3\n";
        assert_eq!(csv_with_rpm(c, &s), c);
    }
}
