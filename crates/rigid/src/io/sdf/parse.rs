//! SDFormat's XML read into links, joints and frames, each pose as written (value and
//! `relative_to`), and the poses resolved to the model frame ([`Poses`]).

use super::{SdfError, SdfWarning};
use crate::collision::Shape;
use crate::spatial::{so3, Transform, Vec3};
use roxmltree::Node;
use std::collections::HashMap;
use std::path::Path;

/// A `<pose>` as written: the transform and the frame it is relative to (`None`: the element's
/// default).
#[derive(Clone, Debug)]
pub(super) struct Pose {
    pub t: Transform,
    pub relative_to: Option<String>,
}

/// A `<link>`.
pub(super) struct Link {
    pub name: String,
    pub line: u32,
    pub pose: Pose,
    /// `<inertial>`: its pose in the link frame, mass, and `ixx iyy izz ixy ixz iyz`.
    pub inertial: Option<(Transform, f64, [f64; 6])>,
    /// The `<inertial>`'s line, its numbers as written (`mass`, then the six moments; empty
    /// where absent) and its byte range in the file.
    pub inertial_text: (u32, [String; 7], std::ops::Range<usize>),
    /// `<collision>`: name, pose in the link frame, shape (a mesh as its hull's points).
    pub collisions: Vec<(String, Transform, Shape)>,
    /// `<visual>`s.
    pub visuals: Vec<super::SdfVisual>,
    /// The file the link is written in when it came from an `<include>`.
    pub file: Option<std::path::PathBuf>,
}

/// An `<axis>` or `<axis2>`.
pub(super) struct Axis {
    pub xyz: Vec3,
    /// `expressed_in` (`None`: the joint frame), `__model__` for 1.4–1.6's
    /// `use_parent_model_frame`.
    pub expressed_in: Option<String>,
    pub lower: f64,
    pub upper: f64,
    pub effort: f64,
    pub velocity: f64,
    pub damping: f64,
    pub friction: f64,
}

/// A `<joint>`.
pub(super) struct Joint {
    pub name: String,
    pub line: u32,
    pub kind: String,
    pub parent: String,
    pub child: String,
    pub pose: Pose,
    pub axis: Option<Axis>,
    pub axis2: Option<Axis>,
    /// `<screw_thread_pitch>` (m per revolution).
    pub pitch: Option<f64>,
    /// A gearbox's `<gearbox_ratio>` and `<gearbox_reference_body>`.
    pub gearbox: Option<(f64, String)>,
}

/// A `<frame>`.
pub(super) struct Frame {
    pub name: String,
    pub line: u32,
    pub attached_to: Option<String>,
    pub pose: Pose,
}

/// A `<model>` as written.
pub(super) struct Raw {
    pub name: String,
    pub version: String,
    pub pose: Transform,
    pub canonical: Option<String>,
    /// `<static>true</static>`: the model is fixed in the world.
    pub fixed: bool,
    /// The `<gravity>` of the `<world>` the model is in, if any.
    pub gravity: Option<Vec3>,
    pub links: Vec<Link>,
    pub joints: Vec<Joint>,
    pub frames: Vec<Frame>,
    /// The links, joints and frames written in an `<include>`d file, with the file (the lines
    /// of their errors and warnings are that file's).
    pub included: HashMap<String, std::path::PathBuf>,
}

pub(super) struct Reader<'a> {
    pub doc: &'a roxmltree::Document<'a>,
    pub dir: &'a Path,
    pub warnings: Vec<SdfWarning>,
    /// The files being read, the outermost first (this one last; none for text): an
    /// `<include>` of one of them is a loop.
    pub chain: Vec<std::path::PathBuf>,
    /// The links, joints and frames read from an `<include>`d file, with the file.
    pub included: HashMap<String, std::path::PathBuf>,
}

pub(super) fn children<'a, 'i>(
    node: Node<'a, 'i>,
    tag: &'a str,
) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |c| c.has_tag_name(tag))
}

pub(super) fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(tag))
}

impl<'a> Reader<'a> {
    pub fn line(&self, node: Node) -> u32 {
        self.doc.text_pos_at(node.range().start).row
    }

    pub fn error(&self, node: Node, element: String, message: impl Into<String>) -> SdfError {
        SdfError::Invalid {
            line: self.line(node),
            element,
            message: message.into(),
        }
    }

