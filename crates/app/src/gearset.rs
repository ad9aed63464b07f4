//! The animated gear set (the page part `anim`, not a view): the Ravigneaux set (or the gear pair)
//! drawn to scale from its tooth counts and module, turning in slow motion,
//! with every mesh coloured by its contact state at that instant of the
//! simulated steady response.
//!
//! Kinematics. The bodies turn with the model's rigid-body mode (ring held,
//! `docs/model.md`): relative to the carrier every mesh passes one tooth per
//! mesh period, so in mesh periods `tau` the carrier turns `2 pi / z_r * tau` and
//! each body its rigid-mode multiple of that. The vibration is not in the
//! bodies' angles (the mesh histories fix the rotations only up to the
//! rigid-body mode) but in the mesh gauges: at each pitch point a bar along
//! the common tangent shows `x = delta - e`, exaggerated by a stated factor,
//! with ticks at `+-b`, and the marker's colour gives the contact state:
//! drive-flank contact (`x > b`), teeth apart (`-b <= x <= b`), back-flank
//! impact (`x < -b`).
//!
//! Everything here is plain geometry with `glam` transforms, tested
//! natively; `web.rs` only strokes the polygons on a canvas.

use glam::{DAffine2, DVec2};
use solver::params::{MeshKind, ModelParams};
use std::f64::consts::PI;

/// The contact state of a mesh at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Contact {
    /// The drive flanks press together: `x > b`.
    Drive,
    /// The teeth are apart, in free flight through the backlash: `-b <= x <= b`.
    Apart,
    /// The back flanks are hit: `x < -b`.
    Back,
}

impl Contact {
    /// The state of relative displacement `x_um` against backlash half-width `b_um`.
    pub fn of(x_um: f64, b_um: f64) -> Self {
        if x_um > b_um {
            Contact::Drive
        } else if x_um < -b_um {
            Contact::Back
        } else {
            Contact::Apart
        }
    }

    /// Marker colour (the regime colours: contact blue, apart orange, back-flank red).
    pub fn rgb(self) -> (u8, u8, u8) {
        match self {
            Contact::Drive => (31, 119, 180),
            Contact::Apart => (230, 120, 0),
            Contact::Back => (200, 30, 40),
        }
    }

    /// Words for the key.
    pub fn label(self) -> &'static str {
        match self {
            Contact::Drive => "drive-flank contact (x > b)",
            Contact::Apart => "teeth apart (−b ≤ x ≤ b)",
            Contact::Back => "back-flank impact (x < −b)",
        }
    }
}

/// What a body is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodyKind {
    /// A sun or the pinion/gear of the pair: external teeth about the centre.
    Sun,
    /// The ring: internal teeth.
    Ring,
    /// A planet on the carrier.
    Planet,
}

/// One toothed body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Label (`s1`, `a2`, `r`, ...).
    pub name: String,
    /// Kind.
    pub kind: BodyKind,
    /// Teeth.
    pub teeth: u32,
    /// Pitch radius (m).
    pub pitch_radius_m: f64,
    /// Centre in the carrier's frame (m); the origin for suns and ring.
    pub centre_m: DVec2,
    /// Spin per mesh period (rad): absolute for suns and ring, relative to
    /// the carrier for planets.
    pub spin_rad: f64,
    /// Angle at tau = 0 that makes the teeth interlock (rad).
    pub phase_rad: f64,
}

/// One mesh's gauge site.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSite {
    /// Index into the model's meshes.
    pub mesh: usize,
    /// Its name.
    pub name: String,
    /// Pitch point in the carrier's frame (m).
    pub point_m: DVec2,
    /// Unit vector along the common tangent (the gauge's direction).
    pub tangent: DVec2,
}

/// The gear set's drawing model.
#[derive(Debug, Clone, PartialEq)]
pub struct GearSet {
    /// Bodies, drawn in this order.
    pub bodies: Vec<Body>,
    /// Mesh sites, in the model's mesh order.
    pub sites: Vec<MeshSite>,
    /// Carrier turn per mesh period (rad); 0 for the gear pair.
    pub carrier_rad: f64,
    /// Carrier arm radius drawn (m); 0 for no carrier.
    pub carrier_radius_m: f64,
    /// Module (m).
    pub module_m: f64,
    /// Radius that contains everything (m).
    pub extent_m: f64,
}

