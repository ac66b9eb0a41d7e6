//! URDF text to [`UrdfRobot`]: XML with `roxmltree`, then every element and the tree checked.

use super::elements::{is, Parser, ROBOT_CHILDREN};
use super::{UrdfError, UrdfJoint, UrdfLink, UrdfRobot};
use roxmltree::{Document, ParsingOptions};
use std::collections::HashMap;
use std::path::Path;

/// Reads and checks a URDF file. A missing `<robot name>` becomes the file's stem.
///
/// # Errors
/// [`UrdfError::Io`] if the file cannot be read, else as [`parse_urdf_str`].
pub fn parse_urdf_file(path: impl AsRef<Path>) -> Result<UrdfRobot, UrdfError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| UrdfError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let mut robot = parse_urdf_str(&text)?;
    if robot.name.is_empty() {
        robot.name = path
            .file_stem()
            .map_or_else(|| "robot".into(), |s| s.to_string_lossy().into_owned());
    }
    robot.path = Some(path.to_path_buf());
    Ok(robot)
}

/// Parses and checks URDF text: well-formed XML, every element and attribute, the tree (one root,
/// no cycle, one parent per link). The inertias' physical validity is checked by
/// [`UrdfRobot::inertia_report`] and when the model is built.
///
/// Tolerated, with a warning in [`UrdfRobot::warnings`]: a `<robot>` without a name (the model
/// is called `robot`), an XML declaration after a blank line (as tinyxml2 reads it), a `<limit>`
/// with `lower > upper` (no position limit, as urdfdom loads it), unknown elements, a mimic of a joint that is not defined (mimic joints are
/// imported as independent joints anyway), an `<inertial>` without `<mass>` or `<inertia>`
/// (zero), and a `<visual>` or `<collision>` whose geometry cannot be read (skipped).
///
/// ```
/// let robot = rigid::io::urdf::parse_urdf_str(
///     r#"<robot name="r"><link name="a"/><link name="b"/>
///        <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"#,
/// ).unwrap();
/// assert_eq!(robot.links[robot.root].name, "a");
/// assert_eq!(robot.joints[0].axis, rigid::spatial::Vec3::x());
/// assert!(robot.warnings.is_empty());
/// ```
///
/// # Errors
/// A [`UrdfError`] naming the link or joint and the line.
pub fn parse_urdf_str(text: &str) -> Result<UrdfRobot, UrdfError> {
    // tinyxml2 (urdfdom) reads an XML declaration that does not stand at the very start (after a
    // blank line); the XML standard and roxmltree do not: blank it out (same length, so that lines
    // and byte spans hold) and warn
    let (blanked, declaration_line) = blank_misplaced_declaration(text);
    let text = blanked.as_deref().unwrap_or(text);
    // urdfdom (TinyXML) ignores XML namespaces, so files with undeclared prefixes such as
    // Drake's `<drake:joint>` load in other tools: declare each such prefix on the root element
    // (same line, so line numbers hold) and warn.
    let mut owned: Option<String> = None;
    let mut inserted = 0usize;
    let mut undeclared: Vec<String> = Vec::new();
    let doc = loop {
        let src = owned.as_deref().unwrap_or(text);
        let opts = ParsingOptions {
            allow_dtd: true,
            ..ParsingOptions::default()
        };
        match Document::parse_with_options(src, opts) {
            Ok(_) => break src,
            Err(roxmltree::Error::UnknownNamespace(prefix, _))
                if undeclared.len() < 16 && !undeclared.contains(&prefix) =>
            {
                let Some(at) = root_tag_end(src) else {
                    return Err(xml_error(&roxmltree::Error::UnknownNamespace(
                        prefix,
                        roxmltree::TextPos::new(1, 1),
                    )));
                };
                let decl = format!(" xmlns:{prefix}=\"urn:rigid:undeclared:{prefix}\"");
                let mut t = src.to_string();
                t.insert_str(at, &decl);
                inserted += decl.len();
                undeclared.push(prefix);
                owned = Some(t);
            }
            Err(e) => return Err(xml_error(&e)),
        }
    };
    let doc = Document::parse_with_options(
        doc,
        ParsingOptions {
            allow_dtd: true,
            ..ParsingOptions::default()
        },
    )
    .map_err(|e| xml_error(&e))?;
    let mut p = Parser {
        warnings: Vec::new(),
        materials: HashMap::new(),
        line_starts: Parser::line_starts(doc.input_text()),
    };
    let root = doc.root_element();
    if !is(&root, "robot") {
        return Err(p.invalid(
            root,
            "document".into(),
            format!(
                "the root element is <{}>, expected <robot>",
                root.tag_name().name()
            ),
        ));
    }
    let name = match root.attribute("name") {
        Some(n) => n.to_string(),
        None => {
            let msg = "<robot> has no \"name\" attribute; the model is named after the file \
                       (or \"robot\")"
                .into();
            p.warn(root, "robot".into(), msg);
            String::new()
        }
    };
    p.warn_unknown_children(root, "robot", ROBOT_CHILDREN);
    for node in root.children().filter(|n| is(n, "material")) {
        p.material(node);
    }

    let mut links = Vec::new();
    let mut link_index: HashMap<String, usize> = HashMap::new();
    for node in root.children().filter(|n| is(n, "link")) {
        let link = p.link(node)?;
        if let Some(&first) = link_index.get(&link.name) {
            let first: &UrdfLink = &links[first];
            return Err(p.invalid(
                node,
                format!("link \"{}\"", link.name),
                format!("duplicate link name (first defined at line {})", first.line),
            ));
        }
        link_index.insert(link.name.clone(), links.len());
        links.push(link);
    }
    if links.is_empty() {
        return Err(p.invalid(root, "robot".into(), "no <link> element".into()));
    }

    let mut joints: Vec<UrdfJoint> = Vec::new();
    let mut joint_index: HashMap<String, usize> = HashMap::new();
    let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
    for node in root.children().filter(|n| is(n, "joint")) {
        let joint = p.joint(node, &link_index)?;
        let what = || format!("joint \"{}\"", joint.name);
        if let Some(&first) = joint_index.get(&joint.name) {
            let msg = format!(
                "duplicate joint name (first defined at line {})",
                joints[first].line
            );
            return Err(p.invalid(node, what(), msg));
        }
        if joint.parent == joint.child {
            let msg = format!(
                "cycle: link \"{}\" is its own parent",
                links[joint.child].name
            );
            return Err(p.invalid(node, what(), msg));
        }
        if let Some(other) = parent_joint[joint.child] {
            let other = &joints[other];
            let msg = format!(
                "link \"{}\" has two parents: joint \"{}\" (line {}) and this joint",
                links[joint.child].name, other.name, other.line
            );
            return Err(p.invalid(node, what(), msg));
        }
        parent_joint[joint.child] = Some(joints.len());
        joint_index.insert(joint.name.clone(), joints.len());
        joints.push(joint);
    }

    for joint in &mut joints {
        let Some(m) = &joint.mimic else { continue };
        let element = format!("joint \"{}\"", joint.name);
        if joint.name == m.joint {
            return Err(UrdfError::Invalid {
                line: joint.line,
                element,
                message: "mimics itself".into(),
            });
        }
        if !joint_index.contains_key(&m.joint) {
            p.warnings.push(super::UrdfWarning {
                line: joint.line,
                element,
                message: format!(
                    "mimics joint \"{}\", which is not defined: the mimic is ignored (mimic \
                     joints are imported as independent joints)",
                    m.joint
                ),
            });
            joint.mimic = None;
        }
    }

    // A chain of mimics that comes back to itself defines no joint: refuse it.
    for start in 0..joints.len() {
        let mut seen = vec![start];
        let mut cur = start;
        while let Some(next) = joints[cur]
            .mimic
            .as_ref()
            .and_then(|m| joint_index.get(&m.joint).copied())
        {
            if next == start {
                let names: Vec<&str> = seen.iter().map(|&j| joints[j].name.as_str()).collect();
                let j = &joints[start];
                return Err(UrdfError::Invalid {
                    line: j.line,
                    element: format!("joint \"{}\"", j.name),
                    message: format!("mimic loop: {} -> {}", names.join(" -> "), j.name),
                });
            }
            if seen.contains(&next) {
                break; // a loop not through `start`: reported from one of its joints
            }
            seen.push(next);
            cur = next;
        }
    }

    let roots: Vec<usize> = (0..links.len())
        .filter(|&l| parent_joint[l].is_none())
        .collect();
    let root_link = match roots.as_slice() {
        [r] => *r,
        [] => {
            // Every link has a parent: the joints close a loop.
            let j = &joints[0];
            return Err(UrdfError::Invalid {
                line: j.line,
                element: format!("joint \"{}\"", j.name),
                message: "cycle: every link has a parent joint, so there is no root link".into(),
            });
        }
        many => {
            let names: Vec<String> = many
                .iter()
                .map(|&l| format!("\"{}\" (line {})", links[l].name, links[l].line))
                .collect();
            let l = &links[many[1]];
            return Err(UrdfError::Invalid {
                line: l.line,
                element: format!("link \"{}\"", l.name),
                message: format!(
                    "no unique root: {} links have no parent joint: {}",
                    many.len(),
                    names.join(", ")
                ),
            });
        }
    };

    let mut children = vec![Vec::new(); links.len()];
    for (j, joint) in joints.iter().enumerate() {
        children[joint.parent].push(j);
    }
    // Links not reached from the root have one parent each yet no path to the root: they sit on
    // a cycle (or hang below one).
    let mut reached = vec![false; links.len()];
    let mut stack = vec![root_link];
    while let Some(l) = stack.pop() {
        reached[l] = true;
        stack.extend(children[l].iter().map(|&j| joints[j].child));
    }
    if let Some(l) = (0..links.len()).find(|&l| !reached[l]) {
        // Walk up the parents from `l` until a link repeats: that joint closes the cycle.
        let mut seen = vec![false; links.len()];
        let mut cur = l;
        while !seen[cur] {
            seen[cur] = true;
            cur = parent_joint[cur].map_or(cur, |j| joints[j].parent);
        }
        let j = &joints[parent_joint[cur].unwrap_or(0)];
        return Err(UrdfError::Invalid {
            line: j.line,
            element: format!("joint \"{}\"", j.name),
            message: format!(
                "cycle: link \"{}\" is its own ancestor (not reachable from the root link \"{}\")",
                links[cur].name, links[root_link].name
            ),
        });
    }

    let mut warnings = p.warnings;
    if let Some(line) = declaration_line {
        warnings.push(super::UrdfWarning {
            line,
            element: "document".into(),
            message: "the XML declaration does not stand at the start of the file; read anyway, \
                      as tinyxml2 (urdfdom) does"
                .into(),
        });
    }
    for prefix in &undeclared {
        warnings.push(super::UrdfWarning {
            line: 1,
            element: "robot".into(),
            message: format!(
                "XML namespace prefix \"{prefix}\" is used but not declared: its elements are \
                 ignored, as other URDF parsers do"
            ),
        });
    }
    warnings.sort_by_key(|w| w.line);
    // Byte spans refer to the text as given, before the declarations were inserted.
    for link in &mut links {
        if let Some(i) = &mut link.inertial {
            i.span = i.span.start - inserted..i.span.end - inserted;
        }
    }
    Ok(UrdfRobot {
        name,
        path: None,
        links,
        joints,
        root: root_link,
        children,
        warnings,
    })
}

