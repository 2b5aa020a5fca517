//! Reading `.asl` files from disk and following `{ include("file.asl") }` directives.
//!
//! An include is resolved relative to the directory of the file that contains it, as Jason
//! does. A missing file is an error located at the directive; a file that includes itself,
//! directly or through others, is an error at the directive that closes the cycle.

use super::ast::{AgentFile, Directive, ExprKind, Item};
use super::diagnostic::Diagnostic;
use super::parser::parse_agent;
use super::source::{FileId, SourceMap, Span};
use std::path::{Path, PathBuf};

/// An agent read from disk: its root file and every file it includes, parsed.
#[derive(Clone, Debug)]
pub struct LoadedAgent {
    /// The file named on the command line (or in the manifest).
    pub root: FileId,
    /// Every parsed file, the root first, then includes in the order they were met.
    pub files: Vec<(FileId, AgentFile)>,
    /// Each `include` directive and the file it brought in.
    pub included: Vec<Include>,
}

/// One resolved `{ include("file.asl") }` or `{ include("file.asl", ns) }`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Include {
    /// The directive's span.
    pub directive: Span,
    /// The file it brought in.
    pub file: FileId,
    /// The namespace its items are put in, when the directive names one.
    pub namespace: Option<String>,
}

impl LoadedAgent {
    /// The parsed tree of one file.
    pub fn file(&self, id: FileId) -> Option<&AgentFile> {
        self.files.iter().find(|(f, _)| *f == id).map(|(_, a)| a)
    }

    /// Every item of the agent in Jason's order: an `include` directive stands for the items
    /// of the included file, at the directive's place; the items of a `begin ... end` block
    /// stand at the block's place.
    pub fn items(&self) -> Vec<&Item> {
        let mut out = Vec::new();
        if let Some(root) = self.file(self.root) {
            self.collect(&root.items, &mut out, 0);
        }
        out
    }

    fn collect<'a>(&'a self, items: &'a [Item], out: &mut Vec<&'a Item>, depth: usize) {
        for item in items {
            match item {
                Item::Directive(d) if d.block.is_some() => {
                    if let Some(block) = &d.block {
                        self.collect(block, out, depth);
                    }
                }
                Item::Directive(d) if d.name == "include" => {
                    // Include cycles were refused at load time; the bound is a second guard.
                    if let Some(id) = self
                        .included
                        .iter()
                        .find(|i| i.directive == d.span)
                        .map(|i| i.file)
                    {
                        if let Some(file) = self.file(id) {
                            if depth < 64 {
                                self.collect(&file.items, out, depth + 1);
                            }
                        }
                    }
                }
                other => out.push(other),
            }
        }
    }
}

/// Reads `path`, parses it and every file it includes. Returns the agent, or every
/// diagnostic met (syntax errors in any file, missing or cyclic includes).
pub fn load_agent(path: &Path, map: &mut SourceMap) -> Result<LoadedAgent, Vec<Diagnostic>> {
    load_agent_with(path, map, &[])
}

/// [`load_agent`] with a source path: an `include` that names no file beside the file
/// that includes it is looked for in these folders, in order (Jason's `aslSourcePath`,
/// `SourcePath.fixPath`).
pub fn load_agent_with(
    path: &Path,
    map: &mut SourceMap,
    source_path: &[PathBuf],
) -> Result<LoadedAgent, Vec<Diagnostic>> {
    let text = match crate::syntax::source::read_input(path) {
        Ok(t) => t,
        Err(e) => {
            return Err(vec![Diagnostic::error(
                "input",
                format!("cannot read `{}`: {e}", path.display()),
            )
            .in_file(path.display().to_string())])
        }
    };
    let root = map.add(path, path.display().to_string(), text);
    let mut loader = Loader {
        map,
        files: Vec::new(),
        included: Vec::new(),
        errors: Vec::new(),
        source_path,
    };
    loader.parse_file(root, &mut vec![canonical(path)]);
    if loader.errors.is_empty() {
        Ok(LoadedAgent {
            root,
            files: loader.files,
            included: loader.included,
        })
    } else {
        Err(loader.errors)
    }
}

struct Loader<'m> {
    map: &'m mut SourceMap,
    files: Vec<(FileId, AgentFile)>,
    included: Vec<Include>,
    errors: Vec<Diagnostic>,
    source_path: &'m [PathBuf],
}

fn canonical(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| p.to_path_buf())
}

