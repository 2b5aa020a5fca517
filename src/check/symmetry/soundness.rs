//! What makes the reduction sound. [`Symmetry::new`] refuses a model that names a
//! symmetric object where renaming would not preserve it, and initial states or requests
//! not closed under renaming; the equivariance check, run on every stored state, finds
//! where the reasoning cycle itself does not treat the objects alike (the report's caveat).

use super::Symmetry;
use crate::check::explore::fingerprint;
use crate::model::atoms::{AtomId, AtomSet};
use crate::model::cond::{Cond, CountCmp};
use crate::model::project::Project;
use crate::semantics::{Compiled, Packed, Semantics, State};
use crate::syntax::{Diagnostic, Span};
use smallvec::SmallVec;
use std::collections::HashSet;
use std::sync::Arc;

impl Symmetry {
    /// Whether the reasoning cycle treats the objects alike at `s`: for each generator `g`
    /// of the renamings, the successors of `g(s)` are renamings of the successors of `s`
    /// (compared as multisets of canonical fingerprints). Reduction is exact when this holds
    /// at every state; Jason's first-answer selection can break it (answers come in belief
    /// order, so `cup1` before `cup2`). `None` when it holds, otherwise the renaming that
    /// breaks it, as object names.
    pub fn equivariance_violation(&self, sem: &Semantics, s: &State) -> Option<String> {
        self.equivariance_violation_with(s, |st| {
            sem.successors(st).into_iter().map(|t| t.next).collect()
        })
    }

    /// [`Symmetry::equivariance_violation`], with the successor states computed by
    /// `successors` (the compiled reasoning cycle's, say).
    pub fn equivariance_violation_with(
        &self,
        s: &State,
        successors: impl Fn(&State) -> Vec<State>,
    ) -> Option<String> {
        let sorted = |mut v: Vec<u64>| {
            v.sort_unstable();
            v
        };
        let classes = |succ: &[State]| sorted(succ.iter().map(|t| self.fingerprint(t)).collect());
        let succ = successors(s);
        let mut here = None;
        self.generators().iter().find_map(|g| {
            let other = successors(&self.apply(s, g));
            // Equivariance itself, and far cheaper than canonical members: the successors
            // of `g(s)` are those of `s` renamed by `g`. When they are not, they may still
            // be renamings of them by other renamings: compare their classes.
            let renamed = sorted(
                succ.iter()
                    .map(|t| fingerprint(&self.apply(t, g)))
                    .collect(),
            );
            if sorted(other.iter().map(fingerprint).collect()) == renamed {
                return None;
            }
            let here = here.get_or_insert_with(|| classes(&succ));
            (classes(&other) != *here).then(|| self.show(g))
        })
    }

    /// A renaming as the objects it moves, `a -> b, ...`.
    fn show(&self, g: &[u16]) -> String {
        let moved: Vec<String> = g
            .iter()
            .enumerate()
            .filter(|(i, &j)| *i != j as usize)
            .map(|(i, &j)| format!("{} -> {}", self.names[i], self.names[j as usize]))
            .collect();
        moved.join(", ")
    }

    /// The first generator of the renamings under which a phase that `c`'s memos
    /// computed does not commute with renaming ([`Compiled::phases_equivariant`]), shown
    /// as the objects it moves. A search on the compiled cycle checks this once, after it
    /// ends, instead of [`Symmetry::equivariance_violation_compiled`] on every state: it
    /// says the same of every state the search expanded (every phase their successors
    /// took was memoized), at a cost that does not grow with the states.
    pub fn phase_violation(&self, c: &Compiled) -> Option<String> {
        self.generators()
            .iter()
            .find(|g| {
                !c.phases_equivariant(self.map_id(c, g), &super::Renaming { sym: self, perm: g })
            })
            .map(|g| self.show(g))
    }

