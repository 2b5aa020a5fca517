//! Jason's project files (`.mas2j`), read with the grammar of Jason 3's
//! `MAS2JavaParser.jj`:
//!
//! ```text
//! mas        ::= "MAS" ASID "{" [infrastructure] [environment] [executionControl]
//!                [agents] [directives] [classpath] [aslSourcePath] "}"
//! agents     ::= "agents" ":" agent+
//! agent      ::= ASID [fileName] [options] ( "agentArchClass" classDef | "agentClass" classDef
//!                | "beliefBaseClass" classDef | "#" NUMBER | "at" STRING )* ";"
//! fileName   ::= [PATH] ASID ["." ASID]          (default: the agent's name, `.asl`)
//! options    ::= "[" option ("," option)* "]"    option ::= ASID "=" value
//! classDef   ::= ID ("." ID)* ["(" [parameter ("," parameter)*] ")"]
//! ```
//!
//! What bdi-check cannot run is refused here with its place: Java classes that change how an
//! agent reasons (`agentClass`, `agentArchClass`, `beliefBaseClass`, `directives`), an
//! `executionControl` (it restricts the interleavings bdi-check explores), and agent options
//! other than Jason's defaults. The `environment` is noted and replaced by the PDDL domain;
//! `infrastructure`, `classpath`, hosts and `verbose` do not change what an agent does.

use super::diagnostic::Diagnostic;
use super::source::{FileId, Span};

/// One `agents:` entry.
#[derive(Clone, Debug, PartialEq)]
pub struct MasAgent {
    /// The agent's name (instances are named after it, see [`instance_names`]).
    pub name: String,
    /// Where the name is written.
    pub span: Span,
    /// The source file as Jason builds it: the file name written, or `name.asl`.
    pub source: String,
    /// `#N`: how many instances (1 when not written).
    pub instances: u32,
}

/// A parsed `.mas2j`.
#[derive(Clone, Debug, PartialEq)]
pub struct MasProject {
    /// The MAS's name.
    pub name: String,
    /// The agents, in the order written.
    pub agents: Vec<MasAgent>,
    /// `aslSourcePath:` entries, in order.
    pub source_path: Vec<String>,
    /// The `environment:` class, when one is named (replaced by the PDDL domain).
    pub environment: Option<(String, Span)>,
}

/// The names Jason gives the instances of an agent (`RunLocalMAS` /
/// `AgentParameters`): the name itself for one instance, `name1` ... `nameN` for `#N`.
pub fn instance_names(a: &MasAgent) -> Vec<String> {
    if a.instances == 1 {
        vec![a.name.clone()]
    } else {
        (1..=a.instances)
            .map(|i| format!("{}{i}", a.name))
            .collect()
    }
}

/// Most instances of one agent.
pub const MAX_INSTANCES: u32 = 64;

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    /// A lower-case identifier (`ASID`), a keyword included.
    Asid(String),
    /// An identifier starting upper-case (`ID`).
    Id(String),
    Number(String),
    Str(String),
    /// `./`, `/x/y/`, `C:` ...: the folder part of a file name.
    Path(String),
    Punct(char),
    Eof,
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Asid(s) | Tok::Id(s) | Tok::Number(s) => format!("`{s}`"),
            Tok::Str(s) => format!("\"{s}\""),
            Tok::Path(s) => format!("the path `{s}`"),
            Tok::Punct(c) => format!("`{c}`"),
            Tok::Eof => "the end of the file".into(),
        }
    }
}

