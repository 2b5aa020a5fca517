//! Runs on a fixed schedule, as the Jason lab's driver runs a recorded scenario: the
//! conformance tests' way of following a recorded run of real Jason.

use crate::semantics::{Note, Step, System, SystemState};

/// One run on a fixed schedule, as the Jason lab's driver runs a recorded scenario: before
/// each cycle, the next request goes to the first agent when it is idle, has perceived the
/// environment and has no mail; then the scheduled agent runs one reasoning cycle (none
/// when it has nothing to do, or only timers while another agent has something to do:
/// the lab's clock moves only when none has). Where a cycle has several outcomes (a timer that may fire,
/// `.random`), the one whose actions continue `want` (`agent: action`, in order) is taken,
/// depth first. Returns the steps of the run that gives `want`, or of the first run when
/// none does.
pub fn run_schedule(
    system: &System,
    start: SystemState,
    requests: &[u8],
    schedule: &[usize],
    want: &[String],
) -> Vec<Step> {
    struct Search<'a, 's> {
        system: &'a System<'s>,
        requests: &'a [u8],
        schedule: &'a [usize],
        want: &'a [String],
        actions: Vec<String>,
        steps: Vec<Step>,
        first: Option<Vec<Step>>,
    }
    impl Search<'_, '_> {
        fn go(&mut self, mut s: SystemState, at: usize, mut next_request: usize) -> bool {
            let system = self.system;
            if next_request < self.requests.len()
                && s.agents[0].is_idle()
                && s.mail[0].is_empty()
                && system.has_perceived(&s, 0)
            {
                let r = self.requests[next_request] as usize;
                system.agents[0].post_request(&mut s.agents[0], r);
                self.steps.push(Step {
                    agent: 0,
                    notes: vec![Note::Request { index: r as u8 }],
                });
                next_request += 1;
            }
            if at == self.schedule.len() {
                if self.first.is_none() {
                    self.first = Some(self.steps.clone());
                }
                return self.actions == self.want;
            }
            let k = self.schedule[at];
            // The lab's clock moves only when no agent has anything else to do: an agent
            // with nothing to do but wait for its timers lets one fire only then, and its
            // cycle changes nothing otherwise (as one with nothing to do at all).
            let quiet = (0..s.agents.len()).all(|j| !system.enabled(&s, j) || system.asleep(&s, j));
            let mut outcomes = if system.enabled(&s, k) && (quiet || !system.asleep(&s, k)) {
                system.cycle_of(&s, k)
            } else {
                Vec::new()
            };
            if outcomes.is_empty() {
                let idle = Step {
                    agent: k as u8,
                    notes: Vec::new(),
                };
                outcomes.push((idle, s.clone()));
            }
            let name = &system.names()[k];
            let (acted, stepped) = (self.actions.len(), self.steps.len());
            for (step, t) in outcomes {
                for n in &step.notes {
                    if let Note::Action { text, .. } = n {
                        self.actions.push(format!("{name}: {text}"));
                    }
                }
                let n = self.actions.len();
                let fits = n <= self.want.len() && self.actions[..] == self.want[..n];
                self.steps.push(step);
                if (fits || self.first.is_none()) && self.go(t, at + 1, next_request) {
                    return true;
                }
                self.actions.truncate(acted);
                self.steps.truncate(stepped);
            }
            false
        }
    }
    let mut search = Search {
        system,
        requests,
        schedule,
        want,
        actions: Vec::new(),
        steps: Vec::new(),
        first: None,
    };
    if search.go(start, 0, 0) {
        search.steps
    } else {
        search.first.unwrap_or_default()
    }
}
