//! Explanations as one English sentence, in the style the paper's users rated best (EC: the
//! key contextual factors and the intention behind the action, nothing redundant):
//!
//! > I go to the dishwasher because cup1 is used, the dishwasher door is not open and my
//! > hands are free: I want to open the dishwasher.
//!
//! The sentence says the explained action, then *every* literal of `Γ`, then the last step of
//! the content. All of `Γ` because Algorithm 2 already selected it: the contexts of the
//! intention chain are the factors that made the robot adopt the plans leading to this
//! action, and they are what separates the paper's EC from EB (all beliefs). The last step
//! `a_k` alone because it is the intention: the step that changes a factor (the paper's
//! "actual intention of moving to the dishwasher"); the steps in between are the way there,
//! and naming them is the redundancy ECR was rated down for. Pieces that are empty or would
//! repeat the action are left out.
//!
//! Words come from phrase templates (`[explanation.phrases]`): the first pattern that matches
//! a term gives its template, with each `{X}` replaced by what the pattern's variable `X`
//! matched (`{{` and `}}` are braces). Without a matching phrase a term reads plainly:
//! `dishwasherDoor(open) holds`, `perform navigateTo(dishwasher)`, `achieve storeCup(cup1)`.
//!
//! A negative literal `not p` with a phrase is negated in the template: `not` goes after its
//! first auxiliary verb (`is`, `are`, `am`, `was`, `were`, `will`, `would`, `should`,
//! `must`, `could`; `can` becomes `cannot`), so "the dishwasher door is {S}" reads "the
//! dishwasher door is not open"; a template without one reads "it is not the case that …".
//! Only the template's own text is searched, never the values put into it.

use super::content::{Content, ContextLiteral, PlanStep};
use super::demand::Observation;
use crate::model::{match_pattern, Substitution, Term};

/// One piece of a template.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Piece {
    Text(String),
    /// `{X}`: the value of the pattern's variable named `X`.
    Var(String),
}

/// A parsed template. Unclosed `{` and stray `}` are kept as text (the manifest rejects
/// them before they get here).
#[derive(Clone, Debug, PartialEq, Eq)]
struct Template(Vec<Piece>);

impl Template {
    fn parse(src: &str) -> Template {
        let mut pieces = Vec::new();
        let mut text = String::new();
        let mut rest = src;
        while let Some(c) = rest.chars().next() {
            if rest.starts_with("{{") || rest.starts_with("}}") {
                text.push(c);
                rest = &rest[2..];
            } else if let (true, Some(close)) = (c == '{', rest.find('}')) {
                if !text.is_empty() {
                    pieces.push(Piece::Text(std::mem::take(&mut text)));
                }
                pieces.push(Piece::Var(rest[1..close].to_string()));
                rest = &rest[close + 1..];
            } else {
                text.push(c);
                rest = &rest[c.len_utf8()..];
            }
        }
        if !text.is_empty() {
            pieces.push(Piece::Text(text));
        }
        Template(pieces)
    }

    /// The template filled from `s`; an unknown `{X}` stays as written.
    fn fill(&self, s: &Substitution) -> String {
        let mut out = String::new();
        for p in &self.0 {
            match p {
                Piece::Text(t) => out.push_str(t),
                Piece::Var(name) => match s.iter().find(|(v, _)| v.name() == name) {
                    Some((v, _)) => out.push_str(&plain(&s.resolve(v))),
                    None => {
                        out.push('{');
                        out.push_str(name);
                        out.push('}');
                    }
                },
            }
        }
        out
    }

    /// The negated template (see the module documentation).
    fn negated(&self) -> Template {
        let mut pieces = self.0.clone();
        for p in &mut pieces {
            if let Piece::Text(t) = p {
                if let Some(neg) = negate_first_auxiliary(t) {
                    *t = neg;
                    return Template(pieces);
                }
            }
        }
        pieces.insert(0, Piece::Text("it is not the case that ".into()));
        Template(pieces)
    }
}

const AUXILIARIES: &[&str] = &[
    "is", "are", "am", "was", "were", "will", "would", "should", "must", "could", "can",
];

/// `text` with `not` after its first auxiliary (`can` → `cannot`), if it has one.
fn negate_first_auxiliary(text: &str) -> Option<String> {
    let is_word = |c: char| c.is_alphanumeric() || c == '\'' || c == '_';
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (start, is_word(c)) {
            (None, true) => start = Some(i),
            (Some(s), false) => {
                let word = &text[s..i];
                if AUXILIARIES.contains(&word) {
                    let neg = if word == "can" { "cannot" } else { "not" };
                    let joined = if word == "can" {
                        format!("{}{neg}{}", &text[..s], &text[i..])
                    } else {
                        format!("{} {neg}{}", &text[..i], &text[i..])
                    };
                    return Some(joined);
                }
                start = None;
            }
            _ => {}
        }
    }
    None
}

/// A term as a sentence shows it: a string's text without quotes, anything else as Jason
/// prints it.
fn plain(t: &Term) -> String {
    match t.as_str() {
        Some(s) => s.to_string(),
        None => t.to_string(),
    }
}