/// `text` with an XML declaration that follows only whitespace replaced by as many spaces, and the
/// declaration's line; `(None, None)` when there is none to blank.
fn blank_misplaced_declaration(text: &str) -> (Option<String>, Option<u32>) {
    let start = text.len() - text.trim_start().len();
    if start == 0 || !text[start..].starts_with("<?xml") {
        return (None, None);
    }
    let Some(len) = text[start..].find("?>") else {
        return (None, None);
    };
    let end = start + len + 2;
    let mut out = String::with_capacity(text.len());
    out.push_str(&text[..start]);
    out.extend(
        text[start..end]
            .chars()
            .map(|c| if c == '\n' { '\n' } else { ' ' }),
    );
    out.push_str(&text[end..]);
    // the spaces replace characters one for one: a multi-byte character in the declaration would
    // shift the byte spans, so keep the text as it was then
    if out.len() != text.len() {
        return (None, None);
    }
    let line = text[..start].matches('\n').count() as u32 + 1;
    (Some(out), Some(line))
}

/// The byte offset just after the root element's tag name (`<robot`), where attributes may be
/// inserted.
fn root_tag_end(text: &str) -> Option<usize> {
    let mut rest = 0;
    loop {
        let i = rest + text[rest..].find('<')?;
        let after = &text[i + 1..];
        if after.starts_with('?') || after.starts_with('!') {
            // declaration, comment, DOCTYPE: skip to its end
            let end = if after.starts_with("!--") {
                after.find("-->")? + 3
            } else {
                after.find('>')? + 1
            };
            rest = i + 1 + end;
            continue;
        }
        let name_len = after
            .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
            .unwrap_or(after.len());
        return Some(i + 1 + name_len);
    }
}

fn xml_error(e: &roxmltree::Error) -> UrdfError {
    let pos = e.pos();
    UrdfError::Xml {
        line: pos.row,
        column: pos.col,
        message: e.to_string(),
    }
}
