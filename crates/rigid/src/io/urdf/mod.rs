//! URDF import: a robot description file read into a validated [`UrdfRobot`], then built into a
//! multibody [`Model`](crate::multibody::Model).
//!
//! # What is read
//!
//! Only the direct children `<link>` and `<joint>` of `<robot>` are read (`<transmission>`,
//! `<gazebo>`, `<material>` are skipped). From a link: its `<inertial>` (`<origin xyz rpy>`,
//! `<mass value>`, `<inertia ixx ixy ixz iyy iyz izz>`); a link without `<inertial>` is massless.
//! From a joint: `type`, `<parent link>`, `<child link>`, `<origin xyz rpy>` (default identity),
//! `<axis xyz>` (default `1 0 0`, normalised), `<limit lower upper effort velocity>`,
//! `<mimic joint multiplier offset>` and `<dynamics damping friction>`. `rpy` is the URDF
//! fixed-axis roll-pitch-yaw, `R = Rz(y) Ry(p) Rx(r)`.
//!
//! # Semantics (as Pinocchio's `buildModelFromUrdf`, except the joint order)
//!
//! - Joint types: `revolute`, `continuous` (one angle), `prismatic`, `fixed`, `floating`
//!   (a free-flyer) and `planar` (motion in the x-y plane of the joint frame; only `axis 0 0 1`
//!   is accepted). Any other type is an error.
//! - A joint's frame is the child link's frame, placed at `origin` in the parent link's frame and
//!   then moved by the joint.
//! - Joints are numbered depth-first from the root link, children in the order the file lists
//!   their joints (Pinocchio, through urdfdom, orders siblings by joint name instead; the
//!   cross-check matches joints by name).
//! - A `fixed` joint merges its child link's inertia into the parent body; the child link's name
//!   is kept as a frame.
//! - The root link is welded to the world, unless a free-flyer root is asked for
//!   (`floating = true`), in which case it becomes the body of a free-flyer joint named
//!   [`ROOT_JOINT_NAME`] (Pinocchio's name). Links welded to the world take no part in the
//!   dynamics (total mass, CoM and potential energy leave them out).
//! - `mimic` joints are imported as independent joints, as Pinocchio's default (`mimic=False`)
//!   does; the mimic data is kept in [`UrdfJoint::mimic`].
//!
//! # Checks
//!
//! Every error names the link or joint and the line of the file: malformed XML, a missing
//! attribute, an unknown joint type, a parent or child link that does not exist, a link with two
//! parents, a cycle, no unique root, duplicate names, a negative mass, a non-finite number, a zero
//! joint axis, an inertia that is not positive semi-definite. An inertia whose principal moments
//! violate the triangle inequality `λ1 + λ2 ≥ λ3` is only a warning, as in Pinocchio and in the
//! multibody builder: published models carry such inertias (ANYmal's URDF has a dummy base
//! inertia with `1e-6` in every entry; the PUMA 560's link 3).
//! A moving joint that carries no mass at all (a zero-mass leaf) is not an error, as in Pinocchio,
//! but its mass matrix is singular and ABA is undefined: [`UrdfRobot::inertia_report`] lists it.

mod build;
mod parse;

pub use build::{build_model, load_urdf, load_urdf_str, ROOT_JOINT_NAME};
pub use parse::{parse_urdf_file, parse_urdf_str};

use crate::error::InertiaError;
use crate::mass::{RotationalInertia, DEFAULT_INERTIA_TOLERANCE};
use crate::spatial::{Transform, Vec3};
use thiserror::Error;

/// A robot read from a URDF file: links and joints in file order, with the tree checked.
#[derive(Clone, Debug)]
pub struct UrdfRobot {
    /// `<robot name>`.
    pub name: String,
    /// The links, in file order.
    pub links: Vec<UrdfLink>,
    /// The joints, in file order.
    pub joints: Vec<UrdfJoint>,
    /// Index (in `links`) of the root link, the one link without a parent joint.
    pub root: usize,
    /// For each link, the indices (in `joints`) of its child joints, in file order.
    pub children: Vec<Vec<usize>>,
}

