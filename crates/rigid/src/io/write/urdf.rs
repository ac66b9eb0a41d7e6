//! A model as a URDF: one `<link>` per moving joint's body (its frame the joint frame) with its
//! `<inertial>` (centre of mass, full inertia about it) and `<collision>` elements, one `<joint>`
//! per moving joint (`<origin>` its placement, `rpy` the fixed-axis roll-pitch-yaw of
//! [`so3::to_rpy`](crate::spatial::so3::to_rpy)), and the links welded by fixed joints and the
//! operational frames as massless links on `fixed` joints.
//!
//! Joint types: revolute → `revolute` (`continuous` when it has no position limit), prismatic →
//! `prismatic`, planar → `planar`, a free-flyer → `floating`, except the usual case of a
//! single tree on a free-flyer at the world's origin, whose joint is left out (the URDF
//! convention for legged robots: load it with `--floating`, or `root_joint=JointModelFreeFlyer()`
//! in Pinocchio). Spherical, universal and helical joints are refused ([`WriteError::Joint`]).
//!
//! URDF requires `effort` and `velocity` on every `<limit>`: a missing one is written as
//! `f64::MAX` (noted). URDF has no capsule, ellipsoid or cone, no armature and no contact
//! masks: a shape without an element is written as the convex hull of points of its surface in
//! an OBJ file (in [`Written::files`]), the others are noted.

use super::{
    esc, geometries_of, num, nums, solid_hull, surface_points, unique, vec3, Outline, Visual,
    VisualShape, WriteError, Written,
};
use crate::collision::{Geometry, Shape};
use crate::multibody::{FrameKind, JointType, Model};
use crate::spatial::{so3, Transform};
use std::collections::HashSet;
use std::fmt::Write;

/// `model` and its collision `geometries` as URDF text, meshes as OBJ files in the folder
/// `mesh_dir` beside it (see the module's documentation).
///
/// ```
/// use rigid::io::write::urdf::write_urdf;
/// let model = rigid::multibody::double_pendulum();
/// let written = write_urdf(&model, &[], &[], "meshes").unwrap();
/// let back = rigid::io::urdf::load_urdf_str(&written.text, false).unwrap();
/// assert_eq!(back.nv(), 2);
/// ```
///
/// # Errors
/// [`WriteError::Joint`] for a joint URDF cannot express.
pub fn write_urdf(
    model: &Model,
    geometries: &[Geometry],
    visuals: &[Visual],
    mesh_dir: &str,
) -> Result<Written, WriteError> {
    let outline = Outline::new(model);
    let mut taken: HashSet<String> = model.frames().iter().map(|f| f.name.clone()).collect();
    taken.extend(outline.link.iter().cloned());
    let mut w = Writer {
        outline: &outline,
        geometries,
        visuals,
        materials: Vec::new(),
        mesh_dir,
        text: String::new(),
        files: Vec::new(),
        notes: Vec::new(),
        mesh_names: HashSet::new(),
        joint_names: model.joints().iter().map(|j| j.name.clone()).collect(),
        unlimited: 0,
        hulls: Vec::new(),
        masked: Vec::new(),
        link_names: outline
            .link
            .iter()
            .cloned()
            .chain(
                model
                    .frames()
                    .iter()
                    .filter(|f| f.kind == FrameKind::Body)
                    .map(|f| f.name.clone()),
            )
            .collect(),
    };
    let free_root = match outline.roots.as_slice() {
        [r] => {
            let j = &model.joints()[*r];
            j.kind == JointType::FreeFlyer && j.placement.is_identity(0.0)
        }
        _ => false,
    };
    let root = if free_root {
        let j = &model.joints()[outline.roots[0]];
        w.notes.push(format!(
            "the free-flyer \"{}\" is left out, as URDF files of floating robots do: load the file \
             with --floating (rigid) or root_joint=JointModelFreeFlyer() (Pinocchio)",
            j.name
        ));
        let dropped = outline.world.len()
            + geometries_of(geometries, None).count()
            + visuals.iter().filter(|v| v.body.is_none()).count();
        if dropped > 0 {
            w.notes.push(format!(
                "{dropped} frames, geometries and visuals fixed in the world are not written: a \
                 floating robot's URDF has no world link"
            ));
        }
        None
    } else {
        let own = outline.world.iter().copied().find(|&f| {
            let f = &model.frames()[f];
            f.kind == FrameKind::Body && f.placement.is_identity(0.0)
        });
        let name = own.map_or_else(
            || unique(&mut taken, "world"),
            |f| model.frames()[f].name.clone(),
        );
        w.link(&name, None);
        w.fixed_frames(&name, &outline.world, own);
        Some(name)
    };
    for &j in &outline.roots {
        w.joint_body(j, root.as_deref())?;
    }
    if !w.hulls.is_empty() {
        w.notes.push(format!(
            "{} capsules, ellipsoids or cones are written as the convex hulls of points of their \
             surfaces (URDF has none of these shapes): {}",
            w.hulls.len(),
            listed(&w.hulls)
        ));
    }
    if !w.masked.is_empty() {
        w.notes.push(format!(
            "{} geometries have contact masks (contype, conaffinity) URDF cannot hold: {}",
            w.masked.len(),
            listed(&w.masked)
        ));
    }
    if model.gravity() != crate::spatial::Vec3::new(0.0, 0.0, -9.81) {
        w.notes.push(format!(
            "the gravity ({}) is not written: URDF holds none, and readers take (0, 0, -9.81)",
            vec3(&model.gravity())
        ));
    }
    let armature = model.armature().iter().filter(|a| **a != 0.0).count();
    if armature > 0 {
        w.notes.push(format!(
            "{armature} armatures are not written: URDF has no armature"
        ));
    }
    if w.unlimited > 0 {
        w.notes.push(format!(
            "{} limits URDF requires were not given (an effort or velocity limit, a prismatic \
             joint's range): written as ±{:e}",
            w.unlimited,
            f64::MAX
        ));
    }
    let text = format!(
        "<?xml version=\"1.0\"?>\n<!-- written by rigid convert -->\n<robot name=\"{}\">\n{}</robot>\n",
        esc(model.name()),
        w.text
    );
    Ok(Written {
        text,
        files: w.files,
        notes: w.notes,
    })
}

