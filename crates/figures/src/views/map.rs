//! The impact-regime map (`ViewId::Map`): its grid, the store that collects the
//! workers' cells, what the plot draws, its note and its exports.
//!
//! A map is a grid of Omega columns (the page's frequency range) and rows of
//! one parameter (`backlash_um` or `te_um`); rows are computed by the
//! workers in shares (`solver::map`), so cells arrive row by row from every
//! worker at once. A click on a cell is turned back into that cell's two
//! values by [`MapGrid::cell_at`].

use crate::protocol::{BoundaryCurve, MapSample, Regime};
use serde::Serialize;

/// The grid of a map: what the job computes and the plot shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapGrid {
    /// The rows' key.
    pub key: String,
    /// Omega of column 0.
    pub omega_from: f64,
    /// Omega of the last column.
    pub omega_to: f64,
    /// Columns.
    pub omega_points: u32,
    /// The key's value on row 0 (um).
    pub value_from: f64,
    /// Its value on the last row (um).
    pub value_to: f64,
    /// Rows.
    pub value_points: u32,
}

impl MapGrid {
    /// The grid the view options ask for (the page's Omega range, the map's
    /// key, range and points), as the page's map job and `gearshock figure
    /// map` compute it.
    pub fn of(v: &crate::settings::ViewOptions) -> Self {
        MapGrid {
            key: v.map_key.clone(),
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            omega_points: v.map_omega_points,
            value_from: v.map_from,
            value_to: v.map_to,
            value_points: v.map_value_points,
        }
    }

    /// Omega of column `c` (as `solver::map::MapSpec::omega`).
    pub fn omega(&self, c: u32) -> f64 {
        self.omega_from
            + (self.omega_to - self.omega_from) * f64::from(c)
                / f64::from(self.omega_points.max(2) - 1)
    }

    /// The key's value on row `r` (as `solver::map::MapSpec::value`).
    pub fn value(&self, r: u32) -> f64 {
        if self.value_points <= 1 {
            return self.value_from;
        }
        self.value_from
            + (self.value_to - self.value_from) * f64::from(r) / f64::from(self.value_points - 1)
    }

    /// Width of a column in Omega.
    pub fn omega_step(&self) -> f64 {
        (self.omega_to - self.omega_from) / f64::from(self.omega_points.max(2) - 1)
    }

    /// Height of a row in the key's unit (a single row spans the range).
    pub fn value_step(&self) -> f64 {
        if self.value_points <= 1 {
            (self.value_to - self.value_from).abs().max(1.0)
        } else {
            (self.value_to - self.value_from) / f64::from(self.value_points - 1)
        }
    }

    /// The plotted Omega range: the cells' outer edges.
    pub fn x_range(&self) -> (f64, f64) {
        let h = 0.5 * self.omega_step();
        (self.omega_from - h, self.omega_to + h)
    }

    /// The plotted value range: the cells' outer edges.
    pub fn y_range(&self) -> (f64, f64) {
        let h = 0.5 * self.value_step();
        (
            self.value(0) - h,
            self.value(self.value_points.max(1) - 1) + h,
        )
    }

    /// Cells in all.
    pub fn cells(&self) -> usize {
        self.omega_points as usize * self.value_points as usize
    }

    /// The cell `(row, column)` containing the point `(omega, value)`, or
    /// `None` outside the map.
    pub fn cell_at(&self, omega: f64, value: f64) -> Option<(u32, u32)> {
        let (x0, x1) = self.x_range();
        let (y0, y1) = self.y_range();
        if !(omega.is_finite() && value.is_finite() && omega >= x0 && omega <= x1) {
            return None;
        }
        if !(value >= y0.min(y1) && value <= y0.max(y1)) {
            return None;
        }
        let c = ((omega - self.omega_from) / self.omega_step()).round();
        let r = if self.value_points <= 1 {
            0.0
        } else {
            ((value - self.value_from) / self.value_step()).round()
        };
        let c = c.clamp(0.0, f64::from(self.omega_points - 1)) as u32;
        let r = r.clamp(0.0, f64::from(self.value_points.max(1) - 1)) as u32;
        Some((r, c))
    }

    /// The axis label of the rows.
    pub fn key_label(&self) -> &'static str {
        key_label(&self.key)
    }
}

/// The axis label of a map key.
pub fn key_label(key: &str) -> &'static str {
    match key {
        "te_um" => "TE sine amplitude on the s1a meshes (µm)",
        _ => "backlash b, all meshes (µm)",
    }
}

