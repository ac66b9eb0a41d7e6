//! URDF text to [`UrdfRobot`]: XML with `roxmltree`, then every element and the tree checked.

use super::{
    UrdfError, UrdfInertial, UrdfJoint, UrdfJointKind, UrdfLimit, UrdfLink, UrdfMimic, UrdfRobot,
};
use crate::mass::RotationalInertia;
use crate::spatial::{Transform, Vec3};
use roxmltree::{Document, Node, ParsingOptions};
use std::collections::HashMap;
use std::path::Path;

/// Reads and checks a URDF file.
///
/// # Errors
/// [`UrdfError::Io`] if the file cannot be read, else as [`parse_urdf_str`].
pub fn parse_urdf_file(path: impl AsRef<Path>) -> Result<UrdfRobot, UrdfError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| UrdfError::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse_urdf_str(&text)
}

/// Parses and checks URDF text: well-formed XML, every element and attribute, the tree (one root,
/// no cycle, one parent per link). The inertias' physical validity is checked by
/// [`UrdfRobot::inertia_report`] and when the model is built.
///
/// ```
/// let robot = rigid::io::urdf::parse_urdf_str(
///     r#"<robot name="r"><link name="a"/><link name="b"/>
///        <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"#,
/// ).unwrap();
/// assert_eq!(robot.links[robot.root].name, "a");
/// assert_eq!(robot.joints[0].axis, rigid::spatial::Vec3::x());
/// ```
///
/// # Errors
/// A [`UrdfError`] naming the link or joint and the line.
pub fn parse_urdf_str(text: &str) -> Result<UrdfRobot, UrdfError> {
    let opts = ParsingOptions {
        allow_dtd: true,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, opts).map_err(|e| {
        let pos = e.pos();
        UrdfError::Xml {
            line: pos.row,
            column: pos.col,
            message: e.to_string(),
        }
    })?;
    let p = Parser { doc: &doc };
    let root = doc.root_element();
    if !root.has_tag_name("robot") {
        return Err(p.invalid(
            root,
            "document".into(),
            format!(
                "the root element is <{}>, expected <robot>",
                root.tag_name().name()
            ),
        ));
    }
    let name = p.attr(root, "robot".into(), "name")?.to_string();

    let mut links = Vec::new();
    let mut link_index: HashMap<String, usize> = HashMap::new();
    for node in root.children().filter(|n| n.has_tag_name("link")) {
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
    let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
    for node in root.children().filter(|n| n.has_tag_name("joint")) {
        let joint = p.joint(node, &link_index)?;
        let what = || format!("joint \"{}\"", joint.name);
        if let Some(first) = joints.iter().find(|j| j.name == joint.name) {
            let msg = format!(
                "duplicate joint name (first defined at line {})",
                first.line
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
        joints.push(joint);
    }

    for (j, joint) in joints.iter().enumerate() {
        if let Some(m) = &joint.mimic {
            if !joints.iter().any(|o| o.name == m.joint) {
                return Err(UrdfError::Invalid {
                    line: joint.line,
                    element: format!("joint \"{}\"", joint.name),
                    message: format!("mimics joint \"{}\", which is not defined", m.joint),
                });
            }
            if joints[j].name == m.joint {
                return Err(UrdfError::Invalid {
                    line: joint.line,
                    element: format!("joint \"{}\"", joint.name),
                    message: "mimics itself".into(),
                });
            }
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

    Ok(UrdfRobot {
        name,
        links,
        joints,
        root: root_link,
        children,
    })
}

/// Element readers that know the document, for line numbers.
struct Parser<'a, 'input> {
    doc: &'a Document<'input>,
}

impl Parser<'_, '_> {
    fn line(&self, node: Node) -> u32 {
        self.doc.text_pos_at(node.range().start).row
    }

    fn invalid(&self, node: Node, element: String, message: String) -> UrdfError {
        UrdfError::Invalid {
            line: self.line(node),
            element,
            message,
        }
    }

    /// A required attribute.
    fn attr<'n>(&self, node: Node<'n, '_>, what: String, name: &str) -> Result<&'n str, UrdfError> {
        node.attribute(name).ok_or_else(|| {
            let msg = format!("<{}> has no \"{name}\" attribute", node.tag_name().name());
            self.invalid(node, what, msg)
        })
    }

    /// An optional finite number.
    fn number(&self, node: Node, what: &str, name: &str) -> Result<Option<f64>, UrdfError> {
        let Some(text) = node.attribute(name) else {
            return Ok(None);
        };
        let tag = node.tag_name().name();
        let x: f64 = text.trim().parse().map_err(|_| {
            let msg = format!("<{tag} {name}=\"{text}\">: not a number");
            self.invalid(node, what.into(), msg)
        })?;
        if !x.is_finite() {
            let msg = format!("<{tag} {name}=\"{text}\">: non-finite value");
            return Err(self.invalid(node, what.into(), msg));
        }
        Ok(Some(x))
    }

    /// A required finite number.
    fn required(&self, node: Node, what: &str, name: &str) -> Result<f64, UrdfError> {
        self.number(node, what, name)?.ok_or_else(|| {
            let msg = format!("<{}> has no \"{name}\" attribute", node.tag_name().name());
            self.invalid(node, what.into(), msg)
        })
    }

    /// An optional triple of finite numbers, `default` if absent.
    fn triple(
        &self,
        node: Node,
        what: &str,
        name: &str,
        default: [f64; 3],
    ) -> Result<[f64; 3], UrdfError> {
        let Some(text) = node.attribute(name) else {
            return Ok(default);
        };
        let tag = node.tag_name().name();
        let bad = |why: &str| {
            let msg = format!("<{tag} {name}=\"{text}\">: {why}");
            self.invalid(node, what.into(), msg)
        };
        let mut out = [0.0; 3];
        let mut count = 0;
        for word in text.split_whitespace() {
            let x: f64 = word
                .parse()
                .map_err(|_| bad("not a list of three numbers"))?;
            if !x.is_finite() {
                return Err(bad("non-finite value"));
            }
            if count < 3 {
                out[count] = x;
            }
            count += 1;
        }
        if count != 3 {
            return Err(bad(&format!("expected three numbers, got {count}")));
        }
        Ok(out)
    }

    /// The first child element with this tag.
    fn child<'n, 'i>(node: Node<'n, 'i>, tag: &str) -> Option<Node<'n, 'i>> {
        node.children().find(|n| n.has_tag_name(tag))
    }

    /// `<origin xyz rpy>` under `node`, identity if absent.
    fn origin(&self, node: Node, what: &str) -> Result<Transform, UrdfError> {
        match Self::child(node, "origin") {
            None => Ok(Transform::identity()),
            Some(o) => {
                let xyz = self.triple(o, what, "xyz", [0.0; 3])?;
                let rpy = self.triple(o, what, "rpy", [0.0; 3])?;
                Ok(Transform::from_xyz_rpy(xyz, rpy))
            }
        }
    }

    fn link(&self, node: Node) -> Result<UrdfLink, UrdfError> {
        let name = self.attr(node, "link".into(), "name")?.to_string();
        let what = format!("link \"{name}\"");
        let inertial = match Self::child(node, "inertial") {
            None => None,
            Some(inode) => {
                let origin = self.origin(inode, &what)?;
                let mass_node = Self::child(inode, "mass").ok_or_else(|| {
                    self.invalid(inode, what.clone(), "<inertial> has no <mass>".into())
                })?;
                let mass = self.required(mass_node, &what, "value")?;
                if mass < 0.0 {
                    let msg = format!("negative mass {mass}");
                    return Err(self.invalid(mass_node, what, msg));
                }
                let inode_i = Self::child(inode, "inertia").ok_or_else(|| {
                    self.invalid(inode, what.clone(), "<inertial> has no <inertia>".into())
                })?;
                let mut e = [0.0; 6];
                for (k, key) in ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"]
                    .iter()
                    .enumerate()
                {
                    e[k] = self.required(inode_i, &what, key)?;
                }
                Some(UrdfInertial {
                    origin,
                    mass,
                    inertia: RotationalInertia::new(e[0], e[1], e[2], e[3], e[4], e[5]),
                    line: self.line(inode),
                })
            }
        };
        Ok(UrdfLink {
            name,
            line: self.line(node),
            inertial,
        })
    }

    fn joint(
        &self,
        node: Node,
        link_index: &HashMap<String, usize>,
    ) -> Result<UrdfJoint, UrdfError> {
        let name = self.attr(node, "joint".into(), "name")?.to_string();
        let what = format!("joint \"{name}\"");
        let type_str = self.attr(node, what.clone(), "type")?;
        let kind = match type_str {
            "revolute" => UrdfJointKind::Revolute,
            "continuous" => UrdfJointKind::Continuous,
            "prismatic" => UrdfJointKind::Prismatic,
            "fixed" => UrdfJointKind::Fixed,
            "floating" => UrdfJointKind::Floating,
            "planar" => UrdfJointKind::Planar,
            other => {
                let msg = format!(
                    "unknown joint type \"{other}\" (expected revolute, continuous, prismatic, \
                     fixed, floating or planar)"
                );
                return Err(self.invalid(node, what, msg));
            }
        };
        let link_of = |tag: &str| -> Result<usize, UrdfError> {
            let n = Self::child(node, tag)
                .ok_or_else(|| self.invalid(node, what.clone(), format!("no <{tag}> element")))?;
            let link = self.attr(n, what.clone(), "link")?;
            link_index.get(link).copied().ok_or_else(|| {
                let msg = format!("{tag} link \"{link}\" is not defined");
                self.invalid(n, what.clone(), msg)
            })
        };
        let parent = link_of("parent")?;
        let child = link_of("child")?;
        let origin = self.origin(node, &what)?;

        let axis = match Self::child(node, "axis") {
            None => Vec3::x(),
            Some(a) => {
                let xyz = Vec3::from(self.triple(a, &what, "xyz", [1.0, 0.0, 0.0])?);
                let n = xyz.norm();
                let uses_axis = !matches!(kind, UrdfJointKind::Fixed | UrdfJointKind::Floating);
                if uses_axis && n == 0.0 {
                    return Err(self.invalid(a, what, "zero joint axis".into()));
                }
                if n == 0.0 {
                    Vec3::x()
                } else {
                    xyz / n
                }
            }
        };
        if kind == UrdfJointKind::Planar && (axis - Vec3::z()).norm() > 1e-12 {
            let msg = format!(
                "planar joint with axis ({}, {}, {}): only axis 0 0 1 (the x-y plane of the joint \
                 frame) is supported",
                axis.x, axis.y, axis.z
            );
            return Err(self.invalid(node, what, msg));
        }

        let limit = match Self::child(node, "limit") {
            None => None,
            Some(l) => {
                let lower = self.number(l, &what, "lower")?.unwrap_or(0.0);
                let upper = self.number(l, &what, "upper")?.unwrap_or(0.0);
                let effort = self.number(l, &what, "effort")?.unwrap_or(f64::INFINITY);
                let velocity = self.number(l, &what, "velocity")?.unwrap_or(f64::INFINITY);
                Some(UrdfLimit {
                    lower,
                    upper,
                    effort,
                    velocity,
                })
            }
        };
        let mimic = match Self::child(node, "mimic") {
            None => None,
            Some(m) => Some(UrdfMimic {
                joint: self.attr(m, what.clone(), "joint")?.to_string(),
                multiplier: self.number(m, &what, "multiplier")?.unwrap_or(1.0),
                offset: self.number(m, &what, "offset")?.unwrap_or(0.0),
            }),
        };
        let (damping, friction) = match Self::child(node, "dynamics") {
            None => (0.0, 0.0),
            Some(d) => (
                self.number(d, &what, "damping")?.unwrap_or(0.0),
                self.number(d, &what, "friction")?.unwrap_or(0.0),
            ),
        };
        Ok(UrdfJoint {
            name,
            line: self.line(node),
            kind,
            parent,
            child,
            origin,
            axis,
            limit,
            mimic,
            damping,
            friction,
        })
    }
}
