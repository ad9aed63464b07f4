//! The input member's speed ([`SpeedInfo`]) and the one relation between
//! the dimensionless mesh frequency Omega and the input member's speed in
//! rpm ([`RpmScale`], from [`crate::system::MeshSystem::rpm_scale`]): the
//! Campbell diagram, the page's speed axes and the dynamic factor's view
//! all convert through it.

use std::f64::consts::PI;

/// How mesh frequency relates to shaft speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedInfo {
    /// Teeth of the input member (s1 or the pinion).
    pub input_teeth: u32,
    /// Input member speed relative to the carrier per unit input speed (1 for the pair).
    pub relative_per_input: f64,
}

impl SpeedInfo {
    /// Mesh frequency (Hz) per input shaft rpm: `z_in |n_in - n_c| / n_in / 60`.
    pub fn mesh_hz_per_rpm(&self) -> f64 {
        f64::from(self.input_teeth) * self.relative_per_input.abs() / 60.0
    }

    /// The carrier's speed per unit input speed, `n_c / n_in` (0 for the
    /// gear pair, whose "carrier" is the frame).
    pub fn carrier_per_input(&self) -> f64 {
        1.0 - self.relative_per_input
    }

    /// Input shaft speed (rpm) that gives mesh frequency `mesh_freq_hz`.
    pub fn input_speed_rpm(&self, mesh_freq_hz: f64) -> f64 {
        mesh_freq_hz / self.mesh_hz_per_rpm()
    }
}

/// The conversion between the dimensionless Omega and the input member's
/// speed (rpm) of one system: Omega 1 is the mesh frequency
/// `omega_ref / 2 pi`, and the input speed is a mesh frequency over
/// [`SpeedInfo::mesh_hz_per_rpm`]. The one place the two are related.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RpmScale {
    /// omega_ref (rad/s).
    pub omega_ref_rad_s: f64,
    /// The input member's teeth and speed relative to the carrier.
    pub speed: SpeedInfo,
}

impl RpmScale {
    /// The mesh frequency (Hz) at `omega`.
    pub fn mesh_hz(&self, omega: f64) -> f64 {
        omega * self.omega_ref_rad_s / (2.0 * PI)
    }

    /// The input member's speed (rpm) at `omega`.
    pub fn rpm(&self, omega: f64) -> f64 {
        self.speed.input_speed_rpm(self.mesh_hz(omega))
    }

    /// Omega at the input member's speed `rpm` (the inverse of [`Self::rpm`]).
    pub fn omega(&self, rpm: f64) -> f64 {
        rpm * self.speed.mesh_hz_per_rpm() * 2.0 * PI / self.omega_ref_rad_s
    }
}