/// The interlocking phase of a body that meshes with a body of known
/// phase at a pitch point: a tooth of one faces a gap of the other.
fn mating_phase(
    known: &Body,
    known_phase: f64,
    known_centre: DVec2,
    other: &Body,
    other_centre: DVec2,
    point: DVec2,
) -> f64 {
    let dir_known = (point - known_centre).to_angle();
    // How many tooth pitches of the known body the pitch point is from a tooth centre.
    let p_known = 2.0 * PI / f64::from(known.teeth);
    let frac = ((dir_known - known_phase) / p_known).rem_euclid(1.0);
    let dir_other = (point - other_centre).to_angle();
    let p_other = 2.0 * PI / f64::from(other.teeth);
    // As the bodies roll, an external mesh keeps f_known + f_other and an
    // internal one (the ring, turning the same way) f_known - f_other
    // constant; a tooth (f = 0) faces a gap (f = 1/2).
    let sign = if other.kind == BodyKind::Ring || known.kind == BodyKind::Ring {
        1.0
    } else {
        -1.0
    };
    dir_other - (sign * frac + 0.5) * p_other
}

impl GearSet {
    /// The drawing model of a parameter set (`None` if its geometry cannot be built).
    pub fn new(params: &ModelParams, meshes: &[(MeshKind, usize)]) -> Option<Self> {
        match params {
            ModelParams::Ravigneaux(p) => Self::ravigneaux(p, meshes),
            ModelParams::GearPair(p) => {
                let m = p.module_mm * 1e-3;
                let (zp, zg) = (p.teeth_pinion, p.teeth_gear);
                let (rp, rg) = (m * f64::from(zp) / 2.0, m * f64::from(zg) / 2.0);
                let cp = DVec2::new(-0.5 * (rp + rg), 0.0);
                let cg = DVec2::new(0.5 * (rp + rg), 0.0);
                let pinion = Body {
                    name: "pinion".into(),
                    kind: BodyKind::Sun,
                    teeth: zp,
                    pitch_radius_m: rp,
                    centre_m: cp,
                    spin_rad: 2.0 * PI / f64::from(zp),
                    phase_rad: 0.0,
                };
                let point = cp + DVec2::new(rp, 0.0);
                let mut gear = Body {
                    name: "gear".into(),
                    kind: BodyKind::Sun,
                    teeth: zg,
                    pitch_radius_m: rg,
                    centre_m: cg,
                    spin_rad: -2.0 * PI / f64::from(zg),
                    phase_rad: 0.0,
                };
                gear.phase_rad = mating_phase(&pinion, 0.0, cp, &gear, cg, point);
                let sites = meshes
                    .iter()
                    .enumerate()
                    .map(|(j, _)| MeshSite {
                        mesh: j,
                        name: "pg".into(),
                        point_m: point,
                        tangent: DVec2::Y,
                    })
                    .collect();
                Some(GearSet {
                    extent_m: cg.x + rg + 1.5 * m,
                    bodies: vec![pinion, gear],
                    sites,
                    carrier_rad: 0.0,
                    carrier_radius_m: 0.0,
                    module_m: m,
                })
            }
        }
    }

