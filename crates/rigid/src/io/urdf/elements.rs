//! Readers of single URDF elements (`<link>`, `<joint>`, `<inertial>`, `<visual>`, `<material>`),
//! with the document at hand for line numbers and a list of warnings for what is tolerated.

use super::{
    UrdfError, UrdfGeometry, UrdfInertial, UrdfJoint, UrdfJointKind, UrdfLimit, UrdfLink,
    UrdfMimic, UrdfShape, UrdfWarning,
};
use crate::mass::RotationalInertia;
use crate::spatial::{Transform, Vec3};
use roxmltree::Node;
use std::collections::HashMap;

/// Children of `<robot>` that are read or knowingly skipped (anything else is a warning).
pub(super) const ROBOT_CHILDREN: &[&str] = &[
    "link",
    "joint",
    "material",
    "transmission",
    "gazebo",
    "sensor",
    "ros2_control",
];
const LINK_CHILDREN: &[&str] = &[
    "inertial",
    "visual",
    "collision",
    "self_collision_checking",
    "contact",
];
const JOINT_CHILDREN: &[&str] = &[
    "parent",
    "child",
    "origin",
    "axis",
    "limit",
    "dynamics",
    "mimic",
    "safety_controller",
    "calibration",
];

/// Element readers that know the document (for line numbers) and collect warnings.
pub(super) struct Parser {
    pub warnings: Vec<UrdfWarning>,
    /// Top-level `<material name>` colours.
    pub materials: HashMap<String, [f64; 4]>,
    /// Byte offset of the start of every line after the first (for line numbers in O(log n):
    /// `Document::text_pos_at` scans from the start, quadratic over a large file).
    pub line_starts: Vec<usize>,
}

/// An attribute value as quoted in a message: at most 40 characters, and where it was cut how long
/// it was (a 10 MB attribute must not become a 10 MB error message).
fn shown(text: &str) -> String {
    match text.char_indices().nth(40) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}… ({} bytes)", &text[..cut], text.len()),
    }
}

/// `true` for a URDF element called `tag`: no XML namespace (so that `<drake:joint>` or
/// `<xacro:link>` are not taken for URDF's `<joint>` and `<link>`).
pub(super) fn is(node: &Node, tag: &str) -> bool {
    node.is_element() && node.tag_name().name() == tag && node.tag_name().namespace().is_none()
}

impl Parser {
    /// The line starts of `text`.
    pub fn line_starts(text: &str) -> Vec<usize> {
        text.bytes()
            .enumerate()
            .filter(|(_, b)| *b == b'\n')
            .map(|(i, _)| i + 1)
            .collect()
    }

    pub fn line(&self, node: Node) -> u32 {
        let at = node.range().start;
        (self.line_starts.partition_point(|&s| s <= at) + 1) as u32
    }

    pub fn invalid(&self, node: Node, element: String, message: String) -> UrdfError {
        UrdfError::Invalid {
            line: self.line(node),
            element,
            message,
        }
    }

    pub fn warn(&mut self, node: Node, element: String, message: String) {
        let line = self.line(node);
        self.warnings.push(UrdfWarning {
            line,
            element,
            message,
        });
    }

    /// A warning for each child element of `node` whose tag is not in `known`.
    pub fn warn_unknown_children(&mut self, node: Node, what: &str, known: &[&str]) {
        for c in node.children().filter(|c| c.is_element()) {
            let tag = c.tag_name().name();
            if !known.contains(&tag) || c.tag_name().namespace().is_some() {
                let msg = format!("unknown element <{tag}> ignored");
                self.warn(c, what.into(), msg);
            }
        }
    }

