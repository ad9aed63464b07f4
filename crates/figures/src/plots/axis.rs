//! The x coordinate of every chart: linear in its data, with its ticks
//! chosen and written in the unit the reader asked for. Over Ω it is
//! plotters' own linear coordinate unchanged; when the speed axes show rpm
//! the ticks are round numbers of rpm, placed at their Ω through
//! [`crate::speed::SpeedScale`] (and the Campbell diagram, drawn over rpm,
//! gets round Ω ticks when the axes show Ω). The data never change unit,
//! so every point, click and frame stays in the data's own.

use crate::speed::{SpeedAxis, SpeedScale};
use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use std::ops::Range;

/// How an x axis's ticks are chosen and written.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) enum Ticks {
    /// In the data's unit.
    #[default]
    Data,
    /// The data are Ω; the ticks round rpm.
    RpmOverOmega(SpeedScale),
    /// The data are rpm; the ticks round Ω.
    OmegaOverRpm(SpeedScale),
}

impl Ticks {
    /// The ticks of a chart over Ω for `axis`.
    pub(crate) fn over_omega(axis: &SpeedAxis) -> Self {
        axis.rpm_scale()
            .map_or(Ticks::Data, |s| Ticks::RpmOverOmega(*s))
    }

    /// The ticks of a chart over rpm for `axis`.
    pub(crate) fn over_rpm(axis: &SpeedAxis) -> Self {
        match (axis.rpm_scale(), axis.scale) {
            (None, Some(s)) => Ticks::OmegaOverRpm(s),
            _ => Ticks::Data,
        }
    }

    fn shown(&self, x: f64) -> f64 {
        match self {
            Ticks::Data => x,
            Ticks::RpmOverOmega(s) => s.rpm(x),
            Ticks::OmegaOverRpm(s) => s.omega(x),
        }
    }

    fn data(&self, x: f64) -> f64 {
        match self {
            Ticks::Data => x,
            Ticks::RpmOverOmega(s) => s.omega(x),
            Ticks::OmegaOverRpm(s) => s.rpm(x),
        }
    }
}

/// A linear x coordinate with [`Ticks`].
#[derive(Clone)]
pub(crate) struct XCoord {
    linear: RangedCoordf64,
    ticks: Ticks,
}

impl XCoord {
    /// The coordinate over `x` (data units) with `ticks`.
    pub(crate) fn new(x: (f64, f64), ticks: Ticks) -> Self {
        XCoord {
            linear: (x.0..x.1).into(),
            ticks,
        }
    }
}

impl Ranged for XCoord {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.linear.map(value, limit)
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if self.ticks == Ticks::Data {
            return self.linear.key_points(hint);
        }
        let r = self.linear.range();
        let (a, b) = (self.ticks.shown(r.start), self.ticks.shown(r.end));
        let shown: RangedCoordf64 = (a.min(b)..a.max(b)).into();
        shown
            .key_points(hint)
            .into_iter()
            .map(|x| self.ticks.data(x))
            .filter(|x| *x >= r.start.min(r.end) && *x <= r.start.max(r.end))
            .collect()
    }

    fn range(&self) -> Range<f64> {
        self.linear.range()
    }
}

impl ValueFormatter<f64> for XCoord {
    fn format_ext(&self, value: &f64) -> String {
        if self.ticks == Ticks::Data {
            return RangedCoordf64::format(value);
        }
        // A tick converted there and back is its round value within a few
        // ulps: snapped to 1e-9 of it before it is written.
        let x = self.ticks.shown(*value);
        let snapped = (x * 1e9).round() / 1e9;
        match self.ticks {
            // Whole rpm with their thousands apart, as the Campbell
            // diagram and the sentences write them ("10 000").
            Ticks::RpmOverOmega(_) if snapped.fract() == 0.0 => crate::speed::grouped(snapped),
            _ => RangedCoordf64::format(&snapped),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::speed::AxisUnit;
    use solver::model::Model;
    use solver::params::{ModelKind, ModelParams};

    /// Over Ω 0.1 to 2 in rpm the ticks are round rpm, written whole
    /// (thousands apart),
    /// each at the Ω of its rpm; over Ω they are plotters' own.
    #[test]
    fn rpm_ticks_are_round_numbers_at_their_omega() {
        let m = Model::new(&ModelParams::defaults(ModelKind::Ravigneaux)).unwrap();
        let axis = SpeedAxis::new(AxisUnit::Rpm, Some(&m));
        let s = SpeedScale::of(&m);
        let x = XCoord::new((0.1, 2.0), Ticks::over_omega(&axis));
        let ticks = x.key_points(8usize);
        assert!(ticks.len() >= 3, "{ticks:?}");
        for t in &ticks {
            let label = x.format_ext(t);
            let rpm: f64 = label.replace('\u{a0}', "").parse().unwrap();
            assert_eq!(rpm.fract(), 0.0, "{label}");
            // Round: a multiple of 1, 2 or 5 times a power of ten.
            let p = 10f64.powf(rpm.abs().log10().floor());
            assert!(
                [1.0, 2.0, 2.5, 5.0].iter().any(|k| (rpm / p) % k == 0.0)
                    || (rpm / p).fract() == 0.0,
                "{label}"
            );
            assert!((s.rpm(*t) - rpm).abs() <= 1e-9 * rpm, "{label}");
        }
        let plain = XCoord::new((0.1, 2.0), Ticks::Data);
        let own: RangedCoordf64 = (0.1..2.0).into();
        assert_eq!(plain.key_points(8usize), own.key_points(8usize));
        assert_eq!(plain.format_ext(&0.5), RangedCoordf64::format(&0.5));
    }
}