/// A `<link>`.
#[derive(Clone, Debug)]
pub struct UrdfLink {
    /// `name`.
    pub name: String,
    /// Line of the `<link>` element in the file (1-based).
    pub line: u32,
    /// `<inertial>`, if present.
    pub inertial: Option<UrdfInertial>,
}

/// A link's `<inertial>` element.
#[derive(Clone, Copy, Debug)]
pub struct UrdfInertial {
    /// `<origin>`: the CoM frame in the link frame (the inertia is given in its axes).
    pub origin: Transform,
    /// `<mass value>` (kg), finite and non-negative.
    pub mass: f64,
    /// `<inertia>` about the CoM in the axes of `origin` (kg·m²), finite.
    pub inertia: RotationalInertia,
    /// Line of the `<inertial>` element.
    pub line: u32,
}

/// The `type` of a `<joint>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UrdfJointKind {
    /// `revolute`: rotation about `axis`, with limits.
    Revolute,
    /// `continuous`: rotation about `axis`, unlimited (one angle).
    Continuous,
    /// `prismatic`: translation along `axis`.
    Prismatic,
    /// `fixed`: no motion; merged into the parent body.
    Fixed,
    /// `floating`: six degrees of freedom (a free-flyer).
    Floating,
    /// `planar`: motion in the x-y plane of the joint frame.
    Planar,
}

impl UrdfJointKind {
    /// The URDF spelling.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Revolute => "revolute",
            Self::Continuous => "continuous",
            Self::Prismatic => "prismatic",
            Self::Fixed => "fixed",
            Self::Floating => "floating",
            Self::Planar => "planar",
        }
    }
}

/// A joint's `<limit>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrdfLimit {
    /// `lower` (rad or m; default 0).
    pub lower: f64,
    /// `upper` (rad or m; default 0).
    pub upper: f64,
    /// `effort` (N·m or N).
    pub effort: f64,
    /// `velocity` (rad/s or m/s).
    pub velocity: f64,
}

/// A joint's `<mimic>`: `q = multiplier * q_joint + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfMimic {
    /// The joint mimicked.
    pub joint: String,
    /// `multiplier` (default 1).
    pub multiplier: f64,
    /// `offset` (default 0).
    pub offset: f64,
}

/// A `<joint>`.
#[derive(Clone, Debug)]
pub struct UrdfJoint {
    /// `name`.
    pub name: String,
    /// Line of the `<joint>` element.
    pub line: u32,
    /// `type`.
    pub kind: UrdfJointKind,
    /// Index (in [`UrdfRobot::links`]) of the parent link.
    pub parent: usize,
    /// Index of the child link.
    pub child: usize,
    /// `<origin>`: the joint frame (= child link frame at `q = 0`) in the parent link frame.
    pub origin: Transform,
    /// `<axis>`, normalised (default `1 0 0`), in the joint frame.
    pub axis: Vec3,
    /// `<limit>`, if present.
    pub limit: Option<UrdfLimit>,
    /// `<mimic>`, if present.
    pub mimic: Option<UrdfMimic>,
    /// `<dynamics damping>` (default 0).
    pub damping: f64,
    /// `<dynamics friction>` (default 0).
    pub friction: f64,
}

