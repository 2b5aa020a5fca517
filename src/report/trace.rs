//! `bdi-check trace`: a replayed counterexample, each transition's steps followed by the
//! agent's whole state.

use super::verify::render_step;
use crate::findings::{StateView, Trace};
use crate::syntax::diagnostic::bold;
use anstyle::AnsiColor::Cyan;

/// The trace for people: the finding, the initial state, then each transition's steps
/// (numbered as in the counterexample) and the state they lead to, and the outcome.
pub fn render_human(t: &Trace, color: bool) -> String {
    let mut out = format!(
        "{}\n  {}\n\n{}\n",
        bold(
            &format!("trace of {} ({})", t.finding, t.check),
            Cyan,
            color
        ),
        t.message,
        bold("initially", Cyan, color)
    );
    state(&mut out, &t.initial);
    let mut n = 0;
    for (k, tr) in t.transitions.iter().enumerate() {
        out.push_str(&format!(
            "\n{}\n",
            bold(&format!("transition {}", k + 1), Cyan, color)
        ));
        if tr.steps.is_empty() {
            out.push_str("    (a reasoning cycle that shows no step)\n");
        }
        for s in &tr.steps {
            n += 1;
            out.push_str(&render_step(n, s));
        }
        state(&mut out, &tr.state);
    }
    let verdict = if t.reached {
        "still reaches"
    } else {
        "no longer reaches"
    };
    out.push_str(&format!(
        "\n{}: {verdict} its violation ({})\n",
        t.finding, t.outcome
    ));
    out
}

fn state(out: &mut String, s: &StateView) {
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    out.push_str(&format!("  beliefs:    {}\n", list(&s.beliefs)));
    out.push_str(&format!("  events:     {}\n", list(&s.events)));
    if s.intentions.is_empty() {
        out.push_str("  intentions: none\n");
    }
    for i in &s.intentions {
        out.push_str(&format!("  intention {} ({})\n", i.intention, i.status));
        for f in &i.frames {
            let mut line = format!("    {}  ({})", f.trigger, f.plan);
            if !f.bindings.is_empty() {
                line.push_str(&format!("  {{{}}}", f.bindings.join(", ")));
            }
            match &f.next {
                Some(next) => line.push_str(&format!("\n      next: {next}")),
                None => line.push_str("\n      next: (body done)"),
            }
            out.push_str(&line);
            out.push('\n');
        }
    }
    for e in &s.expected {
        let learned = if e.learned.is_empty() {
            "nothing learned yet".to_string()
        } else {
            format!("learned {}", e.learned.join(", "))
        };
        out.push_str(&format!(
            "  {} expects: {} pattern pairs; {learned}\n",
            e.user, e.patterns
        ));
    }
}

/// The trace as JSON.
pub fn render_json(t: &Trace) -> String {
    let mut s = serde_json::to_string_pretty(t).expect("a trace serializes");
    s.push('\n');
    s
}