    /// [`Symmetry::equivariance_violation`] on the compiled reasoning cycle: the renamings
    /// of `p` and of its successors are made part by part, each part once per generator
    /// ([`Compiled::map`]), and compared by fingerprint; only where they differ is the
    /// comparison by classes made, on whole states. `succ`: `p`'s successors, when the
    /// caller has them.
    pub fn equivariance_violation_compiled<'c>(
        &self,
        c: &'c Compiled,
        p: &Packed<'c>,
        succ: Option<Vec<&Packed<'c>>>,
    ) -> Option<String> {
        let computed: Vec<Packed>;
        let succ = match succ {
            Some(succ) => succ,
            None => {
                computed = c.successors(p).into_iter().map(|(_, t)| t).collect();
                computed.iter().collect()
            }
        };
        // Parts are interned, so two packed states are the same state exactly when they
        // are equal: the successors are compared as states, with no fingerprint.
        let alike = self.generators().iter().all(|g| {
            let r = super::Renaming { sym: self, perm: g };
            let id = self.map_id(c, g);
            let other = c.successors(&c.map(p, id, &r));
            let mut renamed: SmallVec<[Packed; 4]> =
                succ.iter().map(|t| c.map(t, id, &r)).collect();
            other.len() == renamed.len()
                && other.iter().all(|(_, t)| {
                    // A multiset comparison: each successor of `g(p)` takes one renamed one.
                    renamed
                        .iter()
                        .position(|u| u == t)
                        .map(|k| renamed.swap_remove(k))
                        .is_some()
                })
        });
        if alike {
            return None;
        }
        self.equivariance_violation_with(&c.unpack(p), |st| {
            c.successors(&c.pack(st))
                .iter()
                .map(|(_, next)| c.unpack(next))
                .collect()
        })
    }

    /// Whether the manifest formula `expr` (written as `text`) means the same under every
    /// renaming: it names no symmetric object, or names them alike (`cupAt(cup1, c) &
    /// cupAt(cup2, c)` with two cups).
    pub fn is_symmetric(
        &self,
        project: &Project,
        text: &str,
        expr: &crate::syntax::ast::Expr,
    ) -> bool {
        if !words(text, false)
            .into_iter()
            .any(|(_, w)| self.by_name.contains_key(w))
        {
            return true;
        }
        let gens = self.generators();
        crate::model::formula::compile(expr, &project.atoms, &project.universe)
            .map(|c| {
                let base = self.normal(&c, &self.identity());
                gens.iter().all(|g| self.normal(&c, g) == base)
            })
            .unwrap_or(false)
    }

    fn refuse(&self, span: Span, name: &str, what: &str, types: &[(String, Span)]) -> Diagnostic {
        let s = self.by_name[name];
        let (ty, ty_span) = &types[self.group_of[s as usize] as usize];
        Diagnostic::error(
            "symmetry",
            format!(
                "{what} names `{name}`, an object of type `{ty}`, which `[bounds] symmetry` declares interchangeable: symmetry reduction would be unsound"
            ),
        )
        .with_label(span, format!("names `{name}`"))
        .with_secondary(*ty_span, "declared symmetric here")
        .with_help(format!(
            "use a variable instead of `{name}`, remove \"{ty}\" from `[bounds] symmetry`, or run with `--no-symmetry`"
        ))
    }

    /// Plan library and PDDL files: no symmetric object may be named.
    pub(super) fn check_sources(
        &self,
        project: &Project,
        types: &[(String, Span)],
    ) -> Vec<Diagnostic> {
        let mut out = Vec::new();
        for f in project.map.files() {
            let ext = f.path.extension().and_then(|e| e.to_str()).unwrap_or("");
            let (what, pddl) = match ext {
                "asl" => ("the plan library", false),
                "pddl" => ("the PDDL domain", true),
                _ => continue,
            };
            for (start, word) in words(&f.text, pddl) {
                let hit = if pddl {
                    self.names.iter().find(|n| n.eq_ignore_ascii_case(word))
                } else {
                    self.names.iter().find(|n| &***n == word)
                };
                if let Some(n) = hit {
                    let span = Span::new(f.id, start, start + word.len());
                    out.push(self.refuse(span, n, what, types));
                }
            }
        }
        out
    }

    /// Manifest formulas and requests that name a symmetric object must be symmetric;
    /// explanation patterns and phrases must not name one; initial states and requests must
    /// be closed under renaming.
    pub(super) fn check_manifest(
        &self,
        project: &Project,
        types: &[(String, Span)],
    ) -> Vec<Diagnostic> {
        let m = &project.manifest;
        let mut out = Vec::new();
        let named = |text: &str| -> Option<&Arc<str>> {
            words(text, false)
                .into_iter()
                .find_map(|(_, w)| self.names.iter().find(|n| &***n == w))
        };
        let mut formulas: Vec<(&str, Span, &crate::syntax::ast::Expr, String)> = Vec::new();
        for f in &m.initial.facts {
            formulas.push((&f.text, f.span, &f.expr, "the initial fact".into()));
        }
        for f in &m.initial.constraints {
            formulas.push((&f.text, f.span, &f.expr, "the initial constraint".into()));
        }
        for i in &m.invariants {
            let what = format!("invariant `{}`", i.name.value);
            formulas.push((&i.formula.text, i.formula.span, &i.formula.expr, what));
        }
        // Properties are not refused: those not symmetric are decided on runs, on a search
        // that fixes the objects they name (`Symmetry::is_symmetric`, `plan_runs`).
        let gens = self.generators();
        for (text, span, expr, what) in formulas {
            let Some(name) = named(text) else { continue };
            if !self.is_symmetric(project, text, expr) {
                let what = format!("{what}, which is not symmetric in these objects,");
                out.push(self.refuse(span, name, &what, types));
            }
        }
        // Requests: renaming must map requests to requests.
        let closed = (0..self.requests.len()).all(|r| {
            gens.iter().all(|g| {
                self.rename(&self.requests[r], g)
                    .is_none_or(|t| self.request_index.contains_key(&t))
            })
        });
        if !closed {
            for f in &m.requests.goals {
                if let Some(name) = named(&f.text) {
                    out.push(self.refuse(f.span, name, "the request", types));
                }
            }
        }
        if let Some(e) = &m.explanation {
            let mut patterns: Vec<(&str, Span, &str)> = Vec::new();
            for p in &e.phrases {
                patterns.push((&p.pattern.text, p.pattern.span, "the phrase pattern"));
                patterns.push((&p.template.value, p.template.span, "the phrase"));
            }
            for u in &e.users {
                for pair in &u.expected {
                    for side in [&pair.before, &pair.after] {
                        patterns.push((&side.text, side.span, "the expected pair"));
                    }
                }
            }
            for (text, span, what) in patterns {
                if let Some(name) = named(text) {
                    out.push(self.refuse(span, name, what, types));
                }
            }
        }
        // The initial states: a set closed under renaming (facts and constraints that name
        // no object are; this catches the rest).
        if out.is_empty() {
            // Symmetric as written (the facts and the varying atoms closed under renaming,
            // every condition the same renamed): then so is the set, with no state listed.
            let init = &project.initial;
            let closed = |atoms: &[AtomId], has: &dyn Fn(AtomId) -> bool| {
                atoms
                    .iter()
                    .all(|&a| gens.iter().all(|g| has(self.atom_image(a, g))))
            };
            let facts: Vec<AtomId> = init.facts.iter().collect();
            let vary: HashSet<AtomId> = init.vary.iter().copied().collect();
            let written = closed(&facts, &|a| init.facts.contains(a))
                && closed(&init.vary, &|a| vary.contains(&a))
                && init.conditions.iter().all(|c| {
                    let base = self.normal(c, &self.identity());
                    gens.iter().all(|g| self.normal(c, g) == base)
                });
            let open = !written && {
                let states: HashSet<&AtomSet> = init.states().iter().collect();
                !init.complete()
                    || init.states().iter().any(|s| {
                        gens.iter().any(|g| {
                            let mut img = AtomSet::empty(self.atom_count);
                            s.iter().for_each(|a| img.insert(self.atom_image(a, g)));
                            !states.contains(&img)
                        })
                    })
            };
            if open {
                let span = m
                    .initial
                    .facts
                    .first()
                    .map_or(m.bounds.symmetry[0].span, |f| f.span);
                out.push(
                    Diagnostic::error(
                        "symmetry",
                        "the initial states are not symmetric in the objects `[bounds] symmetry` declares interchangeable: renaming them turns an initial state into one that is not initial",
                    )
                    .with_label(span, "the initial states")
                    .with_help("remove the type from `[bounds] symmetry`, or run with `--no-symmetry`"),
                );
            }
        }
        out
    }

    /// A condition under a renaming, in a form where the order of `&`, `|` and `.count`
    /// operands does not matter.
    fn normal(&self, c: &Cond, perm: &[u16]) -> Normal {
        normal(c, &|a| self.atom_image(a, perm))
    }
}