    fn ravigneaux(
        p: &solver::params::RavigneauxParams,
        meshes: &[(MeshKind, usize)],
    ) -> Option<Self> {
        let g = solver::system::RavigneauxGeometry::derive(p).ok()?;
        let m = p.module_mm * 1e-3;
        let pitch = |z: u32| m * f64::from(z) / 2.0;
        let (z1, z2, za, zb, zr) = (p.teeth_s1, p.teeth_s2, p.teeth_a, g.teeth_b, p.teeth_r);
        let zrf = f64::from(zr);
        // Rigid-body mode per carrier turn (ring held), as `solver::system`.
        let step = 2.0 * PI / zrf;
        let u_s1 = 1.0 - zrf / f64::from(z1);
        let u_s2 = 1.0 + zrf / f64::from(z2);
        let u_a = zrf / f64::from(za);
        let u_b = -zrf / f64::from(zb);
        let n = p.planets as usize;
        let mut bodies = vec![
            Body {
                name: "r".into(),
                kind: BodyKind::Ring,
                teeth: zr,
                pitch_radius_m: pitch(zr),
                centre_m: DVec2::ZERO,
                spin_rad: 0.0,
                phase_rad: 0.0,
            },
            Body {
                name: "s2".into(),
                kind: BodyKind::Sun,
                teeth: z2,
                pitch_radius_m: pitch(z2),
                centre_m: DVec2::ZERO,
                spin_rad: u_s2 * step,
                phase_rad: 0.0,
            },
            Body {
                name: "s1".into(),
                kind: BodyKind::Sun,
                teeth: z1,
                pitch_radius_m: pitch(z1),
                centre_m: DVec2::ZERO,
                spin_rad: u_s1 * step,
                phase_rad: 0.0,
            },
        ];
        // Planet pair i: the short planet at psi_i, its long planet
        // pair_angle further round (planet centres in the carrier frame).
        let mut sites_by_name: Vec<(String, DVec2, DVec2)> = Vec::new();
        for i in 0..n {
            let psi = 2.0 * PI * i as f64 / n as f64 + PI / 2.0;
            let ca = DVec2::from_angle(psi) * g.r_ca_m;
            let cb = DVec2::from_angle(psi + g.pair_angle_rad) * g.r_cb_m;
            let planet = |name: &str, teeth, centre_m, spin_rad| Body {
                name: format!("{name}{}", i + 1),
                kind: BodyKind::Planet,
                teeth,
                pitch_radius_m: pitch(teeth),
                centre_m,
                spin_rad,
                phase_rad: 0.0,
            };
            let mut a = planet("a", za, ca, u_a * step);
            let mut b = planet("b", zb, cb, u_b * step);
            // Teeth interlock: s1 -> a -> b (the suns and ring are drawn with
            // their own phases; with the default counts they interlock too).
            let p_s1a = ca.normalize() * pitch(z1);
            a.phase_rad = mating_phase(&bodies[2], 0.0, DVec2::ZERO, &a, ca, p_s1a);
            let p_ab = ca + (cb - ca).normalize() * pitch(za);
            b.phase_rad = mating_phase(&a, a.phase_rad, ca, &b, cb, p_ab);
            let p_s2b = cb.normalize() * pitch(z2);
            let p_rb = cb.normalize() * pitch(zr);
            if i == 0 {
                let s2 = bodies[1].clone();
                bodies[1].phase_rad = mating_phase(&b, b.phase_rad, cb, &s2, DVec2::ZERO, p_s2b);
                let r = bodies[0].clone();
                bodies[0].phase_rad = mating_phase(&b, b.phase_rad, cb, &r, DVec2::ZERO, p_rb);
            }
            let tangent_at = |pt: DVec2, c: DVec2| (pt - c).normalize().perp();
            sites_by_name.push((
                format!("s1a{}", i + 1),
                p_s1a,
                tangent_at(p_s1a, DVec2::ZERO),
            ));
            sites_by_name.push((
                format!("s2b{}", i + 1),
                p_s2b,
                tangent_at(p_s2b, DVec2::ZERO),
            ));
            sites_by_name.push((format!("a{0}b{0}", i + 1), p_ab, tangent_at(p_ab, ca)));
            sites_by_name.push((format!("rb{}", i + 1), p_rb, tangent_at(p_rb, DVec2::ZERO)));
            bodies.push(a);
            bodies.push(b);
        }
        let sites = meshes
            .iter()
            .enumerate()
            .filter_map(|(j, (kind, planet))| {
                let name = match kind {
                    MeshKind::S1A => format!("s1a{}", planet + 1),
                    MeshKind::S2B => format!("s2b{}", planet + 1),
                    MeshKind::AB => format!("a{0}b{0}", planet + 1),
                    MeshKind::RB => format!("rb{}", planet + 1),
                    MeshKind::Pair => return None,
                };
                let (_, point, tangent) = sites_by_name.iter().find(|s| s.0 == name)?.clone();
                Some(MeshSite {
                    mesh: j,
                    name,
                    point_m: point,
                    tangent,
                })
            })
            .collect();
        Some(GearSet {
            bodies,
            sites,
            carrier_rad: step,
            carrier_radius_m: 0.5 * (g.r_ca_m + g.r_cb_m),
            module_m: m,
            extent_m: pitch(zr) + 2.5 * m,
        })
    }

    /// The carrier's angle at `tau` mesh periods.
    pub fn carrier_angle(&self, tau: f64) -> f64 {
        self.carrier_rad * tau
    }

