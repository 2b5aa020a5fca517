//! Located diagnostics, rendered the way rustc and miette do: a headline, `file:line:column`,
//! and an excerpt with a caret under the offending text.

use super::source::{Location, SourceMap, Span};
use std::fmt;

/// How serious a diagnostic is.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The input is rejected.
    Error,
    /// Suspicious but accepted.
    Warning,
    /// For information.
    Note,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        })
    }
}

/// A secondary label: another place that explains the primary one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What to say there.
    pub text: String,
}

/// One message about the input, with where it points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error, warning or note.
    pub severity: Severity,
    /// A stable, machine-readable kind: `syntax`, `input`, `undefined-action`, ...
    pub code: String,
    /// The headline: what is wrong.
    pub message: String,
    /// The place it is about, if it has one (a missing file has none).
    pub span: Option<Span>,
    /// Text under the caret.
    pub label: Option<String>,
    /// Further places.
    pub secondary: Vec<Label>,
    /// How to fix it.
    pub help: Option<String>,
    /// When the diagnostic is not about a span but about a file as a whole.
    pub file: Option<String>,
}

impl Diagnostic {
    /// An error of the given code.
    pub fn error(code: impl Into<String>, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code: code.into(),
            message: message.into(),
            span: None,
            label: None,
            secondary: Vec::new(),
            help: None,
            file: None,
        }
    }

    /// A warning of the given code.
    pub fn warning(code: impl Into<String>, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, message)
        }
    }

    /// A syntax error at `span`: "expected X, found Y".
    pub fn syntax(span: Span, message: impl Into<String>, label: impl Into<String>) -> Diagnostic {
        Diagnostic::error("syntax", message).with_label(span, label)
    }

    /// Points the diagnostic at `span`, with `text` under the caret.
    pub fn with_label(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.span = Some(span);
        let text = text.into();
        self.label = (!text.is_empty()).then_some(text);
        self
    }

    /// Points the diagnostic at `span` with no text under the caret.
    pub fn at(mut self, span: Span) -> Diagnostic {
        self.span = Some(span);
        self
    }

    /// Adds another place.
    pub fn with_secondary(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.secondary.push(Label {
            span,
            text: text.into(),
        });
        self
    }

    /// Adds a hint.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    /// Names the file a span-less diagnostic is about.
    pub fn in_file(mut self, file: impl Into<String>) -> Diagnostic {
        self.file = Some(file.into());
        self
    }

    /// `file:line:column` of the primary span, or the file alone.
    pub fn location(&self, map: &SourceMap) -> Option<Location> {
        match (self.span, &self.file) {
            (Some(span), _) => Some(map.location(span)),
            (None, Some(file)) => Some(Location {
                file: file.clone(),
                line: 1,
                column: 1,
            }),
            (None, None) => None,
        }
    }

    /// Renders the diagnostic: a `file:line:column: severity[code]: message` headline (so that
    /// editors and `grep` find it) followed by miette's excerpt with carets.
    pub fn render(&self, map: &SourceMap, color: bool) -> String {
        let mut out = String::new();
        if let Some(loc) = self.location(map) {
            out.push_str(&format!("{loc}: "));
        }
        out.push_str(&format!(
            "{}[{}]: {}\n",
            paint(&self.severity.to_string(), self.severity, color),
            self.code,
            self.message
        ));
        if let Some(span) = self.span {
            if let Some(file) = map.get(span.file) {
                out.push_str(&render_excerpt(self, map, file, color));
            }
        } else if let Some(help) = &self.help {
            out.push_str(&format!("  help: {help}\n"));
        }
        out
    }
}

/// `text` in the colour of `severity` (bold red, yellow, cyan), when colour is on.
pub fn paint(text: &str, severity: Severity, color: bool) -> String {
    let c = match severity {
        Severity::Error => anstyle::AnsiColor::Red,
        Severity::Warning => anstyle::AnsiColor::Yellow,
        Severity::Note => anstyle::AnsiColor::Cyan,
    };
    bold(text, c, color)
}

/// `text` in bold `c`, when colour is on.
pub fn bold(text: &str, c: anstyle::AnsiColor, color: bool) -> String {
    if !color {
        return text.to_string();
    }
    let style = anstyle::Style::new().bold().fg_color(Some(c.into()));
    format!("{style}{text}{style:#}")
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}[{}]: {}", self.severity, self.code, self.message)
    }
}

/// The miette view of a diagnostic, for its graphical excerpt.
#[derive(Debug)]
struct MietteView<'f> {
    message: String,
    severity: miette::Severity,
    source: Excerpt<'f>,
    labels: Vec<miette::LabeledSpan>,
    help: Option<String>,
}

