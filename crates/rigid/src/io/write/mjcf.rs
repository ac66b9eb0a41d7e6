//! A model as MuJoCo's MJCF: one `<body>` per moving joint (at the joint frame, so that each
//! `<joint>` sits at its body's origin), nested as the tree, with its `<inertial>` (`mass`, `pos`
//! the centre of mass, `fullinertia` about it) and its geoms; links welded by fixed joints as
//! bodies without joints, operational frames as `<site>`s.
//!
//! Joint types: revolute → `hinge`, prismatic → `slide`, spherical → `ball`, a free-flyer at
//! the top of the tree → `free` (its body placed at the joint's placement, MuJoCo's `qpos0`), a
//! universal joint → two hinges in one body (MuJoCo composes a body's joints in order, each about
//! its axis in the frame the previous ones moved: `exp([a₁] q₁) exp([a₂] q₂)`, rigid's
//! universal joint, with the same coordinates). Planar and helical joints are refused
//! ([`WriteError::Joint`]).
//!
//! `<compiler inertiafromgeom="false">` keeps the geoms from adding mass, and `autolimits`
//! makes a written `range` a limit. MuJoCo has no velocity limit (a note says how many were
//! dropped); an effort limit becomes the joint's `actuatorfrcrange`.

use super::{
    esc, geometries_of, num, nums, quat_wxyz, unique, vec3, Outline, Visual, VisualShape,
    WriteError, Written,
};
use crate::collision::{Geometry, Shape};
use crate::mass::RotationalInertia;
use crate::multibody::{FrameKind, JointType, Model};
use crate::spatial::{Transform, Vec3};
use std::collections::HashSet;
use std::fmt::Write;

/// `model`, its collision `geometries` and its `visuals` as MJCF text (see the module's
/// documentation).
///
/// ```
/// use rigid::io::write::mjcf::write_mjcf;
/// let model = rigid::multibody::double_pendulum();
/// let written = write_mjcf(&model, &[], &[]).unwrap();
/// let back = rigid::io::mjcf::load_mjcf_str(&written.text, ".".as_ref()).unwrap();
/// assert_eq!(back.model.nv(), 2);
/// ```
///
/// # Errors
/// [`WriteError::Joint`] for a joint MJCF cannot express.
pub fn write_mjcf(
    model: &Model,
    geometries: &[Geometry],
    visuals: &[Visual],
) -> Result<Written, WriteError> {
    let outline = Outline::new(model);
    let mut w = Writer {
        outline: &outline,
        geometries,
        visuals,
        body: String::new(),
        assets: String::new(),
        geom_names: HashSet::new(),
        notes: Vec::new(),
        velocity_limits: 0,
    };
    for g in geometries_of(geometries, None) {
        w.geom(g, 4);
    }
    for v in visuals.iter().filter(|v| v.body.is_none()) {
        w.visual(v, 4);
    }
    for &f in &outline.world {
        // MuJoCo's world body is "world": a link of that name is it
        if model.frames()[f].name != "world" {
            w.fixed_frame(f, 4);
        }
    }
    for &j in &outline.roots {
        w.joint_body(j, 4, Vec::new(), Transform::identity())?;
    }
    if w.velocity_limits > 0 {
        w.notes.push(format!(
            "{} velocity limits are not written: MJCF has no velocity limit",
            w.velocity_limits
        ));
    }
    let mut text = format!(
        "<mujoco model=\"{}\">\n  <!-- written by rigid convert -->\n  <compiler angle=\"radian\" \
         autolimits=\"true\" inertiafromgeom=\"false\"/>\n  <option gravity=\"{}\"/>\n",
        esc(model.name()),
        vec3(&model.gravity())
    );
    if !w.assets.is_empty() {
        let _ = write!(text, "  <asset>\n{}  </asset>\n", w.assets);
    }
    let _ = write!(text, "  <worldbody>\n{}  </worldbody>\n</mujoco>\n", w.body);
    Ok(Written {
        text,
        files: Vec::new(),
        notes: w.notes,
    })
}

/// True for a body without mass or rotational inertia.
fn is_zero(g: &crate::mass::SpatialInertia) -> bool {
    g.mass() == 0.0 && g.inertia_origin().matrix().amax() == 0.0
}