/// Map cells as they arrive, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapStore {
    /// Its grid.
    pub grid: Option<MapGrid>,
    /// Cells, row-major (`row * omega_points + column`).
    pub cells: Vec<Option<MapSample>>,
    /// Cells received.
    pub done: usize,
    /// What the job depends on: a new map is only started when this changes.
    pub signature: String,
}

impl MapStore {
    /// An empty store for a new job.
    pub fn new(grid: MapGrid, signature: String) -> Self {
        let n = grid.cells();
        MapStore {
            grid: Some(grid),
            cells: vec![None; n],
            done: 0,
            signature,
        }
    }

    /// Adds cells (ignoring any outside the grid or already received).
    pub fn add(&mut self, cells: Vec<MapSample>) {
        let Some(g) = &self.grid else { return };
        for c in cells {
            if c.row >= g.value_points || c.column >= g.omega_points {
                continue;
            }
            let k = c.row as usize * g.omega_points as usize + c.column as usize;
            if let Some(slot) = self.cells.get_mut(k) {
                if slot.is_none() {
                    self.done += 1;
                }
                *slot = Some(c);
            }
        }
    }

    /// The received cell at `(row, column)`.
    pub fn cell(&self, row: u32, column: u32) -> Option<&MapSample> {
        let g = self.grid.as_ref()?;
        let k = row as usize * g.omega_points as usize + column as usize;
        self.cells.get(k)?.as_ref()
    }

    /// The first failed cell in row-major order, if any.
    pub fn first_failure(&self) -> Option<&MapSample> {
        self.cells.iter().flatten().find(|c| c.error.is_some())
    }

    /// Counts of each regime among the received cells (in [`Regime::ALL`]
    /// order), of cells that are not period 1, and of failed cells.
    pub fn counts(&self) -> ([usize; Regime::ALL.len()], usize, usize) {
        let mut by = [0; Regime::ALL.len()];
        let (mut not_p1, mut failed) = (0, 0);
        for c in self.cells.iter().flatten() {
            if c.error.is_some() {
                failed += 1;
                continue;
            }
            if let Some(i) = Regime::ALL.iter().position(|&r| r == c.regime) {
                by[i] += 1;
            }
            if c.period != Some(1) {
                not_p1 += 1;
            }
        }
        (by, not_p1, failed)
    }
}

/// What the map plot draws.
#[derive(Debug, Clone, PartialEq)]
pub struct MapView<'a> {
    /// The grid and its cells.
    pub store: &'a MapStore,
    /// The mapped mesh in words.
    pub mesh_label: String,
    /// The page's selected Omega and the key's current value (the cursor).
    pub selected: (f64, Option<f64>),
    /// The traced boundaries it shows (`views::boundaries`).
    pub boundaries: Vec<&'a BoundaryCurve>,
    /// The cusps: `(omega, value)`.
    pub cusps: Vec<(f64, f64)>,
    /// The cells `(row, column)` that disagree with the curves.
    pub disagree: Vec<(u32, u32)>,
    /// The clicked curve (its place in `boundaries`) and its picked point
    /// `(omega, value)`, marked on the map.
    pub picked: Option<(usize, (f64, f64))>,
    /// What the speed axis shows.
    pub speed: crate::speed::SpeedAxis,
}

/// The map's cells as CSV, row by row (the format of `gearshock map --format csv`).
pub fn map_csv(store: &MapStore) -> String {
    let key = store.grid.as_ref().map_or("value", |g| g.key.as_str());
    let mut s = format!("row,column,omega,{key},impact,period,error\n");
    for c in store.cells.iter().flatten() {
        s.push_str(&format!(
            "{},{},{},{},{},{},{}\n",
            c.row,
            c.column,
            c.omega,
            c.value,
            if c.error.is_some() {
                ""
            } else {
                c.regime.solver_name()
            },
            c.period.map_or(String::new(), |p| p.to_string()),
            c.error.as_deref().unwrap_or("").replace(',', ";"),
        ));
    }
    s
}

/// The map as JSON: its grid and the computed cells (field names as in
/// `gearshock map`).
pub fn map_json(store: &MapStore) -> serde_json::Value {
    let cells: Vec<serde_json::Value> = store
        .cells
        .iter()
        .flatten()
        .map(|c| {
            serde_json::json!({
                "row": c.row,
                "column": c.column,
                "omega": c.omega,
                "value": c.value,
                "impact": if c.error.is_some() { None } else { Some(c.regime.solver_name()) },
                "period": c.period,
                "error": c.error,
            })
        })
        .collect();
    serde_json::json!({ "grid": store.grid, "cells": cells })
}