impl Loader<'_> {
    fn parse_file(&mut self, id: FileId, stack: &mut Vec<PathBuf>) {
        let (ast, errs) = parse_agent(id, &self.map.file(id).text.clone());
        self.errors.extend(errs);
        let dir = self
            .map
            .file(id)
            .path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut includes = Vec::new();
        collect_includes(&ast.items, &mut includes);
        self.files.push((id, ast));
        for d in includes {
            self.include(&d, &dir, stack);
        }
    }

    fn include(&mut self, d: &Directive, dir: &Path, stack: &mut Vec<PathBuf>) {
        let (file_arg, ns_arg) = match d.args.as_slice() {
            [f] => (f, None),
            [f, ns] => (f, Some(ns)),
            _ => {
                self.errors.push(
                    Diagnostic::error(
                        "input",
                        "`include` expects a file name and an optional namespace",
                    )
                    .with_label(
                        d.span,
                        "expected `{ include(\"file.asl\") }` or `{ include(\"file.asl\", ns) }`",
                    ),
                );
                return;
            }
        };
        let name = match &file_arg.kind {
            ExprKind::Str(s) => s.clone(),
            _ => {
                self.errors.push(
                    Diagnostic::error("input", "`include` expects a file name in a string")
                        .with_label(file_arg.span, "expected a string such as \"plans.asl\""),
                );
                return;
            }
        };
        let namespace = match ns_arg.map(|e| &e.kind) {
            None => None,
            Some(ExprKind::Literal(l)) if l.args.is_empty() && l.annots.is_none() => {
                Some(l.functor.clone())
            }
            Some(_) => {
                let span = ns_arg.map_or(d.span, |e| e.span);
                self.errors.push(
                    Diagnostic::error("input", "the namespace of an `include` must be an atom")
                        .with_label(span, "expected a namespace name such as `hall`"),
                );
                return;
            }
        };
        // `$jasonJar/f` names `f` inside Jason's jar (`SourcePath.fixPath`): bdi-check
        // reads no jar, so it looks for `f` along the source path only.
        let in_jar = name.strip_prefix("$jasonJar/");
        let beside = dir.join(in_jar.unwrap_or(&name));
        let path = if in_jar.is_none() && (beside.is_file() || Path::new(&name).is_absolute()) {
            beside
        } else if let Some(f) = in_jar {
            match self
                .source_path
                .iter()
                .map(|p| p.join(f))
                .find(|p| p.is_file())
            {
                Some(p) => p,
                None => {
                    self.errors.push(
                        Diagnostic::error(
                            "input",
                            format!("cannot include `{name}`: it is a file of Jason's jar, which bdi-check does not read"),
                        )
                        .with_label(d.span, "included here")
                        .with_help(format!(
                            "put the folder that holds `{f}` (Jason's `src/main/resources`, say) in `[agent] source_path` or `parse -I DIR`"
                        )),
                    );
                    return;
                }
            }
        } else {
            match self
                .source_path
                .iter()
                .map(|p| p.join(&name))
                .find(|p| p.is_file())
            {
                Some(p) => p,
                None => {
                    let tried: Vec<String> = std::iter::once(dir.to_path_buf())
                        .chain(self.source_path.iter().cloned())
                        .map(|p| format!("`{}`", p.display()))
                        .collect();
                    self.errors.push(
                        Diagnostic::error("input", format!("cannot include `{name}`: no such file"))
                            .with_label(d.span, "included here")
                            .with_help(format!(
                                "looked in {}; add its folder to `[agent] source_path` (or `parse -I DIR`)",
                                tried.join(", ")
                            )),
                    );
                    return;
                }
            }
        };
        if !path.is_file() {
            self.errors.push(
                Diagnostic::error(
                    "input",
                    format!("cannot include `{name}`: not a regular file"),
                )
                .with_label(d.span, "included here"),
            );
            return;
        }
        let canon = canonical(&path);
        if stack.contains(&canon) {
            self.errors.push(
                Diagnostic::error("input", format!("`{name}` includes itself"))
                    .with_label(d.span, "this include closes a cycle"),
            );
            return;
        }
        // A file included twice (not in a cycle) is parsed once.
        if let Some(file) = self.map.find_path(&path) {
            self.included.push(Include {
                directive: d.span,
                file,
                namespace,
            });
            return;
        }
        let text = match crate::syntax::source::read_input(&path) {
            Ok(t) => t,
            Err(e) => {
                self.errors.push(
                    Diagnostic::error("input", format!("cannot include `{}`: {e}", path.display()))
                        .with_label(d.span, "included here"),
                );
                return;
            }
        };
        let id = self.map.add(&path, path.display().to_string(), text);
        self.included.push(Include {
            directive: d.span,
            file: id,
            namespace,
        });
        stack.push(canon);
        self.parse_file(id, stack);
        stack.pop();
    }
}

fn collect_includes(items: &[Item], out: &mut Vec<Directive>) {
    for item in items {
        if let Item::Directive(d) = item {
            match &d.block {
                Some(block) => collect_includes(block, out),
                None if d.name == "include" => out.push(d.clone()),
                None => {}
            }
        }
    }
}