/// Why a URDF file could not be read or turned into a model. Every variant says where.
#[derive(Debug, Error)]
pub enum UrdfError {
    /// The file could not be read.
    #[error("cannot read URDF file {path}: {source}")]
    Io {
        /// The path given.
        path: String,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not well-formed XML.
    #[error("malformed XML at line {line}, column {column}: {message}")]
    Xml {
        /// Line (1-based).
        line: u32,
        /// Column (1-based).
        column: u32,
        /// The XML parser's message.
        message: String,
    },
    /// The XML is well formed but the robot description is wrong.
    #[error("line {line}: {element}: {message}")]
    Invalid {
        /// Line (1-based) of the offending element.
        line: u32,
        /// The element, with its name: `joint "elbow"`, `link "base"`, `robot`.
        element: String,
        /// What is wrong.
        message: String,
    },
    /// The multibody model refused the robot.
    #[error("building the model from URDF: {0}")]
    Model(String),
}

impl UrdfError {
    /// The line of the file the error points at, if any.
    #[must_use]
    pub fn line(&self) -> Option<u32> {
        match self {
            Self::Xml { line, .. } | Self::Invalid { line, .. } => Some(*line),
            Self::Io { .. } | Self::Model(_) => None,
        }
    }
}

/// One finding of [`UrdfRobot::inertia_report`].
#[derive(Clone, Debug, PartialEq)]
pub struct InertiaIssue {
    /// The link.
    pub link: String,
    /// Line of the link (or of its `<inertial>`).
    pub line: u32,
    /// What is wrong.
    pub kind: InertiaIssueKind,
}

/// What [`InertiaIssue`] found.
#[derive(Clone, Debug, PartialEq)]
pub enum InertiaIssueKind {
    /// The rotational inertia is not physical. Not positive semi-definite (or not finite): an
    /// error, the model is refused. The triangle inequality of the principal moments fails: a
    /// warning, as Pinocchio accepts it and real files carry such dummy inertias (ANYmal's base
    /// link).
    Invalid(InertiaError),
    /// The moving joint `joint` carries no mass at all (its child link and everything below it
    /// are massless): the mass matrix is singular and ABA is undefined (Pinocchio returns NaN).
    /// A warning: the model is still built.
    ZeroMassMovingLink {
        /// The joint that moves the massless subtree.
        joint: String,
    },
}

impl InertiaIssue {
    /// `true` for the findings that make [`build_model`] refuse the robot.
    #[must_use]
    pub fn is_error(&self) -> bool {
        matches!(
            self.kind,
            InertiaIssueKind::Invalid(ref e) if !matches!(e, InertiaError::TriangleInequality { .. })
        )
    }
}

impl std::fmt::Display for InertiaIssue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            InertiaIssueKind::Invalid(e) => {
                write!(f, "line {}: link \"{}\": {e}", self.line, self.link)
            }
            InertiaIssueKind::ZeroMassMovingLink { joint } => write!(
                f,
                "line {}: link \"{}\": moved by joint \"{joint}\" but it and its descendants \
                 have zero mass (singular mass matrix, ABA undefined)",
                self.line, self.link
            ),
        }
    }
}

impl UrdfRobot {
    /// The link with this name.
    #[must_use]
    pub fn link(&self, name: &str) -> Option<&UrdfLink> {
        self.links.iter().find(|l| l.name == name)
    }

    /// The joint with this name.
    #[must_use]
    pub fn joint(&self, name: &str) -> Option<&UrdfJoint> {
        self.joints.iter().find(|j| j.name == name)
    }

    /// The mass of a link (0 without `<inertial>`).
    #[must_use]
    pub fn link_mass(&self, link: usize) -> f64 {
        self.links[link].inertial.map_or(0.0, |i| i.mass)
    }

    /// The total mass of a link and of everything below it.
    #[must_use]
    pub fn subtree_mass(&self, link: usize) -> f64 {
        let (mut m, mut stack) = (0.0, vec![link]);
        while let Some(l) = stack.pop() {
            m += self.link_mass(l);
            stack.extend(self.children[l].iter().map(|&j| self.joints[j].child));
        }
        m
    }

    /// Checks every link's inertia (positive semi-definite, triangle inequality, to
    /// [`DEFAULT_INERTIA_TOLERANCE`] relative) and finds the moving joints that carry no mass.
    /// Links in file order; an empty list means every inertia is fine.
    #[must_use]
    pub fn inertia_report(&self) -> Vec<InertiaIssue> {
        let mut issues = Vec::new();
        for link in &self.links {
            if let Some(i) = &link.inertial {
                if let Err(e) = i.inertia.validate(DEFAULT_INERTIA_TOLERANCE) {
                    issues.push(InertiaIssue {
                        link: link.name.clone(),
                        line: i.line,
                        kind: InertiaIssueKind::Invalid(e),
                    });
                }
            }
        }
        for joint in &self.joints {
            if joint.kind != UrdfJointKind::Fixed && self.subtree_mass(joint.child) == 0.0 {
                let link = &self.links[joint.child];
                issues.push(InertiaIssue {
                    link: link.name.clone(),
                    line: link.line,
                    kind: InertiaIssueKind::ZeroMassMovingLink {
                        joint: joint.name.clone(),
                    },
                });
            }
        }
        issues
    }
}
