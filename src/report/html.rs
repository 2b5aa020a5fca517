//! `--format html`: one self-contained HTML file per `verify` or `explain` run (no network,
//! no external assets: the style and the script are inline).
//!
//! The page shows the verdict and every finding, errors first. Each run (a counterexample,
//! or `explain`'s scenario) is a list of steps beside the goal-plan tree; clicking a step
//! shows the beliefs after it and highlights, in the tree, the plan it comes from. The
//! explanations given are steps of the run, in place. A step can be selected from the
//! address too (`report.html#run-2-step-5`), which is how a link points at one moment of a
//! run, and how the browser test drives the page.

use super::graph::{formula_text, subgoals};
use crate::findings::{Counterexample, Finding, Report, Status, TraceStep, Verdict};
use crate::model::project::Project;
use crate::syntax::Severity;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::fmt::Write;

/// One plan of the goal-plan tree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TreePlan {
    /// `file:line`, as steps name plans.
    pub place: String,
    /// The plan's label or trigger, as traces name it.
    pub name: String,
    /// Its context, as written in the model.
    pub context: String,
    /// The goals its body posts (`name/arity`), in order.
    pub subgoals: Vec<String>,
}

/// The goal-plan tree: for each goal or event (`+!name/arity`), its plans, in library order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlanTree {
    /// The triggers, in order of their first plan.
    pub triggers: Vec<(String, Vec<TreePlan>)>,
    /// The goals the user or the agent posts first (requests, initial goals), as keys
    /// of `triggers`.
    pub roots: Vec<String>,
}

impl PlanTree {
    /// The tree of a project's plan library.
    pub fn of(p: &Project) -> PlanTree {
        let mut triggers: Vec<(String, Vec<TreePlan>)> = Vec::new();
        let mut index: HashMap<String, usize> = HashMap::new();
        for plan in &p.plans.plans {
            let t = &plan.trigger;
            let key = format!(
                "{}{}{}/{}",
                t.op.symbol(),
                t.kind.symbol(),
                t.literal.functor().unwrap_or(""),
                t.literal.arity()
            );
            let loc = p.map.location(plan.span);
            let mut goals = Vec::new();
            subgoals(&plan.body, &mut goals);
            let goals = goals.into_iter().map(|(g, _)| format!("+!{g}")).collect();
            let entry = TreePlan {
                place: format!("{}:{}", loc.file, loc.line),
                name: plan.name(),
                context: formula_text(&plan.context),
                subgoals: goals,
            };
            match index.get(&key) {
                Some(&i) => triggers[i].1.push(entry),
                None => {
                    index.insert(key.clone(), triggers.len());
                    triggers.push((key, vec![entry]));
                }
            }
        }
        // Roots: the triggers no plan posts (what requests, initial goals and percepts
        // start).
        let posted: BTreeSet<&str> = triggers
            .iter()
            .flat_map(|(_, ps)| {
                ps.iter()
                    .flat_map(|p| p.subgoals.iter().map(String::as_str))
            })
            .collect();
        let roots = triggers
            .iter()
            .map(|(k, _)| k.clone())
            .filter(|k| !posted.contains(k.as_str()))
            .collect();
        PlanTree { triggers, roots }
    }
}

/// Escapes text for HTML element content and attribute values (as XML attributes).
fn esc(s: &str) -> String {
    super::junit::attr(s)
}

