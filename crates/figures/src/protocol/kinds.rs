//! The one table of job kinds ([`JobKind`]: its slot in every per-kind
//! array, its name, its place in the order jobs start), sets of kinds
//! ([`KindSet`]: what a change restarts, which kinds' data changed), and
//! whose computation a job belongs to ([`Target`]).

use super::JobSpec;
use serde::{Deserialize, Serialize};

/// The kinds of job. The discriminant is the kind's slot in every per-kind
/// array (a computation's statuses, a worker's jobs); [`JobKind::ALL`]
/// lists them in the order a restart starts them (the selected Omega
/// first: its worker serves it first).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JobKind {
    /// One steady state at the selected Omega (`ViewId::Phase`,
    /// `Poincare`, `Time`, `Spectrum` and the gear set).
    Omega = 0,
    /// The harmonic-balance branch of the frequency response (`ViewId::Fr`).
    HarmonicBalance = 1,
    /// The time-integration overlay of the frequency response (`ViewId::Fr`).
    Overlay = 2,
    /// The bifurcation sweep (`ViewId::Bif`).
    Bif = 3,
    /// The impact-regime map (`ViewId::Map`).
    Map = 4,
    /// The largest Lyapunov exponent over Omega (`ViewId::Lyap`).
    Lyap = 5,
    /// The periodic orbits' branches by shooting, on the bifurcation
    /// diagram (`ViewId::Bif`).
    Orbits = 6,
    /// The regime map's boundaries traced as curves in Omega and the
    /// map's key (`solver::boundaries`), drawn over the map (`ViewId::Map`).
    Boundaries = 7,
}

impl JobKind {
    /// Every kind, by slot.
    pub const ALL: [JobKind; 8] = [
        JobKind::Omega,
        JobKind::HarmonicBalance,
        JobKind::Overlay,
        JobKind::Bif,
        JobKind::Map,
        JobKind::Lyap,
        JobKind::Orbits,
        JobKind::Boundaries,
    ];
    /// The kinds a worker serves first in each computation, in order (the
    /// selected Omega, then the harmonic-balance branch).
    pub const URGENT: [JobKind; 2] = [JobKind::Omega, JobKind::HarmonicBalance];
    /// The kinds whose shards a worker then serves in turns (so the
    /// frequency response's dots and the bifurcation diagram fill in
    /// together and show their first points early).
    pub const TAKING_TURNS: [JobKind; 2] = [JobKind::Overlay, JobKind::Bif];
    /// The kinds served when the others are idle, in order: the slower,
    /// secondary views must not delay the main diagrams, and the shooting
    /// branches and the map's boundaries, which can take a minute or more
    /// on the compound set, must not delay any view (they are drawn as
    /// they come).
    pub const WHEN_IDLE: [JobKind; 4] = [
        JobKind::Lyap,
        JobKind::Map,
        JobKind::Orbits,
        JobKind::Boundaries,
    ];
    /// How many kinds there are (the length of per-kind arrays).
    pub const COUNT: usize = Self::ALL.len();

    /// The kind's slot in per-kind arrays.
    pub const fn slot(self) -> usize {
        self as usize
    }

    /// The set of this kind alone.
    pub const fn set(self) -> KindSet {
        KindSet(1 << self as u8)
    }
}

/// A set of job kinds: what a change restarts, or whose data changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct KindSet(u16);

impl KindSet {
    /// No kind.
    pub const NONE: KindSet = KindSet(0);
    /// Every kind.
    pub const ALL: KindSet = KindSet((1 << JobKind::COUNT) - 1);
    /// The kinds the pinned state A of a comparison computes (drawn under
    /// the current state's).
    pub const PINNED: KindSet = KindSet::of(&[JobKind::HarmonicBalance, JobKind::Bif]);
    /// The selected Omega's kind: the summary and the views at that Omega.
    pub const SELECTED: KindSet = KindSet::of(&[JobKind::Omega]);
    /// The kinds the selected Omega's summary reads: its steady state and
    /// the frequency response's branch, whose stability there it compares
    /// with the state found. Either may finish last, so either rewrites it.
    pub const SUMMARY: KindSet = KindSet::of(&[JobKind::Omega, JobKind::HarmonicBalance]);
    /// The kinds the page's first screen shows (the frequency response,
    /// its dots, the selected Omega): at the page's start the others wait
    /// until these have ended, so that they get the cores.
    pub const FIRST_SCREEN: KindSet =
        KindSet::of(&[JobKind::Omega, JobKind::HarmonicBalance, JobKind::Overlay]);
    /// The long jobs, each held by one worker of the pool (the shooting
    /// branches by the first, the map's boundaries by the last): the
    /// map's rows go to the other workers while they run.
    pub const LONG: KindSet = KindSet::of(&[JobKind::Orbits, JobKind::Boundaries]);
    /// The kinds a family member computes (its curve, its panel, its orbit).
    pub const MEMBER: KindSet =
        KindSet::of(&[JobKind::Omega, JobKind::HarmonicBalance, JobKind::Bif]);