struct Writer<'a> {
    outline: &'a Outline<'a>,
    geometries: &'a [Geometry],
    visuals: &'a [Visual],
    /// The colours named so far (`color_k` is the `k`-th).
    materials: Vec<[f64; 4]>,
    mesh_dir: &'a str,
    text: String,
    files: Vec<(String, String)>,
    notes: Vec<String>,
    mesh_names: HashSet<String>,
    joint_names: HashSet<String>,
    unlimited: usize,
    /// The link names written or to be written.
    link_names: HashSet<String>,
    /// Geometries written as hulls for want of their shape.
    hulls: Vec<String>,
    /// Geometries whose contact masks are not the default.
    masked: Vec<String>,
}

/// The first names, quoted, and how many more.
fn listed(names: &[String]) -> String {
    let shown: Vec<String> = names.iter().take(4).map(|n| format!("\"{n}\"")).collect();
    match names.len() {
        n if n > 4 => format!("{} and {} more", shown.join(", "), n - 4),
        _ => shown.join(", "),
    }
}

/// `<origin xyz rpy>` of a placement on its line, indented by `indent` (nothing for the
/// identity).
fn origin(t: &Transform, indent: usize) -> String {
    if t.is_identity(0.0) {
        return String::new();
    }
    let (r, p, y) = so3::to_rpy(&t.rotation);
    format!(
        "{:indent$}<origin xyz=\"{}\" rpy=\"{} {} {}\"/>\n",
        "",
        vec3(&t.translation),
        num(r),
        num(p),
        num(y)
    )
}