const STYLE: &str = r#"
body { font-family: system-ui, sans-serif; margin: 0; color: #222; }
header { padding: 12px 20px; border-bottom: 1px solid #ccc; }
h1 { font-size: 20px; margin: 0 0 6px 0; }
.verdict { display: inline-block; padding: 2px 10px; border-radius: 4px; font-weight: bold; }
.verdict.pass { background: #d9ead3; } .verdict.fail, .verdict.error { background: #f4cccc; }
.verdict.incomplete { background: #fff2cc; }
main { display: flex; gap: 16px; padding: 12px 20px; align-items: flex-start; }
#findings { flex: 3; min-width: 0; }
#tree { flex: 2; position: sticky; top: 0; max-height: 100vh; overflow: auto; font-size: 13px; }
.finding { border: 1px solid #ddd; border-left: 6px solid #999; margin: 0 0 12px 0; padding: 8px 12px; }
.finding.error { border-left-color: #c00; } .finding.warning { border-left-color: #e69138; }
.finding.note, .finding.pass, .finding.suppressed { border-left-color: #6aa84f; }
.finding h2 { font-size: 15px; margin: 0 0 4px 0; } .where { color: #666; font-weight: normal; }
.run { display: flex; gap: 12px; } .steps { flex: 3; font-family: monospace; font-size: 13px; }
.step { cursor: pointer; padding: 1px 4px; } .step:hover { background: #eef; }
.step.selected { background: #cfe2f3; } .step.k-explanation { color: #38761d; font-style: italic; }
.step .kind { display: inline-block; width: 7.5em; color: #666; }
.state { flex: 2; font-family: monospace; font-size: 12px; background: #f7f7f7; padding: 6px; white-space: pre-wrap; }
.plan { font-family: monospace; padding: 1px 4px; } .plan.running { background: #ffe599; font-weight: bold; }
details > summary { cursor: pointer; }
"#;

/// Selecting a step: the beliefs after it in the run's state pane, its plan highlighted in
/// the tree. `#run-R-step-S` selects on load.
const SCRIPT: &str = r#"
function select(run, step) {
  const r = document.getElementById('run-' + run);
  if (!r) return;
  r.querySelectorAll('.step').forEach(s => s.classList.remove('selected'));
  const s = document.getElementById('run-' + run + '-step-' + step);
  if (!s) return;
  s.classList.add('selected');
  const beliefs = JSON.parse(s.dataset.beliefs);
  const pane = document.getElementById('state-' + run);
  pane.textContent = 'after step ' + step + ':\n' + (beliefs.length ? beliefs.join('\n') : '(no beliefs)');
  document.querySelectorAll('.plan').forEach(p => p.classList.remove('running'));
  if (s.dataset.plan) {
    document.querySelectorAll('.plan[data-plan="' + CSS.escape(s.dataset.plan) + '"]')
      .forEach(p => p.classList.add('running'));
  }
}
document.addEventListener('click', e => {
  const s = e.target.closest('.step');
  if (s) { select(s.dataset.run, s.dataset.step); history.replaceState(null, '', '#' + s.id); }
});
function fromHash() {
  const m = location.hash.match(/^#run-(\d+)-step-(\d+)$/);
  if (m) select(m[1], m[2]);
}
window.addEventListener('hashchange', fromHash);
fromHash();
"#;

/// A `verify` (or `lint`) report as a page: `command` names the run in the title.
pub fn render(report: &Report, tree: &PlanTree, command: &str) -> String {
    let mut runs = 0;
    let mut body = String::new();
    let mut shown: Vec<&Finding> = report
        .findings
        .iter()
        .filter(|f| f.status != Status::Pass)
        .collect();
    shown.sort_by_key(|f| super::verify::rank(f));
    for f in &shown {
        body.push_str(&finding(f, &mut runs));
    }
    let passed: Vec<&Finding> = report
        .findings
        .iter()
        .filter(|f| f.status == Status::Pass)
        .collect();
    if !passed.is_empty() {
        let _ = write!(
            body,
            "<details><summary>{} checks passed</summary><ul>",
            passed.len()
        );
        for f in passed {
            let _ = write!(
                body,
                "<li><b>{}</b> {}</li>",
                esc(&f.check),
                esc(&f.message)
            );
        }
        body.push_str("</ul></details>");
    }
    let stats = report.stats.as_ref().map_or(String::new(), |s| {
        format!(
            "<p id=\"stats\">{} states ({} initial), {} transitions, depth {}; the search was {}.</p>",
            s.states,
            s.initial_states,
            s.transitions,
            s.depth,
            if s.complete { "complete" } else { "incomplete" }
        )
    });
    let warnings: String = report
        .warnings
        .iter()
        .map(|w| format!("<p class=\"warning\">warning: {}</p>", esc(w)))
        .collect();
    page(
        &format!("bdi-check {command} {}", report.project),
        report.verdict,
        &format!("{stats}{warnings}"),
        &body,
        tree,
    )
}

/// An `explain --scenario` run as a page: the run with its explanations in place.
pub fn render_explain(
    report: &Report,
    run: &Counterexample,
    outcome: &str,
    tree: &PlanTree,
) -> String {
    let mut runs = 0;
    let body = format!(
        "<article class=\"finding note\" id=\"scenario\"><h2>the scenario's run <span class=\"where\">({})</span></h2>{}</article>",
        esc(outcome),
        run_html(run, &mut runs)
    );
    page(
        &format!("bdi-check explain {}", report.project),
        report.verdict,
        "",
        &body,
        tree,
    )
}

fn page(title: &str, verdict: Verdict, head: &str, body: &str, tree: &PlanTree) -> String {
    let verdict = match verdict {
        Verdict::Pass => "pass",
        Verdict::Fail => "fail",
        Verdict::Incomplete => "incomplete",
        Verdict::Error => "error",
    };
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head>\n<body><header><h1>{t}</h1><span class=\"verdict {verdict}\" id=\"verdict\">{verdict}</span>{head}</header>\n<main><section id=\"findings\">{body}</section>\n<aside id=\"tree\"><h2>goal-plan tree</h2>{}</aside></main>\n<script>{SCRIPT}</script></body></html>\n",
        tree_html(tree),
        t = esc(title),
    )
}

fn finding(f: &Finding, runs: &mut usize) -> String {
    let class = match (f.status, f.severity, &f.suppressed) {
        (_, _, Some(_)) => "suppressed",
        (Status::Unknown, _, _) => "warning",
        (_, Severity::Error, _) => "error",
        (_, Severity::Warning, _) => "warning",
        (_, Severity::Note, _) => "note",
    };
    let place = f
        .location
        .as_ref()
        .map(|l| format!(" <span class=\"where\">{}</span>", esc(&l.to_string())))
        .unwrap_or_default();
    let mut out = format!(
        "<article class=\"finding {class}\" data-id=\"{}\"><h2>{class}[{}]{place}</h2><p class=\"message\">{}</p>",
        esc(&f.id),
        esc(&f.check),
        esc(&f.message)
    );
    if let Some(why) = &f.suppressed {
        let _ = write!(
            out,
            "<p>suppressed by <code>[[allow]]</code>: {}</p>",
            esc(why)
        );
    }
    match &f.counterexample {
        Some(c) if !c.steps.is_empty() && f.severity != Severity::Note => {
            out.push_str(&run_html(c, runs));
        }
        Some(c) => {
            let _ = write!(
                out,
                "<p>a state where this holds: <code>{}</code></p>",
                esc(&c.initial.join(", "))
            );
        }
        None => {}
    }
    out.push_str("</article>\n");
    out
}

/// A run: its steps (each with the beliefs after it) beside its state pane.
fn run_html(c: &Counterexample, runs: &mut usize) -> String {
    *runs += 1;
    let r = *runs;
    let mut beliefs: BTreeMap<String, ()> = c.initial.iter().map(|a| (a.clone(), ())).collect();
    let mut out = format!(
        "<div class=\"run\" id=\"run-{r}\"><ol class=\"steps\" start=\"0\"><li class=\"step\" id=\"run-{r}-step-0\" data-run=\"{r}\" data-step=\"0\" data-beliefs=\"{}\"><span class=\"kind\">start</span>initially{}</li>",
        esc(&json_list(beliefs.keys())),
        if c.requests.is_empty() {
            String::new()
        } else {
            format!("; requests {}", esc(&c.requests.join(", ")))
        }
    );
    for (i, s) in c.steps.iter().enumerate() {
        for a in &s.removed {
            beliefs.remove(a);
        }
        for a in &s.added {
            beliefs.insert(a.clone(), ());
        }
        if c.loop_start == Some(i) {
            out.push_str("<li class=\"loop\">from here the run repeats forever</li>");
        }
        out.push_str(&step_html(r, i + 1, s, &json_list(beliefs.keys())));
    }
    let _ = write!(
        out,
        "</ol><div class=\"state\" id=\"state-{r}\">click a step to see the beliefs after it</div></div>"
    );
    out
}

fn step_html(r: usize, n: usize, s: &TraceStep, beliefs: &str) -> String {
    let kind = s.kind.name();
    let plan = s
        .plan
        .as_ref()
        .map(|p| format!(" data-plan=\"{}\"", esc(p)))
        .unwrap_or_default();
    let intention = s
        .intention
        .map(|i| format!(" <span class=\"where\">[intention {i}]</span>"))
        .unwrap_or_default();
    let changes = s.changes();
    let changes = if changes.is_empty() {
        String::new()
    } else {
        format!(" <span class=\"where\">{}</span>", esc(&changes.join(" ")))
    };
    format!(
        "<li class=\"step k-{kind}\" id=\"run-{r}-step-{n}\" data-run=\"{r}\" data-step=\"{n}\"{plan} data-beliefs=\"{}\"><span class=\"kind\">{kind}</span>{}{intention}{changes}</li>",
        esc(beliefs),
        esc(&s.text)
    )
}

fn json_list<'a>(items: impl Iterator<Item = &'a String>) -> String {
    serde_json::to_string(&items.collect::<Vec<_>>()).unwrap_or_else(|_| "[]".into())
}

/// The tree as nested lists: each root goal, its plans, their subgoals' plans, and so on.
/// Each goal is expanded once, where it first appears; later it is named only. So the page
/// grows linearly with the library, and is built with an explicit stack, not recursion, so
/// that a long chain of subgoals cannot overflow the stack.
fn tree_html(tree: &PlanTree) -> String {
    enum Work<'t> {
        Goal(&'t str),
        Plan(&'t TreePlan),
        Text(&'static str),
    }
    let plans: HashMap<&str, &[TreePlan]> = tree
        .triggers
        .iter()
        .map(|(k, ps)| (k.as_str(), ps.as_slice()))
        .collect();
    let mut expanded: HashSet<&str> = HashSet::new();
    let mut out = String::from("<ul>");
    // The roots, then what no root reaches (goals only a cycle of subgoals posts).
    let starts = tree
        .roots
        .iter()
        .map(String::as_str)
        .chain(tree.triggers.iter().map(|(k, _)| k.as_str()));
    for start in starts {
        if expanded.contains(start) {
            continue;
        }
        let mut stack = vec![Work::Goal(start)];
        while let Some(w) = stack.pop() {
            match w {
                Work::Text(t) => out.push_str(t),
                Work::Plan(p) => {
                    let _ = write!(
                        out,
                        "<li><span class=\"plan\" data-plan=\"{}\">{} : {} <span class=\"where\">{}</span></span>",
                        esc(&p.place),
                        esc(&p.name),
                        esc(&p.context),
                        esc(&p.place)
                    );
                }
                Work::Goal(key) => {
                    let _ = write!(out, "<li><b>{}</b>", esc(key));
                    let Some(ps) = plans.get(key) else {
                        out.push_str(" <i>(no plan)</i></li>");
                        continue;
                    };
                    if !expanded.insert(key) {
                        out.push_str(" <i>(shown above)</i></li>");
                        continue;
                    }
                    out.push_str("<ul>");
                    // Pushed in reverse, so that they are written in order.
                    stack.push(Work::Text("</ul></li>"));
                    for p in ps.iter().rev() {
                        stack.push(Work::Text("</li>"));
                        if !p.subgoals.is_empty() {
                            stack.push(Work::Text("</ul>"));
                            stack.extend(p.subgoals.iter().rev().map(|g| Work::Goal(g)));
                            stack.push(Work::Text("<ul>"));
                        }
                        stack.push(Work::Plan(p));
                    }
                }
            }
        }
    }
    out.push_str("</ul>");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(place: &str, subgoals: &[&str]) -> TreePlan {
        TreePlan {
            place: place.into(),
            name: place.into(),
            context: "true".into(),
            subgoals: subgoals.iter().map(|s| s.to_string()).collect(),
        }
    }

    #[test]
    fn each_plan_is_drawn_once_and_a_long_chain_does_not_overflow_the_stack() {
        // A diamond, repeated: g0 posts a and b, both post g1, and so on. Expanding every
        // path would draw 2^n copies of the last goal.
        let n = 40;
        let mut triggers = Vec::new();
        for i in 0..n {
            let next = format!("+!g{}/0", i + 1);
            triggers.push((
                format!("+!g{i}/0"),
                vec![plan(
                    &format!("g{i}"),
                    &[&format!("+!a{i}/0"), &format!("+!b{i}/0")],
                )],
            ));
            triggers.push((format!("+!a{i}/0"), vec![plan(&format!("a{i}"), &[&next])]));
            triggers.push((format!("+!b{i}/0"), vec![plan(&format!("b{i}"), &[&next])]));
        }
        let tree = PlanTree {
            triggers,
            roots: vec!["+!g0/0".into()],
        };
        let html = tree_html(&tree);
        assert_eq!(html.matches("class=\"plan\"").count(), 3 * n);
        assert_eq!(html.matches("(shown above)").count(), n - 1);
        assert_eq!(
            html.matches("(no plan)").count(),
            2,
            "g{n} has no plan, from a and b"
        );
        assert_eq!(html.matches("<li").count(), html.matches("</li>").count());
        // A chain of 200,000 subgoals, on a test thread's 2 MiB stack.
        let m = 200_000;
        let triggers = (0..m)
            .map(|i| {
                (
                    format!("+!c{i}/0"),
                    vec![plan(&format!("c{i}"), &[&format!("+!c{}/0", i + 1)])],
                )
            })
            .collect();
        let tree = PlanTree {
            triggers,
            roots: vec!["+!c0/0".into()],
        };
        let html = tree_html(&tree);
        assert_eq!(html.matches("class=\"plan\"").count(), m);
    }
}
