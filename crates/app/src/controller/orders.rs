//! The mesh force by order on the page: its view model from the selected
//! state (the worker's force by order of the plotted mesh), its text
//! alternative, its note and its exports.

use super::Controller;
use figures::views::orders::{orders_csv, orders_json, OrdersView};
use figures::views::ViewError;

impl Controller {
    /// The selected state's mesh force by order; why not, as its reason
    /// (no model, no state yet, or a state without the mesh's history).
    pub fn orders_view(&self) -> Result<OrdersView, ViewError> {
        let model = self.model().map_err(Clone::clone)?;
        let r = self.main.omega.as_ref().ok_or(ViewError::Computing)?;
        let rpm_per_omega = model.system.rpm_scale().rpm(1.0);
        OrdersView::new(r, &self.settings.params, rpm_per_omega).ok_or(ViewError::NoForceHistory)
    }

    /// The plot's text alternative.
    pub fn orders_label(&self) -> String {
        match self.orders_view() {
            Ok(v) => v.label(),
            Err(e) => format!("Mesh force by order: not computed: {e}"),
        }
    }

    /// The note over the plot: the largest lines and the planets' sum.
    pub fn orders_note(&self) -> String {
        self.orders_view().map(|v| v.note()).unwrap_or_default()
    }

    /// The lines as CSV, or the view as JSON.
    pub fn orders_export(&self, csv: bool) -> Result<String, ViewError> {
        let v = self.orders_view()?;
        Ok(if csv {
            orders_csv(&v)
        } else {
            orders_json(&v).to_string()
        })
    }
}