    /// A required attribute.
    pub fn attr<'n>(
        &self,
        node: Node<'n, '_>,
        what: String,
        name: &str,
    ) -> Result<&'n str, UrdfError> {
        node.attribute(name).ok_or_else(|| {
            let msg = format!("<{}> has no \"{name}\" attribute", node.tag_name().name());
            self.invalid(node, what, msg)
        })
    }

    /// An optional finite number.
    pub fn number(&self, node: Node, what: &str, name: &str) -> Result<Option<f64>, UrdfError> {
        let Some(text) = node.attribute(name) else {
            return Ok(None);
        };
        let tag = node.tag_name().name();
        let x: f64 = text.trim().parse().map_err(|_| {
            let msg = format!("<{tag} {name}=\"{}\">: not a number", shown(text));
            self.invalid(node, what.into(), msg)
        })?;
        if !x.is_finite() {
            let msg = format!("<{tag} {name}=\"{}\">: non-finite value", shown(text));
            return Err(self.invalid(node, what.into(), msg));
        }
        Ok(Some(x))
    }

    /// A required finite number.
    pub fn required(&self, node: Node, what: &str, name: &str) -> Result<f64, UrdfError> {
        self.number(node, what, name)?.ok_or_else(|| {
            let msg = format!("<{}> has no \"{name}\" attribute", node.tag_name().name());
            self.invalid(node, what.into(), msg)
        })
    }

    /// An optional list of `N` finite numbers, `default` if absent.
    pub fn numbers<const N: usize>(
        &self,
        node: Node,
        what: &str,
        name: &str,
        default: [f64; N],
    ) -> Result<[f64; N], UrdfError> {
        let Some(text) = node.attribute(name) else {
            return Ok(default);
        };
        let tag = node.tag_name().name();
        let bad = |why: &str| {
            let msg = format!("<{tag} {name}=\"{}\">: {why}", shown(text));
            self.invalid(node, what.into(), msg)
        };
        let mut out = [0.0; N];
        let mut count = 0;
        for word in text.split_whitespace() {
            let x: f64 = word
                .parse()
                .map_err(|_| bad(&format!("not a list of {N} numbers")))?;
            if !x.is_finite() {
                return Err(bad("non-finite value"));
            }
            if count < N {
                out[count] = x;
            }
            count += 1;
        }
        if count != N {
            return Err(bad(&format!("expected {N} numbers, got {count}")));
        }
        Ok(out)
    }

    /// The first child element with this tag.
    pub fn child<'n, 'i>(node: Node<'n, 'i>, tag: &str) -> Option<Node<'n, 'i>> {
        node.children().find(|n| is(n, tag))
    }

    /// `<origin xyz rpy>` under `node`: the transform and the `rpy` as written (identity if
    /// absent).
    pub fn origin(&self, node: Node, what: &str) -> Result<(Transform, [f64; 3]), UrdfError> {
        match Self::child(node, "origin") {
            None => Ok((Transform::identity(), [0.0; 3])),
            Some(o) => {
                let xyz = self.numbers(o, what, "xyz", [0.0; 3])?;
                let rpy = self.numbers(o, what, "rpy", [0.0; 3])?;
                Ok((Transform::from_xyz_rpy(xyz, rpy), rpy))
            }
        }
    }

    /// A top-level `<material name>` with a `<color rgba>`.
    pub fn material(&mut self, node: Node) {
        let Some(name) = node.attribute("name") else {
            return;
        };
        if let Some(rgba) = self.color(node, &format!("material \"{name}\"")) {
            self.materials.insert(name.to_string(), rgba);
        }
    }

    /// The `<color rgba>` under a `<material>`, if readable (a warning otherwise).
    fn color(&mut self, material: Node, what: &str) -> Option<[f64; 4]> {
        let c = Self::child(material, "color")?;
        match self.numbers(c, what, "rgba", [0.5, 0.5, 0.5, 1.0]) {
            Ok(rgba) => Some(rgba.map(|x| x.clamp(0.0, 1.0))),
            Err(e) => {
                self.warn(c, what.into(), format!("colour ignored: {e}"));
                None
            }
        }
    }

    pub fn link(&mut self, node: Node) -> Result<UrdfLink, UrdfError> {
        let name = self.attr(node, "link".into(), "name")?.to_string();
        let what = format!("link \"{name}\"");
        self.warn_unknown_children(node, &what, LINK_CHILDREN);
        let inertial = match Self::child(node, "inertial") {
            None => None,
            Some(inode) => Some(self.inertial(inode, &what)?),
        };
        let mut visuals = Vec::new();
        let mut collisions = Vec::new();
        for g in node
            .children()
            .filter(|c| c.is_element() && c.tag_name().namespace().is_none())
        {
            let list = match g.tag_name().name() {
                "visual" => &mut visuals,
                "collision" => &mut collisions,
                _ => continue,
            };
            match self.geometry(g, &what) {
                Ok(Some(geom)) => list.push(geom),
                Ok(None) => {}
                Err(e) => {
                    let tag = g.tag_name().name();
                    self.warn(g, what.clone(), format!("<{tag}> ignored: {e}"));
                }
            }
        }
        Ok(UrdfLink {
            name,
            line: self.line(node),
            span: node.range(),
            inertial,
            visuals,
            collisions,
        })
    }

    fn inertial(&mut self, inode: Node, what: &str) -> Result<UrdfInertial, UrdfError> {
        let (origin, rpy) = self.origin(inode, what)?;
        let mut text: [String; 7] = Default::default();
        let mass = match Self::child(inode, "mass") {
            Some(m) => {
                text[0] = m.attribute("value").unwrap_or_default().trim().to_string();
                self.required(m, what, "value")?
            }
            None => {
                let msg = "<inertial> has no <mass>: mass 0".to_string();
                self.warn(inode, what.into(), msg);
                0.0
            }
        };
        let mut e = [0.0; 6];
        match Self::child(inode, "inertia") {
            Some(i) => {
                for (k, key) in ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"]
                    .iter()
                    .enumerate()
                {
                    text[k + 1] = i.attribute(*key).unwrap_or_default().trim().to_string();
                    e[k] = self.required(i, what, key)?;
                }
            }
            None => {
                let msg = "<inertial> has no <inertia>: a zero inertia".to_string();
                self.warn(inode, what.into(), msg);
            }
        }
        Ok(UrdfInertial {
            origin,
            rpy,
            mass,
            inertia: RotationalInertia::new(e[0], e[1], e[2], e[3], e[4], e[5]),
            line: self.line(inode),
            text,
            span: inode.range(),
        })
    }

    /// A `<visual>` or `<collision>`: `Ok(None)` when it has no `<geometry>` shape.
    fn geometry(&mut self, g: Node, what: &str) -> Result<Option<UrdfGeometry>, UrdfError> {
        let (origin, _) = self.origin(g, what)?;
        let Some(shape) = Self::child(g, "geometry").and_then(|n| n.first_element_child()) else {
            return Ok(None);
        };
        let pos = |x: f64, field: &str| -> Result<f64, UrdfError> {
            if x > 0.0 {
                Ok(x)
            } else {
                let msg = format!(
                    "<{}> {field} must be positive, got {x}",
                    shape.tag_name().name()
                );
                Err(self.invalid(shape, what.into(), msg))
            }
        };
        let s = match shape.tag_name().name() {
            "box" => {
                let size = self.numbers(shape, what, "size", [f64::NAN; 3])?;
                if size.iter().any(|x| x.is_nan()) {
                    return Err(self.invalid(shape, what.into(), "<box> has no size".into()));
                }
                let size = Vec3::from(size);
                // A zero edge (a plate) is allowed; a negative one is not.
                if size.iter().any(|x| *x < 0.0) {
                    let msg = "<box> size must not be negative".into();
                    return Err(self.invalid(shape, what.into(), msg));
                }
                UrdfShape::Box { size }
            }
            "cylinder" => UrdfShape::Cylinder {
                radius: pos(self.required(shape, what, "radius")?, "radius")?,
                length: pos(self.required(shape, what, "length")?, "length")?,
            },
            "capsule" => UrdfShape::Capsule {
                radius: pos(self.required(shape, what, "radius")?, "radius")?,
                length: self.required(shape, what, "length")?.max(0.0),
            },
            "sphere" => UrdfShape::Sphere {
                radius: pos(self.required(shape, what, "radius")?, "radius")?,
            },
            "mesh" => UrdfShape::Mesh {
                filename: self.attr(shape, what.into(), "filename")?.to_string(),
                scale: Vec3::from(self.numbers(shape, what, "scale", [1.0; 3])?),
            },
            other => {
                let msg = format!("unknown geometry <{other}>");
                return Err(self.invalid(shape, what.into(), msg));
            }
        };
        // urdfdom's rule: a named material already known (top-level, or given inline by an
        // earlier element) is that one, whatever colour this element gives; an unknown name is
        // defined by this element's colour, for the elements after it
        let rgba = match Self::child(g, "material") {
            None => None,
            Some(m) => match m.attribute("name").filter(|n| !n.is_empty()) {
                Some(n) => match self.materials.get(n).copied() {
                    Some(known) => Some(known),
                    None => {
                        let c = self.color(m, what);
                        if let Some(c) = c {
                            self.materials.insert(n.to_string(), c);
                        }
                        c
                    }
                },
                None => self.color(m, what),
            },
        };
        Ok(Some(UrdfGeometry {
            origin,
            shape: s,
            rgba,
            line: self.line(g),
        }))
    }

    pub fn joint(
        &mut self,
        node: Node,
        link_index: &HashMap<String, usize>,
    ) -> Result<UrdfJoint, UrdfError> {
        let name = self.attr(node, "joint".into(), "name")?.to_string();
        let what = format!("joint \"{name}\"");
        self.warn_unknown_children(node, &what, JOINT_CHILDREN);
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
        let (origin, _) = self.origin(node, &what)?;

        let axis = match Self::child(node, "axis") {
            None => Vec3::x(),
            Some(a) => {
                let xyz = Vec3::from(self.numbers(a, &what, "xyz", [1.0, 0.0, 0.0])?);
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
                let mut limit = UrdfLimit {
                    lower: self.number(l, &what, "lower")?.unwrap_or(0.0),
                    upper: self.number(l, &what, "upper")?.unwrap_or(0.0),
                    effort: self.number(l, &what, "effort")?.unwrap_or(f64::INFINITY),
                    velocity: self.number(l, &what, "velocity")?.unwrap_or(f64::INFINITY),
                };
                // Bullet writes "no limit" as lower > upper, and urdfdom loads it: no position
                // limit, with a warning
                if limit.lower > limit.upper {
                    let msg = format!(
                        "<limit> lower = {} is above upper = {}: read as no position limit \
                         (Bullet's way of writing none; urdfdom loads it)",
                        limit.lower, limit.upper
                    );
                    self.warn(l, what.clone(), msg);
                    limit.lower = f64::NEG_INFINITY;
                    limit.upper = f64::INFINITY;
                }
                Some(limit)
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