/// The smallest principal moment of inertia written (kg·m²): MuJoCo refuses a moving body with
/// one below its `mjMINVAL` (1e-15).
const MIN_MOMENT: f64 = 1e-12;

struct Writer<'a> {
    outline: &'a Outline<'a>,
    geometries: &'a [Geometry],
    visuals: &'a [Visual],
    body: String,
    assets: String,
    geom_names: HashSet<String>,
    notes: Vec<String>,
    velocity_limits: usize,
}

/// ` pos="…" quat="…"` of a placement (each left out when it is the identity's).
fn pose(t: &Transform) -> String {
    let mut s = String::new();
    if t.translation != Vec3::zeros() {
        let _ = write!(s, " pos=\"{}\"", vec3(&t.translation));
    }
    if let Some(q) = quat_wxyz(t) {
        let _ = write!(s, " quat=\"{}\"", nums(q));
    }
    s
}

impl Writer<'_> {
    fn line(&mut self, depth: usize, text: &str) {
        let _ = writeln!(self.body, "{:depth$}{text}", "");
    }

    /// True when joint `j`'s body is massless, moved by a hinge or a slide, with one child body
    /// and nothing else in it: MuJoCo refuses massless moving bodies ("mass and inertia of
    /// moving bodies must be larger than mjMINVAL"), so its joint goes into the child's body.
    fn merged_away(&self, j: usize) -> bool {
        let model = self.outline.model;
        let scalar = matches!(
            model.joints()[j].kind,
            JointType::Revolute { .. } | JointType::Prismatic { .. }
        );
        scalar
            && is_zero(&model.inertias()[j])
            && self.outline.children[j].len() == 1
            && geometries_of(self.geometries, Some(j)).next().is_none()
            && self.outline.fixed[j]
                .iter()
                .all(|&f| model.frames()[f].kind == FrameKind::FixedJoint)
    }

    /// The `<body>` of joint `j`, its joints, inertia, geoms, fixed frames and children.
    /// `carried` are the joints of massless ancestors merged into it ([`Self::merged_away`]),
    /// each with its frame in the frame `j`'s placement is given in, and `before` the
    /// placement of that frame in the parent body's.
    fn joint_body(
        &mut self,
        j: usize,
        depth: usize,
        carried: Vec<(usize, Transform)>,
        before: Transform,
    ) -> Result<(), WriteError> {
        let model = self.outline.model;
        let joint = &model.joints()[j];
        if self.merged_away(j) {
            let inv = joint.placement.inverse();
            let mut carried: Vec<_> = carried.into_iter().map(|(k, f)| (k, inv * f)).collect();
            carried.push((j, Transform::identity()));
            let c = self.outline.children[j][0];
            self.notes.push(format!(
                "the massless body \"{}\" is merged into \"{}\", its joint \"{}\" with it \
                 (MuJoCo refuses massless moving bodies): the same motion and coordinates",
                self.outline.link[j], self.outline.link[c], joint.name
            ));
            let lost = self
                .visuals
                .iter()
                .filter(|v| v.body.map(|b| b.0) == Some(j))
                .count();
            if lost > 0 {
                self.notes.push(format!(
                    "the {lost} visuals of the merged body \"{}\" are not written (it has no \
                     body of its own in the file)",
                    self.outline.link[j]
                ));
            }
            return self.joint_body(c, depth, carried, before * joint.placement);
        }
        let name = esc(&self.outline.link[j]);
        let at = before * joint.placement;
        self.line(depth, &format!("<body name=\"{name}\"{}>", pose(&at)));
        let d = depth + 2;
        let inv = joint.placement.inverse();
        for (k, f) in carried {
            let (kind, axis) = match model.joints()[k].kind {
                JointType::Revolute { axis } => ("hinge", axis),
                JointType::Prismatic { axis } => ("slide", axis),
                JointType::Spherical
                | JointType::FreeFlyer
                | JointType::Planar
                | JointType::Helical { .. }
                | JointType::Universal { .. } => {
                    unreachable!("merged_away takes hinges and slides only")
                }
            };
            self.dof(k, 0, "", kind, Some(axis), &(inv * f), d);
        }
        let refuse = |hint: &str| WriteError::Joint {
            joint: joint.name.clone(),
            kind: joint.kind.name(),
            format: "MJCF",
            hint: hint.into(),
        };
        let here = Transform::identity();
        match joint.kind {
            JointType::Revolute { axis } => self.dof(j, 0, "", "hinge", Some(axis), &here, d),
            JointType::Prismatic { axis } => self.dof(j, 0, "", "slide", Some(axis), &here, d),
            JointType::Spherical => self.dof(j, 0, "", "ball", None, &here, d),
            JointType::FreeFlyer if joint.parent.is_none() => {
                self.dof(j, 0, "", "free", None, &here, d);
            }
            JointType::FreeFlyer => {
                return Err(refuse(
                    ": MuJoCo's free joint can only move a top-level body",
                ))
            }
            JointType::Universal { axis1, axis2 } => {
                self.dof(j, 0, "_1", "hinge", Some(axis1), &here, d);
                self.dof(j, 1, "_2", "hinge", Some(axis2), &here, d);
                self.notes.push(format!(
                    "joint \"{0}\" (universal) is written as two hinges, \"{0}_1\" and \"{0}_2\", \
                     in one body: the same motion and coordinates",
                    joint.name
                ));
            }
            JointType::Planar => return Err(refuse("")),
            JointType::Helical { .. } => return Err(refuse("")),
        }
        self.inertial(j, d);
        for g in geometries_of(self.geometries, Some(j)) {
            self.geom(g, d);
        }
        for v in self
            .visuals
            .iter()
            .filter(|v| v.body.map(|b| b.0) == Some(j))
        {
            self.visual(v, d);
        }
        for f in self.outline.fixed[j].clone() {
            self.fixed_frame(f, d);
        }
        for c in self.outline.children[j].clone() {
            self.joint_body(c, d, Vec::new(), Transform::identity())?;
        }
        self.line(depth, "</body>");
        Ok(())
    }

    /// One `<joint>` for degree of freedom `k` of joint `j` (its limits, armature, damping,
    /// friction), named after the joint with `suffix`, its frame at `frame` in the body's.
    #[allow(clippy::too_many_arguments)]
    fn dof(
        &mut self,
        j: usize,
        k: usize,
        suffix: &str,
        kind: &str,
        axis: Option<Vec3>,
        frame: &Transform,
        depth: usize,
    ) {
        let model = self.outline.model;
        let joint = &model.joints()[j];
        let (dof, coord) = (joint.idx_v + k, joint.idx_q + k);
        let mut s = format!(
            "<joint name=\"{}{suffix}\" type=\"{kind}\"",
            esc(&joint.name)
        );
        if frame.translation != Vec3::zeros() {
            let _ = write!(s, " pos=\"{}\"", vec3(&frame.translation));
        }
        if let Some(axis) = axis {
            let _ = write!(s, " axis=\"{}\"", vec3(&(frame.rotation * axis)));
        }
        let scalar = kind == "hinge" || kind == "slide";
        let (lo, hi) = (model.lower_limits()[coord], model.upper_limits()[coord]);
        if scalar && lo.is_finite() && hi.is_finite() {
            let _ = write!(s, " range=\"{} {}\"", num(lo), num(hi));
        } else if scalar && (lo.is_finite() || hi.is_finite()) {
            self.notes.push(format!(
                "joint \"{}\": a one-sided limit ({} to {}) is not written: MJCF's range has two",
                joint.name,
                num(lo),
                num(hi)
            ));
        }
        let dofs = joint.dofs();
        let one = |v: &[f64]| v[dof];
        let all_same = |v: &[f64]| v[dofs.clone()].iter().all(|x| *x == v[dof]);
        for (attr, v) in [
            ("armature", model.armature()),
            ("damping", model.damping()),
            ("frictionloss", model.friction()),
        ] {
            if one(v) != 0.0 {
                if !scalar && !all_same(v) {
                    self.notes.push(format!(
                        "joint \"{}\": MJCF gives one {attr} to all of its degrees of freedom: \
                         the first one's is written",
                        joint.name
                    ));
                }
                let _ = write!(s, " {attr}=\"{}\"", num(one(v)));
            }
        }
        let effort = model.effort_limits()[dof];
        if scalar && effort.is_finite() {
            let _ = write!(s, " actuatorfrcrange=\"{} {}\"", num(-effort), num(effort));
        }
        if model.velocity_limits()[dof].is_finite() {
            self.velocity_limits += 1;
        }
        s.push_str("/>");
        self.line(depth, &s);
    }

    /// The `<inertial>` of joint `j`'s body (none when it carries no mass).
    fn inertial(&mut self, j: usize, depth: usize) {
        let g = &self.outline.model.inertias()[j];
        if is_zero(g) {
            if !self.outline.children[j].is_empty() || self.outline.model.joints()[j].nv > 0 {
                self.notes.push(format!(
                    "body \"{}\" moves and has no mass: MuJoCo refuses it (\"mass and inertia of \
                     moving bodies must be larger than mjMINVAL\"); give it a mass, or set \
                     <compiler boundmass boundinertia>",
                    self.outline.link[j]
                ));
            }
            return;
        }
        let mut m = *g.inertia_com().matrix();
        let (moments, axes) = g.inertia_com().principal();
        if moments.z > moments.x + moments.y + 1e-12 * moments.z {
            self.notes.push(format!(
                "body \"{}\": principal moments {} kg·m² violate A + B >= C, which MuJoCo refuses \
                 (its <compiler balanceinertia=\"true\"> would change them; rigid doctor says why)",
                self.outline.link[j],
                vec3(&moments)
            ));
        }
        if moments.min() < MIN_MOMENT {
            let raise = moments.map(|l| (MIN_MOMENT - l).max(0.0));
            m += axes * crate::spatial::Mat3::from_diagonal(&raise) * axes.transpose();
            self.notes.push(format!(
                "body \"{}\": principal moments of inertia {} kg·m² (a point mass or a thin rod), \
                 which MuJoCo refuses: the smallest raised to {MIN_MOMENT:e}",
                self.outline.link[j],
                vec3(&moments)
            ));
        }
        let full = nums(RotationalInertia::from_matrix_unchecked(&m).entries());
        self.line(
            depth,
            &format!(
                "<inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{full}\"/>",
                vec3(&g.com()),
                num(g.mass())
            ),
        );
    }

    /// A frame fixed in a body: a welded link as a `<body>` without joints, an operational
    /// frame as a `<site>`; a fixed joint's frame is the welded link's and is not repeated.
    fn fixed_frame(&mut self, f: usize, depth: usize) {
        let frame = &self.outline.model.frames()[f];
        let at = pose(&frame.placement);
        let name = esc(&frame.name);
        match frame.kind {
            FrameKind::Body => self.line(depth, &format!("<body name=\"{name}\"{at}/>")),
            FrameKind::Operational => self.line(depth, &format!("<site name=\"{name}\"{at}/>")),
            FrameKind::FixedJoint => {}
        }
    }

    /// The `type` and `size` (or `mesh`) attributes of `shape`, for a geom named `name` (a
    /// cone or hull as an inline `<mesh vertex>` asset of that name); `None` when MuJoCo cannot
    /// take it (a flat hull), with a note.
    fn shape_attrs(&mut self, name: &str, shape: &Shape) -> Option<String> {
        Some(match shape {
            Shape::Sphere { radius } => format!("type=\"sphere\" size=\"{}\"", num(*radius)),
            Shape::Box { size } => format!("type=\"box\" size=\"{}\"", vec3(&(size / 2.0))),
            Shape::Cylinder { radius, length } => format!(
                "type=\"cylinder\" size=\"{} {}\"",
                num(*radius),
                num(length / 2.0)
            ),
            Shape::Capsule { radius, length } => format!(
                "type=\"capsule\" size=\"{} {}\"",
                num(*radius),
                num(length / 2.0)
            ),
            Shape::Ellipsoid { semi_axes } => {
                format!("type=\"ellipsoid\" size=\"{}\"", vec3(semi_axes))
            }
            Shape::Cone { .. } | Shape::ConvexHull { .. } => {
                if matches!(shape, Shape::Cone { .. }) {
                    self.notes.push(format!(
                        "geometry \"{}\": MJCF has no cone: written as the hull of 33 points of it",
                        name
                    ));
                }
                // the hull's vertices: MuJoCo collides a mesh as its hull too
                let points = super::surface_points(shape, 32);
                let Some((points, _)) = super::solid_hull(&points) else {
                    self.notes.push(format!(
                        "geometry \"{}\": its hull is flat, which MuJoCo refuses: not written",
                        name
                    ));
                    return None;
                };
                let _ = writeln!(
                    self.assets,
                    "    <mesh name=\"{}\" vertex=\"{}\"/>",
                    esc(name),
                    nums(points.iter().flat_map(|p| p.iter().copied()))
                );
                format!("type=\"mesh\" mesh=\"{}\"", esc(name))
            }
        })
    }

    /// A visual `<geom>` (no contact, no mass: `contype="0" conaffinity="0" group="1"`): a
    /// primitive (a degenerate one left out with a note), or a mesh asset by its file for OBJ,
    /// else by its vertices and faces read by rigid (STL, COLLADA), with its colour.
    fn visual(&mut self, v: &Visual, depth: usize) {
        let name = unique(&mut self.geom_names, &v.name);
        let shape = match &v.shape {
            VisualShape::Primitive(shape) => match shape.check() {
                Err(e) => {
                    self.notes.push(format!(
                        "visual \"{}\": {e}, which MuJoCo refuses: not written",
                        v.name
                    ));
                    return;
                }
                Ok(()) => match self.shape_attrs(&name, shape) {
                    Some(a) => a,
                    None => return,
                },
            },
            VisualShape::Mesh { file, scale } => {
                let ext = file
                    .extension()
                    .and_then(|e| e.to_str())
                    .map(str::to_ascii_lowercase);
                let scale = if *scale == Vec3::repeat(1.0) {
                    String::new()
                } else {
                    format!(" scale=\"{}\"", vec3(scale))
                };
                // MuJoCo reads OBJ; its STL reader takes binary files of at most 200,000 faces
                // only, so an STL (like a COLLADA file) goes in as its triangles
                let source = if ext.as_deref() == Some("obj") {
                    format!("file=\"{}\"", esc(&file.display().to_string()))
                } else {
                    match crate::io::mesh_file::read_mesh(file) {
                        Ok(m) if !m.triangles.is_empty() => format!(
                            "vertex=\"{}\" face=\"{}\"",
                            nums(m.vertices.iter().flat_map(|p| p.iter().copied())),
                            m.triangles
                                .iter()
                                .flat_map(|t| t.iter().map(ToString::to_string))
                                .collect::<Vec<_>>()
                                .join(" ")
                        ),
                        Ok(_) | Err(_) => {
                            self.notes.push(format!(
                                "visual \"{}\": its mesh {} cannot be read: not written",
                                v.name,
                                file.display()
                            ));
                            return;
                        }
                    }
                };
                // a visual mesh need not bound a volume: MuJoCo's shell inertia accepts it
                let _ = writeln!(
                    self.assets,
                    "    <mesh name=\"{}\" {source}{scale} inertia=\"shell\"/>",
                    esc(&name)
                );
                format!("type=\"mesh\" mesh=\"{}\"", esc(&name))
            }
        };
        let mut s = format!(
            "<geom name=\"{}\" {shape}{} contype=\"0\" conaffinity=\"0\" group=\"1\"",
            esc(&name),
            pose(&v.placement)
        );
        if let Some(c) = v.rgba {
            let _ = write!(s, " rgba=\"{}\"", nums(c));
        }
        s.push_str("/>");
        self.line(depth, &s);
    }

    /// A `<geom>` (a mesh's hull as an inline `<mesh vertex>` asset).
    fn geom(&mut self, g: &Geometry, depth: usize) {
        let name = unique(&mut self.geom_names, &g.name);
        let Some(shape) = self.shape_attrs(&name, &g.shape) else {
            return;
        };
        let mut s = format!(
            "<geom name=\"{}\" {shape}{}",
            esc(&name),
            pose(&g.placement)
        );
        if let Some(mu) = g.friction {
            let _ = write!(s, " friction=\"{}\"", num(mu));
        }
        if g.contype != 1 {
            let _ = write!(s, " contype=\"{}\"", g.contype);
        }
        if g.conaffinity != 1 {
            let _ = write!(s, " conaffinity=\"{}\"", g.conaffinity);
        }
        s.push_str("/>");
        self.line(depth, &s);
    }
}
