//! The links and joints of an SDF model built into a [`Model`]: a depth-first walk from the world
//! and from each floating root, one rigid joint per moving SDF joint (its frame the SDF joint
//! frame), the links welded by fixed joints merged into their parent body, and each joint that
//! closes a loop made a constraint model.

use super::parse::{Axis, Joint, Link, Poses, Raw};
use super::{SdfError, SdfModel, SdfWarning};
use crate::collision::Geometry;
use crate::io::urdf::ROOT_JOINT_NAME;
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::multibody::constraints::ConstraintModel;
use crate::multibody::{FrameKind, JointId, JointType, ModelBuilder};
use crate::spatial::{Transform, Vec3};
use std::collections::HashMap;

/// Distance between the two points that hold a revolute joint closing a loop (m).
const HINGE_SPAN: f64 = 0.1;

struct Walk<'a> {
    raw: &'a Raw,
    /// Each link's pose in the world (the model's pose times its pose in the model).
    world: Vec<Transform>,
    /// Each named frame's pose in the world.
    poses: HashMap<String, Transform>,
    by_name: HashMap<&'a str, usize>,
    /// Each link's body and its pose in the body's joint frame, once placed.
    at: Vec<Option<(Option<JointId>, Transform)>>,
    /// Each body's joint frame in the world.
    frame_of: HashMap<Option<JointId>, Transform>,
    b: ModelBuilder,
    loops: Vec<&'a Joint>,
    geometries: Vec<Geometry>,
    warnings: Vec<SdfWarning>,
}

fn invalid(j: &Joint, message: impl Into<String>) -> SdfError {
    SdfError::Invalid {
        line: j.line,
        element: format!("joint \"{}\"", j.name),
        message: message.into(),
    }
}

impl<'a> Walk<'a> {
    /// Link `l`'s inertia in its link frame.
    fn inertia(&self, l: &Link) -> Result<SpatialInertia, SdfError> {
        let Some((pose, mass, i)) = &l.inertial else {
            return Ok(SpatialInertia::zero());
        };
        let at = |e: String| SdfError::Invalid {
            line: l.line,
            element: format!("link \"{}\"", l.name),
            message: e,
        };
        if *mass < 0.0 {
            return Err(at(format!("negative mass {mass}")));
        }
        let rot = RotationalInertia::new(i[0], i[1], i[2], i[3], i[4], i[5]);
        // about the centre of mass, in the inertial frame; then into the link frame
        let g = SpatialInertia::from_com(*mass, Vec3::zeros(), rot);
        Ok(g.transformed(pose))
    }

    /// `axis` in the frame of joint `j` (at pose `jw` in the world).
    fn axis_in_joint(&self, j: &Joint, axis: &Axis, jw: &Transform) -> Result<Vec3, SdfError> {
        let Some(f) = axis.expressed_in.as_deref() else {
            return Ok(axis.xyz);
        };
        let fw = match f {
            "__model__" | "world" => self.poses["__model__"],
            name => *self.poses.get(name).ok_or_else(|| {
                invalid(
                    j,
                    format!("the axis is expressed in \"{name}\", which is not defined"),
                )
            })?,
        };
        Ok(jw.rotation.transpose() * fw.rotation * axis.xyz)
    }