#[derive(Clone, Debug)]
struct Entry {
    /// A `!g` pattern: used for goals (requests and subgoals) only.
    goal: bool,
    pattern: Term,
    template: Template,
}

/// Phrase templates: how literals, actions and goals read in sentences.
#[derive(Clone, Debug, Default)]
pub struct Phrases {
    entries: Vec<Entry>,
}

impl Phrases {
    /// Phrases for literals, actions and goals from `(pattern, template)` pairs, tried in
    /// order (the first match wins).
    pub fn new(entries: impl IntoIterator<Item = (Term, String)>) -> Phrases {
        let mut p = Phrases::default();
        for (pattern, template) in entries {
            p.push(pattern, &template);
        }
        p
    }

    /// Adds a phrase for literals, actions and goals that match `pattern`, after the
    /// existing ones.
    pub fn push(&mut self, pattern: Term, template: &str) {
        self.entries.push(Entry {
            goal: false,
            pattern,
            template: Template::parse(template),
        });
    }

    /// Adds a phrase for goals only (a `!g(X)` key of `[explanation.phrases]`). Goal
    /// phrases are tried before the others for requests and subgoals.
    pub fn push_goal(&mut self, pattern: Term, template: &str) {
        self.entries.push(Entry {
            goal: true,
            pattern,
            template: Template::parse(template),
        });
    }

    /// Adds a phrase keyed as in the manifest: a request pattern `!g` is a goal phrase, an
    /// action pattern a plain one.
    pub fn push_observation(&mut self, pattern: &Observation, template: &str) {
        match pattern {
            Observation::Request(g) => self.push_goal(g.clone(), template),
            Observation::Action(a) => self.push(a.clone(), template),
        }
    }

    /// The first entry (goal phrases first when `goal`) matching `t`, with the bindings.
    fn find(&self, t: &Term, goal: bool) -> Option<(&Entry, Substitution)> {
        let goal_first = self.entries.iter().filter(|e| goal && e.goal);
        let plain = self.entries.iter().filter(|e| !e.goal);
        goal_first.chain(plain).find_map(|e| {
            let mut s = Substitution::new();
            match_pattern(&e.pattern, t, &mut s).then_some((e, s))
        })
    }

    /// A context literal as a clause: "the dishwasher door is not open", or
    /// "dishwasherDoor(open) does not hold" without a phrase.
    pub fn literal(&self, l: &ContextLiteral) -> String {
        match (self.find(&l.atom, false), l.positive) {
            (Some((e, s)), true) => e.template.fill(&s),
            (Some((e, s)), false) => e.template.negated().fill(&s),
            (None, true) => format!("{} holds", l.atom),
            (None, false) => format!("{} does not hold", l.atom),
        }
    }

    /// An action as a verb phrase for "I …": "go to the dishwasher", or
    /// "perform navigateTo(dishwasher)" without a phrase.
    pub fn action(&self, a: &Term) -> String {
        match self.find(a, false) {
            Some((e, s)) => e.template.fill(&s),
            None => format!("perform {a}"),
        }
    }

    /// A goal as a verb phrase for "I want to …": "store cup1", or
    /// "achieve storeCup(cup1)" without a phrase.
    pub fn goal(&self, g: &Term) -> String {
        match self.find(g, true) {
            Some((e, s)) => e.template.fill(&s),
            None => format!("achieve {g}"),
        }
    }

    /// A plan step as a verb phrase ([`Phrases::action`] or [`Phrases::goal`]).
    pub fn step(&self, s: &PlanStep) -> String {
        match s {
            PlanStep::Action(a) => self.action(a),
            PlanStep::Subgoal(g) => self.goal(g),
        }
    }

    /// An observation as a verb phrase ([`Phrases::goal`] for a request).
    pub fn observation(&self, o: &Observation) -> String {
        match o {
            Observation::Request(g) => self.goal(g),
            Observation::Action(a) => self.action(a),
        }
    }
}

/// `a`, `a and b`, `a, b and c`.
fn join(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The explanation of `action` with content `content`, as one sentence:
/// "I ⟨action⟩ because ⟨Γ⟩: I want to ⟨a_k⟩." (see the module documentation). Without `Γ` it
/// reads "I ⟨action⟩ because I want to ⟨a_k⟩."; when the content is the action alone the
/// intention part is left out; clauses that read the same are said once.
pub fn sentence(action: &Term, content: &Content, phrases: &Phrases) -> String {
    let mut factors: Vec<String> = Vec::new();
    for l in &content.context {
        let clause = phrases.literal(l);
        if !factors.contains(&clause) {
            factors.push(clause);
        }
    }
    let intention = match content.actions.as_slice() {
        [_, .., last] => Some(phrases.step(last)),
        _ => None,
    };
    let mut out = format!("I {}", phrases.action(action));
    match (factors.is_empty(), intention) {
        (false, Some(i)) => out += &format!(" because {}: I want to {i}", join(&factors)),
        (false, None) => out += &format!(" because {}", join(&factors)),
        (true, Some(i)) => out += &format!(" because I want to {i}"),
        (true, None) => {}
    }
    out.push('.');
    out
}
