//! A TE table fitted to a mesh kind's harmonics, as the page shows it: the
//! table's points in mesh periods, the fit (`solver::te_file`), and the fit
//! said in plain words. The page and the native tests share it; the plot
//! is `plots::te_fit`.

use solver::te_file::{TeFit, TeTable};
use std::f64::consts::PI;

/// The most points the plot draws, each a ring (every k-th beyond).
pub const MAX_DRAWN_POINTS: usize = 72;

/// A fitted TE table.
#[derive(Debug, Clone, PartialEq)]
pub struct TeFitView {
    /// The mesh kind fitted (`pair`, `s1a`, ...).
    pub kind: String,
    /// The file's name as the user gave it.
    pub file: String,
    /// The table's abscissa in mesh periods.
    pub x_periods: Vec<f64>,
    /// The table's TE (µm).
    pub te_um: Vec<f64>,
    /// The fit.
    pub fit: TeFit,
}

impl TeFitView {
    /// The view of `table` (one mesh period `period` in its abscissa)
    /// and its `fit`, for mesh kind `kind`, read from `file`.
    pub fn new(kind: &str, file: &str, table: &TeTable, period: f64, fit: TeFit) -> Self {
        TeFitView {
            kind: kind.into(),
            file: solver::keys::truncate(file, 60).to_string(),
            x_periods: table.x.iter().map(|x| x / period).collect(),
            te_um: table.te_um.clone(),
            fit,
        }
    }

    /// The fitted curve at `samples` points across the table's span.
    pub fn curve(&self, samples: usize) -> Vec<(f64, f64)> {
        let (Some(&a), Some(&b)) = (self.x_periods.first(), self.x_periods.last()) else {
            return Vec::new();
        };
        let n = samples.max(2);
        (0..n)
            .map(|i| {
                let x = a + (b - a) * i as f64 / (n - 1) as f64;
                (x, self.fit.value_um(2.0 * PI * x))
            })
            .collect()
    }

    /// The table's points, at most [`MAX_DRAWN_POINTS`] of them.
    pub fn drawn_points(&self) -> Vec<(f64, f64)> {
        let step = self.x_periods.len().div_ceil(MAX_DRAWN_POINTS).max(1);
        self.x_periods
            .iter()
            .zip(&self.te_um)
            .step_by(step)
            .map(|(&x, &t)| (x, t))
            .collect()
    }

    /// The fit in plain words: the file, the points, the harmonics, the
    /// residual in µm against the TE's own size.
    pub fn sentence(&self) -> String {
        let f = &self.fit;
        let h = f.harmonics_um.len();
        let misses = if f.rms_residual_um < 1e-6 {
            "by less than 0.000001 µm: the harmonics describe the table exactly".to_string()
        } else {
            format!(
                "by {} µm (root mean square), against a TE that varies by {} µm about its mean",
                um_text(f.rms_residual_um),
                um_text(f.rms_um)
            )
        };
        let periods = um_text(f.periods);
        let plural = |n: &str| if n == "1" { "" } else { "s" };
        format!(
            "{}: {} points over {periods} mesh period{}, fitted with {h} harmonic{} of the mesh \
             frequency for {}. The fitted curve misses the points {misses}; the harmonics \
             are kept to {} µm and are in the fields above and in the link.",
            self.file,
            f.points,
            plural(&periods),
            plural(&h.to_string()),
            kind_words(&self.kind),
            um_text(10f64.powi(-(f.decimals as i32))),
        )
    }
}

/// A mesh kind in words.
pub fn kind_words(kind: &str) -> String {
    match kind {
        "pair" => "the gear pair's mesh".into(),
        k => format!("the {k} meshes"),
    }
}

/// A number with two significant digits, written out (no exponent).
pub fn um_text(x: f64) -> String {
    if !(x.is_finite() && x > 0.0) {
        return "0".into();
    }
    let digits = (1 - x.log10().floor() as i32).clamp(0, 9) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::te_file::{fit, parse};

    #[test]
    fn the_view_maps_roll_angle_to_periods_and_says_the_fit() {
        // Two mesh periods of 12 degrees of 1 + 2 cos(theta), 24 points.
        let mut text = String::from("roll_deg,te_um\n");
        for i in 0..24 {
            let x = f64::from(i);
            text.push_str(&format!(
                "{x},{}\n",
                1.0 + 2.0 * (2.0 * PI * x / 12.0).cos()
            ));
        }
        let table = parse(&text).unwrap();
        let v = TeFitView::new("s1a", "te.csv", &table, 12.0, fit(&table, 12.0, 2).unwrap());
        assert_eq!(v.x_periods[6], 0.5);
        let c = v.curve(3);
        // At 0 and 23/12 periods: 1 + 2 cos(2 pi x).
        assert!((c[0].1 - 3.0).abs() < 1e-9);
        let x = 23.0 / 12.0;
        assert!((c[2].1 - (1.0 + 2.0 * (2.0 * PI * x).cos())).abs() < 1e-9);
        let s = v.sentence();
        assert!(
            s.starts_with("te.csv: 24 points over 2 mesh periods"),
            "{s}"
        );
        assert!(
            s.contains("2 harmonics") && s.contains("the s1a meshes"),
            "{s}"
        );
        assert!(s.contains("less than 0.000001 µm"), "{s}");
        assert!(!s.contains('_'), "{s}");
    }

    #[test]
    fn numbers_are_written_out_to_two_digits() {
        assert_eq!(um_text(0.01234), "0.012");
        assert_eq!(um_text(8.985), "9");
        assert_eq!(um_text(12.4), "12");
        assert_eq!(um_text(0.000001), "0.000001");
    }
}