    /// Places the link `c` under joint `j` from the parent body `pb`, then walks on.
    fn attach(&mut self, j: &'a Joint, pb: Option<JointId>, c: usize) -> Result<(), SdfError> {
        let link = &self.raw.links[c];
        let g = self.inertia(link)?;
        let base = self.frame_of[&pb];
        let jw = self.poses[&j.name];
        let at_err = |e: crate::multibody::ModelError| invalid(j, e.to_string());
        let axis = |w: &Self, which: &Option<Axis>, tag: &str| -> Result<Vec3, SdfError> {
            let a = which
                .as_ref()
                .ok_or_else(|| invalid(j, format!("no <{tag}>")))?;
            w.axis_in_joint(j, a, &jw)
        };
        let kind = match j.kind.as_str() {
            "fixed" => None,
            "revolute" | "continuous" => {
                Some(JointType::Revolute {
                    axis: axis(self, &j.axis, "axis")?,
                })
            }
            "prismatic" => Some(JointType::Prismatic {
                axis: axis(self, &j.axis, "axis")?,
            }),
            "ball" => Some(JointType::Spherical),
            // two rotations in series, `axis` then `axis2` (which turns with the first): the
            // universal joint's kinematics, whether or not the axes are perpendicular
            "universal" | "revolute2" => Some(JointType::Universal {
                axis1: axis(self, &j.axis, "axis")?,
                axis2: axis(self, &j.axis2, "axis2")?,
            }),
            "screw" => {
                let pitch = j.pitch.ok_or_else(|| {
                    invalid(j, "a screw joint needs <screw_thread_pitch> (m per revolution; the older thread_pitch differs in sign and unit between simulators)")
                })?;
                Some(JointType::Helical {
                    axis: axis(self, &j.axis, "axis")?,
                    pitch: pitch / std::f64::consts::TAU,
                })
            }
            other => {
                return Err(invalid(
                    j,
                    format!("joint type \"{other}\" is not supported (revolute, continuous, prismatic, ball, universal, revolute2, screw, fixed)"),
                ))
            }
        };
        let Some(kind) = kind else {
            let x = base.inverse() * self.world[c];
            self.b
                .add_fixed_body(pb, &link.name, x, g)
                .map_err(at_err)?;
            self.b
                .add_frame_of_kind(pb, &j.name, x, FrameKind::FixedJoint)
                .map_err(at_err)?;
            self.at[c] = Some((pb, x));
            return self.walk(c);
        };
        // exactly the inverse of the joint's pose on its child by default (no round-off: the
        // link keeps being the body's own frame)
        let link_in_joint = if j.pose.relative_to.is_none() {
            j.pose.t.inverse()
        } else {
            jw.inverse() * self.world[c]
        };
        let id = self
            .b
            .add_joint(
                pb,
                &j.name,
                kind,
                base.inverse() * jw,
                g.transformed(&link_in_joint),
            )
            .map_err(at_err)?;
        self.b
            .add_frame_of_kind(Some(id), &link.name, link_in_joint, FrameKind::Body)
            .map_err(at_err)?;
        let axes: Vec<&Axis> = [&j.axis, &j.axis2].into_iter().flatten().collect();
        let nv = kind.nv();
        if kind.nq() == 1 {
            let a = axes[0];
            let revolute = matches!(kind, JointType::Revolute { .. });
            if revolute
                && (j.kind == "continuous" || (a.lower.is_infinite() && a.upper.is_infinite()))
            {
                self.b.set_continuous(id).map_err(at_err)?;
            }
            if j.kind != "continuous" {
                self.b
                    .set_limits(id, &[a.lower], &[a.upper], &[a.velocity], &[a.effort])
                    .map_err(at_err)?;
            }
        } else if matches!(kind, JointType::Universal { .. }) && axes.len() == 2 {
            // one coordinate per axis (`universal`, `revolute2`)
            let each = |f: fn(&Axis) -> f64| [f(axes[0]), f(axes[1])];
            self.b
                .set_limits(
                    id,
                    &each(|a| a.lower),
                    &each(|a| a.upper),
                    &each(|a| a.velocity),
                    &each(|a| a.effort),
                )
                .map_err(at_err)?;
        }
        if !axes.is_empty() {
            let pick = |f: fn(&Axis) -> f64| -> Vec<f64> {
                (0..nv).map(|k| f(axes[k.min(axes.len() - 1)])).collect()
            };
            self.b
                .set_joint_dynamics(id, &pick(|a| a.damping), &pick(|a| a.friction))
                .map_err(at_err)?;
        }
        self.frame_of.insert(Some(id), jw);
        self.at[c] = Some((Some(id), link_in_joint));
        self.walk(c)
    }

