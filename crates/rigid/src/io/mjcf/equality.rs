//! MuJoCo's `<equality>` constraints as rigid's [`ConstraintModel`]s (the reading of
//! `mjEQ_CONNECT`, `mjEQ_WELD` and `mjEQ_JOINT` in MuJoCo's XML reference and
//! `engine_core_constraint.c`):
//!
//! | MJCF | constraint |
//! | --- | --- |
//! | `<connect body1 body2 anchor>` | [`ConstraintKind::Point`]: `anchor` (in body1's frame) on body2 at the point it occupies at `qpos0` |
//! | `<connect site1 site2>` | [`ConstraintKind::Point`]: the two site origins coincide |
//! | `<weld body1 body2 anchor relpose>` | [`ConstraintKind::Frame`]: body2's frame moved to `anchor` coincides with body1's frame moved by `relpose` (a position and a quaternion in body1's frame); when `relpose`'s quaternion is zero (MuJoCo's default), body1's frame that coincides with it at `qpos0` |
//! | `<weld site1 site2>` | [`ConstraintKind::Frame`]: the two site frames coincide |
//! | `<joint joint1 joint2 polycoef>` | [`ConstraintKind::JointCoordinate`]: `q1 − ref1 = Σ c_k (q2 − ref2)^k`, which is rigid's `q_j1 = p(q_j2)` since rigid counts a hinge or slide from its `ref` |
//!
//! Every constraint is hard (MuJoCo's `solref`/`solimp` soften them; rigid solves them exactly,
//! with Baumgarte gains the caller chooses) and expressed in world-aligned axes
//! ([`ReferenceFrame::WorldAligned`]), as MuJoCo's `efc` rows. What cannot be converted is a
//! warning with its line: `<tendon>` and `<flex>` equalities, a weld's `torquescale` other than
//! 1, an inactive (`active="false"`) constraint (MuJoCo can switch it on at run time; rigid
//! leaves it out).

use super::{MjcfEquality, MjcfEqualityKind, MjcfError, MjcfJointKind, MjcfModel, MjcfWarning};
#[cfg(doc)]
use crate::multibody::constraints::ConstraintKind;
use crate::multibody::constraints::ConstraintModel;
use crate::multibody::{forward_kinematics_q, Data, JointId, Mimic, ReferenceFrame};
use crate::spatial::{so3, Transform, Vec3};

/// A frame fixed to the model: a joint (`None`: the world) and a placement in its frame.
type Anchor = (Option<JointId>, Transform);

