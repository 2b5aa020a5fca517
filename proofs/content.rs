//! Algorithm 2 (`content`, with the paper's `Syntactic` test): on every bounded body and
//! intention stack, `Γ` holds every frame's instantiated context literals (each once, bottom
//! frame first), and the content is the top frame's steps from the explained action up to the
//! first one whose `Eff±` meets `Γ`, or to the body's end.
//!
//! Stacks of 1 to [`MAX_FRAMES`] frames; each frame has up to [`MAX_LITERALS`] context
//! literals over `used(C)`, `at(C)`, `at(b)`, `door(open)` (positive or under `not`) and
//! binds its `C` to `a`, `b` or nothing; the top body has up to [`MAX_STEPS`] steps among
//! `go(C)`, `go(b)`, `open`, `wait` and the subgoal `!sub`. `go(L)` adds `at(L)`, `open` adds
//! `door(open)` and deletes `door(closed)`, `wait` and subgoals change nothing.

use crate::explain::{
    content, Content, ContextLiteral, Effects, FrameSnapshot, PlanStep, Syntactic,
};
use crate::model::{Substitution, Term, Var};

/// Most frames on the stack.
pub const MAX_FRAMES: usize = 3;
/// Most context literals of one frame.
pub const MAX_LITERALS: usize = 2;
/// Most steps of the top body.
pub const MAX_STEPS: usize = 4;
/// Literal codes: 0 none, then (atom, polarity) pairs.
pub const LITERALS: u8 = 9;
/// Binding codes: unbound, `C = a`, `C = b`.
pub const BINDINGS: u8 = 3;
/// Step codes: 0 none, `go(C)`, `go(b)`, `open`, `wait`, `!sub`.
pub const STEPS: u8 = 6;

/// An argument after instantiation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Arg {
    None,
    Const(&'static str),
    Var,
}

/// An atom after instantiation: predicate and argument.
type Atom = (&'static str, Arg);

fn bound(binding: u8) -> Arg {
    match binding {
        1 => Arg::Const("a"),
        2 => Arg::Const("b"),
        _ => Arg::Var,
    }
}

/// A literal code's atom (with `C` instantiated by `binding`) and polarity.
fn literal(code: u8, binding: u8) -> (Atom, bool) {
    let k = code - 1;
    let atom = match k / 2 {
        0 => ("used", bound(binding)),
        1 => ("at", bound(binding)),
        2 => ("at", Arg::Const("b")),
        _ => ("door", Arg::Const("open")),
    };
    (atom, k & 1 == 0)
}

fn term(atom: &Atom) -> Term {
    match atom.1 {
        Arg::None => Term::atom(atom.0),
        Arg::Const(c) => Term::structure(atom.0, vec![Term::atom(c)]),
        Arg::Var => Term::structure(atom.0, vec![Term::var("C")]),
    }
}

/// A step code's instantiation: whether it is an action, its term, its `Eff±` atoms.
fn step(code: u8, binding: u8) -> (bool, Atom, Vec<Atom>) {
    match code {
        1 => (true, ("go", bound(binding)), vec![("at", bound(binding))]),
        2 => (true, ("go", Arg::Const("b")), vec![("at", Arg::Const("b"))]),
        3 => (
            true,
            ("open", Arg::None),
            vec![("door", Arg::Const("open")), ("door", Arg::Const("closed"))],
        ),
        4 => (true, ("wait", Arg::None), vec![]),
        _ => (false, ("sub", Arg::None), vec![]),
    }
}

/// The effects Algorithm 2 is given: `Eff±` of the (instantiated) action terms.
pub fn effects(action: &Term) -> Effects {
    let at = |arg: &Term| Term::structure("at", vec![arg.clone()]);
    match (action.functor(), action.args()) {
        (Some("go"), [l]) => Effects::new(vec![at(l)], vec![]),
        (Some("open"), []) => Effects::new(
            vec![Term::structure("door", vec![Term::atom("open")])],
            vec![Term::structure("door", vec![Term::atom("closed")])],
        ),
        _ => Effects::none(),
    }
}

/// Reference meeting of two atoms, variables apart: same predicate, and equal arguments
/// unless one is a variable.
fn meet(e: &Atom, c: &Atom) -> bool {
    e.0 == c.0
        && match (e.1, c.1) {
            (Arg::Var, _) | (_, Arg::Var) => true,
            (x, y) => x == y,
        }
}

/// A stack: frames bottom first, each with literal codes and a binding code; the top body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SmallStack {
    frames: u8,
    literals: [[u8; MAX_LITERALS]; MAX_FRAMES],
    bindings: [u8; MAX_FRAMES],
    body: [u8; MAX_STEPS],
}

fn canonical_list(codes: &[u8], limit: u8) -> bool {
    codes.iter().all(|&c| c < limit) && codes.windows(2).all(|w| w[0] != 0 || w[1] == 0)
}