/// A condition with its atoms mapped by `image`, in a form where the order of `&`, `|` and
/// `.count` operands does not matter: a condition is symmetric under a renaming when its
/// normal form under the renaming is its normal form.
pub(super) fn normal(c: &Cond, image: &impl Fn(AtomId) -> AtomId) -> Normal {
    match c {
        Cond::True => Normal::True,
        Cond::False => Normal::False,
        Cond::Atom(a) => Normal::Atom(image(*a).0),
        Cond::Not(inner) => Normal::Not(Box::new(normal(inner, image))),
        Cond::And(parts) | Cond::Or(parts) => {
            let mut v: Vec<Normal> = parts.iter().map(|p| normal(p, image)).collect();
            v.sort();
            if matches!(c, Cond::And(_)) {
                Normal::And(v)
            } else {
                Normal::Or(v)
            }
        }
        Cond::Count { atoms, cmp, n } => {
            let mut v: Vec<u32> = atoms.iter().map(|a| image(*a).0).collect();
            v.sort();
            let cmp = match cmp {
                CountCmp::Eq => 0,
                CountCmp::Lt => 1,
                CountCmp::Le => 2,
                CountCmp::Gt => 3,
                CountCmp::Ge => 4,
                CountCmp::Ne => 5,
            };
            Normal::Count(v, cmp, *n)
        }
    }
}