    /// The joints whose parent is link `l` (`usize::MAX`: the world), in file order: a child
    /// not yet placed hangs below; one already placed closes a loop.
    fn walk(&mut self, l: usize) -> Result<(), SdfError> {
        let body = if l == usize::MAX {
            None
        } else {
            self.at[l].expect("placed").0
        };
        if l != usize::MAX {
            let link = &self.raw.links[l];
            let x = self.at[l].expect("placed").1;
            for (name, pose, shape) in &link.collisions {
                self.geometries
                    .push(Geometry::new(name.clone(), body, x * *pose, shape.clone()));
            }
        }
        let raw = self.raw;
        for j in &raw.joints {
            let parent = if j.parent == "world" {
                usize::MAX
            } else {
                self.by_name[j.parent.as_str()]
            };
            if parent != l {
                continue;
            }
            let c = self.by_name[j.child.as_str()];
            // a gearbox couples two joints that hold its links already: never a tree joint
            if self.at[c].is_some() || j.kind == "gearbox" {
                self.loops.push(j);
            } else {
                self.attach(j, body, c)?;
            }
        }
        Ok(())
    }

    /// The constraint model holding loop joint `j`, `None` (with a warning) for a joint type a
    /// point or a weld cannot hold.
    fn closure(&mut self, j: &Joint) -> Result<Option<Vec<ConstraintModel>>, SdfError> {
        let jw = self.poses[&j.name];
        let side = |w: &Self, link: &str| -> (Option<JointId>, Transform) {
            let body = if link == "world" {
                None
            } else {
                w.at[w.by_name[link]].expect("placed").0
            };
            (body, w.frame_of[&body].inverse())
        };
        let (b1, x1) = side(self, &j.parent);
        let (b2, x2) = side(self, &j.child);
        let name = j.name.clone();
        let out = match j.kind.as_str() {
            "ball" => vec![ConstraintModel::point(b1, x1 * jw, b2, x2 * jw).with_name(name)],
            "fixed" => vec![ConstraintModel::frame(b1, x1 * jw, b2, x2 * jw).with_name(name)],
            "revolute" | "continuous" => {
                let a = j.axis.as_ref().ok_or_else(|| invalid(j, "no <axis>"))?;
                let axis = self.axis_in_joint(j, a, &jw)?;
                let far = jw * Transform::from_translation(HINGE_SPAN * axis);
                vec![
                    ConstraintModel::point(b1, x1 * jw, b2, x2 * jw).with_name(name.clone()),
                    ConstraintModel::point(b1, x1 * far, b2, x2 * far).with_name(name),
                ]
            }
            other => {
                self.warnings.push(SdfWarning {
                    line: j.line,
                    element: format!("joint \"{}\"", j.name),
                    message: format!(
                        "closes a loop, and a {other} joint cannot be held by rigid's point and weld constraints: left out (the loop stays open)"
                    ),
                });
                return Ok(None);
            }
        };
        Ok(Some(out))
    }
}

