//! SRDF files (MoveIt's semantic robot description, read by Pinocchio's `removeCollisionPairs`
//! and `loadReferenceConfigurations`): the pairs of links whose collisions are disabled, and the
//! named configurations (`<group_state>`).

use std::path::Path;

/// What rigid reads of an SRDF file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Srdf {
    /// `<disable_collisions link1 link2>`: the two links, and the element's line.
    pub disabled: Vec<(String, String, u32)>,
    /// `<group_state name group>`, in file order.
    pub group_states: Vec<GroupState>,
}

/// A named configuration: `<group_state name group>` with its `<joint name value>` elements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroupState {
    /// `name` (`half_sitting`, `standing`).
    pub name: String,
    /// `group`.
    pub group: String,
    /// Each `<joint name value>`: the joint and its values (one per coordinate, several for a
    /// free-flyer or a ball joint, quaternions x, y, z, w as Pinocchio reads them).
    pub joints: Vec<(String, Vec<f64>)>,
}

/// An SRDF element that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum SrdfError {
    /// The file cannot be read or is not XML.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What failed.
        message: String,
    },
    /// An element without an attribute it needs, or with a value that is not a number.
    #[error("{path}: <{element}> (line {line}): {message}")]
    Element {
        /// The file.
        path: String,
        /// The element's tag.
        element: String,
        /// Its line.
        line: u32,
        /// What is wrong.
        message: String,
    },
}

/// Reads the SRDF file at `path`.
///
/// ```
/// let path = std::env::temp_dir().join("rigid_doc_srdf.srdf");
/// std::fs::write(&path, r#"<robot name="r">
///   <group_state name="home" group="all"><joint name="j1" value="0.5"/></group_state>
///   <disable_collisions link1="a" link2="b" reason="Adjacent"/>
/// </robot>"#).unwrap();
/// let s = rigid::io::srdf::read_srdf(&path).unwrap();
/// assert_eq!(s.disabled[0].0, "a");
/// assert_eq!(s.group_states[0].joints, vec![("j1".to_string(), vec![0.5])]);
/// ```
///
/// # Errors
/// [`SrdfError`]: the file cannot be read or parsed, a `<disable_collisions>` without `link1` or
/// `link2`, a `<group_state>` or its `<joint>` without `name`, a `value` that is not numbers.
pub fn read_srdf(path: &Path) -> Result<Srdf, SrdfError> {
    let shown = path.display().to_string();
    let file = |message: String| SrdfError::File {
        path: shown.clone(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| file(e.to_string()))?;
    let doc = roxmltree::Document::parse(&text).map_err(|e| file(e.to_string()))?;
    let mut out = Srdf::default();
    for e in doc.descendants().filter(roxmltree::Node::is_element) {
        let line = doc.text_pos_at(e.range().start).row;
        let fail = |e: roxmltree::Node<'_, '_>, message: String| SrdfError::Element {
            path: shown.clone(),
            element: e.tag_name().name().to_string(),
            line: doc.text_pos_at(e.range().start).row,
            message,
        };
        let need = |e: roxmltree::Node<'_, '_>, key: &str| {
            e.attribute(key)
                .map(str::to_string)
                .ok_or_else(|| fail(e, format!("needs \"{key}\"")))
        };
        match e.tag_name().name() {
            "disable_collisions" => {
                out.disabled
                    .push((need(e, "link1")?, need(e, "link2")?, line));
            }
            "group_state" => {
                let mut state = GroupState {
                    name: need(e, "name")?,
                    group: e.attribute("group").unwrap_or_default().to_string(),
                    joints: Vec::new(),
                };
                for j in e.children().filter(|c| c.has_tag_name("joint")) {
                    let value = need(j, "value")?;
                    let values = value
                        .split_whitespace()
                        .map(str::parse::<f64>)
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(|_| fail(j, format!("value \"{value}\" is not numbers")))?;
                    state.joints.push((need(j, "name")?, values));
                }
                out.group_states.push(state);
            }
            _ => {}
        }
    }
    Ok(out)
}