/// A file as miette reads it for an excerpt: only the lines around a span, found by the
/// file's line index. (miette's own `[u8]` source counts lines from the top of the file
/// for every excerpt, and each report copied the whole file: a library with many findings
/// cost the square of its size.)
#[derive(Debug)]
struct Excerpt<'f>(&'f super::source::SourceFile);

impl miette::SourceCode for Excerpt<'_> {
    fn read_span<'a>(
        &'a self,
        span: &miette::SourceSpan,
        before: usize,
        after: usize,
    ) -> Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        let file = self.0;
        let text = file.text.as_bytes();
        let (start, end) = (span.offset(), span.offset() + span.len());
        if end > text.len() {
            return Err(miette::MietteError::OutOfBounds);
        }
        let (line, _) = file.line_col(start);
        let (last, _) = file.line_col(end);
        // From the start of the first context line to past the last one: the lines
        // miette's reader would see, with every offset and line number kept.
        let first = (line - 1).saturating_sub(before);
        let from = file.line_start(first).unwrap_or(0);
        let to = file.line_start(last + after).unwrap_or(text.len());
        let window = &text[from..to];
        let inner = miette::SourceSpan::new((start - from).into(), span.len());
        let c = window.read_span(&inner, before, after)?;
        let at = miette::SourceSpan::new((c.span().offset() + from).into(), c.span().len());
        Ok(Box::new(miette::MietteSpanContents::new_named(
            file.name.clone(),
            c.data(),
            at,
            c.line() + first,
            c.column(),
            c.line_count(),
        )))
    }
}

impl fmt::Display for MietteView<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for MietteView<'_> {}

impl miette::Diagnostic for MietteView<'_> {
    fn severity(&self) -> Option<miette::Severity> {
        Some(self.severity)
    }
    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn fmt::Display + 'a>)
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        Some(&self.source)
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        Some(Box::new(self.labels.iter().cloned()))
    }
}

fn render_excerpt(
    d: &Diagnostic,
    map: &SourceMap,
    file: &super::source::SourceFile,
    color: bool,
) -> String {
    let clamp = |s: Span| {
        let start = (s.start as usize).min(file.text.len());
        let end = (s.end as usize).clamp(start, file.text.len());
        (start, end - start)
    };
    let mut labels = Vec::new();
    if let Some(span) = d.span {
        labels.push(miette::LabeledSpan::new_primary_with_span(
            d.label.clone(),
            clamp(span),
        ));
    }
    // Secondary labels in other files cannot share one excerpt; they are listed as notes.
    let mut elsewhere = String::new();
    for l in &d.secondary {
        if l.span.file == file.id {
            labels.push(miette::LabeledSpan::new_with_span(
                Some(l.text.clone()),
                clamp(l.span),
            ));
        } else {
            elsewhere.push_str(&format!("  note: {}: {}\n", map.location(l.span), l.text));
        }
    }
    let view = MietteView {
        message: d.message.clone(),
        severity: match d.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
            Severity::Note => miette::Severity::Advice,
        },
        source: Excerpt(file),
        labels,
        help: d.help.clone(),
    };
    let theme = if color {
        miette::GraphicalTheme::unicode()
    } else {
        miette::GraphicalTheme::unicode_nocolor()
    };
    let handler = miette::GraphicalReportHandler::new_themed(theme)
        .with_context_lines(1)
        .with_width(100);
    let mut out = String::new();
    if handler.render_report(&mut out, &view).is_err() {
        out.clear();
    }
    // The headline is already printed by `render` (miette may wrap it over several lines):
    // keep miette's excerpt, which starts with the box's top-left corner.
    let excerpt: Vec<&str> = out.lines().skip_while(|l| !l.contains('╭')).collect();
    let mut s = excerpt.join("\n");
    if excerpt.is_empty() {
        if let Some(help) = &d.help {
            s.push_str(&format!("  help: {help}"));
        }
    }
    s.push('\n');
    s.push_str(&elsewhere);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_names_file_line_column_and_shows_caret() {
        let mut map = SourceMap::new();
        let id = map.add("x.asl", "x.asl", "+!g <- a(.\n".to_string());
        let d = Diagnostic::syntax(Span::new(id, 9, 10), "expected a term, found `.`", "here");
        let text = d.render(&map, false);
        assert!(
            text.starts_with("x.asl:1:10: error[syntax]: expected a term"),
            "{text}"
        );
        assert!(text.contains("+!g <- a(."), "{text}");
        assert!(text.contains("here"), "{text}");
    }
}