impl Walk<'_> {
    /// A gearbox, `θ_2 = −ratio · θ_1` (SDFormat: `θ_1` the parent link's angle about `axis`,
    /// `θ_2` the child link's about `axis2`, both relative to the `gearbox_reference_body`), as a
    /// joint-coordinate constraint `q_c = −ratio · s_1 s_2 · q_p` between the two revolute
    /// joints that turn its links straight from the reference body (`s_k = ±1`: the joint's axis
    /// along or against the gearbox's); a mimic under `--mimic`. Any other gearbox is left out
    /// with a warning that says why.
    fn gearbox(
        &mut self,
        j: &Joint,
        loops: &[&Joint],
    ) -> Result<Option<ConstraintModel>, SdfError> {
        let Some((ratio, reference)) = j.gearbox.clone() else {
            return Err(invalid(
                j,
                "a gearbox needs <gearbox_ratio> and <gearbox_reference_body>",
            ));
        };
        let jw = self.poses[&j.name];
        // the tree joint turning `link` from the reference body, and its axis's sign against
        // the gearbox axis `a` (world directions)
        let turn = |w: &Self,
                    link: &str,
                    a: &Option<Axis>|
         -> Result<Result<(JointId, f64), String>, SdfError> {
            let Some(a) = a else {
                return Ok(Err("it has no axis for this link".into()));
            };
            let along = jw.rotation * w.axis_in_joint(j, a, &jw)?;
            let by = w.raw.joints.iter().find(|t| {
                t.child == link && t.kind != "gearbox" && !loops.iter().any(|l| l.name == t.name)
            });
            let Some(t) = by.filter(|t| {
                t.parent == reference && matches!(t.kind.as_str(), "revolute" | "continuous")
            }) else {
                return Ok(Err(format!(
                    "\"{link}\" is not turned by a revolute joint from \"{reference}\""
                )));
            };
            let tw = w.poses[&t.name];
            let axis = tw.rotation
                * w.axis_in_joint(
                    t,
                    t.axis.as_ref().ok_or_else(|| invalid(t, "no <axis>"))?,
                    &tw,
                )?;
            let s = axis.dot(&along);
            let Some((Some(id), _)) = w.at[w.by_name[link]] else {
                return Ok(Err(format!("\"{link}\" is not a moving body")));
            };
            if (s.abs() - 1.0).abs() > 1e-9 {
                return Ok(Err(format!(
                    "joint \"{}\" turns about another axis",
                    t.name
                )));
            }
            Ok(Ok((id, s.signum())))
        };
        let (p, c) = (
            turn(self, &j.parent, &j.axis)?,
            turn(self, &j.child, &j.axis2)?,
        );
        match (p, c) {
            (Ok((jp, s1)), Ok((jc, s2))) => {
                let poly = [0.0, -ratio * s1 * s2, 0.0, 0.0, 0.0];
                let c =
                    ConstraintModel::joint_coordinate(jc, Some(jp), poly).with_name(j.name.clone());
                Ok(Some(c))
            }
            (Err(why), _) | (_, Err(why)) => {
                self.warnings.push(SdfWarning {
                    line: j.line,
                    element: format!("joint \"{}\"", j.name),
                    message: format!(
                        "a gearbox rigid cannot hold as a coupling of two joints ({why}): left out"
                    ),
                });
                Ok(None)
            }
        }
    }
}

