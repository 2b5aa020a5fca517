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

impl Replayed {
    /// A finding whose run does not reach its violation, and why.
    pub fn missed(id: &str, detail: &str) -> Replayed {
        Replayed {
            id: id.to_string(),
            reached: false,
            detail: detail.to_string(),
        }
    }
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
