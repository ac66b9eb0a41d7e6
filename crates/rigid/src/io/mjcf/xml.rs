//! MJCF text to an owned element tree, with every `<include file>` replaced by the children of the
//! included file's root element (MuJoCo's `IncludeXML`, `src/xml/xml.cc`), each element
//! remembering its file and line for the messages.
//!
//! An included file is looked up first relative to the main file's folder (MuJoCo's "legacy"
//! rule), then relative to the folder of the file that includes it. A file included twice is an
//! error, as in MuJoCo; when the second inclusion closes a loop the message shows the loop.

use super::MjcfError;
use roxmltree::{Document, Node, ParsingOptions};
use std::path::{Path, PathBuf};

/// At most this many nested `<include>` levels (a loop is caught before; this bounds a chain).
const MAX_INCLUDE_DEPTH: usize = 64;

/// Elements nested deeper than this are refused (the conversion is recursive).
const MAX_DEPTH: usize = 1000;

/// One XML element, owned.
#[derive(Clone, Debug)]
pub(super) struct Element {
    /// The tag name.
    pub tag: String,
    /// Attributes in document order.
    pub attrs: Vec<(String, String)>,
    /// Child elements in document order (includes expanded).
    pub children: Vec<Element>,
    /// Line (1-based) in its file.
    pub line: u32,
    /// Index of its file in [`Sources::files`] (0: the main file).
    pub file: usize,
}

impl Element {
    /// The value of attribute `name`.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// The child elements called `tag`.
    pub fn children_named<'a>(&'a self, tag: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |c| c.tag == tag)
    }
}

/// The files a document was read from: the main file first, then each included file.
#[derive(Clone, Debug, Default)]
pub(super) struct Sources {
    /// Paths as opened (the main file's may be empty for text given directly).
    pub files: Vec<PathBuf>,
    /// The main file's folder (where relative paths start).
    pub dir: PathBuf,
}

impl Sources {
    /// The name of file `i` for a message: `None` for the main file.
    pub fn name(&self, i: usize) -> Option<String> {
        (i > 0).then(|| self.files[i].display().to_string())
    }

    /// The folder of file `i`.
    pub fn folder(&self, i: usize) -> PathBuf {
        if i == 0 {
            return self.dir.clone();
        }
        self.files[i]
            .parent()
            .map_or_else(|| self.dir.clone(), Path::to_path_buf)
    }
}

/// Reads `text` (the main file, in folder `dir`) and the files it includes.
///
/// # Errors
/// Malformed XML (in any file), an `<include>` without `file`, with children, of a file that
/// cannot be read or is included twice (a loop is named as such), or a root element that is not
/// `<mujoco>`.
pub(super) fn read_document(
    text: &str,
    main: Option<&Path>,
    dir: &Path,
) -> Result<(Element, Sources), MjcfError> {
    let mut sources = Sources {
        files: vec![main.map(Path::to_path_buf).unwrap_or_default()],
        dir: dir.to_path_buf(),
    };
    let doc = parse_xml(text, None)?;
    let root = doc.doc.root_element();
    if root.tag_name().name() != "mujoco" {
        return Err(MjcfError::Invalid {
            file: None,
            line: doc.line(root),
            element: format!("<{}>", root.tag_name().name()),
            message: "the root element is not <mujoco> (an MJCF model starts with <mujoco>)".into(),
        });
    }
    let mut chain = vec![0usize];
    let root = convert(&doc, root, 0, &mut sources, &mut chain, 0)?;
    Ok((root, sources))
}

fn parse_xml<'a>(text: &'a str, file: Option<String>) -> Result<Doc<'a>, MjcfError> {
    let opts = ParsingOptions {
        allow_dtd: true,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, opts).map_err(|e| {
        let pos = e.pos();
        MjcfError::Xml {
            file,
            line: pos.row,
            column: pos.col,
            message: e.to_string(),
        }
    })?;
    Ok(Doc {
        doc,
        starts: line_starts(text),
    })
}

/// A parsed file and the byte offsets where its lines start (a line number in O(log n):
/// `Document::text_pos_at` scans from the start, quadratic over a large file).
struct Doc<'a> {
    doc: Document<'a>,
    starts: Vec<usize>,
}