/// The model of `raw` (see the module's documentation of [`super`]).
pub(super) fn build(
    raw: &Raw,
    poses: &Poses,
    mut warnings: Vec<SdfWarning>,
    path: Option<std::path::PathBuf>,
) -> Result<SdfModel, SdfError> {
    let mut by_name = HashMap::new();
    for (i, l) in raw.links.iter().enumerate() {
        if by_name.insert(l.name.as_str(), i).is_some() {
            return Err(SdfError::Invalid {
                line: l.line,
                element: format!("link \"{}\"", l.name),
                message: "a second link of this name".into(),
            });
        }
    }
    let mut is_child = vec![false; raw.links.len()];
    for j in &raw.joints {
        if j.parent != "world" && !by_name.contains_key(j.parent.as_str()) {
            return Err(invalid(
                j,
                format!("its parent \"{}\" is not a link of the model", j.parent),
            ));
        }
        match by_name.get(j.child.as_str()) {
            Some(&c) => is_child[c] = true,
            None => {
                return Err(invalid(
                    j,
                    format!("its child \"{}\" is not a link of the model", j.child),
                ))
            }
        }
    }
    let model_pose = raw.pose;
    let world_of = |name: &str| model_pose * poses.of[name];
    let mut b = ModelBuilder::new(&raw.name);
    b.set_gravity(raw.gravity.unwrap_or(Vec3::new(0.0, 0.0, -9.81)));
    let mut walk = Walk {
        raw,
        world: raw.links.iter().map(|l| world_of(&l.name)).collect(),
        poses: poses
            .of
            .iter()
            .map(|(k, v)| (k.clone(), model_pose * *v))
            .collect(),
        by_name,
        at: vec![None; raw.links.len()],
        frame_of: HashMap::from([(None, Transform::identity())]),
        b,
        loops: Vec::new(),
        geometries: Vec::new(),
        warnings: Vec::new(),
    };
    walk.walk(usize::MAX)?;
    // each link nobody's child is a root: floating, or welded to the world in a static model
    let mut roots: Vec<usize> = (0..raw.links.len()).filter(|&i| !is_child[i]).collect();
    if let Some(c) = &raw.canonical {
        roots.sort_by_key(|&i| raw.links[i].name != *c);
    }
    let mut home_free = Vec::new();
    for (k, r) in roots.into_iter().enumerate() {
        let link = &raw.links[r];
        let g = walk.inertia(link)?;
        let at = |e: crate::multibody::ModelError| SdfError::Invalid {
            line: link.line,
            element: format!("link \"{}\"", link.name),
            message: e.to_string(),
        };
        if raw.fixed {
            walk.b
                .add_fixed_body(None, &link.name, walk.world[r], g)
                .map_err(at)?;
            walk.at[r] = Some((None, walk.world[r]));
        } else {
            let name = if k == 0 {
                ROOT_JOINT_NAME.to_string()
            } else {
                format!("{}_{ROOT_JOINT_NAME}", link.name)
            };
            let id = walk
                .b
                .add_joint(None, &name, JointType::FreeFlyer, Transform::identity(), g)
                .map_err(at)?;
            walk.b
                .add_frame_of_kind(Some(id), &link.name, Transform::identity(), FrameKind::Body)
                .map_err(at)?;
            // the root's joint frame is its link, where `home` puts it
            walk.frame_of.insert(Some(id), walk.world[r]);
            walk.at[r] = Some((Some(id), Transform::identity()));
            home_free.push((id, walk.world[r]));
        }
        walk.walk(r)?;
    }
    if let Some(l) = (0..raw.links.len()).find(|&i| walk.at[i].is_none()) {
        let link = &raw.links[l];
        return Err(SdfError::Invalid {
            line: link.line,
            element: format!("link \"{}\"", link.name),
            message: "not reachable from the world or a root link: its joints form a loop only"
                .into(),
        });
    }
    let mut constraints = Vec::new();
    let loops = std::mem::take(&mut walk.loops);
    for &j in &loops {
        if j.kind == "gearbox" {
            constraints.extend(walk.gearbox(j, &loops)?);
            continue;
        }
        if let Some(c) = walk.closure(j)? {
            constraints.extend(c);
        }
    }
    warnings.append(&mut walk.warnings);
    let model = walk.b.build().map_err(|e| SdfError::Model(e.to_string()))?;
    let mut home = crate::multibody::neutral(&model);
    for (id, pose) in home_free {
        let j = model.joint(id);
        let [x, y, z, w] = crate::spatial::so3::to_quaternion(&pose.rotation);
        home[j.idx_q..j.idx_q + 7].copy_from_slice(&[
            pose.translation.x,
            pose.translation.y,
            pose.translation.z,
            x,
            y,
            z,
            w,
        ]);
    }
    let links = raw
        .links
        .iter()
        .map(|l| super::SdfLink {
            name: l.name.clone(),
            line: l.line,
            file: l.file.clone(),
            inertial: l.inertial.map(|(pose, mass, i)| super::SdfInertial {
                pose,
                mass,
                inertia: RotationalInertia::new(i[0], i[1], i[2], i[3], i[4], i[5]),
                line: l.inertial_text.0,
                text: l.inertial_text.1.clone(),
                span: l.inertial_text.2.clone(),
            }),
            collisions: l
                .collisions
                .iter()
                .map(|(_, t, s)| (*t, s.clone()))
                .collect(),
            visuals: l.visuals.clone(),
        })
        .collect();
    Ok(SdfModel {
        model,
        constraints,
        geometries: walk.geometries,
        home,
        version: raw.version.clone(),
        warnings,
        path,
        links,
    })
}
