//! One z3 solver with a deterministic budget, and what its answers mean.

use std::time::Instant;
use z3::ast::{Bool, Int};
use z3::{Model, Params, SatResult, Solver};

/// The budget of one check, in z3's resource units (`rlimit`): deterministic, unlike a
/// timeout, so a check that ran out once runs out on every machine.
pub const DEFAULT_RLIMIT: u32 = 20_000_000;

/// A solver's answer.
#[derive(Debug)]
pub enum Outcome {
    /// Satisfiable, with a model.
    Sat(Model),
    /// Unsatisfiable, with the assumptions in the unsat core.
    Unsat(Vec<Bool>),
    /// Not decided within the budget, with z3's reason.
    Unknown(String),
}

/// A solver with the budget set on every check.
pub struct Session {
    /// The z3 solver.
    pub solver: Solver,
    /// Past this moment every check is `Unknown` without asking z3 (`verify --timeout`);
    /// a check begun before it still ends within its `rlimit`.
    deadline: Option<Instant>,
}

/// Why a check past its deadline was not made.
pub const OUT_OF_TIME: &str = "the time limit (--timeout) ran out before this check";

impl Session {
    /// A solver in the current context whose every check may spend `rlimit` resource units,
    /// and none is begun after `deadline`.
    pub fn new(rlimit: u32, deadline: Option<Instant>) -> Session {
        let solver = Solver::new();
        let mut p = Params::new();
        p.set_u32("rlimit", rlimit);
        solver.set_params(&p);
        Session { solver, deadline }
    }

    /// Checks the assertions under `assumptions`.
    pub fn check(&self, assumptions: &[Bool]) -> Outcome {
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            return Outcome::Unknown(OUT_OF_TIME.into());
        }
        match self.solver.check_assumptions(assumptions) {
            SatResult::Sat => match self.solver.get_model() {
                Some(m) => Outcome::Sat(m),
                None => Outcome::Unknown("z3 gave no model".into()),
            },
            SatResult::Unsat => Outcome::Unsat(self.solver.get_unsat_core()),
            SatResult::Unknown => Outcome::Unknown(
                self.solver
                    .get_reason_unknown()
                    .filter(|r| !r.is_empty())
                    .unwrap_or_else(|| "unknown".into()),
            ),
        }
    }

    /// Checks `extra` on top of the assertions, under `assumptions`, and forgets it.
    pub fn check_with(&self, extra: &Bool, assumptions: &[Bool]) -> Outcome {
        self.solver.push();
        self.solver.assert(extra);
        let out = self.check(assumptions);
        self.solver.pop(1);
        out
    }

    /// A small subset of `candidates` that, with `fixed`, is still unsatisfiable (deletion
    /// over the unsat core, in order, so the result is the same on every run). `None` when
    /// `fixed ∪ candidates` is not unsatisfiable within the budget.
    pub fn minimize(&self, fixed: &[Bool], candidates: &[Bool]) -> Option<Vec<usize>> {
        let all: Vec<Bool> = fixed.iter().chain(candidates).cloned().collect();
        let core = match self.check(&all) {
            Outcome::Unsat(core) => core,
            _ => return None,
        };
        let mut keep: Vec<usize> = (0..candidates.len())
            .filter(|&i| core.iter().any(|c| c.ast_eq(&candidates[i])))
            .collect();
        let mut i = 0;
        while i < keep.len() {
            let trial: Vec<usize> = keep.iter().copied().filter(|&j| j != keep[i]).collect();
            let mut lits: Vec<Bool> = fixed.to_vec();
            lits.extend(trial.iter().map(|&j| candidates[j].clone()));
            match self.check(&lits) {
                Outcome::Unsat(_) => keep = trial,
                _ => i += 1,
            }
        }
        Some(keep)
    }
}

/// The value of `b` in `m` (unconstrained Booleans are false).
pub fn truth(m: &Model, b: &Bool) -> bool {
    m.eval(b, true).and_then(|v| v.as_bool()).unwrap_or(false)
}

/// The value of `i` in `m`.
pub fn int(m: &Model, i: &Int) -> Option<i64> {
    m.eval(i, true).and_then(|v| v.as_i64())
}
