//! Reading each section of the manifest (SPEC §1) and of a scenario file (SPEC §2) into its
//! parsed value; a section or key left out keeps its default.

use super::spans::StrMap;
use super::types::*;
use super::validate::{
    a_type, entries, is_atom, is_name, is_type_name, vars, Cx, Entry, FACT, GOAL, SCENARIO_ATOM,
    SCENARIO_REQUEST,
};
use crate::syntax::ast::*;
use crate::syntax::diagnostic::Diagnostic;
use crate::syntax::mas2j::MAX_INSTANCES;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::{DeArray, DeString, DeTable, DeValue};
use toml::Spanned;

impl<'a> Cx<'a> {
    // ----- the manifest ------------------------------------------------------------------

    pub(super) fn manifest(&mut self, root: &DeTable, path: &Path, dir: &Path) -> Option<Manifest> {
        const TOP: &[&str] = &[
            "agent",
            "objects",
            "initial",
            "requests",
            "invariants",
            "property",
            "explanation",
            "bounds",
            "allow",
        ];
        self.check_keys(root, TOP, "at the top level");
        let agent = self.agent(root, dir);
        let objects = self.objects(root);
        let initial = self.initial(root);
        let requests = self.requests(root);
        let invariants = self.invariants(root);
        let properties = self.properties(root);
        let explanation = self.explanation(root);
        let bounds = self.bounds(root, &objects);
        let allows = self.allows(root);
        Some(Manifest {
            file: self.file,
            path: path.to_path_buf(),
            dir: dir.to_path_buf(),
            agent: agent?,
            objects,
            initial,
            requests,
            invariants,
            properties,
            explanation,
            bounds,
            allows,
        })
    }