impl Writer<'_> {
    /// A finite limit, or `±f64::MAX` (counted).
    fn limit(&mut self, x: f64) -> String {
        if x.is_finite() {
            num(x)
        } else {
            self.unlimited += 1;
            num(f64::MAX.copysign(x))
        }
    }

    /// Joint `j`'s link, its joint to `parent` (`None`: the free-flyer root, left out), its
    /// fixed frames and its children.
    fn joint_body(&mut self, j: usize, parent: Option<&str>) -> Result<(), WriteError> {
        let link = self.outline.link[j].clone();
        self.link(&link, Some(j));
        if let Some(parent) = parent {
            self.joint(j, parent, &link)?;
        }
        let fixed = self.outline.fixed[j].clone();
        self.fixed_frames(&link, &fixed, None);
        for c in self.outline.children[j].clone() {
            self.joint_body(c, Some(&link))?;
        }
        Ok(())
    }

    /// The `<joint>` of joint `j` from link `parent` to link `child`.
    fn joint(&mut self, j: usize, parent: &str, child: &str) -> Result<(), WriteError> {
        let model = self.outline.model;
        let joint = &model.joints()[j];
        let refuse = |hint: &str| WriteError::Joint {
            joint: joint.name.clone(),
            kind: joint.kind.name(),
            format: "URDF",
            hint: hint.into(),
        };
        let (lo, hi) = (
            model.lower_limits()[joint.idx_q],
            model.upper_limits()[joint.idx_q],
        );
        let (kind, axis) = match joint.kind {
            JointType::Revolute { axis } => {
                let free = joint.continuous || (lo.is_infinite() && hi.is_infinite());
                (if free { "continuous" } else { "revolute" }, Some(axis))
            }
            JointType::Prismatic { axis } => ("prismatic", Some(axis)),
            JointType::Planar => ("planar", Some(crate::spatial::Vec3::z())),
            JointType::FreeFlyer => ("floating", None),
            JointType::Spherical | JointType::Universal { .. } => {
                return Err(refuse(": MJCF has one (rigid convert to .xml)"))
            }
            JointType::Helical { .. } => return Err(refuse("")),
        };
        let mut s = format!(
            "  <joint name=\"{}\" type=\"{kind}\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n{}",
            esc(&joint.name),
            esc(parent),
            esc(child),
            origin(&joint.placement, 4)
        );
        if let Some(a) = axis {
            let _ = writeln!(s, "    <axis xyz=\"{}\"/>", vec3(&a));
        }
        if joint.nv == 1 {
            let dof = joint.idx_v;
            let (effort, velocity) = (model.effort_limits()[dof], model.velocity_limits()[dof]);
            let bounded = kind != "continuous";
            if bounded || effort.is_finite() || velocity.is_finite() {
                let mut l = String::from("    <limit");
                if bounded {
                    let _ = write!(
                        l,
                        " lower=\"{}\" upper=\"{}\"",
                        self.limit(lo),
                        self.limit(hi)
                    );
                }
                let _ = writeln!(
                    l,
                    " effort=\"{}\" velocity=\"{}\"/>",
                    self.limit(effort),
                    self.limit(velocity)
                );
                s.push_str(&l);
            }
        }
        let dofs = joint.dofs();
        let (b, f) = (&model.damping()[dofs.clone()], &model.friction()[dofs]);
        if b.iter().chain(f).any(|x| *x != 0.0) {
            if b.iter().any(|x| *x != b[0]) || f.iter().any(|x| *x != f[0]) {
                self.notes.push(format!(
                    "joint \"{}\": URDF gives one damping and one friction to all of its degrees \
                     of freedom: the first one's are written",
                    joint.name
                ));
            }
            let _ = writeln!(
                s,
                "    <dynamics damping=\"{}\" friction=\"{}\"/>",
                num(b[0]),
                num(f[0])
            );
        }
        s.push_str("  </joint>\n");
        self.text.push_str(&s);
        Ok(())
    }

    /// A `<link>` with body `body`'s inertia and collisions (`None`: the world's root link,
    /// massless, with the geometries fixed in the world).
    fn link(&mut self, name: &str, body: Option<usize>) {
        let mut s = format!("  <link name=\"{}\">\n", esc(name));
        if let Some(j) = body {
            let g = &self.outline.model.inertias()[j];
            if g.mass() != 0.0 || g.inertia_origin().matrix().amax() != 0.0 {
                let m = *g.inertia_com().matrix();
                let _ = write!(
                    s,
                    "    <inertial>\n      <origin xyz=\"{}\"/>\n      <mass value=\"{}\"/>\n      \
                     <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n    \
                     </inertial>\n",
                    vec3(&g.com()),
                    num(g.mass()),
                    num(m[(0, 0)]),
                    num(m[(0, 1)]),
                    num(m[(0, 2)]),
                    num(m[(1, 1)]),
                    num(m[(1, 2)]),
                    num(m[(2, 2)])
                );
            }
        }
        // the body's visuals but those of the links welded to it (written on those links)
        let welded = self.welded_links(body);
        let visuals: Vec<&Visual> = self
            .visuals
            .iter()
            .filter(|v| {
                v.body.map(|b| b.0) == body && (v.link == name || !welded.contains(&v.link))
            })
            .collect();
        for v in visuals {
            if let Some(e) = self.visual(v, &Transform::identity()) {
                s.push_str(&e);
            }
        }
        let geometries: Vec<&Geometry> = geometries_of(self.geometries, body).collect();
        for g in geometries {
            if let Some(c) = self.collision(g) {
                s.push_str(&c);
            }
        }
        s.push_str("  </link>\n");
        self.text.push_str(&s);
    }

    /// The frames `frames` fixed in link `link`, each a massless link on a `fixed` joint named
    /// as the model's fixed-joint frame at the same place, else after the link; `skip` is the
    /// link's own frame.
    fn fixed_frames(&mut self, link: &str, frames: &[usize], skip: Option<usize>) {
        let model = self.outline.model;
        let mut operational = 0;
        for &f in frames {
            let frame = &model.frames()[f];
            if Some(f) == skip || frame.kind == FrameKind::FixedJoint {
                continue;
            }
            operational += usize::from(frame.kind == FrameKind::Operational);
            // an operational frame may share its name with a link (two namespaces in rigid)
            let lname = match frame.kind {
                FrameKind::Operational => unique(&mut self.link_names, &frame.name),
                FrameKind::Body | FrameKind::FixedJoint => frame.name.clone(),
            };
            let named = frames.iter().map(|&k| &model.frames()[k]).find(|k| {
                k.kind == FrameKind::FixedJoint
                    && k.placement == frame.placement
                    && !self.joint_names.contains(&k.name)
            });
            let jname = match named {
                Some(k) => k.name.clone(),
                None => format!("{lname}_joint"),
            };
            let jname = unique(&mut self.joint_names, &jname);
            let mut visuals = String::new();
            if frame.kind == FrameKind::Body {
                let mine: Vec<&Visual> = self
                    .visuals
                    .iter()
                    .filter(|v| v.link == frame.name && v.body == frame.parent)
                    .collect();
                for v in mine {
                    if let Some(e) = self.visual(v, &frame.placement) {
                        visuals.push_str(&e);
                    }
                }
            }
            let link_element = if visuals.is_empty() {
                format!("  <link name=\"{}\"/>\n", esc(&lname))
            } else {
                format!("  <link name=\"{}\">\n{visuals}  </link>\n", esc(&lname))
            };
            let _ = write!(
                self.text,
                "{link_element}  <joint name=\"{}\" type=\"fixed\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n{}  </joint>\n",
                esc(&jname),
                esc(link),
                esc(&lname),
                origin(&frame.placement, 4)
            );
        }
        if operational > 0 {
            self.notes.push(format!(
                "{operational} operational frames of \"{link}\" are written as links on fixed \
                 joints (URDF has no frames): read back, they are links"
            ));
        }
    }

    /// The `<geometry>` child of `shape` (named `name` in notes): a shape URDF lacks (capsule,
    /// cone, ellipsoid, hull) as an OBJ mesh of its hull, written into `mesh_dir`.
    fn geometry_tag(&mut self, name: &str, shape: &Shape) -> Option<String> {
        Some(match shape {
            Shape::Sphere { radius } => format!("<sphere radius=\"{}\"/>", num(*radius)),
            Shape::Box { size } => format!("<box size=\"{}\"/>", vec3(size)),
            Shape::Cylinder { radius, length } => format!(
                "<cylinder radius=\"{}\" length=\"{}\"/>",
                num(*radius),
                num(*length)
            ),
            Shape::Capsule { .. }
            | Shape::Cone { .. }
            | Shape::Ellipsoid { .. }
            | Shape::ConvexHull { .. } => {
                let Some((vertices, triangles)) = solid_hull(&surface_points(shape, 32)) else {
                    self.notes.push(format!(
                        "geometry \"{}\": its hull is flat: not written",
                        name
                    ));
                    return None;
                };
                if !matches!(shape, Shape::ConvexHull { .. }) {
                    self.hulls.push(name.to_string());
                }
                let stem: String = name
                    .chars()
                    .map(|c| {
                        if c.is_ascii_alphanumeric() || c == '-' {
                            c
                        } else {
                            '_'
                        }
                    })
                    .collect();
                let mut obj =
                    String::from("# the convex hull of this shape (as rigid collides it)\n");
                for v in &vertices {
                    let _ = writeln!(obj, "v {}", vec3(v));
                }
                for t in &triangles {
                    let _ = writeln!(obj, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
                }
                // a shape both collided and drawn (an MJCF geom) is one file
                let file = match self.files.iter().find(|(_, text)| *text == obj) {
                    Some((file, _)) => file.clone(),
                    None => {
                        let file = format!(
                            "{}/{}.obj",
                            self.mesh_dir,
                            unique(&mut self.mesh_names, &stem)
                        );
                        self.files.push((file.clone(), obj));
                        file
                    }
                };
                format!("<mesh filename=\"{}\"/>", esc(&file))
            }
        })
    }

    /// A `<visual>` element: a primitive, or a mesh by its file's absolute path and its scale,
    /// with its colour as a material named after it (`color_k`, one name per colour).
    /// `link_placement` is the pose of the link it is written on in the body's joint frame.
    fn visual(&mut self, v: &Visual, link_placement: &Transform) -> Option<String> {
        let geometry = match &v.shape {
            VisualShape::Primitive(shape) => self.geometry_tag(&v.name, shape)?,
            VisualShape::Mesh { file, scale } => {
                let scale = if *scale == crate::spatial::Vec3::repeat(1.0) {
                    String::new()
                } else {
                    format!(" scale=\"{}\"", vec3(scale))
                };
                format!(
                    "<mesh filename=\"{}\"{scale}/>",
                    esc(&file.display().to_string())
                )
            }
        };
        let material = match v.rgba {
            None => String::new(),
            Some(c) => {
                let k = match self.materials.iter().position(|m| *m == c) {
                    Some(k) => k,
                    None => {
                        self.materials.push(c);
                        self.materials.len() - 1
                    }
                };
                format!(
                    "      <material name=\"color_{k}\">\n        <color rgba=\"{}\"/>\n      </material>\n",
                    nums(c)
                )
            }
        };
        Some(format!(
            "    <visual name=\"{}\">\n{}      <geometry>\n        {geometry}\n      </geometry>\n{material}    </visual>\n",
            esc(&v.name),
            origin(&(link_placement.inverse() * v.placement), 6)
        ))
    }

    /// The links welded to body `body` (`None`: the world) that are written as links of their
    /// own (its [`FrameKind::Body`] frames but its own link's).
    fn welded_links(&self, body: Option<usize>) -> Vec<String> {
        let frames = match body {
            Some(j) => &self.outline.fixed[j],
            None => &self.outline.world,
        };
        frames
            .iter()
            .map(|&f| &self.outline.model.frames()[f])
            .filter(|f| f.kind == FrameKind::Body)
            .map(|f| f.name.clone())
            .collect()
    }

    /// A `<collision>` element (a shape URDF lacks as an OBJ mesh of its hull).
    fn collision(&mut self, g: &Geometry) -> Option<String> {
        let geometry = self.geometry_tag(&g.name, &g.shape)?;
        if g.contype != 1 || g.conaffinity != 1 {
            self.masked.push(g.name.clone());
        }
        Some(format!(
            "    <collision name=\"{}\">\n{}      <geometry>\n        {geometry}\n      </geometry>\n    </collision>\n",
            esc(&g.name),
            origin(&g.placement, 6)
        ))
    }
}