/// Every regime present with its count, by its one label, in the fixed
/// order ("36 no gap (linear contact)"), from [`MapStore::counts`].
pub fn regime_counts(by: &[usize; Regime::ALL.len()]) -> Vec<String> {
    Regime::ALL
        .iter()
        .zip(by)
        .filter(|(_, n)| **n > 0)
        .map(|(r, n)| format!("{n} {}", r.label()))
        .collect()
}

/// The note under the map: cells done, counts per regime, failures with
/// an example, and what a click does.
pub fn map_note(store: &MapStore, total: usize) -> String {
    let (by, not_p1, failed) = store.counts();
    let parts = regime_counts(&by);
    let parts = if parts.is_empty() {
        "none yet".to_string()
    } else {
        parts.join(", ")
    };
    let mut note = format!(
        "{} of {} cells: {parts}; {not_p1} not period 1",
        store.done, total
    );
    if failed > 0 {
        note.push_str(&format!("; {failed} failed (dark grey)"));
        if let Some(c) = store.first_failure() {
            let key = store.grid.as_ref().map_or("", |g| g.key.as_str());
            note.push_str(&format!(
                ", e.g. at Ω {}, {}: {}",
                super::unstable::short(c.omega),
                crate::words::setting(key, &super::unstable::short(c.value)),
                c.error.as_deref().unwrap_or("")
            ));
        }
    }
    note.push_str(". Click a cell to set both parameters.");
    note
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> MapGrid {
        crate::views::test_support::backlash_grid(150.0, 16)
    }

    #[test]
    fn every_cell_centre_maps_back_to_its_cell() {
        let g = grid();
        for r in 0..g.value_points {
            for c in 0..g.omega_points {
                assert_eq!(g.cell_at(g.omega(c), g.value(r)), Some((r, c)));
                // Anywhere inside the cell, not only its centre.
                let (dx, dy) = (0.45 * g.omega_step(), 0.45 * g.value_step());
                assert_eq!(g.cell_at(g.omega(c) + dx, g.value(r) - dy), Some((r, c)));
            }
        }
        assert_eq!(g.value(15), 150.0);
        assert_eq!(g.omega(19), 2.0);
        assert_eq!(g.cell_at(2.2, 10.0), None);
        assert_eq!(g.cell_at(1.0, -20.0), None);
        assert_eq!(g.cell_at(f64::NAN, 10.0), None);
        let one = MapGrid {
            value_points: 1,
            ..g
        };
        assert_eq!(one.cell_at(1.0, 10.0), Some((0, 9)));
    }

    #[test]
    fn the_store_counts_regimes_once_per_cell() {
        let mut s = MapStore::new(grid(), "sig".into());
        let cell = crate::views::test_support::map_cell;
        s.add(vec![
            cell(0, 0, Regime::NoImpact, Some(1)),
            cell(0, 1, Regime::DoubleSided, Some(2)),
            cell(0, 1, Regime::DoubleSided, Some(2)),
            cell(99, 0, Regime::NoImpact, Some(1)),
        ]);
        assert_eq!(s.done, 2);
        let (by, not_p1, failed) = s.counts();
        assert_eq!(by, [0, 1, 0, 1, 0]);
        assert_eq!((not_p1, failed), (1, 0));
        assert_eq!(s.cell(0, 1).map(|c| c.period), Some(Some(2)));
    }

    #[test]
    fn exports_match_the_cli_formats() {
        let mut s = MapStore::new(grid(), "sig".into());
        s.add(vec![
            MapSample {
                row: 1,
                column: 2,
                omega: 0.3,
                value: 10.0,
                regime: Regime::SingleSided,
                period: Some(2),
                error: None,
            },
            MapSample {
                row: 0,
                column: 0,
                omega: 0.1,
                value: 0.0,
                regime: Regime::NoImpact,
                period: None,
                error: Some("step size, too small".into()),
            },
        ]);
        assert_eq!(s.first_failure().map(|c| (c.row, c.column)), Some((0, 0)));
        assert_eq!(s.counts().2, 1);
        let csv = map_csv(&s);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "row,column,omega,backlash_um,impact,period,error");
        assert_eq!(lines.len(), 3);
        assert!(lines.contains(&"1,2,0.3,10,single-sided,2,"));
        assert!(lines.contains(&"0,0,0.1,0,,,step size; too small"));
        let j = map_json(&s);
        assert_eq!(j["grid"]["key"], "backlash_um");
        assert_eq!(j["cells"].as_array().map(Vec::len), Some(2));
    }
}