impl SmallStack {
    /// The stack these codes spell, if canonical: 1 to 3 frames, codes in range, lists
    /// ending at their first 0, unused frames all 0.
    pub fn new(
        frames: u8,
        literals: [[u8; MAX_LITERALS]; MAX_FRAMES],
        bindings: [u8; MAX_FRAMES],
        body: [u8; MAX_STEPS],
    ) -> Option<SmallStack> {
        let n = usize::from(frames);
        let ok = (1..=MAX_FRAMES).contains(&n)
            && canonical_list(&body, STEPS)
            && (0..MAX_FRAMES).all(|f| {
                if f < n {
                    canonical_list(&literals[f], LITERALS) && bindings[f] < BINDINGS
                } else {
                    literals[f] == [0; MAX_LITERALS] && bindings[f] == 0
                }
            });
        ok.then_some(SmallStack {
            frames,
            literals,
            bindings,
            body,
        })
    }

    fn n(&self) -> usize {
        usize::from(self.frames)
    }

    fn top_binding(&self) -> u8 {
        self.bindings[self.n() - 1]
    }

    fn body(&self) -> impl Iterator<Item = u8> + '_ {
        self.body.iter().copied().take_while(|&c| c != 0)
    }

    /// The crate's stack, bottom first.
    pub fn snapshots(&self) -> Vec<FrameSnapshot> {
        (0..self.n())
            .map(|f| {
                let mut bindings = Substitution::new();
                if let Arg::Const(c) = bound(self.bindings[f]) {
                    bindings.bind(Var::named("C"), Term::atom(c));
                }
                let context = self.literals[f]
                    .iter()
                    .take_while(|&&c| c != 0)
                    .map(|&c| {
                        // As written: `C` uninstantiated; the frame's bindings apply to it.
                        let (atom, positive) = literal(c, 0);
                        ContextLiteral {
                            atom: term(&atom),
                            positive,
                        }
                    })
                    .collect();
                let body = if f + 1 == self.n() {
                    self.body()
                        .map(|c| {
                            let (action, atom, _) = step(c, 0);
                            if action {
                                PlanStep::Action(term(&atom))
                            } else {
                                PlanStep::Subgoal(term(&atom))
                            }
                        })
                        .collect()
                } else {
                    vec![PlanStep::Subgoal(Term::atom("sub"))]
                };
                FrameSnapshot {
                    context,
                    bindings,
                    body,
                }
            })
            .collect()
    }

    /// The reference `Γ`: every frame's instantiated literals, bottom first, each once.
    fn gamma(&self) -> Vec<(Atom, bool)> {
        let mut out: Vec<(Atom, bool)> = Vec::new();
        for f in 0..self.n() {
            for &c in self.literals[f].iter().take_while(|&&c| c != 0) {
                let l = literal(c, self.bindings[f]);
                if !out.contains(&l) {
                    out.push(l);
                }
            }
        }
        out
    }

    /// The reference content's steps (as the number of steps), or `None` when the body is
    /// empty or starts with a subgoal.
    fn reference_len(&self) -> Option<usize> {
        let steps: Vec<(bool, Atom, Vec<Atom>)> =
            self.body().map(|c| step(c, self.top_binding())).collect();
        if !steps.first()?.0 {
            return None;
        }
        let gamma = self.gamma();
        let k = steps
            .iter()
            .position(|(_, _, eff)| eff.iter().any(|e| gamma.iter().any(|(c, _)| meet(e, c))))
            .unwrap_or(steps.len() - 1);
        Some(k + 1)
    }

    fn reference_steps(&self) -> Vec<PlanStep> {
        self.body()
            .map(|c| {
                let (action, atom, _) = step(c, self.top_binding());
                if action {
                    PlanStep::Action(term(&atom))
                } else {
                    PlanStep::Subgoal(term(&atom))
                }
            })
            .collect()
    }
}