    pub(super) fn warn(&mut self, node: Node, element: String, message: impl Into<String>) {
        let line = self.line(node);
        self.warnings.push(SdfWarning {
            line,
            element,
            message: message.into(),
        });
    }

    /// The finite numbers of `node`'s text, exactly `n` of them when `n` is given.
    pub(super) fn numbers(
        &self,
        node: Node,
        what: &str,
        n: Option<usize>,
    ) -> Result<Vec<f64>, SdfError> {
        let text = node.text().unwrap_or("");
        let v: Result<Vec<f64>, _> = text.split_whitespace().map(str::parse::<f64>).collect();
        let v =
            v.map_err(|_| self.error(node, what.into(), format!("\"{text}\" is not numbers")))?;
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.error(node, what.into(), format!("\"{text}\": not finite")));
        }
        if let Some(n) = n.filter(|n| *n != v.len()) {
            return Err(self.error(
                node,
                what.into(),
                format!(
                    "expected {n} numbers, got {} (\"{}\")",
                    v.len(),
                    text.trim()
                ),
            ));
        }
        Ok(v)
    }

    /// The number in child `tag` of `node`, `default` without it.
    pub(super) fn number(
        &self,
        node: Node,
        tag: &str,
        default: f64,
        what: &str,
    ) -> Result<f64, SdfError> {
        match child(node, tag) {
            Some(c) => Ok(self.numbers(c, &format!("{what} <{tag}>"), Some(1))?[0]),
            None => Ok(default),
        }
    }

    /// `<pose>` of `node` (identity without one): `x y z roll pitch yaw` (radians, or degrees
    /// with `degrees="true"`), or `x y z qx qy qz qw` with `rotation_format="quat_xyzw"`.
    pub(super) fn pose(&self, node: Node, what: &str) -> Result<Pose, SdfError> {
        let Some(p) = child(node, "pose") else {
            return Ok(Pose {
                t: Transform::identity(),
                relative_to: None,
            });
        };
        let what = format!("{what} <pose>");
        let quat = p.attribute("rotation_format") == Some("quat_xyzw");
        let v = self.numbers(p, &what, Some(if quat { 7 } else { 6 }))?;
        let rotation = if quat {
            so3::from_quaternion(v[3], v[4], v[5], v[6], 1e-3)
                .map_err(|e| self.error(p, what.clone(), e.to_string()))?
        } else {
            let k = if p.attribute("degrees") == Some("true") {
                std::f64::consts::PI / 180.0
            } else {
                1.0
            };
            so3::from_rpy(k * v[3], k * v[4], k * v[5])
        };
        // SDFormat 1.7+ `relative_to`; 1.4–1.6 `frame` (empty: the default)
        let relative_to = p
            .attribute("relative_to")
            .or_else(|| p.attribute("frame"))
            .filter(|s| !s.is_empty())
            .map(str::to_string);
        Ok(Pose {
            t: Transform::new(rotation, Vec3::new(v[0], v[1], v[2])),
            relative_to,
        })
    }

    pub(super) fn shape(&mut self, g: Node, what: &str) -> Result<Option<Shape>, SdfError> {
        let Some(s) = g.children().find(Node::is_element) else {
            return Ok(None);
        };
        let what = format!("{what} <{}>", s.tag_name().name());
        let num = |r: &Self, tag: &str| r.number(s, tag, f64::NAN, &what);
        let shape = match s.tag_name().name() {
            "box" => {
                let size =
                    child(s, "size").ok_or_else(|| self.error(s, what.clone(), "no <size>"))?;
                let v = self.numbers(size, &what, Some(3))?;
                Shape::Box {
                    size: Vec3::new(v[0], v[1], v[2]),
                }
            }
            "sphere" => Shape::Sphere {
                radius: num(self, "radius")?,
            },
            "cylinder" => Shape::Cylinder {
                radius: num(self, "radius")?,
                length: num(self, "length")?,
            },
            "capsule" => Shape::Capsule {
                radius: num(self, "radius")?,
                length: num(self, "length")?,
            },
            "ellipsoid" => {
                let radii =
                    child(s, "radii").ok_or_else(|| self.error(s, what.clone(), "no <radii>"))?;
                let v = self.numbers(radii, &what, Some(3))?;
                Shape::Ellipsoid {
                    semi_axes: Vec3::new(v[0], v[1], v[2]),
                }
            }
            "mesh" => {
                let (path, scale) = self.mesh_file(s, &what)?;
                let mesh = path.and_then(|(uri, p)| {
                    crate::io::mesh_file::read_mesh(&p).map_err(|e| format!("{uri}: {e}"))
                });
                match mesh {
                    Ok(m) => Shape::ConvexHull {
                        points: m.vertices.iter().map(|v| v.component_mul(&scale)).collect(),
                    },
                    Err(e) => {
                        self.warn(s, what, format!("{e}: the collision is skipped"));
                        return Ok(None);
                    }
                }
            }
            "plane" | "heightmap" | "polyline" | "image" => {
                self.warn(s, what, "not read: the collision is skipped");
                return Ok(None);
            }
            other => return Err(self.error(s, what, format!("unknown geometry <{other}>"))),
        };
        shape.check().map_err(|e| self.error(s, what.clone(), e))?;
        Ok(Some(shape))
    }

    /// A `<mesh>`'s file (`<uri>`: `model://NAME/...` beside the model's folder, else from the
    /// file's folder; the URI as written with the path, or why it is not found) and `<scale>`.
    #[allow(clippy::type_complexity)]
    pub(super) fn mesh_file(
        &self,
        s: Node,
        what: &str,
    ) -> Result<(Result<(String, std::path::PathBuf), String>, Vec3), SdfError> {
        let uri = child(s, "uri").and_then(|u| u.text()).unwrap_or("").trim();
        let scale = match child(s, "scale") {
            Some(c) => Vec3::from_iterator(self.numbers(c, what, Some(3))?),
            None => Vec3::repeat(1.0),
        };
        let local = uri
            .strip_prefix("model://")
            .map_or(uri.to_string(), |rest| {
                // a model's own resources: `model://NAME/...` beside the model's folder
                format!("../{rest}")
            });
        let anchor = self.dir.join("model.sdf");
        let path = crate::io::urdf::resolve_mesh_path(&local, Some(&anchor))
            .map(|p| (uri.to_string(), p))
            .ok_or_else(|| format!("mesh {uri} not found"));
        Ok((path, scale))
    }

    fn link(&mut self, l: Node) -> Result<Link, SdfError> {
        let name = l.attribute("name").unwrap_or("").to_string();
        let what = format!("link \"{name}\"");
        let mut inertial_text = (0, Default::default(), 0..0);
        if let Some(i) = child(l, "inertial") {
            let text = |n: Option<Node>, tag: &str| -> String {
                n.and_then(|n| child(n, tag))
                    .and_then(|c| c.text())
                    .map_or(String::new(), |t| t.trim().to_string())
            };
            let inertia = child(i, "inertia");
            inertial_text = (
                self.line(i),
                [
                    text(Some(i), "mass"),
                    text(inertia, "ixx"),
                    text(inertia, "iyy"),
                    text(inertia, "izz"),
                    text(inertia, "ixy"),
                    text(inertia, "ixz"),
                    text(inertia, "iyz"),
                ],
                i.range(),
            );
        }
        let inertial = match child(l, "inertial") {
            None => None,
            Some(i) => {
                let pose = self.pose(i, &what)?;
                if pose.relative_to.is_some() {
                    return Err(self.error(i, what, "an inertial's pose is relative to its link"));
                }
                let mass = self.number(i, "mass", 1.0, &what)?;
                let m = match child(i, "inertia") {
                    Some(n) => {
                        let f = |t: &str, d: f64| self.number(n, t, d, &what);
                        [
                            f("ixx", 1.0)?,
                            f("iyy", 1.0)?,
                            f("izz", 1.0)?,
                            f("ixy", 0.0)?,
                            f("ixz", 0.0)?,
                            f("iyz", 0.0)?,
                        ]
                    }
                    None => [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
                };
                Some((pose.t, mass, m))
            }
        };
        let mut collisions = Vec::new();
        for (k, c) in children(l, "collision").enumerate() {
            let cname = c
                .attribute("name")
                .map_or_else(|| format!("{name}/{k}"), str::to_string);
            let pose = self.pose(c, &what)?;
            if pose.relative_to.is_some() {
                self.warn(
                    c,
                    what.clone(),
                    "a collision's pose relative_to another frame is read as relative to its link",
                );
            }
            if let Some(g) = child(c, "geometry") {
                if let Some(shape) = self.shape(g, &format!("{what} collision \"{cname}\""))? {
                    collisions.push((cname, pose.t, shape));
                }
            }
        }
        let visuals = self.visuals(l, &what)?;
        Ok(Link {
            line: self.line(l),
            pose: self.pose(l, &what)?,
            name,
            inertial,
            inertial_text,
            collisions,
            visuals,
            file: None,
        })
    }

    fn axis(&self, a: Node, what: &str, old: bool) -> Result<Axis, SdfError> {
        let xyz_node = child(a, "xyz");
        let xyz = match xyz_node {
            Some(n) => Vec3::from_iterator(self.numbers(n, what, Some(3))?),
            None => Vec3::z(),
        };
        if xyz.norm() < 1e-12 {
            return Err(self.error(a, what.into(), "the axis is zero"));
        }
        let parent_model = child(a, "use_parent_model_frame")
            .and_then(|n| n.text())
            .is_some_and(|t| matches!(t.trim(), "1" | "true"));
        let expressed_in = xyz_node
            .and_then(|n| n.attribute("expressed_in"))
            .map(str::to_string)
            .or_else(|| (old && parent_model).then(|| "__model__".to_string()));
        let limit = child(a, "limit");
        let lim = |tag: &str, d: f64| limit.map_or(Ok(d), |l| self.number(l, tag, d, what));
        let dynamics = child(a, "dynamics");
        let dyn_ = |tag: &str| dynamics.map_or(Ok(0.0), |d| self.number(d, tag, 0.0, what));
        // SDFormat's "no limit": ±1e16 for positions, -1 for effort and velocity
        let unbounded = |x: f64, inf: f64| if x.abs() >= 1e16 { inf } else { x };
        let rate = |x: f64| if x < 0.0 { f64::INFINITY } else { x };
        Ok(Axis {
            xyz: xyz.normalize(),
            expressed_in,
            lower: unbounded(lim("lower", -1e16)?, f64::NEG_INFINITY),
            upper: unbounded(lim("upper", 1e16)?, f64::INFINITY),
            effort: rate(lim("effort", -1.0)?),
            velocity: rate(lim("velocity", -1.0)?),
            damping: dyn_("damping")?,
            friction: dyn_("friction")?,
        })
    }

    fn joint(&self, j: Node, old: bool) -> Result<Joint, SdfError> {
        let name = j.attribute("name").unwrap_or("").to_string();
        let what = format!("joint \"{name}\"");
        let text = |tag: &str| -> Result<String, SdfError> {
            let n =
                child(j, tag).ok_or_else(|| self.error(j, what.clone(), format!("no <{tag}>")))?;
            Ok(n.text().unwrap_or("").trim().to_string())
        };
        let axis = |tag: &str| {
            child(j, tag)
                .map(|a| self.axis(a, &format!("{what} <{tag}>"), old))
                .transpose()
        };
        let pitch = match child(j, "screw_thread_pitch") {
            Some(n) => Some(self.numbers(n, &what, Some(1))?[0]),
            None => None,
        };
        let gearbox = match (
            child(j, "gearbox_ratio"),
            child(j, "gearbox_reference_body"),
        ) {
            (Some(r), Some(b)) => Some((
                self.numbers(r, &what, Some(1))?[0],
                b.text().unwrap_or("").trim().to_string(),
            )),
            _ => None,
        };
        Ok(Joint {
            line: self.line(j),
            kind: j.attribute("type").unwrap_or("").to_string(),
            parent: text("parent")?,
            child: text("child")?,
            pose: self.pose(j, &what)?,
            axis: axis("axis")?,
            axis2: axis("axis2")?,
            pitch,
            gearbox,
            name,
        })
    }

    /// The links, joints and frames of model `m` and of the models nested in it, whose names
    /// (and the names they refer to) get the nested model's scope `prefix` (`inner::link`); a
    /// nested model is a frame `inner::__model__`, placed by its `<pose>` in its parent's.
    pub(super) fn collect(
        &mut self,
        m: Node,
        prefix: &str,
        old: bool,
        links: &mut Vec<Link>,
        joints: &mut Vec<Joint>,
        frames: &mut Vec<Frame>,
    ) -> Result<(), SdfError> {
        // a name as seen from this scope: `world` is the world's, the rest is the scope's
        let scoped = |n: &str| -> String {
            match n {
                "world" => n.to_string(),
                "__model__" | "" => format!("{prefix}__model__"),
                _ => format!("{prefix}{n}"),
            }
        };
        let scope_pose = |p: &mut Pose| {
            p.relative_to = Some(scoped(p.relative_to.as_deref().unwrap_or("__model__")));
        };
        for n in m.children().filter(Node::is_element) {
            let tag = n.tag_name().name();
            match tag {
                "link" => {
                    let mut l = self.link(n)?;
                    l.name = scoped(&l.name);
                    scope_pose(&mut l.pose);
                    links.push(l);
                }
                "joint" => {
                    let mut j = self.joint(n, old)?;
                    j.name = scoped(&j.name);
                    j.parent = scoped(&j.parent);
                    j.child = scoped(&j.child);
                    if let Some((_, body)) = &mut j.gearbox {
                        *body = scoped(body);
                    }
                    if let Some(r) = j.pose.relative_to.take() {
                        j.pose.relative_to = Some(scoped(&r));
                    }
                    for a in [&mut j.axis, &mut j.axis2].into_iter().flatten() {
                        if let Some(e) = a.expressed_in.take() {
                            a.expressed_in = Some(scoped(&e));
                        }
                    }
                    joints.push(j);
                }
                "frame" => {
                    let name = n.attribute("name").unwrap_or("").to_string();
                    let mut pose = self.pose(n, &format!("frame \"{name}\""))?;
                    let attached = scoped(n.attribute("attached_to").unwrap_or(""));
                    pose.relative_to =
                        Some(pose.relative_to.map_or(attached.clone(), |r| scoped(&r)));
                    frames.push(Frame {
                        name: scoped(&name),
                        line: self.line(n),
                        attached_to: Some(attached),
                        pose,
                    });
                }
                "model" => {
                    let name = n.attribute("name").unwrap_or("model").to_string();
                    let inner = format!("{prefix}{name}::");
                    let mut pose = self.pose(n, &format!("model \"{name}\""))?;
                    scope_pose(&mut pose);
                    frames.push(Frame {
                        name: format!("{inner}__model__"),
                        line: self.line(n),
                        attached_to: None,
                        pose,
                    });
                    self.collect(n, &inner, old, links, joints, frames)?;
                }
                "pose" | "static" | "self_collide" | "allow_auto_disable" | "enable_wind" => {}
                "include" => {
                    let (name, mut pose) = self.include(n, prefix, links, joints, frames)?;
                    scope_pose(&mut pose);
                    frames.push(Frame {
                        name: format!("{prefix}{name}::__model__"),
                        line: self.line(n),
                        attached_to: None,
                        pose,
                    });
                }
                _ => self.warn(n, format!("<{tag}>"), "not read"),
            }
        }
        Ok(())
    }

    /// The one `<model>` of the file (directly under `<sdf>`, or in its `<world>`), the
    /// `<sdf version>` and the `<world>`'s `<gravity>`.
    pub(super) fn the_model(&self) -> Result<(Node<'a, 'a>, String, Option<Vec3>), SdfError> {
        let root = self.doc.root_element();
        if !root.has_tag_name("sdf") {
            return Err(self.error(
                root,
                format!("<{}>", root.tag_name().name()),
                "the root element must be <sdf>",
            ));
        }
        let version = root.attribute("version").unwrap_or("1.7").to_string();
        let mut models: Vec<Node> = children(root, "model").collect();
        let mut gravity = None;
        for w in children(root, "world") {
            models.extend(children(w, "model"));
            if let Some(g) = child(w, "gravity") {
                gravity = Some(Vec3::from_iterator(self.numbers(
                    g,
                    "<world> <gravity>",
                    Some(3),
                )?));
            }
        }
        match models.as_slice() {
            [m] => Ok((*m, version, gravity)),
            [] => Err(self.error(root, "<sdf>".into(), "no <model>")),
            [_, second, ..] => Err(self.error(
                *second,
                "<model>".into(),
                "a file of several models: rigid reads one",
            )),
        }
    }

    /// The one `<model>` of the file (directly under `<sdf>`, or in its `<world>`).
    pub fn model(&mut self) -> Result<Raw, SdfError> {
        let (m, version, gravity) = self.the_model()?;
        let old = version_is_old(&version);
        let name = m.attribute("name").unwrap_or("model").to_string();
        let (mut links, mut joints, mut frames) = (Vec::new(), Vec::new(), Vec::new());
        self.collect(m, "", old, &mut links, &mut joints, &mut frames)?;
        Ok(Raw {
            pose: self.pose(m, &format!("model \"{name}\""))?.t,
            canonical: m.attribute("canonical_link").map(str::to_string),
            gravity,
            fixed: child(m, "static")
                .and_then(|n| n.text())
                .is_some_and(|t| matches!(t.trim(), "1" | "true")),
            name,
            version,
            links,
            joints,
            frames,
            included: std::mem::take(&mut self.included),
        })
    }
}