fn lex(file: FileId, text: &str) -> Result<Vec<(Tok, Span)>, Diagnostic> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let span = |s: usize, e: usize| Span::new(file, s, e);
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            match text[i + 2..].find("*/") {
                Some(k) => i += k + 4,
                None => {
                    return Err(Diagnostic::syntax(
                        span(start, start + 2),
                        "unterminated comment",
                        "this `/*` has no `*/`",
                    ))
                }
            }
        } else if c == b'"' {
            i += 1;
            let mut s = String::new();
            loop {
                match b.get(i) {
                    None | Some(b'\n') | Some(b'\r') => {
                        return Err(Diagnostic::syntax(
                            span(start, i),
                            "unterminated string",
                            "this string has no closing `\"`",
                        ))
                    }
                    Some(b'"') => {
                        i += 1;
                        break;
                    }
                    Some(b'\\') if i + 1 < b.len() => {
                        s.push(b[i + 1] as char);
                        i += 2;
                    }
                    Some(_) => {
                        let ch = text[i..].chars().next().expect("a char");
                        s.push(ch);
                        i += ch.len_utf8();
                    }
                }
            }
            out.push((Tok::Str(s), span(start, i)));
        } else if c.is_ascii_digit() {
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            out.push((Tok::Number(text[start..i].into()), span(start, i)));
        } else if c == b'/' || c == b'\\' || (c == b'.' && b.get(i + 1) == Some(&b'/')) {
            // A PATH: a root, then `segment/` as often as written.
            i += if c == b'.' { 2 } else { 1 };
            loop {
                let mut j = i;
                while j < b.len() && word(b[j]) {
                    j += 1;
                }
                if j < b.len() && (b[j] == b'/' || b[j] == b'\\') {
                    i = j + 1;
                } else {
                    break;
                }
            }
            out.push((Tok::Path(text[start..i].into()), span(start, i)));
        } else if c.is_ascii_alphabetic() {
            while i < b.len() && word(b[i]) {
                i += 1;
            }
            let w = text[start..i].to_string();
            out.push((
                if c.is_ascii_lowercase() {
                    Tok::Asid(w)
                } else {
                    Tok::Id(w)
                },
                span(start, i),
            ));
        } else if "{}:;#[](),=.".contains(c as char) {
            i += 1;
            out.push((Tok::Punct(c as char), span(start, i)));
        } else {
            let ch = text[i..].chars().next().expect("a char");
            return Err(Diagnostic::syntax(
                span(start, start + ch.len_utf8()),
                format!("unexpected character `{ch}` in a Jason project file"),
                "not part of the .mas2j grammar",
            ));
        }
    }
    out.push((Tok::Eof, span(b.len(), b.len())));
    Ok(out)
}

struct Parser {
    toks: Vec<(Tok, Span)>,
    at: usize,
    errors: Vec<Diagnostic>,
}

type Fail = Diagnostic;

impl Parser {
    fn peek(&self) -> &Tok {
        &self.toks[self.at].0
    }

    fn span(&self) -> Span {
        self.toks[self.at].1
    }

    fn bump(&mut self) -> (Tok, Span) {
        let t = self.toks[self.at].clone();
        if self.at + 1 < self.toks.len() {
            self.at += 1;
        }
        t
    }

    fn expected(&self, what: &str) -> Fail {
        Diagnostic::syntax(
            self.span(),
            format!("expected {what}, found {}", self.peek().describe()),
            format!("expected {what}"),
        )
    }

    fn punct(&mut self, c: char) -> Result<Span, Fail> {
        if *self.peek() == Tok::Punct(c) {
            Ok(self.bump().1)
        } else {
            Err(self.expected(&format!("`{c}`")))
        }
    }

    fn is_word(&self, w: &str) -> bool {
        matches!(self.peek(), Tok::Asid(s) if s == w)
    }

    fn asid(&mut self, what: &str) -> Result<(String, Span), Fail> {
        match self.peek().clone() {
            Tok::Asid(s) => {
                let sp = self.bump().1;
                Ok((s, sp))
            }
            _ => Err(self.expected(what)),
        }
    }

    /// `classDef`: a dotted class name with optional parameters; returns the name and span.
    fn class_def(&mut self) -> Result<(String, Span), Fail> {
        let start = self.span();
        let mut name = match self.peek().clone() {
            Tok::Asid(s) | Tok::Id(s) => {
                self.bump();
                s
            }
            _ => return Err(self.expected("a class name")),
        };
        while *self.peek() == Tok::Punct('.') {
            self.bump();
            match self.peek().clone() {
                Tok::Asid(s) | Tok::Id(s) => {
                    self.bump();
                    name = format!("{name}.{s}");
                }
                _ => return Err(self.expected("a class name after `.`")),
            }
        }
        let mut end = self.toks[self.at - 1].1;
        if *self.peek() == Tok::Punct('(') {
            self.bump();
            if *self.peek() != Tok::Punct(')') {
                self.parameter()?;
                while *self.peek() == Tok::Punct(',') {
                    self.bump();
                    self.parameter()?;
                }
            }
            end = self.punct(')')?;
        }
        Ok((name, start.to(end)))
    }

