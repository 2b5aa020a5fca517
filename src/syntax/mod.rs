//! Text to AST: the AgentSpeak front end, diagnostics with spans.
//!
//! [`parse_agent`] turns one `.asl` text into an [`ast::AgentFile`], recovering from errors so
//! that one run reports all of them; [`load_agent`] reads a file from disk and follows its
//! `include` directives. [`printer`] writes a tree back as Jason text.

pub mod ast;
pub mod diagnostic;
pub mod lexer;
pub mod loader;
pub mod manifest;
pub mod mas2j;
pub mod parser;
pub mod pddl;
pub mod printer;
pub mod source;

pub use diagnostic::{Diagnostic, Severity};
pub use loader::{load_agent, Include, LoadedAgent};
pub use parser::{parse_agent, parse_expr};
pub use source::{FileId, Location, SourceMap, Span};