    /// A body's placement (local tooth coordinates to world metres) at `tau`.
    pub fn body_transform(&self, body: &Body, tau: f64) -> DAffine2 {
        let c = self.carrier_angle(tau);
        match body.kind {
            BodyKind::Planet => {
                let centre = DVec2::from_angle(c).rotate(body.centre_m);
                DAffine2::from_angle_translation(body.phase_rad + c + body.spin_rad * tau, centre)
            }
            _ => DAffine2::from_angle_translation(
                body.phase_rad + body.spin_rad * tau,
                body.centre_m,
            ),
        }
    }

    /// A mesh site's pitch point and tangent in world metres at `tau`.
    pub fn site_at(&self, site: &MeshSite, tau: f64) -> (DVec2, DVec2) {
        let rot = DVec2::from_angle(self.carrier_angle(tau));
        (rot.rotate(site.point_m), rot.rotate(site.tangent))
    }
}

/// The outline of a body's teeth in its own frame (m): trapezoidal teeth,
/// addendum one module, dedendum 1.25 modules; inward for the ring.
pub fn tooth_outline(body: &Body, module_m: f64) -> Vec<DVec2> {
    let z = body.teeth.max(3);
    let pitch = 2.0 * PI / f64::from(z);
    let r = body.pitch_radius_m;
    let (tip, root) = match body.kind {
        BodyKind::Ring => (r - module_m, r + 1.25 * module_m),
        _ => (r + module_m, r - 1.25 * module_m),
    };
    let mut out = Vec::with_capacity(4 * z as usize);
    for k in 0..z {
        let c = f64::from(k) * pitch;
        for (radius, da) in [(root, -0.32), (tip, -0.16), (tip, 0.16), (root, 0.32)] {
            out.push(DVec2::from_angle(c + da * pitch) * radius);
        }
    }
    out
}

/// The world-to-canvas transform: the set centred, `extent_m` fitting
/// `size_px` with a margin, y up.
pub fn view_transform(extent_m: f64, size_px: (f64, f64)) -> DAffine2 {
    let s = 0.5 * size_px.0.min(size_px.1) / (extent_m.max(1e-6) * 1.06);
    DAffine2::from_translation(DVec2::new(0.5 * size_px.0, 0.5 * size_px.1))
        * DAffine2::from_scale(DVec2::new(s, -s))
}

/// The exaggeration of the mesh gauges: a round factor that draws the
/// largest backlash (or the largest |x|) as about 1.5 modules.
pub fn gauge_factor(module_m: f64, backlash_um: &[f64], x_max_um: f64) -> f64 {
    let b = backlash_um.iter().fold(0.0_f64, |m, b| m.max(*b));
    let span_um = if b > 1.0 { b } else { x_max_um.max(1.0) };
    let raw = 1.5 * module_m / (span_um * 1e-6);
    let decade = 10f64.powf(raw.log10().floor());
    let nice = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|k| k * decade)
        .filter(|f| *f <= raw)
        .fold(decade, f64::max);
    nice
}

/// Every mesh's x (um) at the animation's sample `k` of a window (`x_um[mesh][sample]`).
pub fn sample_at(x_um: &[Vec<f64>], k: usize) -> Vec<f64> {
    x_um.iter()
        .map(|h| h.get(k).copied().unwrap_or(f64::NAN))
        .collect()
}

/// The slow-motion clock of the animation, in mesh periods within a
/// window of `len` samples at `spp` samples per period (it loops).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnimClock {
    /// Position in samples from the window's start (fractional).
    pub pos: f64,
    /// Playing (else paused).
    pub playing: bool,
    /// Mesh periods per second of wall time.
    pub periods_per_s: f64,
}

impl Default for AnimClock {
    fn default() -> Self {
        AnimClock {
            pos: 0.0,
            playing: true,
            periods_per_s: 0.5,
        }
    }
}

impl AnimClock {
    /// Advances by `dt_s` of wall time (if playing), wrapping in a window of `len` samples.
    pub fn advance(&mut self, dt_s: f64, spp: u32, len: usize) {
        if self.playing && len > 0 {
            let d = dt_s.clamp(0.0, 0.25) * self.periods_per_s * f64::from(spp);
            self.pos = (self.pos + d).rem_euclid(len as f64);
        }
    }

