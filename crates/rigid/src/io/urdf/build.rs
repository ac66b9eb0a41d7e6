//! [`UrdfRobot`] to [`Model`]: depth-first from the root link, children in file order, fixed
//! joints merged into their parent body.

use super::{parse_urdf_file, parse_urdf_str, UrdfError, UrdfJointKind, UrdfRobot};
use crate::mass::SpatialInertia;
use crate::multibody::{JointId, JointType, Model, ModelBuilder, ModelError};
use crate::spatial::Transform;
use std::collections::HashSet;
use std::path::Path;

/// The name of the free-flyer joint added by `floating = true` (Pinocchio's name).
pub const ROOT_JOINT_NAME: &str = "root_joint";

/// Reads a URDF file and builds its [`Model`]; `floating` adds a free-flyer root joint
/// ([`ROOT_JOINT_NAME`]) carrying the root link, otherwise the root link is welded to the world.
///
/// # Errors
/// A [`UrdfError`] naming the file, link or joint and the line.
pub fn load_urdf(path: impl AsRef<Path>, floating: bool) -> Result<Model, UrdfError> {
    build_model(&parse_urdf_file(path)?, floating)
}

/// As [`load_urdf`], from URDF text.
///
/// ```
/// let model = rigid::io::urdf::load_urdf_str(
///     r#"<robot name="pendulum">
///          <link name="base"/>
///          <link name="bob">
///            <inertial><origin xyz="0 0 -1"/><mass value="1"/>
///              <inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial>
///          </link>
///          <joint name="hinge" type="continuous">
///            <parent link="base"/><child link="bob"/><axis xyz="0 1 0"/>
///          </joint>
///        </robot>"#,
///     false,
/// ).unwrap();
/// assert_eq!((model.nq(), model.nv()), (1, 1));
/// assert_eq!(model.joints()[0].name, "hinge");
/// ```
///
/// # Errors
/// As [`load_urdf`].
pub fn load_urdf_str(text: &str, floating: bool) -> Result<Model, UrdfError> {
    build_model(&parse_urdf_str(text)?, floating)
}

/// Builds the [`Model`] of a parsed robot (see the [module documentation](super) for the
/// semantics).
///
/// Frames kept: every link (at its link frame), and every fixed joint whose name is not also a
/// link's name (at its child link's frame, where it coincides).
///
/// # Errors
/// A link inertia that is not positive semi-definite (the first error of
/// [`UrdfRobot::inertia_report`]); a link named like a moving joint (joints and frames share one
/// namespace in a [`Model`]); limits with `lower > upper`; or anything else the [`ModelBuilder`]
/// refuses, with the joint or link and the line.
pub fn build_model(robot: &UrdfRobot, floating: bool) -> Result<Model, UrdfError> {
    if let Some(issue) = robot.inertia_report().into_iter().find(|i| i.is_error()) {
        return Err(UrdfError::Invalid {
            line: issue.line,
            element: format!("link \"{}\"", issue.link),
            message: match issue.kind {
                super::InertiaIssueKind::Invalid(e) => format!("inertia: {e}"),
                super::InertiaIssueKind::ZeroMassMovingLink { .. } => issue.to_string(),
            },
        });
    }
    let mut joint_names: HashSet<&str> = robot
        .joints
        .iter()
        .filter(|j| j.kind != UrdfJointKind::Fixed)
        .map(|j| j.name.as_str())
        .collect();
    if floating {
        joint_names.insert(ROOT_JOINT_NAME);
    }
    for link in &robot.links {
        if joint_names.contains(link.name.as_str()) {
            return Err(UrdfError::Invalid {
                line: link.line,
                element: format!("link \"{}\"", link.name),
                message: "the link has the name of a moving joint; rigid keeps joints and \
                          frames in one namespace, so rename one of them"
                    .into(),
            });
        }
    }
    let link_names: HashSet<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();

    let mut b = ModelBuilder::new(&robot.name);
    let root = &robot.links[robot.root];
    let root_inertia = link_inertia(robot, robot.root);
    let root_joint = if floating {
        // Added with its composite inertia by `add_joints`.
        Some(JointId(0))
    } else {
        // Welded to the world: its inertia takes no part in the dynamics.
        b.add_fixed_body(
            None,
            &root.name,
            Transform::identity(),
            SpatialInertia::zero(),
        )
        .map_err(|e| UrdfError::Invalid {
            line: root.line,
            element: format!("link \"{}\"", root.name),
            message: e.to_string(),
        })?;
        None
    };

    add_joints(robot, &mut b, root_joint, root_inertia, &link_names)?;
    b.build().map_err(|e| UrdfError::Model(e.to_string()))
}

/// One step of the depth-first walk: a joint of the URDF, the body (moving joint) its parent
/// link belongs to, and its own frame in that body's joint frame.
struct Step {
    joint: usize,
    body: Option<usize>,
    placement: Transform,
    /// The body this joint's child link belongs to (itself if it moves).
    child_body: Option<usize>,
}