/// Every named frame's pose in the model frame: links (relative to the model by default),
/// joints (to their child link), frames (to what they are attached to), `__model__`.
pub(super) struct Poses {
    pub of: HashMap<String, Transform>,
}

impl Poses {
    pub fn resolve(raw: &Raw) -> Result<Self, SdfError> {
        // name -> (pose as written, what it is relative to by default)
        // names are unique among a model's links, joints and frames (SDFormat 1.7+, as
        // libsdformat refuses a clash): a second one would hide the first's pose
        let mut written: HashMap<&str, (&Pose, Option<&str>, u32)> = HashMap::new();
        let entries = (raw
            .links
            .iter()
            .map(|l| ("link", &l.name, &l.pose, None, l.line)))
        .chain(
            raw.joints
                .iter()
                .map(|j| ("joint", &j.name, &j.pose, Some(j.child.as_str()), j.line)),
        )
        .chain(
            raw.frames
                .iter()
                .map(|f| ("frame", &f.name, &f.pose, f.attached_to.as_deref(), f.line)),
        );
        for (kind, name, pose, default, line) in entries {
            if let Some((_, _, first)) = written.insert(name, (pose, default, line)) {
                return Err(SdfError::Invalid {
                    line,
                    element: format!("{kind} \"{name}\""),
                    message: format!(
                        "the name is already taken by the element at line {first}: links, \
                         joints and frames of a model need distinct names"
                    ),
                });
            }
        }
        let joints: std::collections::HashSet<&str> =
            raw.joints.iter().map(|j| j.name.as_str()).collect();
        let mut of = HashMap::new();
        of.insert("__model__".to_string(), Transform::identity());
        let names: Vec<&str> = written.keys().copied().collect();
        for name in names {
            let mut chain = vec![name];
            loop {
                let top = *chain.last().unwrap();
                let (pose, default, line) = written[top];
                let base = pose
                    .relative_to
                    .as_deref()
                    .or(default)
                    .unwrap_or("__model__");
                let base = if base == "world" { "__model__" } else { base };
                if let Some(b) = of.get(base).copied() {
                    of.insert(top.to_string(), b * pose.t);
                    chain.pop();
                    if chain.is_empty() {
                        break;
                    }
                } else if !written.contains_key(base) {
                    let joint = joints.contains(top);
                    return Err(SdfError::Invalid {
                        line,
                        element: if joint {
                            format!("joint \"{top}\"")
                        } else {
                            format!("\"{top}\"")
                        },
                        message: if joint && pose.relative_to.is_none() {
                            format!("its child \"{base}\" is not a link of the model")
                        } else {
                            format!("its pose is relative to \"{base}\", which is not defined")
                        },
                    });
                } else if chain.contains(&base) {
                    return Err(SdfError::Invalid {
                        line,
                        element: format!("\"{top}\""),
                        message: format!(
                            "its pose is relative to itself through {}",
                            chain.join(" -> ")
                        ),
                    });
                } else {
                    chain.push(base);
                }
            }
        }
        Ok(Self { of })
    }
}

/// SDFormat 1.0–1.6: `use_parent_model_frame` and a pose's `frame`.
pub(super) fn version_is_old(version: &str) -> bool {
    matches!(version, "1.0" | "1.2" | "1.3" | "1.4" | "1.5" | "1.6")
}
