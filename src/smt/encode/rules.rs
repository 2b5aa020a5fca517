//! The agent's rules: converted clause by clause, and inlined where a formula uses them
//! (non-recursive rules only: a recursive one is unsupported).

use super::{and, or, val_eq, Clause, Enc, Encoder, Env, Frame, Mode, State, Unsupported};
use crate::model::from_ast::{ConvertError, Converter};
use crate::model::plans::Formula;
use crate::model::project::Project;
use crate::model::term::Term;
use crate::syntax::ast::{Expr, Item};
use std::collections::HashMap;
use z3::ast::Bool;

impl Encoder<'_> {
    pub(super) fn rule_of(&self, t: &Term) -> Option<&Enc<Vec<Clause>>> {
        let key = (t.functor()?.to_string(), t.arity());
        self.rules.get(&key)
    }

    pub(super) fn rule_call(
        &self,
        t: &Term,
        clauses: &[Clause],
        env: &mut Env,
        frame: &mut Frame,
        st: &State,
        mode: Mode,
    ) -> Enc<Bool> {
        let key = (t.functor().unwrap_or("").to_string(), t.arity());
        if self.active_rules.borrow().contains(&key) {
            return Err(Unsupported(format!(
                "the rule `{}/{}` is recursive; lint inlines non-recursive rules only",
                key.0, key.1
            )));
        }
        let mut extra = if mode == Mode::Assert {
            self.bind_args(t, env, frame)
        } else {
            Vec::new()
        };
        self.active_rules.borrow_mut().push(key);
        let result = (|| {
            let mut parts = Vec::new();
            for clause in clauses {
                let mut cenv = Env::new();
                let mut cframe = self.frame();
                let mut eqs = Vec::new();
                for (h, c) in clause.head.args().iter().zip(t.args()) {
                    let cv = self.term_val(c, env)?;
                    match h {
                        Term::Var(hv) => match (cenv.get(hv).cloned(), cv) {
                            (None, Some(cv)) => {
                                cenv.insert(hv.clone(), cv);
                            }
                            (Some(prev), Some(cv)) => eqs.push(val_eq(&prev, &cv)),
                            _ => {}
                        },
                        _ => {
                            let Some(hv) = self.term_val(h, &cenv)? else {
                                return Err(Unsupported(format!(
                                    "the rule head `{}` has structured arguments",
                                    clause.head
                                )));
                            };
                            if let Some(cv) = cv {
                                eqs.push(val_eq(&hv, &cv));
                            }
                        }
                    }
                }
                let body = self.chain(&[&clause.body], &mut cenv, &mut cframe, st, mode)?;
                eqs.push(body);
                parts.push(and(eqs));
            }
            Ok(or(parts))
        })();
        self.active_rules.borrow_mut().pop();
        extra.push(result?);
        Ok(and(extra))
    }
}

// ----- rules ------------------------------------------------------------------------------

/// The agent's rules, converted clause by clause (a clause that cannot be converted makes
/// its rule unsupported).
pub(super) fn rules_of(project: &Project) -> HashMap<(String, usize), Enc<Vec<Clause>>> {
    let mut out: HashMap<(String, usize), Enc<Vec<Clause>>> = HashMap::new();
    for item in project.agent.items() {
        let Item::Rule(r) = item else { continue };
        let key = (r.head.functor.clone(), r.head.args.len());
        let mut conv = Converter::new();
        let clause = conv
            .literal(&r.head)
            .map_err(|e| convert_unsupported(&e))
            .and_then(|head| {
                Ok(Clause {
                    head,
                    body: expr_formula(&mut conv, &r.body)?,
                })
            });
        let entry = out.entry(key).or_insert_with(|| Ok(Vec::new()));
        match (entry.as_mut(), clause) {
            (Ok(v), Ok(c)) => v.push(c),
            (Ok(_), Err(e)) => *entry = Err(e),
            (Err(_), _) => {}
        }
    }
    out
}

fn convert_unsupported(e: &ConvertError) -> Unsupported {
    Unsupported(format!("a rule: {}", e.message))
}

/// A rule body as a formula, converted exactly as the plan library converts contexts.
fn expr_formula(c: &mut Converter, e: &Expr) -> Enc<Formula> {
    crate::model::plans::formula(c, e).map_err(|d| Unsupported(format!("a rule: {}", d.message)))
}

/// The agent's rules as clauses, for evaluators outside the encoding (tests, reports).
pub fn rule_clauses(project: &Project) -> HashMap<(String, usize), Result<Vec<Clause>, String>> {
    rules_of(project)
        .into_iter()
        .map(|(k, v)| (k, v.map_err(|u| u.0)))
        .collect()
}