impl Doc<'_> {
    fn line(&self, node: Node) -> u32 {
        let at = node.range().start;
        (self.starts.partition_point(|&s| s <= at) + 1) as u32
    }
}

fn line_starts(text: &str) -> Vec<usize> {
    text.bytes()
        .enumerate()
        .filter(|(_, b)| *b == b'\n')
        .map(|(i, _)| i + 1)
        .collect()
}

/// The owned copy of `node` (an element of file `file`), with its includes expanded. `chain` is
/// the stack of files being included (for the loop message).
fn convert(
    doc: &Doc,
    node: Node,
    file: usize,
    sources: &mut Sources,
    chain: &mut Vec<usize>,
    depth: usize,
) -> Result<Element, MjcfError> {
    if depth > MAX_DEPTH {
        return Err(MjcfError::Invalid {
            file: sources.name(file),
            line: doc.line(node),
            element: format!("<{}>", node.tag_name().name()),
            message: format!("elements nested more than {MAX_DEPTH} deep"),
        });
    }
    let mut out = Element {
        tag: node.tag_name().name().to_string(),
        attrs: node
            .attributes()
            .map(|a| (a.name().to_string(), a.value().to_string()))
            .collect(),
        children: Vec::new(),
        line: doc.line(node),
        file,
    };
    for child in node.children().filter(Node::is_element) {
        if child.tag_name().name() == "include" {
            out.children
                .extend(include(doc, child, file, sources, chain, depth + 1)?);
        } else {
            out.children
                .push(convert(doc, child, file, sources, chain, depth + 1)?);
        }
    }
    Ok(out)
}

/// The elements an `<include>` stands for: the children of the included file's root.
fn include(
    doc: &Doc,
    node: Node,
    file: usize,
    sources: &mut Sources,
    chain: &mut Vec<usize>,
    depth: usize,
) -> Result<Vec<Element>, MjcfError> {
    let line = doc.line(node);
    let err = |sources: &Sources, message: String| MjcfError::Invalid {
        file: sources.name(file),
        line,
        element: "<include>".into(),
        message,
    };
    if node.children().any(|c| c.is_element()) {
        return Err(err(sources, "an <include> cannot have children".into()));
    }
    let Some(name) = node.attribute("file") else {
        return Err(err(sources, "<include> has no \"file\" attribute".into()));
    };
    if chain.len() > MAX_INCLUDE_DEPTH {
        return Err(err(
            sources,
            format!("more than {MAX_INCLUDE_DEPTH} nested includes"),
        ));
    }
    // MuJoCo's order: the main file's folder first, then the including file's.
    let candidates = [sources.dir.join(name), sources.folder(file).join(name)];
    let Some(path) = candidates.iter().find(|p| p.is_file()).cloned() else {
        return Err(err(
            sources,
            format!(
                "included file \"{name}\" not found (looked for {})",
                candidates[0].display()
            ),
        ));
    };
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    };
    if let Some(k) = (0..sources.files.len()).find(|&k| same(&sources.files[k], &path)) {
        let message = if let Some(at) = chain.iter().position(|&c| c == k) {
            let names: Vec<String> = chain[at..]
                .iter()
                .map(|&c| file_label(sources, c))
                .chain(std::iter::once(file_label(sources, k)))
                .collect();
            format!("include loop: {}", names.join(" -> "))
        } else {
            format!("file \"{name}\" is already included (MuJoCo includes a file once)")
        };
        return Err(err(sources, message));
    }
    let text = std::fs::read_to_string(&path).map_err(|e| {
        err(
            sources,
            format!("cannot read included file {}: {e}", path.display()),
        )
    })?;
    sources.files.push(path.clone());
    let index = sources.files.len() - 1;
    let inner = parse_xml(&text, Some(path.display().to_string()))?;
    chain.push(index);
    let root = inner.doc.root_element();
    let mut out = Vec::new();
    for child in root.children().filter(Node::is_element) {
        if child.tag_name().name() == "include" {
            out.extend(include(&inner, child, index, sources, chain, depth + 1)?);
        } else {
            out.push(convert(&inner, child, index, sources, chain, depth + 1)?);
        }
    }
    chain.pop();
    Ok(out)
}

fn file_label(sources: &Sources, i: usize) -> String {
    sources.files[i].file_name().map_or_else(
        || "(main)".to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}