    fn parameter(&mut self) -> Result<(), Fail> {
        match self.peek() {
            Tok::Number(_) | Tok::Str(_) => {
                self.bump();
                Ok(())
            }
            Tok::Punct('[') => {
                self.bump();
                self.parameter()?;
                while *self.peek() == Tok::Punct(',') {
                    self.bump();
                    self.parameter()?;
                }
                self.punct(']').map(|_| ())
            }
            _ => self.class_def().map(|_| ()),
        }
    }

    fn refuse(&mut self, span: Span, what: &str, why: &str) {
        self.errors.push(
            Diagnostic::error("input", format!("{what} is not supported: {why}"))
                .with_label(span, "here"),
        );
    }

    fn mas(&mut self) -> Result<MasProject, Fail> {
        match self.peek() {
            Tok::Id(s) if s == "MAS" => {
                self.bump();
            }
            _ => return Err(self.expected("`MAS`")),
        }
        let (name, _) = self.asid("the MAS's name (lower-case)")?;
        self.punct('{')?;
        let mut p = MasProject {
            name,
            agents: Vec::new(),
            source_path: Vec::new(),
            environment: None,
        };
        // The sections in the grammar's order, each optional.
        if self.is_word("infrastructure") {
            self.bump();
            self.punct(':')?;
            self.class_def()?;
        }
        if self.is_word("environment") {
            self.bump();
            self.punct(':')?;
            p.environment = Some(self.class_def()?);
            self.host()?;
        }
        if self.is_word("executionControl") {
            let at = self.bump().1;
            self.punct(':')?;
            self.class_def()?;
            self.host()?;
            self.refuse(
                at,
                "`executionControl`",
                "bdi-check explores every interleaving of the agents' reasoning cycles, and an execution control allows only some",
            );
        }
        if self.is_word("agents") {
            self.bump();
            self.punct(':')?;
            loop {
                p.agents.push(self.agent()?);
                if !matches!(self.peek(), Tok::Asid(s) if !KEYWORDS.contains(&s.as_str())) {
                    break;
                }
            }
        }
        if self.is_word("directives") {
            let at = self.bump().1;
            self.punct(':')?;
            loop {
                self.asid("a directive's name")?;
                self.punct('=')?;
                self.class_def()?;
                self.punct(';')?;
                if !matches!(self.peek(), Tok::Asid(s) if !KEYWORDS.contains(&s.as_str())) {
                    break;
                }
            }
            self.refuse(
                at,
                "`directives`",
                "a directive written in Java changes the agents' source as Jason loads it",
            );
        }
        for (key, into_path) in [("classpath", false), ("aslSourcePath", true)] {
            if self.is_word(key) {
                self.bump();
                self.punct(':')?;
                loop {
                    match self.peek().clone() {
                        Tok::Str(s) => {
                            self.bump();
                            if into_path {
                                p.source_path.push(s);
                            }
                        }
                        _ => return Err(self.expected("a string")),
                    }
                    self.punct(';')?;
                    if !matches!(self.peek(), Tok::Str(_)) {
                        break;
                    }
                }
            }
        }
        if *self.peek() != Tok::Punct('}') {
            return Err(self.expected(
                "`}` or a section (`infrastructure`, `environment`, `executionControl`, `agents`, `directives`, `classpath`, `aslSourcePath`, in this order)",
            ));
        }
        self.bump();
        if *self.peek() != Tok::Eof {
            return Err(self.expected("the end of the file"));
        }
        Ok(p)
    }

    fn host(&mut self) -> Result<(), Fail> {
        if self.is_word("at") {
            self.bump();
            match self.peek() {
                Tok::Str(_) => {
                    self.bump();
                }
                _ => return Err(self.expected("a host name string")),
            }
        }
        Ok(())
    }