/// A condition with sorted operands (see [`normal`]).
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Normal {
    True,
    False,
    Atom(u32),
    Not(Box<Normal>),
    And(Vec<Normal>),
    Or(Vec<Normal>),
    Count(Vec<u32>, u8, i64),
}

/// The lower-case identifiers of a source text (object names are those), with their byte
/// offsets; comments and strings skipped. `pddl` selects `;` comments, otherwise `//` and
/// `/* */`. An identifier right after `.` (an internal action) or `?` (a PDDL variable) is
/// not a name.
pub(super) fn words(text: &str, pddl: bool) -> Vec<(usize, &str)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if pddl && c == b';' || !pddl && c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if !pddl && c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                i += 1;
            }
            i += 2;
        } else if c == b'"' || !pddl && c == b'\'' {
            i += 1;
            while i < b.len() && b[i] != c {
                if b[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || pddl && b[i] == b'-')
            {
                i += 1;
            }
            let prev = start.checked_sub(1).map(|p| b[p]);
            let variable = !pddl && (c.is_ascii_uppercase() || c == b'_');
            if !variable && prev != Some(b'.') && prev != Some(b'?') {
                out.push((start, &text[start..i]));
            }
        } else {
            i += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_skip_comments_strings_variables_and_internal_actions() {
        let asl = "+!g(C) : cupAt(C, cup1) // cup2\n <- .print(\"cup3\"); /* cup4 */ go(cup5).";
        let w: Vec<&str> = words(asl, false).into_iter().map(|(_, w)| w).collect();
        assert_eq!(w, ["g", "cupAt", "cup1", "go", "cup5"]);
        let pddl = "(:action a :parameters (?cup1 - cup) ; cup2\n :effect (used cup3))";
        let w: Vec<&str> = words(pddl, true).into_iter().map(|(_, w)| w).collect();
        assert!(w.contains(&"cup3") && !w.contains(&"cup1") && !w.contains(&"cup2"));
    }

    #[test]
    fn compiled_images_are_the_whole_states_renamed_under_each_generator() {
        // The kitchen with three cups: two generators (a swap and a rotation), and cups in
        // different places, so that an image kept for one renaming and served for another
        // shows.
        let specs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("specs/kitchen");
        let dir = std::env::temp_dir().join(format!("bdi-check-images-{}", std::process::id()));
        /// Removes the folder when the test ends, failed or not.
        struct Gone(std::path::PathBuf);
        impl Drop for Gone {
            fn drop(&mut self) {
                std::fs::remove_dir_all(&self.0).ok();
            }
        }
        let _gone = Gone(dir.clone());
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        for f in ["kitchen.asl", "kitchen.pddl"] {
            std::fs::copy(specs.join(f), dir.join(f)).expect("the kitchen's files");
        }
        let manifest = std::fs::read_to_string(specs.join("bdi-check.toml")).expect("readable");
        let three = manifest.replace(
            r#"cup = ["cup1", "cup2"]"#,
            r#"cup = ["cup1", "cup2", "cup3"]"#,
        );
        assert_ne!(three, manifest, "the kitchen names its cups");
        std::fs::write(dir.join("bdi-check.toml"), three).expect("writable");
        let project = crate::model::project::load_project(&dir).expect("the project loads");
        let sem = Semantics::new(&project).expect("the semantics");
        let sym = Symmetry::new(&project, &sem)
            .expect("symmetry is sound here")
            .expect("the manifest declares symmetry");
        let c = Compiled::new(&sem).expect("a local library");
        let generators = sym.generators();
        assert!(generators.len() >= 2, "{generators:?}");
        let mut seen: HashSet<u64> = HashSet::new();
        let mut queue: std::collections::VecDeque<Packed> = c.initial_iter().collect();
        let mut compared = 0;
        while let Some(p) = queue.pop_front() {
            if !seen.insert(fingerprint(&p)) || compared == 2_000 {
                continue;
            }
            compared += 1;
            let whole = c.unpack(&p);
            // The canonical fingerprint made without unpacking, from what is kept per
            // agenda and per belief base, is the one made on the whole state.
            assert_eq!(sym.fingerprint_compiled(&c, &p), sym.fingerprint(&whole));
            for g in generators {
                let r = super::super::Renaming { sym: &sym, perm: g };
                let image = c.map(&p, c.map_id(g), &r);
                assert_eq!(c.unpack(&image), sym.apply(&whole, g), "{g:?}");
            }
            queue.extend(c.successors(&p).into_iter().map(|(_, t)| t));
        }
        assert!(compared == 2_000, "{compared} states");
        // Every phase the walk computed commutes with both generators.
        assert_eq!(sym.phase_violation(&c), None);
    }
}