    /// Moves by `samples` (either way), wrapping, and pauses.
    pub fn step(&mut self, samples: i64, len: usize) {
        self.playing = false;
        if len > 0 {
            self.pos = (self.pos.floor() + samples as f64).rem_euclid(len as f64);
        }
    }

    /// Moves to the time `t_periods` (mesh periods since the recording
    /// began, the time history's axis) of a window of `len` samples that
    /// starts at sample `start` of the record, `spp` samples per period;
    /// pauses.
    pub fn seek(&mut self, t_periods: f64, (start, spp): (u32, u32), len: usize) {
        let pos = (t_periods * f64::from(spp.max(1))).round() - f64::from(start);
        self.playing = false;
        self.pos = pos.clamp(0.0, len.saturating_sub(1) as f64);
    }

    /// The time (mesh periods since the recording began) of the sample
    /// shown, in a window that starts at sample `start`, `spp` per period.
    pub fn time_periods(&self, (start, spp): (u32, u32)) -> f64 {
        (f64::from(start) + self.pos.floor()) / f64::from(spp.max(1))
    }

    /// The sample shown.
    pub fn sample(&self, len: usize) -> usize {
        if len == 0 {
            0
        } else {
            (self.pos.floor() as usize).min(len - 1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::model::Model;

    fn set(query: &str) -> (GearSet, Model) {
        let s = figures::link::decode(query).settings;
        let model = Model::new(&s.params).unwrap();
        let meshes: Vec<(MeshKind, usize)> = model
            .system
            .meshes
            .iter()
            .map(|m| (m.kind, m.planet))
            .collect();
        (GearSet::new(&s.params, &meshes).unwrap(), model)
    }

    #[test]
    fn contact_states_follow_the_dead_zone() {
        assert_eq!(Contact::of(101.0, 100.0), Contact::Drive);
        assert_eq!(Contact::of(100.0, 100.0), Contact::Apart);
        assert_eq!(Contact::of(-100.0, 100.0), Contact::Apart);
        assert_eq!(Contact::of(-100.5, 100.0), Contact::Back);
        assert_eq!(Contact::of(0.0, 0.0), Contact::Apart);
    }

    #[test]
    fn the_set_is_to_scale_and_every_mesh_has_a_site_on_both_pitch_circles() {
        let (g, model) = set("");
        // Module 4 mm, teeth 36/48/21/84: s1 72 mm, ring 168 mm pitch radius.
        let r = |n: &str| {
            g.bodies
                .iter()
                .find(|b| b.name == n)
                .unwrap()
                .pitch_radius_m
        };
        assert!((r("s1") - 0.072).abs() < 1e-12 && (r("r") - 0.168).abs() < 1e-12);
        assert!((r("b1") - 0.036).abs() < 1e-12, "z_b = (84 - 48) / 2 = 18");
        assert_eq!(g.sites.len(), model.system.meshes.len());
        for s in &g.sites {
            let (a, b) = match &s.name[..2] {
                "s1" => ("s1", format!("a{}", &s.name[3..])),
                "s2" => ("s2", format!("b{}", &s.name[3..])),
                "rb" => ("r", format!("b{}", &s.name[2..])),
                _ => ("", format!("b{}", &s.name[3..])),
            };
            let body = |n: &str| g.bodies.iter().find(|x| x.name == n).unwrap();
            let other = body(&b);
            // The pitch point lies on the planet's pitch circle ...
            assert!(
                ((s.point_m - other.centre_m).length() - other.pitch_radius_m).abs() < 1e-9,
                "{}",
                s.name
            );
            // ... and on the central member's.
            if !a.is_empty() {
                assert!(
                    (s.point_m.length() - body(a).pitch_radius_m).abs() < 1e-9,
                    "{}",
                    s.name
                );
            }
            assert!((s.tangent.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn every_mesh_passes_one_tooth_per_mesh_period() {
        let (g, _) = set("");
        for b in &g.bodies {
            // Relative to the carrier (planets are already relative).
            let rel = match b.kind {
                BodyKind::Planet => b.spin_rad,
                _ => b.spin_rad - g.carrier_rad,
            };
            let teeth = rel.abs() / (2.0 * PI) * f64::from(b.teeth);
            assert!((teeth - 1.0).abs() < 1e-12, "{}: {teeth}", b.name);
        }
        // The ring is held; the transforms place planets on the turning carrier.
        let a1 = g.bodies.iter().find(|b| b.name == "a1").unwrap();
        let t = g.body_transform(a1, 7.0);
        let want = DVec2::from_angle(g.carrier_angle(7.0)).rotate(a1.centre_m);
        assert!((t.translation - want).length() < 1e-12);
    }

    #[test]
    fn teeth_interlock_where_s1_meets_a_and_a_meets_b() {
        let (g, _) = set("");
        let body = |n: &str| g.bodies.iter().find(|x| x.name == n).unwrap().clone();
        // At the pitch point, a tooth centre of one body faces a gap centre
        // of the other: fractional tooth positions differ by one half.
        for tau in [0.0, 0.37, 5.5] {
            for (one, two, site) in [
                ("s1", "a1", "s1a1"),
                ("a1", "b1", "a1b1"),
                ("b1", "r", "rb1"),
            ] {
                let (b1, b2) = (body(one), body(two));
                let s = g.sites.iter().find(|s| s.name == site).unwrap();
                let (pt, _) = g.site_at(s, tau);
                let frac = |b: &Body| {
                    let t = g.body_transform(b, tau);
                    let local = t.inverse().transform_point2(pt);
                    (local.to_angle() / (2.0 * PI / f64::from(b.teeth))).rem_euclid(1.0)
                };
                let d = (frac(&b1) - frac(&b2)).rem_euclid(1.0);
                let d = d.min(1.0 - d);
                // Tooth against gap: the two positions are half a pitch apart, or
                // mirror images summing to a half (external meshes turn oppositely).
                let s = (frac(&b1) + frac(&b2)).rem_euclid(1.0);
                let ok = (d - 0.5).abs() < 1e-6 || (s - 0.5).abs() < 1e-6;
                assert!(ok, "{site} at tau {tau}: {} {}", frac(&b1), frac(&b2));
            }
        }
    }

    #[test]
    fn gauge_factor_is_round_and_the_clock_loops() {
        let f = gauge_factor(0.004, &[100.0, 100.0], 0.0);
        assert_eq!(f, 50.0);
        let mut c = AnimClock::default();
        // A quarter second at half a period per second is 8 of 64 samples;
        // longer frame gaps (a hidden tab) are clamped to a quarter second.
        c.advance(0.25, 64, 128);
        assert_eq!(c.sample(128), 8);
        c.advance(5.0, 64, 128);
        assert_eq!(c.sample(128), 16);
        c.advance(0.2, 64, 128);
        c.advance(0.2, 64, 128);
        c.advance(0.2, 64, 128);
        c.advance(0.2, 64, 128);
        assert!(c.pos < 128.0);
        c.step(-200, 128);
        assert!(!c.playing && c.pos >= 0.0);
        let outline = tooth_outline(&g_body(), 0.004);
        assert_eq!(outline.len(), 4 * 36);
        let v = view_transform(0.17, (600.0, 400.0));
        let p = v.transform_point2(DVec2::new(0.0, 0.17));
        assert!(p.y > 0.0 && p.y < 200.0);
    }

    fn g_body() -> Body {
        Body {
            name: "s1".into(),
            kind: BodyKind::Sun,
            teeth: 36,
            pitch_radius_m: 0.072,
            centre_m: DVec2::ZERO,
            spin_rad: 0.0,
            phase_rad: 0.0,
        }
    }

    /// A click on the time history at t moves the clock to the sample of t
    /// (rounded), clamped to the window, and pauses; the cursor then stands
    /// at that sample's time.
    #[test]
    fn seeking_maps_time_history_clicks_to_samples_and_back() {
        let mut c = AnimClock::default();
        // Record of 20 periods at 32 samples per period; the window starts
        // at sample 256 (period 8) and holds 384 samples.
        let (start, spp, len) = (256, 32, 384);
        c.seek(10.5, (start, spp), len);
        assert!(!c.playing);
        assert_eq!(c.pos, 10.5 * 32.0 - 256.0);
        assert_eq!(c.time_periods((start, spp)), 10.5);
        c.seek(3.0, (start, spp), len);
        assert_eq!(c.pos, 0.0, "before the window: its first sample");
        c.seek(99.0, (start, spp), len);
        assert_eq!(c.pos, 383.0, "after it: its last");
        assert_eq!(c.time_periods((start, spp)), (256.0 + 383.0) / 32.0);
    }
}