    fn agent(&mut self) -> Result<MasAgent, Fail> {
        let (name, span) = self.asid("an agent's name (lower-case)")?;
        if KEYWORDS.contains(&name.as_str()) {
            return Err(Diagnostic::syntax(
                span,
                format!("`{name}` is a keyword of the .mas2j grammar, not an agent's name"),
                "expected an agent's name",
            ));
        }
        let mut source = format!("{name}.asl");
        // fileName: [PATH] ASID ["." ASID]; an ASID here is a file name unless it is a
        // keyword of the agent's clauses.
        let path = match self.peek().clone() {
            Tok::Path(pth) => {
                self.bump();
                Some(pth)
            }
            _ => None,
        };
        let file_word = matches!(self.peek(), Tok::Asid(s) if !AGENT_CLAUSES.contains(&s.as_str()));
        if path.is_some() || file_word {
            let (stem, _) = self.asid("a file name")?;
            let mut ext = ".asl".to_string();
            if *self.peek() == Tok::Punct('.') {
                self.bump();
                let (e, _) = self.asid("a file extension")?;
                ext = format!(".{e}");
            }
            source = format!("{}{stem}{ext}", path.unwrap_or_default());
        }
        if *self.peek() == Tok::Punct('[') {
            self.bump();
            loop {
                self.option()?;
                if *self.peek() == Tok::Punct(',') {
                    self.bump();
                } else {
                    break;
                }
            }
            self.punct(']')?;
        }
        let mut instances = 1;
        loop {
            match self.peek().clone() {
                Tok::Asid(k)
                    if ["agentArchClass", "agentClass", "beliefBaseClass"]
                        .contains(&k.as_str()) =>
                {
                    let at = self.bump().1;
                    let (class, cs) = self.class_def()?;
                    self.refuse(
                        at.to(cs),
                        &format!("`{k} {class}`"),
                        "a Java class changes how the agent reasons, and bdi-check runs Jason's own",
                    );
                }
                Tok::Punct('#') => {
                    self.bump();
                    match self.peek().clone() {
                        Tok::Number(n) => {
                            let ns = self.bump().1;
                            match n.parse::<u32>() {
                                Ok(k) if (1..=MAX_INSTANCES).contains(&k) => instances = k,
                                _ => self.errors.push(
                                    Diagnostic::error(
                                        "input",
                                        format!("`#{n}`: an agent has from 1 to {MAX_INSTANCES} instances here"),
                                    )
                                    .with_label(ns, "the number of instances"),
                                ),
                            }
                        }
                        _ => return Err(self.expected("the number of instances")),
                    }
                }
                Tok::Asid(k) if k == "at" => {
                    self.host()?;
                }
                _ => break,
            }
        }
        self.punct(';')?;
        Ok(MasAgent {
            name,
            span,
            source,
            instances,
        })
    }

    /// One agent option: Jason's defaults and `verbose` are accepted, anything else is
    /// refused (it changes the reasoning cycle bdi-check runs).
    fn option(&mut self) -> Result<(), Fail> {
        let (key, ks) = self.asid("an option's name")?;
        self.punct('=')?;
        let (value, vs) = match self.peek().clone() {
            Tok::Asid(v) | Tok::Id(v) | Tok::Number(v) | Tok::Str(v) => {
                let vs = self.bump().1;
                (v, vs)
            }
            _ => return Err(self.expected("an option's value")),
        };
        let default = match key.as_str() {
            "events" => Some("discard"),
            "intBels" => Some("sameFocus"),
            "nrcbp" => Some("1"),
            "synchronised" => Some("false"),
            "verbose" => return Ok(()),
            _ => None,
        };
        match default {
            Some(d) if d == value => {}
            Some(d) => self.refuse(
                ks.to(vs),
                &format!("the option `{key}={value}`"),
                &format!("bdi-check runs Jason's default reasoning cycle (`{key}={d}`)"),
            ),
            None => self.refuse(
                ks.to(vs),
                &format!("the option `{key}={value}`"),
                "bdi-check runs Jason's default reasoning cycle, and does not know what this option changes",
            ),
        }
        Ok(())
    }
}

/// The words that start a section.
const KEYWORDS: [&str; 7] = [
    "infrastructure",
    "environment",
    "executionControl",
    "agents",
    "directives",
    "classpath",
    "aslSourcePath",
];

/// The words that start an agent's clauses after its name.
const AGENT_CLAUSES: [&str; 4] = ["agentArchClass", "agentClass", "beliefBaseClass", "at"];

