//! How a branch of periodic orbits loses or changes stability: the labels
//! that harmonic balance ([`crate::hbm`]) and shooting
//! ([`crate::shooting`]) put on their branches' points.

/// A bifurcation detected between two branch points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bifurcation {
    /// The branch turns back in Omega (a jump in a sweep).
    Fold,
    /// A real multiplier crosses -1.
    PeriodDoubling,
    /// A complex pair crosses the unit circle.
    NeimarkSacker,
    /// A real multiplier crosses +1 without a turn (symmetry breaking or transcritical).
    BranchPoint,
}

impl Bifurcation {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Bifurcation::Fold => "fold",
            Bifurcation::PeriodDoubling => "period-doubling",
            Bifurcation::NeimarkSacker => "neimark-sacker",
            Bifurcation::BranchPoint => "branch-point",
        }
    }
}