    /// The set of `kinds`.
    pub const fn of(kinds: &[JobKind]) -> KindSet {
        let mut bits = 0;
        let mut i = 0;
        while i < kinds.len() {
            bits |= 1 << kinds[i] as u8;
            i += 1;
        }
        KindSet(bits)
    }

    /// Whether `kind` is in the set.
    pub const fn contains(self, kind: JobKind) -> bool {
        self.0 & (1 << kind as u8) != 0
    }

    /// Both sets' kinds.
    #[must_use]
    pub const fn with(self, other: KindSet) -> KindSet {
        KindSet(self.0 | other.0)
    }

    /// The kinds in both sets.
    #[must_use]
    pub const fn and(self, other: KindSet) -> KindSet {
        KindSet(self.0 & other.0)
    }

    /// This set's kinds that are not in `other`.
    #[must_use]
    pub const fn without(self, other: KindSet) -> KindSet {
        KindSet(self.0 & !other.0)
    }

    /// Adds `kind`.
    pub fn insert(&mut self, kind: JobKind) {
        self.0 |= 1 << kind as u8;
    }

    /// Whether the sets share a kind.
    pub const fn intersects(self, other: KindSet) -> bool {
        self.0 & other.0 != 0
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The kinds in the set, in [`JobKind::ALL`] order.
    pub fn iter(self) -> impl Iterator<Item = JobKind> {
        JobKind::ALL.into_iter().filter(move |k| self.contains(*k))
    }
}

impl From<JobKind> for KindSet {
    fn from(k: JobKind) -> Self {
        k.set()
    }
}

/// Whose computation a job belongs to: the current state, the pinned
/// state A of an A/B comparison, or member `i` (1, 2, ...) of a parameter
/// family (member 0 is the current state itself).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// The current state (B when comparing).
    #[default]
    Main,
    /// The pinned state A.
    A,
    /// A family member, 1-based.
    Member(u32),
}

impl JobSpec {
    /// The kind of this job.
    pub fn kind(&self) -> JobKind {
        match self {
            JobSpec::Omega(_) => JobKind::Omega,
            JobSpec::HarmonicBalance { .. } => JobKind::HarmonicBalance,
            JobSpec::Overlay { .. } => JobKind::Overlay,
            JobSpec::Bif { .. } => JobKind::Bif,
            JobSpec::Map { .. } => JobKind::Map,
            JobSpec::Lyap { .. } => JobKind::Lyap,
            JobSpec::Orbits { .. } => JobKind::Orbits,
            JobSpec::Boundaries { .. } => JobKind::Boundaries,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_are_the_positions_in_all_and_sets_hold_what_was_put_in() {
        for (i, k) in JobKind::ALL.into_iter().enumerate() {
            assert_eq!(k.slot(), i);
            assert!(k.set().contains(k));
            assert_eq!(k.set().iter().collect::<Vec<_>>(), vec![k]);
        }
        assert_eq!(KindSet::ALL.iter().count(), JobKind::COUNT);
        let s = KindSet::of(&[JobKind::Map, JobKind::Omega]);
        assert_eq!(s.iter().collect::<Vec<_>>(), [JobKind::Omega, JobKind::Map]);
        assert_eq!(s.without(JobKind::Map.set()), JobKind::Omega.set());
        assert!(KindSet::NONE.is_empty() && !s.is_empty());
    }

    #[test]
    fn targets_travel_as_json() {
        for t in [Target::Main, Target::A, Target::Member(3)] {
            let text = serde_json::to_string(&t).unwrap();
            assert_eq!(serde_json::from_str::<Target>(&text).unwrap(), t);
        }
        assert_eq!(
            serde_json::to_string(&Target::Member(2)).unwrap(),
            r#"{"member":2}"#
        );
    }
}