/// Every canonical stack of at most `frames` frames with at most `literals` literals each
/// and a body of at most `steps` steps.
pub fn all_stacks(frames: usize, literals: usize, steps: usize) -> Vec<SmallStack> {
    fn lists(len: usize, limit: u8, max: usize) -> Vec<Vec<u8>> {
        let mut out = vec![vec![0; len]];
        let mut frontier = vec![Vec::new()];
        for _ in 0..max.min(len) {
            frontier = frontier
                .iter()
                .flat_map(|l: &Vec<u8>| {
                    (1..limit).map(move |c| {
                        let mut l = l.clone();
                        l.push(c);
                        l
                    })
                })
                .collect();
            out.extend(frontier.iter().map(|l| {
                let mut l = l.clone();
                l.resize(len, 0);
                l
            }));
        }
        out
    }
    let lits = lists(MAX_LITERALS, LITERALS, literals);
    let bodies = lists(MAX_STEPS, STEPS, steps);
    let mut frame_choices: Vec<(Vec<u8>, u8)> = Vec::new();
    for l in &lits {
        for b in 0..BINDINGS {
            frame_choices.push((l.clone(), b));
        }
    }
    let mut stacks: Vec<Vec<(Vec<u8>, u8)>> = vec![Vec::new()];
    let mut out = Vec::new();
    for _ in 0..frames.min(MAX_FRAMES) {
        stacks = stacks
            .iter()
            .flat_map(|s| {
                frame_choices.iter().map(move |f| {
                    let mut s = s.clone();
                    s.push(f.clone());
                    s
                })
            })
            .collect();
        for s in &stacks {
            let mut literals = [[0; MAX_LITERALS]; MAX_FRAMES];
            let mut bindings = [0; MAX_FRAMES];
            for (i, (l, b)) in s.iter().enumerate() {
                literals[i].copy_from_slice(l);
                bindings[i] = *b;
            }
            for body in &bodies {
                let mut bd = [0; MAX_STEPS];
                bd.copy_from_slice(body);
                out.push(
                    SmallStack::new(s.len() as u8, literals, bindings, bd).expect("canonical"),
                );
            }
        }
    }
    out
}

/// What was seen, for coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seen {
    /// There was a content.
    pub explained: bool,
    /// The content stopped before the body's end.
    pub stopped_early: bool,
    /// `Γ` merged a literal of two frames.
    pub shared_literal: bool,
}

/// The property, with `kernel` Algorithm 2 on a stack (`content` with [`Syntactic`] and
/// [`effects`]): no content exactly when the body is empty or starts with a subgoal;
/// otherwise its `Γ` holds every frame's instantiated literals, each once, in the reference
/// order, and its steps are the top body's (instantiated) from the first up to the first
/// that modifies `Γ`, or all of them.
pub fn content_is_gamma_up_to_first_modifier(
    stack: &SmallStack,
    kernel: impl Fn(&[FrameSnapshot]) -> Option<Content>,
) -> Result<Seen, String> {
    let frames = stack.snapshots();
    let got = kernel(&frames);
    let want_len = stack.reference_len();
    let steps = stack.reference_steps();
    let shown = || format!("{stack:?}");
    let Some(c) = got else {
        return match want_len {
            None => Ok(Seen {
                explained: false,
                stopped_early: false,
                shared_literal: false,
            }),
            Some(_) => Err(format!(
                "{}: no content, but the first step is an action",
                shown()
            )),
        };
    };
    let Some(len) = want_len else {
        return Err(format!(
            "{}: a content {c}, but there is no action to explain",
            shown()
        ));
    };
    let gamma: Vec<ContextLiteral> = stack
        .gamma()
        .iter()
        .map(|(a, positive)| ContextLiteral {
            atom: term(a),
            positive: *positive,
        })
        .collect();
    for (f, frame) in frames.iter().enumerate() {
        for l in &frame.context {
            let inst = l.instantiate(&frame.bindings);
            if !c.context.contains(&inst) {
                return Err(format!("{}: Γ of {c} misses {inst} of frame {f}", shown()));
            }
        }
    }
    if c.context != gamma {
        let want: Vec<String> = gamma.iter().map(|l| l.to_string()).collect();
        return Err(format!(
            "{}: Γ of {c} is not [{}]",
            shown(),
            want.join(", ")
        ));
    }
    if c.actions != steps[..len] {
        let want: Vec<String> = steps[..len].iter().map(|s| s.to_string()).collect();
        return Err(format!(
            "{}: content {c}, the steps should be ({})",
            shown(),
            want.join(", ")
        ));
    }
    let total: usize = frames.iter().map(|f| f.context.len()).sum();
    Ok(Seen {
        explained: true,
        stopped_early: len < steps.len(),
        shared_literal: gamma.len() < total,
    })
}

/// Algorithm 2 as the crate runs it: [`content`] with [`Syntactic`] over [`effects`].
pub fn real_content(stack: &[FrameSnapshot]) -> Option<Content> {
    content(stack, &Syntactic::new(effects))
}

#[cfg(kani)]
mod harnesses {
    use super::*;

    /// Stacks of 1-3 frames, up to 2 context literals each, bodies of up to 4 steps.
    #[kani::proof]
    #[kani::unwind(6)]
    fn content_is_gamma_and_the_steps_up_to_the_first_modifier() {
        let stack = SmallStack::new(kani::any(), kani::any(), kani::any(), kani::any());
        kani::assume(stack.is_some());
        let stack = stack.unwrap();
        let seen = content_is_gamma_up_to_first_modifier(&stack, real_content);
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.stopped_early),
            "the content stops early"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.explained && !s.stopped_early),
            "to the body's end"
        );
        kani::cover!(
            seen.as_ref().is_ok_and(|s| s.shared_literal),
            "a literal of two frames"
        );
        assert!(seen.is_ok());
    }
}
