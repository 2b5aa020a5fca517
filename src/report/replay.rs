//! `bdi-check replay`: one line per replayed counterexample.

/// The outcome of replaying one finding.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Replayed {
    /// The finding's id.
    pub id: String,
    /// Whether the run still reaches the violation.
    pub reached: bool,
    /// What happened, for people.
    pub detail: String,
}

/// One line per finding: whether it still reaches its violation, and what happened.
pub fn render(results: &[Replayed]) -> String {
    results
        .iter()
        .map(|r| {
            let verdict = if r.reached {
                "still reaches"
            } else {
                "no longer reaches"
            };
            format!("{}: {verdict} its violation ({})\n", r.id, r.detail)
        })
        .collect()
}