impl MjcfModel {
    /// The model's active `<equality>` constraints as [`ConstraintModel`]s, in the file's order,
    /// with a warning for each one left out (MuJoCo's rules element by element: the
    /// [`equality`](crate::io::mjcf::equality) module).
    ///
    /// ```
    /// let mj = rigid::io::mjcf::load_mjcf_str(r#"
    ///   <mujoco>
    ///     <worldbody>
    ///       <body name="a"><joint name="ja" axis="0 1 0"/><geom size="0.1" pos="0 0 -1"/>
    ///         <body name="b" pos="0 0 -1"><joint name="jb" axis="0 1 0"/>
    ///           <geom size="0.1" pos="1 0 0"/></body></body>
    ///     </worldbody>
    ///     <equality><connect body1="b" body2="world" anchor="1 0 0"/>
    ///       <joint joint1="jb" joint2="ja" polycoef="0 -2 0 0 0"/></equality>
    ///   </mujoco>"#, std::path::Path::new(".")).unwrap();
    /// let (constraints, skipped) = mj.constraint_models().unwrap();
    /// assert_eq!((constraints.len(), skipped.len()), (2, 0));
    /// // the anchor (1, 0, -1) in the world holds b's point (1, 0, 0)
    /// assert_eq!(constraints[0].placement2.translation, rigid::spatial::Vec3::new(1.0, 0.0, -1.0));
    /// ```
    ///
    /// # Errors
    /// [`MjcfError::Invalid`] naming the `<equality>` element's line: an unknown body, site or
    /// joint, a joint constraint on a ball or free joint, a `relpose` that is not finite.
    pub fn constraint_models(&self) -> Result<(Vec<ConstraintModel>, Vec<MjcfWarning>), MjcfError> {
        let mut data = Data::new(&self.model);
        let mut q = vec![0.0; self.model.nq()];
        self.layout()
            .q_from_mujoco(&self.qpos0, &mut q)
            .and_then(|()| forward_kinematics_q(&self.model, &mut data, &q))
            .map_err(|e| MjcfError::Model(format!("the configuration qpos0: {e}")))?;
        // a joint's frame at qpos0 (the world's for `None`)
        let at_qpos0 =
            |j: Option<JointId>| j.map_or_else(Transform::identity, |j| data.placements[j.0]);
        let (mut out, mut skipped) = (Vec::new(), Vec::new());
        for eq in &self.equalities {
            let skip = |message: String| MjcfWarning {
                file: None,
                line: eq.line,
                element: label(eq),
                message,
            };
            if !eq.active {
                skipped.push(skip(
                    "active=\"false\": left out (rigid has no run-time switch)".into(),
                ));
                continue;
            }
            let c = match &eq.kind {
                MjcfEqualityKind::Connect {
                    targets,
                    sites,
                    anchor,
                } => {
                    let (f1, f2) = self.frames(eq, targets, *sites)?;
                    let (a1, a2) = if *sites {
                        (f1, f2)
                    } else {
                        // anchor on body1; its point on body2 is where it is at qpos0
                        let a1 = (f1.0, f1.1 * Transform::from_translation(*anchor));
                        let world = at_qpos0(a1.0) * a1.1;
                        let on2 = at_qpos0(f2.0).inverse().act_point(&world.translation);
                        (a1, (f2.0, Transform::from_translation(on2)))
                    };
                    ConstraintModel::point(a1.0, a1.1, a2.0, a2.1)
                }
                MjcfEqualityKind::Weld {
                    targets,
                    sites,
                    anchor,
                    relpose,
                    torquescale,
                } => {
                    if *torquescale != 1.0 {
                        skipped.push(skip(format!(
                            "torquescale=\"{torquescale}\": not modelled (the constraint is hard; \
                             its rotation is held as its translation)"
                        )));
                    }
                    let (f1, f2) = self.frames(eq, targets, *sites)?;
                    let (c1, c2) = if *sites {
                        (f1, f2)
                    } else {
                        let c2 = (f2.0, f2.1 * Transform::from_translation(*anchor));
                        // c1 on body1: `relpose` as given (MuJoCo's body1 point `relpos`,
                        // its rotation `relquat`), or where c2 is at qpos0
                        let on1 = match relpose {
                            Some(p) if p[3..].iter().any(|x| *x != 0.0) => {
                                let n = p[3..].iter().map(|x| x * x).sum::<f64>().sqrt();
                                let [w, x, y, z] = [p[3] / n, p[4] / n, p[5] / n, p[6] / n];
                                let r = so3::from_quaternion(x, y, z, w, 1e-9)
                                    .map_err(|e| invalid(eq, format!("relpose: {e}")))?;
                                Transform::new(r, Vec3::new(p[0], p[1], p[2]))
                            }
                            _ => (at_qpos0(f1.0) * f1.1).inverse() * (at_qpos0(c2.0) * c2.1),
                        };
                        ((f1.0, f1.1 * on1), c2)
                    };
                    ConstraintModel::frame(c1.0, c1.1, c2.0, c2.1)
                }
                MjcfEqualityKind::Joint { joints, polycoef } => {
                    let j1 = self.one_dof(eq, joints[0].as_deref())?;
                    let j2 = joints[1]
                        .as_deref()
                        .map(|n| self.one_dof(eq, Some(n)))
                        .transpose()?;
                    ConstraintModel::joint_coordinate(j1, j2, *polycoef)
                }
                MjcfEqualityKind::Tendon { .. } => {
                    skipped.push(skip("tendon equalities are not modelled: left out".into()));
                    continue;
                }
                MjcfEqualityKind::Other(tag) => {
                    skipped.push(skip(format!(
                        "<{tag}> equalities are not modelled: left out"
                    )));
                    continue;
                }
            };
            out.push(ConstraintModel {
                name: eq.name.clone().unwrap_or_else(|| label(eq)),
                reference: ReferenceFrame::WorldAligned,
                ..c
            });
        }
        Ok((out, skipped))
    }

