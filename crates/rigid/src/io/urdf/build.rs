//! [`UrdfRobot`] to [`Model`]: depth-first from the root link, children in file order (or by
//! name), fixed joints merged into their parent body, non-physical inertias under a policy.

use super::{
    parse_urdf_file, parse_urdf_str, InertiaIssueKind, InertiaPolicy, SiblingOrder, UrdfError,
    UrdfJointKind, UrdfOptions, UrdfRobot, UrdfWarning,
};
use crate::doctor::Doctor;
use crate::error::InertiaError;
use crate::mass::SpatialInertia;
use crate::multibody::{
    FrameKind, InertiaCheck, JointId, JointType, Model, ModelBuilder, ModelError,
};
use crate::spatial::Transform;
use std::path::Path;

/// The name of the free-flyer joint added by `floating = true` (Pinocchio's name).
pub const ROOT_JOINT_NAME: &str = "root_joint";

/// Reads a URDF file and builds its [`Model`] with the default options (inertia policy
/// [`InertiaPolicy::Warn`], siblings in file order); `floating` adds a free-flyer root joint
/// ([`ROOT_JOINT_NAME`]) carrying the root link, otherwise the root link is welded to the world.
/// The warnings are dropped: use [`load_urdf_with`] to see them.
///
/// # Errors
/// A [`UrdfError`] naming the file, link or joint and the line.
pub fn load_urdf(path: impl AsRef<Path>, floating: bool) -> Result<Model, UrdfError> {
    let opts = UrdfOptions {
        floating,
        ..UrdfOptions::default()
    };
    Ok(load_urdf_with(path, &opts)?.0)
}