/// Adds every joint below the root, with its body and frames, depth-first with children in file
/// order (an explicit stack, so that a deep chain cannot overflow the call stack).
///
/// Each moving body gets the composite inertia of its link and of every link welded to it,
/// computed first and checked by the [`ModelBuilder`] as a whole.
fn add_joints(
    robot: &UrdfRobot,
    b: &mut ModelBuilder,
    root_joint: Option<JointId>,
    root_inertia: SpatialInertia,
    link_names: &HashSet<&str>,
) -> Result<(), UrdfError> {
    // Pass 1: the walk, and the composite inertia of each moving body (index = JointId).
    let mut steps = Vec::with_capacity(robot.joints.len());
    let mut bodies: Vec<SpatialInertia> = root_joint.iter().map(|_| root_inertia).collect();
    let root_body = root_joint.map(|j| j.0);
    let mut stack: Vec<(usize, Option<usize>, Transform)> = robot.children[robot.root]
        .iter()
        .rev()
        .map(|&j| (j, root_body, Transform::identity()))
        .collect();
    while let Some((j, body, t_body_link)) = stack.pop() {
        let joint = &robot.joints[j];
        let placement = t_body_link * joint.origin;
        let inertia = link_inertia(robot, joint.child);
        let (child_body, t_child) = if joint.kind == UrdfJointKind::Fixed {
            if let Some(k) = body {
                bodies[k] += inertia.transformed(&placement);
            }
            (body, placement)
        } else {
            bodies.push(inertia);
            (Some(bodies.len() - 1), Transform::identity())
        };
        steps.push(Step {
            joint: j,
            body,
            placement,
            child_body,
        });
        stack.extend(
            robot.children[joint.child]
                .iter()
                .rev()
                .map(|&c| (c, child_body, t_child)),
        );
    }

    // Pass 2: the builder calls, in the same order.
    if root_joint.is_some() {
        let root = &robot.links[robot.root];
        let at_root = |e: ModelError| UrdfError::Invalid {
            line: root.line,
            element: format!("link \"{}\"", root.name),
            message: format!("as the body of the free-flyer root: {e}"),
        };
        let id = b
            .add_joint(
                None,
                ROOT_JOINT_NAME,
                JointType::FreeFlyer,
                Transform::identity(),
                bodies[0],
            )
            .map_err(at_root)?;
        b.add_frame(Some(id), &root.name, Transform::identity())
            .map_err(at_root)?;
    }
    for step in steps {
        let joint = &robot.joints[step.joint];
        let child = &robot.links[joint.child];
        let body = step.body.map(JointId);
        let at_joint = |e: ModelError| UrdfError::Invalid {
            line: joint.line,
            element: format!("joint \"{}\"", joint.name),
            message: e.to_string(),
        };
        let kind = match joint.kind {
            UrdfJointKind::Fixed => {
                // The inertia is already in the composite body (or welded to the world).
                b.add_fixed_body(body, &child.name, step.placement, SpatialInertia::zero())
                    .map_err(at_joint)?;
                if !link_names.contains(joint.name.as_str()) {
                    b.add_frame(body, &joint.name, step.placement)
                        .map_err(at_joint)?;
                }
                continue;
            }
            UrdfJointKind::Revolute => JointType::Revolute { axis: joint.axis },
            UrdfJointKind::Continuous => JointType::Continuous { axis: joint.axis },
            UrdfJointKind::Prismatic => JointType::Prismatic { axis: joint.axis },
            UrdfJointKind::Floating => JointType::FreeFlyer,
            UrdfJointKind::Planar => JointType::Planar,
        };
        let k = step.child_body.unwrap_or_default();
        let id = b
            .add_joint(body, &joint.name, kind, step.placement, bodies[k])
            .map_err(|e| UrdfError::Invalid {
                line: joint.line,
                element: format!("joint \"{}\"", joint.name),
                message: format!(
                    "its body, link \"{}\" with the links welded to it: {e}",
                    child.name
                ),
            })?;
        debug_assert_eq!(id.0, k);
        if let (Some(l), 1) = (joint.limit, kind.nq()) {
            let (lower, upper) = match joint.kind {
                UrdfJointKind::Revolute | UrdfJointKind::Prismatic => (l.lower, l.upper),
                _ => (f64::NEG_INFINITY, f64::INFINITY),
            };
            b.set_limits(id, &[lower], &[upper], &[l.velocity], &[l.effort])
                .map_err(at_joint)?;
        }
        b.add_frame(Some(id), &child.name, Transform::identity())
            .map_err(at_joint)?;
    }
    Ok(())
}

/// The spatial inertia of a link in its link frame: `<inertial>`'s mass, CoM at its origin, and
/// inertia `R I Rᵀ` rotated from the inertial frame's axes into the link's.
fn link_inertia(robot: &UrdfRobot, link: usize) -> SpatialInertia {
    match &robot.links[link].inertial {
        None => SpatialInertia::zero(),
        Some(i) => SpatialInertia::from_com(
            i.mass,
            i.origin.translation,
            i.inertia.rotated_by(&i.origin.rotation),
        ),
    }
}
