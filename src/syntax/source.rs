//! Source files and spans.
//!
//! Every AST node carries a [`Span`]: a byte range in one file of a [`SourceMap`]. Spans are
//! turned into `file:line:column` only when something is reported, so the parser stays cheap.

use std::path::{Path, PathBuf};

/// Index of a file in a [`SourceMap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

impl FileId {
    /// The plans every Jason agent has for the messages it receives ([`KQML_PLANS`]): a
    /// file of bdi-check's own that every map resolves, though no project holds it.
    pub const KQML: FileId = FileId(u32::MAX);
}

/// bdi-check's rendering of the plans Jason 3 gives every agent for the performatives its
/// reasoning cycle does not take by a shortcut (Jason's `kqmlPlans.asl`).
pub const KQML_PLANS: &str = include_str!("builtin/kqml.asl");

/// The file [`FileId::KQML`] names.
fn kqml_file() -> &'static SourceFile {
    static FILE: std::sync::OnceLock<SourceFile> = std::sync::OnceLock::new();
    FILE.get_or_init(|| {
        SourceFile::new(
            FileId::KQML,
            "kqmlPlans.asl",
            "kqmlPlans.asl",
            KQML_PLANS.into(),
        )
    })
}

/// A byte range `start..end` in one source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file the range is in.
    pub file: FileId,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

impl Span {
    /// A span in `file` from byte `start` to byte `end`.
    pub fn new(file: FileId, start: usize, end: usize) -> Span {
        Span {
            file,
            start: start as u32,
            end: end.max(start) as u32,
        }
    }

    /// The smallest span covering `self` and `other` (both must be in the same file).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    /// The empty span at the start of `self`.
    pub fn shrink_to_start(self) -> Span {
        Span {
            end: self.start,
            ..self
        }
    }

    /// Length in bytes.
    pub fn len(self) -> usize {
        (self.end - self.start) as usize
    }

    /// Whether the span covers no byte.
    pub fn is_empty(self) -> bool {
        self.start == self.end
    }
}

/// A resolved, human-readable position: 1-based line and column (in characters).
#[derive(
    Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct Location {
    /// The file's display name (as given on the command line or relative to the project).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// One loaded source file.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// Its id in the map.
    pub id: FileId,
    /// Where it was read from.
    pub path: PathBuf,
    /// How reports name it.
    pub name: String,
    /// Its full text.
    pub text: String,
    line_starts: Vec<usize>,
}

impl SourceFile {
    fn new(
        id: FileId,
        path: impl AsRef<Path>,
        name: impl Into<String>,
        text: String,
    ) -> SourceFile {
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        SourceFile {
            id,
            path: path.as_ref().to_path_buf(),
            name: name.into(),
            text,
            line_starts,
        }
    }

    /// 1-based (line, column) of a byte offset; the column counts characters.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.line_starts[line];
        let col = self
            .text
            .get(start..offset)
            .map_or(offset - start, |s| s.chars().count());
        (line + 1, col + 1)
    }

    /// Where the 0-based line `line` starts, if the file has it.
    pub fn line_start(&self, line: usize) -> Option<usize> {
        self.line_starts.get(line).copied()
    }

    /// The text of a span (empty when the span is not on a char boundary).
    pub fn slice(&self, span: Span) -> &str {
        self.text
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }
}

/// All files of one run, so that spans from included files resolve too.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    /// Adds a file's text under a display name and returns its id.
    pub fn add(&mut self, path: impl AsRef<Path>, name: impl Into<String>, text: String) -> FileId {
        let id = FileId(self.files.len() as u32);
        self.files.push(SourceFile::new(id, path, name, text));
        id
    }

    /// The file with this id.
    ///
    /// # Panics
    /// When the id does not come from this map.
    pub fn file(&self, id: FileId) -> &SourceFile {
        self.get(id).expect("a file of this map")
    }

    /// The file with this id, if it is in the map (or is [`FileId::KQML`]).
    pub fn get(&self, id: FileId) -> Option<&SourceFile> {
        if id == FileId::KQML {
            return Some(kqml_file());
        }
        self.files.get(id.0 as usize)
    }

    /// Every file, in the order they were added ([`FileId::KQML`] is none of them).
    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// The id of a file already loaded from `path`, if any.
    pub fn find_path(&self, path: &Path) -> Option<FileId> {
        self.files.iter().find(|f| f.path == path).map(|f| f.id)
    }

    /// `file:line:column` of the start of a span.
    pub fn location(&self, span: Span) -> Location {
        match self.get(span.file) {
            Some(f) => {
                let (line, column) = f.line_col(span.start as usize);
                Location {
                    file: f.name.clone(),
                    line,
                    column,
                }
            }
            None => Location {
                file: "<unknown>".into(),
                line: 1,
                column: 1,
            },
        }
    }

    /// The source text a span covers.
    pub fn slice(&self, span: Span) -> &str {
        self.get(span.file).map_or("", |f| f.slice(span))
    }
}

/// The largest input file bdi-check reads (agents, domains, manifests, scenarios, reports).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// Reads a text input: a regular file of at most [`MAX_INPUT_BYTES`]. A device, a pipe or
/// a folder (`/dev/zero`, say) is refused before any byte is read, so no input is read
/// without bound.
pub fn read_input(path: &Path) -> std::io::Result<String> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::other("it is not a regular file"));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(std::io::Error::other(format!(
            "it holds {} bytes, more than bdi-check reads ({} MiB)",
            meta.len(),
            MAX_INPUT_BYTES >> 20
        )));
    }
    std::fs::read_to_string(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_are_one_based_and_count_chars() {
        let mut map = SourceMap::new();
        let id = map.add("a.asl", "a.asl", "ab\ncé d\n".to_string());
        let f = map.file(id);
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(3), (2, 1));
        // 'é' is two bytes but one column.
        assert_eq!(f.line_col(6), (2, 3));
        assert_eq!(map.location(Span::new(id, 6, 7)).to_string(), "a.asl:2:3");
    }
}