/// Reads a URDF file and builds its [`Model`] under `opts`; returns the model and every warning
/// (the parser's, then the inertia findings and repairs), each naming the link or joint and the
/// line.
///
/// # Errors
/// A [`UrdfError`] naming the file, link or joint and the line.
pub fn load_urdf_with(
    path: impl AsRef<Path>,
    opts: &UrdfOptions,
) -> Result<(Model, Vec<UrdfWarning>), UrdfError> {
    build_model_with(&parse_urdf_file(path)?, opts)
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

/// Builds the [`Model`] of a parsed robot with the default options (see [`load_urdf`]).
///
/// # Errors
/// As [`build_model_with`].
pub fn build_model(robot: &UrdfRobot, floating: bool) -> Result<Model, UrdfError> {
    let opts = UrdfOptions {
        floating,
        ..UrdfOptions::default()
    };
    Ok(build_model_with(robot, &opts)?.0)
}

/// Builds the [`Model`] of a parsed robot under `opts` (see the [module documentation](super)
/// for the semantics), with the warnings: the parser's ([`UrdfRobot::warnings`]), then each
/// finding of [`UrdfRobot::inertia_report`] that the policy tolerates, and each repair.
///
/// Frames kept: every link (a [`FrameKind::Body`] frame at its link frame) and every fixed joint
/// (a [`FrameKind::FixedJoint`] frame at its child link's frame). Links and joints are separate
/// namespaces, as in URDF: a link may share its name with a joint.
///
/// ```
/// use rigid::io::urdf::{build_model_with, parse_urdf_str, InertiaPolicy, UrdfOptions};
/// // ixx + iyy < izz: no mass distribution has these moments
/// let robot = parse_urdf_str(r#"<robot name="r"><link name="base"/>
///   <link name="arm"><inertial><mass value="1"/>
///     <inertia ixx="0.1" iyy="0.1" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial></link>
///   <joint name="arm" type="continuous"><parent link="base"/><child link="arm"/></joint>
///   </robot>"#).unwrap();
/// let warn = UrdfOptions::default(); // InertiaPolicy::Warn
/// let (model, warnings) = build_model_with(&robot, &warn).unwrap();
/// assert_eq!(model.joints()[0].name, "arm"); // a link and a joint may share a name
/// assert!(warnings[0].to_string().contains("link \"arm\""));
/// let repair = UrdfOptions { inertia: InertiaPolicy::Repair, ..warn };
/// let (fixed, _) = build_model_with(&robot, &repair).unwrap();
/// assert!(fixed.inertia_issues().is_empty());
/// ```
///
/// # Errors
/// A negative mass; under [`InertiaPolicy::Strict`] an inertia that is not positive
/// semi-definite beyond round-off; a negative velocity or effort limit; or anything else the
/// [`ModelBuilder`] refuses, with the joint or link and the line.
pub fn build_model_with(
    robot: &UrdfRobot,
    opts: &UrdfOptions,
) -> Result<(Model, Vec<UrdfWarning>), UrdfError> {
    let mut warnings = robot.warnings.clone();
    let mut inertias: Vec<SpatialInertia> = (0..robot.links.len())
        .map(|l| robot.link_inertia(l))
        .collect();
    let issues = robot.inertia_report();
    let needs_repair = |e: &InertiaError| {
        matches!(
            e,
            InertiaError::NotPositiveSemiDefinite { .. } | InertiaError::TriangleInequality { .. }
        )
    };
    let doctor = (opts.inertia == InertiaPolicy::Repair
        && issues
            .iter()
            .any(|i| matches!(&i.kind, InertiaIssueKind::Invalid(e) if needs_repair(e))))
    .then(|| Doctor::new().examine(robot));
    for issue in issues {
        let element = format!("link \"{}\"", issue.link);
        if issue.is_error_under(opts.inertia) {
            let hint = if opts.inertia == InertiaPolicy::Strict {
                " (refused by the strict inertia policy; `warn` loads it as written, `repair` \
                 loads the doctor's repair, `rigid doctor` explains it)"
            } else {
                ""
            };
            return Err(UrdfError::Invalid {
                line: issue.line,
                element,
                message: format!("{}{hint}", issue.description()),
            });
        }
        let InertiaIssueKind::Invalid(e) = &issue.kind else {
            warnings.push(UrdfWarning {
                line: issue.line,
                element,
                message: issue.description(),
            });
            continue;
        };
        let repaired = doctor
            .as_ref()
            .filter(|_| needs_repair(e))
            .and_then(|d| d.body(&issue.link))
            .and_then(|b| Some((b.repaired.as_ref()?, b)));
        let message = match repaired {
            Some((r, b)) => {
                if let Some(l) = robot.link_index(&issue.link) {
                    inertias[l] = r.spatial_inertia();
                }
                let cause = b.likely_cause.map_or("unknown", |c| c.code());
                format!("inertia: {e}; repaired ({cause}: {})", b.explanation)
            }
            None => format!("inertia: {e}; loaded as written"),
        };
        warnings.push(UrdfWarning {
            line: issue.line,
            element,
            message,
        });
    }
    let model = build_checked(robot, opts, &inertias)?;
    Ok((model, warnings))
}

/// The model of `robot` with the link inertias `inertias` (in link frames, indexed like
/// `robot.links`).
fn build_checked(
    robot: &UrdfRobot,
    opts: &UrdfOptions,
    inertias: &[SpatialInertia],
) -> Result<Model, UrdfError> {
    let mut b = ModelBuilder::new(if robot.name.is_empty() {
        "robot"
    } else {
        &robot.name
    });
    if opts.inertia == InertiaPolicy::Warn {
        b.set_inertia_check(InertiaCheck::AsWritten);
    }
    let root = &robot.links[robot.root];
    let root_joint = if opts.floating {
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
    let children = match opts.sibling_order {
        SiblingOrder::File => robot.children.clone(),
        SiblingOrder::Name => robot
            .children
            .iter()
            .map(|c| {
                let mut c = c.clone();
                c.sort_by(|&a, &b| robot.joints[a].name.cmp(&robot.joints[b].name));
                c
            })
            .collect(),
    };
    add_joints(robot, &children, &mut b, root_joint, inertias)?;
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
    children: &[Vec<usize>],
    b: &mut ModelBuilder,
    root_joint: Option<JointId>,
    inertias: &[SpatialInertia],
) -> Result<(), UrdfError> {
    // Pass 1: the walk, and the composite inertia of each moving body (index = JointId).
    let mut steps = Vec::with_capacity(robot.joints.len());
    let mut bodies: Vec<SpatialInertia> = root_joint.iter().map(|_| inertias[robot.root]).collect();
    let root_body = root_joint.map(|j| j.0);
    let mut stack: Vec<(usize, Option<usize>, Transform)> = children[robot.root]
        .iter()
        .rev()
        .map(|&j| (j, root_body, Transform::identity()))
        .collect();
    while let Some((j, body, t_body_link)) = stack.pop() {
        let joint = &robot.joints[j];
        let placement = t_body_link * joint.origin;
        let inertia = inertias[joint.child];
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
            children[joint.child]
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
        b.add_frame_of_kind(Some(id), &root.name, Transform::identity(), FrameKind::Body)
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
                b.add_frame_of_kind(body, &joint.name, step.placement, FrameKind::FixedJoint)
                    .map_err(at_joint)?;
                continue;
            }
            UrdfJointKind::Revolute | UrdfJointKind::Continuous => {
                JointType::Revolute { axis: joint.axis }
            }
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
        if joint.kind == UrdfJointKind::Continuous {
            b.set_continuous(id).map_err(at_joint)?;
        }
        if let (Some(l), 1) = (joint.limit, kind.nq()) {
            let (lower, upper) = match joint.kind {
                UrdfJointKind::Revolute | UrdfJointKind::Prismatic => (l.lower, l.upper),
                _ => (f64::NEG_INFINITY, f64::INFINITY),
            };
            b.set_limits(id, &[lower], &[upper], &[l.velocity], &[l.effort])
                .map_err(at_joint)?;
        }
        if joint.damping != 0.0 || joint.friction != 0.0 {
            let n = kind.nv();
            b.set_joint_dynamics(id, &vec![joint.damping; n], &vec![joint.friction; n])
                .map_err(at_joint)?;
        }
        b.add_frame_of_kind(
            Some(id),
            &child.name,
            Transform::identity(),
            FrameKind::Body,
        )
        .map_err(at_joint)?;
    }
    Ok(())
}
