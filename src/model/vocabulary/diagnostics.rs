//! The wording shared by every pass: diagnostics about objects and type conflicts, how
//! signatures, types and counts are phrased ("a `cup`", "2 arguments"), and the "did you
//! mean" suggestions for likely typos.

use super::{Checker, GoalInfo, Occ, Sig, VarInfo};
use crate::model::universe::TypeId;
use crate::syntax::{Diagnostic, Span};

impl Checker<'_> {
    pub(super) fn not_an_object(&self, name: &str, span: Span) -> Diagnostic {
        if name.parse::<i64>().is_ok() {
            let (msg, help) = match &self.manifest_numbers {
                Some((lo, hi)) => (
                    format!("`{name}` is not among the model's numbers, {lo} to {hi}"),
                    "widen `[bounds] numbers`",
                ),
                None => (
                    format!("`{name}` is a number, and the model has none"),
                    "declare the integers mental notes may hold, such as `[bounds] numbers = [0, 10]`",
                ),
            };
            return Diagnostic::error("input", msg)
                .with_label(span, "number outside the model")
                .with_help(help);
        }
        let hint = suggest(
            name,
            self.universe
                .objects()
                .map(|o| self.universe.object_name(o)),
        )
        .map(|s| format!("; did you mean `{s}`?"))
        .unwrap_or_default();
        Diagnostic::error("input", format!("`{name}` is not an object{hint}"))
            .with_label(span, "unknown object")
            .with_help("objects are the PDDL domain's constants and the manifest's `[objects]`")
    }

    pub(super) fn conflict(&self, v: &str, first: &VarInfo, o: &Occ, want: TypeId) -> Diagnostic {
        let tn = |t| self.universe.type_name(t);
        Diagnostic::error(
            "input",
            format!(
                "variable `{v}` is {} at {} and {} at {}",
                a_type(tn(first.ty)),
                self.map.location(first.span),
                a_type(tn(want)),
                self.map.location(o.span),
            ),
        )
        .with_label(o.span, self.expects(o.sig, o.index, want))
        .with_secondary(first.span, self.expects(first.sig, first.index, first.ty))
        .with_help(format!(
            "no object is both {} and {}",
            a_type(tn(first.ty)),
            a_type(tn(want))
        ))
    }

    /// "`pickUp` expects a `cup`", "`cupAt` expects a `location` as argument 2".
    pub(super) fn expects(&self, sig: Sig, i: usize, t: TypeId) -> String {
        let arity = match sig {
            Sig::Pred(p) => self.preds[p].arity,
            Sig::Action(a) => self.actions[a].params.len(),
            Sig::Goal(g) => self.goals[g].arity,
            Sig::Rule(r) => self.rules[r].arity,
        };
        let what = a_type(self.universe.type_name(t));
        if arity == 1 {
            format!("`{}` expects {what}", self.sig_name(sig))
        } else {
            format!(
                "`{}` expects {what} as argument {}",
                self.sig_name(sig),
                i + 1
            )
        }
    }

    pub(super) fn sig_name(&self, sig: Sig) -> String {
        match sig {
            Sig::Pred(p) => self.preds[p].name.clone(),
            Sig::Action(a) => self.actions[a].name.clone(),
            Sig::Goal(g) => format!("!{}", self.goals[g].name),
            Sig::Rule(r) => self.rules[r].name.clone(),
        }
    }
}

/// What the secondary label at a goal's span says.
pub(super) fn goal_place(g: &GoalInfo) -> String {
    let what = if g.plan_span.is_some() {
        "its first plan"
    } else {
        "first used here"
    };
    format!("`{}/{}`: {what}", g.name, g.arity)
}

/// "a `cup`", "an `item`".
pub(super) fn a_type(name: &str) -> String {
    let article = if name
        .chars()
        .next()
        .is_some_and(|c| "aeiouAEIOU".contains(c))
    {
        "an"
    } else {
        "a"
    };
    format!("{article} `{name}`")
}

/// "1 argument", "2 arguments".
pub(super) fn count(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}

/// "1 is", "2 are".
pub(super) fn given(n: usize) -> String {
    if n == 1 {
        "1 is".to_string()
    } else {
        format!("{n} are")
    }
}

/// "1 argument", "1 or 2 arguments".
pub(super) fn plural_or(ns: &[String], what: &str) -> String {
    match ns {
        [one] if one == "1" => format!("1 {what}"),
        [one] => format!("{one} {what}s"),
        _ => format!(
            "{} or {} {what}s",
            ns[..ns.len() - 1].join(", "),
            ns[ns.len() - 1]
        ),
    }
}

/// The nearest of `candidates` to `name`, if one is near enough to be a likely typo.
pub(super) fn suggest<'c>(
    name: &str,
    candidates: impl IntoIterator<Item = &'c str>,
) -> Option<&'c str> {
    let limit = (name.chars().count() / 3).max(1);
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c == name {
            continue;
        }
        let d = if c.eq_ignore_ascii_case(name) {
            1
        } else {
            edit_distance(name, c)
        };
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Edit distance with adjacent transpositions (optimal string alignment): `tabel` is one edit
/// from `table`.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, v) in d[0].iter_mut().enumerate() {
        *v = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_are_near_names_only() {
        assert_eq!(suggest("tabel", ["table", "cupboard"]), Some("table"));
        assert_eq!(suggest("usd", ["used", "dirty"]), Some("used"));
        assert_eq!(suggest("xyz", ["used", "dirty"]), None);
        assert_eq!(suggest("cupat", ["cupAt"]), Some("cupAt"));
    }

    #[test]
    fn articles_and_counts() {
        assert_eq!(a_type("item"), "an `item`");
        assert_eq!(a_type("cup"), "a `cup`");
        assert_eq!(count(1, "argument"), "1 argument");
        assert_eq!(
            plural_or(&["1".into(), "2".into()], "argument"),
            "1 or 2 arguments"
        );
    }
}