/// Parses a `.mas2j` text. Returns the project, or every error (a syntax error stops the
/// parse; unsupported constructs are all reported).
pub fn parse_mas2j(file: FileId, text: &str) -> Result<MasProject, Vec<Diagnostic>> {
    let toks = lex(file, text).map_err(|d| vec![d])?;
    let mut p = Parser {
        toks,
        at: 0,
        errors: Vec::new(),
    };
    let mas = p.mas().map_err(|d| vec![d])?;
    let mut errors = p.errors;
    if mas.agents.is_empty() {
        errors.push(
            Diagnostic::error("input", "the project names no agent").with_label(
                Span::new(file, 0, 0),
                "expected `agents:` with at least one agent",
            ),
        );
    }
    let mut seen: Vec<(&str, Span)> = Vec::new();
    for a in &mas.agents {
        if let Some((_, first)) = seen.iter().find(|(n, _)| *n == a.name) {
            errors.push(
                Diagnostic::error("input", format!("agent `{}` is named twice", a.name))
                    .with_label(a.span, "named again here")
                    .with_secondary(*first, "first named here"),
            );
        } else {
            seen.push((&a.name, a.span));
        }
    }
    if errors.is_empty() {
        Ok(mas)
    } else {
        Err(errors)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::SourceMap;

    fn parse(text: &str) -> (SourceMap, Result<MasProject, Vec<Diagnostic>>) {
        let mut map = SourceMap::new();
        let id = map.add("p.mas2j", "p.mas2j", text.to_string());
        let r = parse_mas2j(id, text);
        (map, r)
    }

    fn error(text: &str) -> (String, usize, usize) {
        let (map, r) = parse(text);
        let d = r.expect_err("an error").remove(0);
        let at = d.location(&map).expect("a place");
        (d.message, at.line, at.column)
    }

    #[test]
    fn jasons_examples_read_with_their_agents_files_and_instances() {
        let text = r#"
            /* the house */
            MAS house {
                infrastructure: Centralised
                environment: HouseEnv(gui) at "localhost"
                agents:
                    robot;                   // robot.asl
                    owner owner_agent [verbose=1] #2;
                    sup ./lib/super.txt at "h";
                aslSourcePath: "src/asl"; "lib";
            }"#;
        let (_, r) = parse(text);
        let p = r.expect("parses");
        assert_eq!(p.name, "house");
        assert_eq!(
            p.environment.as_ref().map(|e| e.0.as_str()),
            Some("HouseEnv")
        );
        let got: Vec<(&str, &str, u32)> = p
            .agents
            .iter()
            .map(|a| (a.name.as_str(), a.source.as_str(), a.instances))
            .collect();
        assert_eq!(
            got,
            [
                ("robot", "robot.asl", 1),
                ("owner", "owner_agent.asl", 2),
                ("sup", "./lib/super.txt", 1)
            ]
        );
        assert_eq!(p.source_path, ["src/asl", "lib"]);
        assert_eq!(instance_names(&p.agents[1]), ["owner1", "owner2"]);
        assert_eq!(instance_names(&p.agents[0]), ["robot"]);
    }

    #[test]
    fn syntax_errors_are_located() {
        assert_eq!(
            error("MAS m {\n  agents: a\n}"),
            ("expected `;`, found `}`".into(), 3, 1)
        );
        assert_eq!(
            error("MAS M { }"),
            (
                "expected the MAS's name (lower-case), found `M`".into(),
                1,
                5
            )
        );
        assert_eq!(error("mas m {}").0, "expected `MAS`, found `mas`");
        assert_eq!(
            error("MAS m { agents: a; } x").0,
            "expected the end of the file, found `x`"
        );
        assert_eq!(error("MAS m { agents: a; \"x").0, "unterminated string");
        assert!(error("MAS m { agents: a #0; }").0.contains("from 1 to 64"));
        assert_eq!(
            error("MAS m { agents: a; a; }").0,
            "agent `a` is named twice"
        );
        assert_eq!(error("MAS m { }").0, "the project names no agent");
        assert_eq!(error("MAS m { agents: a; ? }").1, 1);
    }

    #[test]
    fn what_changes_the_reasoning_cycle_is_refused_where_written() {
        let (msg, line, col) = error("MAS m {\n agents: a [events=requeue];\n}");
        assert!(msg.contains("`events=requeue`"), "{msg}");
        assert_eq!((line, col), (2, 13));
        assert!(error("MAS m { agents: a agentClass my.Ag; }")
            .0
            .contains("agentClass my.Ag"));
        assert!(
            error("MAS m { executionControl: jason.control.ExecutionControl agents: a; }")
                .0
                .contains("executionControl")
        );
        assert!(error("MAS m { agents: a [mindinspector=\"gui\"]; }")
            .0
            .contains("mindinspector"));
        // Jason's defaults are accepted.
        let (_, r) = parse("MAS m { agents: a [events=discard, intBels=sameFocus, verbose=2]; }");
        assert!(r.is_ok());
    }
}