    /// The frames of a constraint's two targets: bodies (body2 the world when absent) or sites.
    fn frames(
        &self,
        eq: &MjcfEquality,
        targets: &[Option<String>; 2],
        sites: bool,
    ) -> Result<(Anchor, Anchor), MjcfError> {
        let frame = |k: usize| -> Result<Anchor, MjcfError> {
            let key = if sites { "site" } else { "body" };
            let Some(name) = targets[k].as_deref() else {
                return if k == 1 && !sites {
                    Ok((None, Transform::identity()))
                } else {
                    Err(invalid(eq, format!("{key}{} is missing", k + 1)))
                };
            };
            let unknown = || invalid(eq, format!("{key}{}: no {key} named \"{name}\"", k + 1));
            if sites {
                let s = self
                    .sites
                    .iter()
                    .find(|s| s.name.as_deref() == Some(name))
                    .ok_or_else(unknown)?;
                Ok((s.parent, s.placement))
            } else {
                let b = self
                    .bodies
                    .iter()
                    .find(|b| b.name == name)
                    .ok_or_else(unknown)?;
                Ok((b.joint, b.placement))
            }
        };
        Ok((frame(0)?, frame(1)?))
    }

    /// The rigid joint of a hinge or slide named in a joint equality.
    fn one_dof(&self, eq: &MjcfEquality, name: Option<&str>) -> Result<JointId, MjcfError> {
        let name = name.ok_or_else(|| invalid(eq, "joint1 is missing".into()))?;
        let j = self
            .joints
            .iter()
            .find(|j| j.name == name)
            .ok_or_else(|| invalid(eq, format!("no joint named \"{name}\"")))?;
        match j.kind {
            MjcfJointKind::Hinge | MjcfJointKind::Slide => Ok(j.id),
            k => Err(invalid(
                eq,
                format!(
                    "joint \"{name}\" is a {} joint: a joint equality ties hinges and slides",
                    k.as_str()
                ),
            )),
        }
    }
}

/// `equality "name"` or `<connect>`.
fn label(eq: &MjcfEquality) -> String {
    let tag = match &eq.kind {
        MjcfEqualityKind::Connect { .. } => "connect",
        MjcfEqualityKind::Weld { .. } => "weld",
        MjcfEqualityKind::Joint { .. } => "joint",
        MjcfEqualityKind::Tendon { .. } => "tendon",
        MjcfEqualityKind::Other(t) => t,
    };
    match &eq.name {
        Some(n) => format!("{tag} \"{n}\""),
        None => format!("<{tag}>"),
    }
}

fn invalid(eq: &MjcfEquality, message: String) -> MjcfError {
    MjcfError::Invalid {
        file: None,
        line: eq.line,
        element: label(eq),
        message,
    }
}

impl MjcfModel {
    /// The couplings among the [`constraint_models`](Self::constraint_models): each `<equality
    /// joint>` whose polynomial is linear, `q₁ = c₀ + c₁ q₂`, as a [`Mimic`] (the reduced
    /// model `MimicModel::new(model, &mimics)` has no coordinate for `joint1`; `rigid ...
    /// --mimic`, Python's `Model.from_mjcf(path, mimic=True)`). The file's other equalities
    /// are not among them.
    ///
    /// # Errors
    /// As [`constraint_models`](Self::constraint_models).
    pub fn mimics(&self) -> Result<Vec<Mimic>, MjcfError> {
        let (constraints, _) = self.constraint_models()?;
        Ok(constraints
            .iter()
            .filter_map(Mimic::from_constraint)
            .collect())
    }
}