    fn allows(&mut self, root: &DeTable) -> Vec<Allow> {
        const KEYS: &[&str] = &["check", "at", "why"];
        let Some(v) = root.get("allow") else {
            return Vec::new();
        };
        let Some(a) = self.array(v, "`allow`", "an array of tables `[[allow]]`") else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, av) in a.iter().enumerate() {
            let Some(t) = self.table(av, &format!("[[allow]] #{}", i + 1)) else {
                continue;
            };
            self.check_keys(t, KEYS, "in [[allow]]");
            let required = |cx: &mut Self, key: &str| match t.get(key) {
                Some(x) => cx.string(x, &format!("`allow.{key}`")),
                None => {
                    cx.missing(av.span(), key, "[[allow]]");
                    None
                }
            };
            let check = required(self, "check");
            let why = required(self, "why");
            if let Some(w) = &why {
                if w.value.trim().is_empty() {
                    let r = w.span.start as usize..w.span.end as usize;
                    self.err(r, "an `[[allow]]` needs a reason", "empty `why`");
                }
            }
            let at = t
                .get("at")
                .and_then(|x| self.string(x, "`allow.at`"))
                .map(|at| {
                    let place = match at.value.rsplit_once(':') {
                        Some((file, line)) if !file.is_empty() => match line.parse::<usize>() {
                            Ok(n) if n > 0 => (file.to_string(), Some(n)),
                            _ => {
                                let r = at.span.start as usize..at.span.end as usize;
                                self.err(
                                    r,
                                    format!("\"{}\" is not `file:line`", at.value.escape_debug()),
                                    "expected a file, then `:` and a line number from 1",
                                );
                                (file.to_string(), None)
                            }
                        },
                        _ => (at.value.clone(), None),
                    };
                    Located {
                        value: place,
                        span: at.span,
                    }
                });
            if let (Some(check), Some(why)) = (check, why) {
                out.push(Allow {
                    check,
                    at,
                    why,
                    span: self.span(av.span()),
                });
            }
        }
        out
    }

    fn agent(&mut self, root: &DeTable, dir: &Path) -> Option<AgentSection> {
        let Some(v) = root.get("agent") else {
            self.err(
                0..0,
                "missing section [agent]: the manifest must name the plan library and the action model",
                "expected `[agent]` with `plans` and `actions`",
            );
            return None;
        };
        if let DeValue::Array(entries) = v.get_ref() {
            return self.agent_list(entries, v.span(), dir);
        }
        let t = self.section(root, "agent", &["plans", "mas", "actions", "source_path"])?;
        let header = v.span();
        let actions = match t.get("actions") {
            Some(a) => self.file_ref(a, "actions", "action model", dir),
            None => {
                self.missing(header.clone(), "actions", "[agent]");
                None
            }
        };
        let source_path = t
            .get("source_path")
            .map(|v| self.source_path(v, dir))
            .unwrap_or_default();
        let (plans, mas) = match (t.get("plans"), t.get("mas")) {
            (Some(p), None) => (self.file_ref(p, "plans", "plan library", dir), None),
            (None, Some(m)) => {
                // The agents are read from the project file once it is loaded; until then
                // `plans` names the project file.
                let mas = self.file_ref(m, "mas", "Jason project", dir);
                (mas.clone(), mas)
            }
            (Some(_), Some(m)) => {
                self.err(
                    m.span(),
                    "`plans` and `mas` are both given in [agent]",
                    "a project names one agent's plans or a Jason project file, not both",
                );
                return None;
            }
            (None, None) => {
                self.missing(header, "plans", "[agent]");
                return None;
            }
        };
        Some(AgentSection {
            source_path,
            plans: plans?,
            actions: actions?,
            agents: Vec::new(),
            mas,
        })
    }

    /// `[[agent]]`: the agents of a multi-agent project, each with `name`, `plans` and
    /// `instances`; `actions` (the shared environment) and `source_path` are given in one
    /// entry, or the same in several.
    fn agent_list(
        &mut self,
        entries: &DeArray,
        header: std::ops::Range<usize>,
        dir: &Path,
    ) -> Option<AgentSection> {
        const KEYS: &[&str] = &["name", "plans", "instances", "actions", "source_path"];
        let mut agents: Vec<AgentEntry> = Vec::new();
        let mut actions: Option<(FileRef, std::ops::Range<usize>)> = None;
        let mut source_path: Vec<PathBuf> = Vec::new();
        let mut ok = true;
        for (i, av) in entries.iter().enumerate() {
            let Some(t) = self.table(av, &format!("[[agent]] #{}", i + 1)) else {
                ok = false;
                continue;
            };
            self.check_keys(t, KEYS, "in [[agent]]");
            let name = match t.get("name") {
                Some(n) => self.string(n, "`agent.name`"),
                None => {
                    self.missing(av.span(), "name", "[[agent]]");
                    None
                }
            };
            if let Some(n) = &name {
                let v = &n.value;
                let good = v.starts_with(|c: char| c.is_ascii_lowercase())
                    && v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
                if !good {
                    let r = n.span.start as usize..n.span.end as usize;
                    self.err(
                        r,
                        format!("\"{}\" is not an agent's name", v.escape_debug()),
                        "expected a Jason atom: a lower-case letter, then letters, digits or `_`",
                    );
                }
            }
            let plans = match t.get("plans") {
                Some(p) => self.file_ref(p, "plans", "plan library", dir),
                None => {
                    self.missing(av.span(), "plans", "[[agent]]");
                    None
                }
            };
            let instances = t
                .get("instances")
                .and_then(|x| self.integer(x, "`agent.instances`", 1, MAX_INSTANCES as u64))
                .unwrap_or(1) as u32;
            if let Some(a) = t.get("actions") {
                if let Some(f) = self.file_ref(a, "actions", "action model", dir) {
                    match &actions {
                        Some((first, _)) if first.path != f.path => {
                            let d = Diagnostic::error(
                                "input",
                                "the agents of a project share one environment: `actions` names two domains",
                            )
                            .with_label(f.written.span, "a second domain")
                            .with_secondary(first.written.span, "the first");
                            self.errors.push(d);
                        }
                        Some(_) => {}
                        None => actions = Some((f, a.span())),
                    }
                }
            }
            if let Some(v) = t.get("source_path") {
                for p in self.source_path(v, dir) {
                    if !source_path.contains(&p) {
                        source_path.push(p);
                    }
                }
            }
            match (name, plans) {
                (Some(name), Some(plans)) => agents.push(AgentEntry {
                    name,
                    plans,
                    instances,
                }),
                _ => ok = false,
            }
        }
        let names: Vec<Located<String>> = agents.iter().map(|a| a.name.clone()).collect();
        self.no_duplicates(&names, "agent");
        let Some((actions, _)) = actions else {
            self.err(
                header,
                "missing key `actions` in [[agent]]",
                "one `[[agent]]` names the PDDL domain the agents share",
            );
            return None;
        };
        if !ok || agents.is_empty() {
            return None;
        }
        Some(AgentSection {
            plans: agents[0].plans.clone(),
            actions,
            source_path,
            agents,
            mas: None,
        })
    }

    /// A file the manifest names under `key`, resolved against `dir` and checked to exist.
    fn file_ref(
        &mut self,
        v: &Spanned<DeValue>,
        key: &str,
        kind: &str,
        dir: &Path,
    ) -> Option<FileRef> {
        let written = self.string(v, &format!("`agent.{key}`"))?;
        let path = dir.join(&written.value);
        if written.value.is_empty() || !path.is_file() {
            let why = if path.is_dir() {
                "is a folder"
            } else if path.exists() {
                "is not a regular file"
            } else {
                "does not exist"
            };
            let d = Diagnostic::error("input", format!("{kind} file `{}` {why}", written.value))
                .with_label(self.span(v.span()), "no such file")
                .with_help(format!(
                    "paths are relative to the manifest's folder; looked for `{}`",
                    path.display()
                ));
            self.errors.push(d);
            return None;
        }
        Some(FileRef { written, path })
    }

    /// `source_path`: folders that must exist.
    fn source_path(&mut self, v: &Spanned<DeValue>, dir: &Path) -> Vec<PathBuf> {
        let mut out = Vec::new();
        for (folder, span) in self.strings(v, "`agent.source_path`") {
            let path = dir.join(&folder.value);
            if path.is_dir() {
                out.push(path);
            } else {
                self.err(
                    span,
                    format!("source path folder `{}` does not exist", folder.value),
                    "no such folder",
                );
            }
        }
        out
    }

    fn objects(&mut self, root: &DeTable) -> Vec<ObjectType> {
        let Some(v) = root.get("objects") else {
            return Vec::new();
        };
        let Some(t) = self.table(v, "[objects]") else {
            return Vec::new();
        };
        let mut types = Vec::new();
        let mut all = Vec::new();
        for (k, v) in entries(t) {
            let name = Located {
                value: k.get_ref().to_string(),
                span: self.span(k.span()),
            };
            if !is_type_name(&name.value) {
                self.err(
                    k.span(),
                    format!("`{}` is not a PDDL type name", name.value),
                    "expected a name such as `cup`",
                );
            }
            let mut objects = Vec::new();
            for (o, _) in self.strings(v, &format!("`objects.{}`", name.value)) {
                if is_atom(&o.value) {
                    all.push(o.clone());
                    objects.push(o);
                } else {
                    let r = o.span.start as usize..o.span.end as usize;
                    self.err(
                        r,
                        format!(
                            "object name \"{}\" is not a Jason atom (a lowercase letter, then letters, digits, `_`)",
                            o.value.escape_debug()
                        ),
                        "expected a name such as `cup1`",
                    );
                }
            }
            types.push(ObjectType { name, objects });
        }
        self.no_duplicates(&all, "object");
        types
    }

    fn initial(&mut self, root: &DeTable) -> InitialSection {
        let mut out = InitialSection::default();
        let Some(t) = self.section(root, "initial", &["facts", "vary", "constraints"]) else {
            return out;
        };
        if let Some(v) = t.get("facts") {
            out.facts = self.atoms(v, "`initial.facts`", FACT);
        }
        if let Some(v) = t.get("vary") {
            if let Some(a) = self.array(v, "`initial.vary`", "an array of strings") {
                out.vary = a
                    .iter()
                    .filter_map(|x| self.name_in_string(x, "an element of `initial.vary`"))
                    .collect();
                let vary = out.vary.clone();
                self.no_duplicates(&vary, "predicate in `initial.vary`");
            }
        }
        if let Some(v) = t.get("constraints") {
            out.constraints = self.formulas(v, "`initial.constraints`");
        }
        out
    }

    fn requests(&mut self, root: &DeTable) -> RequestsSection {
        let mut out = RequestsSection::default();
        let Some(t) = self.section(root, "requests", &["goals", "max", "arrival", "from", "to"])
        else {
            return out;
        };
        if let Some(v) = t.get("goals") {
            out.goals = self.atoms(v, "`requests.goals`", GOAL);
        }
        if let Some(v) = t.get("max") {
            if let Some(n) = self.integer(v, "`requests.max`", 0, u32::MAX as u64) {
                out.max = n as u32;
            }
        }
        if let Some(v) = t.get("arrival") {
            match self.choice(v, "`requests.arrival`", &["idle", "any"]) {
                Some(0) => out.arrival = Arrival::Idle,
                Some(_) => out.arrival = Arrival::Any,
                None => {}
            }
        }
        for (key, field) in [("from", &mut out.from), ("to", &mut out.to)] {
            if let Some(v) = t.get(key) {
                *field = self.agent_name(v, &format!("`requests.{key}`"));
            }
        }
        out
    }

    /// A string that names an agent (a Jason atom), or an error at it.
    fn agent_name(&mut self, v: &Spanned<DeValue>, what: &str) -> Option<Located<String>> {
        let name = self.string(v, what)?;
        let ok = name
            .value
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_lowercase())
            && name
                .value
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_');
        if ok {
            return Some(name);
        }
        self.err(
            v.span(),
            format!("`{}` is not an agent name", name.value),
            "expected a Jason atom such as `owner`",
        );
        None
    }

    pub(super) fn invariants(&mut self, root: &DeTable) -> Vec<Invariant> {
        let Some(v) = root.get("invariants") else {
            return Vec::new();
        };
        let Some(t) = self.table(v, "[invariants]") else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (k, v) in entries(t) {
            let name = Located {
                value: k.get_ref().to_string(),
                span: self.span(k.span()),
            };
            if !is_name(&name.value) {
                self.err(
                    k.span(),
                    format!("`{}` is not a valid invariant name", name.value),
                    "expected letters, digits, `_` or `-`",
                );
            }
            if let Some(formula) = self.formula(v, &format!("invariant `{}`", name.value)) {
                out.push(Invariant { name, formula });
            }
        }
        out
    }

    fn properties(&mut self, root: &DeTable) -> Vec<Property> {
        const KEYS: &[&str] = &["name", "always", "eventually", "reachable", "ltl"];
        let Some(v) = root.get("property") else {
            return Vec::new();
        };
        let Some(a) = self.array(v, "`property`", "an array of tables `[[property]]`") else {
            return Vec::new();
        };
        let mut out = Vec::new();
        let mut names = Vec::new();
        for (i, pv) in a.iter().enumerate() {
            let place = format!("[[property]] #{}", i + 1);
            let Some(t) = self.table(pv, &place) else {
                continue;
            };
            self.check_keys(t, KEYS, "in [[property]]");
            let name = match t.get("name") {
                Some(n) => self.string(n, "`property.name`"),
                None => {
                    self.missing(pv.span(), "name", "[[property]]");
                    None
                }
            };
            if let Some(n) = &name {
                if !is_name(&n.value) {
                    let r = n.span.start as usize..n.span.end as usize;
                    self.err(
                        r,
                        format!(
                            "\"{}\" is not a valid property name",
                            n.value.escape_debug()
                        ),
                        "expected letters, digits, `_` or `-`",
                    );
                }
                names.push(n.clone());
            }
            let label = name.as_ref().map_or("this property".to_string(), |n| {
                format!("property `{}`", n.value)
            });
            let mut kinds: Vec<(PropertyKind, Entry)> = entries(t)
                .into_iter()
                .filter_map(|e| {
                    let k = match e.0.get_ref().as_ref() {
                        "always" => PropertyKind::Always,
                        "eventually" => PropertyKind::Eventually,
                        "reachable" => PropertyKind::Reachable,
                        "ltl" => PropertyKind::Ltl,
                        _ => return None,
                    };
                    Some((k, e))
                })
                .collect();
            kinds.sort_by_key(|(_, (k, _))| k.span().start);
            if kinds.is_empty() {
                self.err(
                    pv.span(),
                    format!("{label} needs one of `always`, `eventually`, `reachable` or `ltl`"),
                    "no formula",
                );
                continue;
            }
            for (k, (key, _)) in &kinds[1..] {
                self.err(
                    key.span(),
                    format!(
                        "{label} has both `{}` and `{}`: give exactly one of `always`, `eventually`, `reachable`, `ltl`",
                        kinds[0].0.key(),
                        k.key()
                    ),
                    "second formula",
                );
            }
            let (kind, (_, fv)) = kinds[0];
            let what = format!("`{}` of {label}", kind.key());
            let (formula, ltl) = if kind == PropertyKind::Ltl {
                match self.ltl(fv, &what) {
                    Some((f, l)) => (Some(f), Some(l)),
                    None => (None, None),
                }
            } else {
                (self.formula(fv, &what), None)
            };
            if let (Some(name), Some(formula), 1) = (name, formula, kinds.len()) {
                out.push(Property {
                    name,
                    kind,
                    formula,
                    ltl,
                    span: self.span(pv.span()),
                });
            }
        }
        self.no_duplicates(&names, "property name");
        out
    }

    fn explanation(&mut self, root: &DeTable) -> Option<ExplanationSection> {
        const KEYS: &[&str] = &["robot", "modifies", "emitted_by", "phrases", "users"];
        let t = self.section(root, "explanation", KEYS)?;
        let mut out = ExplanationSection::default();
        if let Some((k, _)) = entries(root)
            .into_iter()
            .find(|(k, _)| k.get_ref() == "explanation")
        {
            out.span = self.span(k.span());
        }
        if let Some(v) = t.get("robot") {
            out.robot = self.agent_name(v, "`explanation.robot`");
        }
        if let Some(v) = t.get("modifies") {
            match self.choice(v, "`explanation.modifies`", &["syntactic", "semantic"]) {
                Some(0) => out.modifies = Modifies::Syntactic,
                Some(_) => out.modifies = Modifies::Semantic,
                None => {}
            }
        }
        if let Some(v) = t.get("emitted_by") {
            out.emitted_by = self.name_in_string(v, "`explanation.emitted_by`");
        }
        if let Some(v) = t.get("phrases") {
            if let Some(pt) = self.table(v, "[explanation.phrases]") {
                for (k, v) in entries(pt) {
                    let key = Located {
                        value: k.get_ref().to_string(),
                        span: self.span(k.span()),
                    };
                    let pattern = self.observed_step(key, k.span(), "a phrase pattern");
                    let template = self.string(v, "a phrase template");
                    if let (Some(pattern), Some(template)) = (pattern, template) {
                        if self.template(&pattern, &template, v.span()) {
                            out.phrases.push(Phrase { pattern, template });
                        }
                    }
                }
            }
        }
        if let Some(v) = t.get("users") {
            if let Some(ut) = self.table(v, "[explanation.users]") {
                for (k, v) in entries(ut) {
                    if let Some(u) = self.user(k, v) {
                        out.users.push(u);
                    }
                }
            }
        }
        Some(out)
    }

    /// Checks that every `{X}` of a template names a variable of the pattern.
    fn template(
        &mut self,
        pattern: &StepFormula,
        template: &Located<String>,
        raw: Range<usize>,
    ) -> bool {
        let mut vs = Vec::new();
        if let StepKind::Action(e) | StepKind::Achieve(e) = &pattern.step.kind {
            vars(e, &mut vs);
        }
        let map = StrMap::new(self.text, raw, &template.value);
        let t = template.value.as_str();
        let mut ok = true;
        let mut i = 0;
        while i < t.len() {
            let rest = &t[i..];
            if rest.starts_with("{{") || rest.starts_with("}}") {
                i += 2;
            } else if rest.starts_with('{') {
                let Some(close) = rest.find('}') else {
                    let at = map.map_range(self.file, i..i + 1);
                    self.errors.push(
                        Diagnostic::error(
                            "input",
                            "unclosed `{` in a phrase template (write `{{` for a brace)",
                        )
                        .with_label(at, "unclosed"),
                    );
                    return false;
                };
                let name = &rest[1..close];
                if !vs.iter().any(|(v, _)| *v == name) {
                    let at = map.map_range(self.file, i..i + close + 1);
                    self.errors.push(
                        Diagnostic::error(
                            "input",
                            format!(
                                "`{{{name}}}` names no variable of the pattern `{}`",
                                pattern.text
                            ),
                        )
                        .with_label(at, "unknown variable")
                        .with_secondary(pattern.step.span, "the pattern"),
                    );
                    ok = false;
                }
                i += close + 1;
            } else if rest.starts_with('}') {
                let at = map.map_range(self.file, i..i + 1);
                self.errors.push(
                    Diagnostic::error(
                        "input",
                        "unmatched `}` in a phrase template (write `}}` for a brace)",
                    )
                    .with_label(at, "unmatched"),
                );
                return false;
            } else {
                i += rest.chars().next().map_or(1, char::len_utf8);
            }
        }
        ok
    }

    fn user(&mut self, k: &Spanned<DeString>, v: &Spanned<DeValue>) -> Option<User> {
        let name = Located {
            value: k.get_ref().to_string(),
            span: self.span(k.span()),
        };
        let place = format!("[explanation.users.{}]", name.value);
        if !is_name(&name.value) {
            self.err(
                k.span(),
                format!("`{}` is not a valid user name", name.value),
                "expected letters, digits, `_` or `-`",
            );
        }
        let t = self.table(v, &place)?;
        self.check_keys(t, &["expected"], &format!("in {place}"));
        let mut expected = Vec::new();
        let what = format!("`explanation.users.{}.expected`", name.value);
        if let Some(ev) = t.get("expected") {
            let a = self.array(ev, &what, "an array of pairs")?;
            for pv in a.iter() {
                let bad = |cx: &mut Self, found: String| {
                    let d = Diagnostic::error(
                        "input",
                        format!(
                            "an expected pair must be a list of exactly 2 strings; found {found}"
                        ),
                    )
                    .with_label(cx.span(pv.span()), "expected [\"before\", \"after\"]")
                    .with_help("write a pair as [\"!storeCup(C)\", \"navigateTo(table)\"]");
                    cx.errors.push(d);
                };
                let DeValue::Array(pair) = pv.get_ref() else {
                    bad(self, a_type(pv.get_ref()).to_string());
                    continue;
                };
                if pair.len() != 2 {
                    bad(
                        self,
                        format!(
                            "{} element{}",
                            pair.len(),
                            if pair.len() == 1 { "" } else { "s" }
                        ),
                    );
                    continue;
                }
                let (DeValue::String(b), DeValue::String(e)) =
                    (pair[0].get_ref(), pair[1].get_ref())
                else {
                    let odd = pair
                        .iter()
                        .find(|x| !x.get_ref().is_str())
                        .unwrap_or(&pair[0]);
                    bad(self, format!("{} in it", a_type(odd.get_ref())));
                    continue;
                };
                let loc = |s: &str, r: Range<usize>, cx: &Self| Located {
                    value: s.to_string(),
                    span: cx.span(r),
                };
                let before = loc(b, pair[0].span(), self);
                let after = loc(e, pair[1].span(), self);
                let before =
                    self.observed_step(before, pair[0].span(), "an element of an expected pair");
                let after =
                    self.observed_step(after, pair[1].span(), "an element of an expected pair");
                if let (Some(before), Some(after)) = (before, after) {
                    expected.push(ExpectedPair {
                        before,
                        after,
                        span: self.span(pv.span()),
                    });
                }
            }
        }
        Some(User { name, expected })
    }

    fn bounds(&mut self, root: &DeTable, objects: &[ObjectType]) -> Bounds {
        const KEYS: &[&str] = &[
            "max_states",
            "max_depth",
            "symmetry",
            "plan_selection",
            "numbers",
            "random",
            "fairness",
        ];
        let mut out = Bounds::default();
        let Some(t) = self.section(root, "bounds", KEYS) else {
            return out;
        };
        if let Some(v) = t.get("max_states") {
            if let Some(n) = self.integer(v, "`bounds.max_states`", 1, i64::MAX as u64) {
                out.max_states = n;
            }
        }
        if let Some(v) = t.get("max_depth") {
            if let Some(n) = self.integer(v, "`bounds.max_depth`", 1, i64::MAX as u64) {
                out.max_depth = n;
            }
        }
        if let Some(v) = t.get("symmetry") {
            for (s, r) in self.strings(v, "`bounds.symmetry`") {
                if objects.iter().any(|o| o.name.value == s.value) {
                    out.symmetry.push(s);
                } else {
                    self.err(
                        r,
                        format!(
                            "symmetry type \"{}\" is not a type of [objects]",
                            s.value.escape_debug()
                        ),
                        "not in [objects]",
                    );
                }
            }
            let sym = out.symmetry.clone();
            self.no_duplicates(&sym, "symmetry type");
        }
        if let Some(v) = t.get("fairness") {
            let kinds = self.strings(v, "`bounds.fairness`");
            let mut intentions = false;
            out.fair_agents = false;
            for (s, r) in &kinds {
                match s.value.as_str() {
                    "intentions" => intentions = true,
                    "agents" => out.fair_agents = true,
                    other => self.err(
                        r.clone(),
                        format!(
                            "\"{}\" is not a kind of fairness: `bounds.fairness` lists \"intentions\" and \"agents\"",
                            other.escape_debug()
                        ),
                        "expected \"intentions\" or \"agents\"",
                    ),
                }
            }
            if !intentions {
                self.err(
                    v.span(),
                    "`bounds.fairness` must list \"intentions\": the reasoning cycle selects intentions round-robin, as Jason does by default, and that is fair",
                    "add \"intentions\"",
                );
            }
        }
        if let Some(v) = t.get("plan_selection") {
            match self.choice(v, "`bounds.plan_selection`", &["first", "any"]) {
                Some(0) => out.plan_selection = PlanSelection::First,
                Some(_) => out.plan_selection = PlanSelection::Any,
                None => {}
            }
        }
        if let Some(v) = t.get("numbers") {
            let ints: Option<Vec<i64>> = match v.get_ref() {
                DeValue::Array(a) => a
                    .iter()
                    .map(|x| match x.get_ref() {
                        DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok(),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            };
            match ints.as_deref() {
                Some(&[lo, hi]) if lo <= hi && hi - lo < MAX_NUMBERS => {
                    out.numbers = Some(Located {
                        value: (lo, hi),
                        span: self.span(v.span()),
                    })
                }
                _ => self.err(
                    v.span(),
                    format!(
                        "`bounds.numbers` must be `[lo, hi]`, two integers with lo <= hi and fewer than {MAX_NUMBERS} numbers"
                    ),
                    "expected `[lo, hi]`",
                ),
            }
        }
        if let Some(v) = t.get("random") {
            let values: Option<Vec<f64>> = match v.get_ref() {
                DeValue::Array(a) => a
                    .iter()
                    .map(|x| match x.get_ref() {
                        DeValue::Float(f) => f.as_str().parse::<f64>().ok(),
                        DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                            .ok()
                            .map(|i| i as f64),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            };
            match values {
                Some(vals)
                    if !vals.is_empty()
                        && vals.len() <= MAX_RANDOM
                        && vals.iter().all(|x| (0.0..1.0).contains(x)) =>
                {
                    out.random = Some(Located {
                        value: vals,
                        span: self.span(v.span()),
                    })
                }
                _ => self.err(
                    v.span(),
                    format!(
                        "`bounds.random` must list from 1 to {MAX_RANDOM} numbers in [0, 1), the values `.random(X)` may give"
                    ),
                    "expected numbers such as `[0.0, 0.5, 0.9]`",
                ),
            }
        }
        out
    }

    // ----- scenarios ---------------------------------------------------------------------

    pub(super) fn scenario(&mut self, root: &DeTable, path: &Path) -> Option<Scenario> {
        self.check_keys(root, &["initial", "requests"], "in a scenario");
        let initial = match root.get("initial") {
            Some(v) => Some(self.atoms(v, "`initial`", SCENARIO_ATOM)),
            None => {
                self.missing(0..0, "initial", "a scenario");
                None
            }
        };
        let requests = match root.get("requests") {
            Some(v) => self.atoms(v, "`requests`", SCENARIO_REQUEST),
            None => Vec::new(),
        };
        Some(Scenario {
            file: self.file,
            path: path.to_path_buf(),
            initial: initial?,
            requests,
        })
    }
}
