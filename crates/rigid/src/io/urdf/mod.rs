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
//! - `<dynamics damping friction>` become the joint's [`Model::damping`](crate::multibody::Model::damping)
//!   and [`Model::friction`](crate::multibody::Model::friction) (every dof of the joint), used
//!   by the simulator only.
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

mod elements;
mod inertials;
mod mesh_path;
mod mimic;
mod parse;

pub use build::{
    build_model, build_model_with, load_urdf, load_urdf_str, load_urdf_with, ROOT_JOINT_NAME,
};
pub(crate) use inertials::indent_at;
pub use inertials::{edit_inertials, was_comment, with_body_inertials, InertialEdit};
pub use mesh_path::resolve_mesh_path;
pub use mimic::{load_urdf_mimic, mimic_model, mimics};
pub use parse::{parse_urdf_file, parse_urdf_str};

use crate::error::InertiaError;
use crate::mass::{Consistency, RotationalInertia, SpatialInertia, Verdict};
use crate::spatial::{Transform, Vec3};
use thiserror::Error;

/// A robot read from a URDF file: links and joints in file order, with the tree checked.
#[derive(Clone, Debug)]
pub struct UrdfRobot {
    /// `<robot name>` (the file's stem, or `robot`, when the attribute is missing: a warning).
    pub name: String,
    /// The file it was read from (`None` for text).
    pub path: Option<std::path::PathBuf>,
    /// The links, in file order.
    pub links: Vec<UrdfLink>,
    /// The joints, in file order.
    pub joints: Vec<UrdfJoint>,
    /// Index (in `links`) of the root link, the one link without a parent joint.
    pub root: usize,
    /// For each link, the indices (in `joints`) of its child joints, in file order.
    pub children: Vec<Vec<usize>>,
    /// What was read but ignored or tolerated: unknown elements, a mimic of an unknown joint, a
    /// missing robot name, an `<inertial>` without `<mass>` or `<inertia>`, a geometry that
    /// cannot be read. Each names the element and the line.
    pub warnings: Vec<UrdfWarning>,
}

/// Something in a URDF file that was tolerated: the file loads, the user should know.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UrdfWarning {
    /// Line (1-based).
    pub line: u32,
    /// The element, with its name: `joint "elbow"`, `link "base"`, `robot`.
    pub element: String,
    /// What was tolerated and how.
    pub message: String,
}

impl std::fmt::Display for UrdfWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}: {}", self.line, self.element, self.message)
    }
}

/// A `<link>`.
#[derive(Clone, Debug)]
pub struct UrdfLink {
    /// `name`.
    pub name: String,
    /// Line of the `<link>` element in the file (1-based).
    pub line: u32,
    /// Byte range of the `<link>` element in the file (to write an `<inertial>` into it).
    pub span: std::ops::Range<usize>,
    /// `<inertial>`, if present.
    pub inertial: Option<UrdfInertial>,
    /// `<visual>` elements whose geometry could be read, in file order.
    pub visuals: Vec<UrdfGeometry>,
    /// `<collision>` elements whose geometry could be read, in file order.
    pub collisions: Vec<UrdfGeometry>,
}

/// A link's `<inertial>` element.
#[derive(Clone, Debug)]
pub struct UrdfInertial {
    /// `<origin>`: the CoM frame in the link frame (the inertia is given in its axes).
    pub origin: Transform,
    /// `<origin rpy>` as written (`[0, 0, 0]` when absent).
    pub rpy: [f64; 3],
    /// `<mass value>` (kg), finite (a negative mass is refused when the model is built).
    pub mass: f64,
    /// `<inertia>` about the CoM in the axes of `origin` (kg·m²), finite.
    pub inertia: RotationalInertia,
    /// Line of the `<inertial>` element.
    pub line: u32,
    /// The numbers as written: `mass`, then `ixx, iyy, izz, ixy, ixz, iyz` (for the doctor's
    /// typo search; empty for a missing attribute).
    pub text: [String; 7],
    /// Byte range of the `<inertial>` element in the file (for `rigid doctor --fix`).
    pub span: std::ops::Range<usize>,
}

impl UrdfInertial {
    /// The link's spatial inertia in the link frame: mass, CoM at `origin`, and the inertia
    /// rotated from `origin`'s axes into the link's, `R I Rᵀ`.
    #[must_use]
    pub fn spatial_inertia(&self) -> SpatialInertia {
        SpatialInertia::from_com(
            self.mass,
            self.origin.translation,
            self.inertia.rotated_by(&self.origin.rotation),
        )
    }
}

/// A `<visual>` or `<collision>` element: a shape placed in the link frame.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfGeometry {
    /// `<origin>`: the shape's frame in the link frame.
    pub origin: Transform,
    /// The shape.
    pub shape: UrdfShape,
    /// The colour `rgba` (in `[0, 1]`) of its `<material>`, as urdfdom reads it: a material
    /// name already known (a top-level `<material>`, or one an earlier element gave a colour) is
    /// that colour, else the element's own `<color>`; `None` when none is given.
    pub rgba: Option<[f64; 4]>,
    /// Line of the `<visual>` or `<collision>` element.
    pub line: u32,
}

/// A URDF `<geometry>`.
#[derive(Clone, Debug, PartialEq)]
pub enum UrdfShape {
    /// `<box size>`, centred on its frame.
    Box {
        /// Edge lengths along x, y, z (m).
        size: Vec3,
    },
    /// `<cylinder radius length>`, axis along z, centred.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Length (m).
        length: f64,
    },
    /// `<sphere radius>`.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// `<capsule radius length>` (urdfdom extension): a cylinder with hemispherical caps.
    Capsule {
        /// Radius (m).
        radius: f64,
        /// Length of the cylindrical part (m).
        length: f64,
    },
    /// `<mesh filename scale>`: a mesh file (`package://`, `file://` or relative path).
    Mesh {
        /// The file name as written.
        filename: String,
        /// `scale` (default `1 1 1`).
        scale: Vec3,
    },
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

/// How non-physical inertias are treated when a model is built from a URDF.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum InertiaPolicy {
    /// Refuse a link whose inertia about the CoM is not positive semi-definite beyond round-off
    /// (an error naming the link and line). A triangle-inequality violation is a warning.
    Strict,
    /// Load every inertia as written; each non-physical one is a warning naming the link and
    /// line (as Pinocchio, Drake and MuJoCo load them).
    #[default]
    Warn,
    /// Replace each non-physical inertia by the doctor's repair (the undone fault when a cause
    /// is found, else the nearest physically consistent parameters) and warn what was done.
    Repair,
}

impl InertiaPolicy {
    /// `strict`, `warn` or `repair`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Strict => "strict",
            Self::Warn => "warn",
            Self::Repair => "repair",
        }
    }
}

impl std::str::FromStr for InertiaPolicy {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "strict" => Ok(Self::Strict),
            "warn" => Ok(Self::Warn),
            "repair" => Ok(Self::Repair),
            _ => Err(format!(
                "unknown inertia policy \"{s}\" (expected strict, warn or repair)"
            )),
        }
    }
}

/// The order of sibling joints (children of one link) in the model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SiblingOrder {
    /// The order the file lists the joints (rigid's default).
    #[default]
    File,
    /// Sorted by joint name, byte-wise, as urdfdom (and so Pinocchio) does: with it, the joint
    /// order of a model equals Pinocchio's `buildModelFromUrdf`.
    Name,
}

/// Options of [`load_urdf_with`] and [`build_model_with`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UrdfOptions {
    /// Add a free-flyer root joint ([`ROOT_JOINT_NAME`]) carrying the root link; otherwise the
    /// root link is welded to the world.
    pub floating: bool,
    /// What to do with non-physical inertias.
    pub inertia: InertiaPolicy,
    /// The order of sibling joints.
    pub sibling_order: SiblingOrder,
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
    /// The inertial parameters are not physical, beyond round-off ([`crate::mass::Consistency`]):
    /// a negative mass (an error under every policy), a zero mass with a non-zero inertia (a
    /// warning), an inertia about the CoM that is not positive semi-definite (an error under
    /// [`InertiaPolicy::Strict`], else a warning), or principal moments violating the triangle
    /// inequality (a warning: Pinocchio accepts it and real files carry such dummy inertias,
    /// ANYmal's base link).
    Invalid(InertiaError),
    /// The moving joint `joint` carries no mass at all (its child link and everything below it
    /// are massless): the mass matrix is singular and ABA is undefined (Pinocchio returns NaN).
    /// A warning: the model is still built. (The same check on a built model, with no file and
    /// lines to name: [`Model::massless_subtrees`](crate::multibody::Model::massless_subtrees).)
    ZeroMassMovingLink {
        /// The joint that moves the massless subtree.
        joint: String,
    },
    /// A mass above [`HUGE_MASS`] (1000 t): no robot link weighs that much, and the dynamics
    /// of such numbers may overflow. A warning.
    HugeMass {
        /// The mass (kg).
        mass: f64,
    },
}

/// The mass (kg) above which a link's mass is reported as implausible.
pub const HUGE_MASS: f64 = 1e6;

impl InertiaIssue {
    /// `true` for the findings that make [`build_model`] refuse the robot under
    /// [`InertiaPolicy::Strict`].
    #[must_use]
    pub fn is_error(&self) -> bool {
        self.is_error_under(InertiaPolicy::Strict)
    }

    /// `true` for the findings that refuse the robot under `policy`: a negative mass always; an
    /// inertia that is not positive semi-definite under [`InertiaPolicy::Strict`].
    #[must_use]
    pub fn is_error_under(&self, policy: InertiaPolicy) -> bool {
        match &self.kind {
            InertiaIssueKind::Invalid(InertiaError::BadMass { mass }) => *mass < 0.0,
            InertiaIssueKind::Invalid(InertiaError::NotPositiveSemiDefinite { .. }) => {
                policy == InertiaPolicy::Strict
            }
            _ => false,
        }
    }
}

impl InertiaIssue {
    /// What is wrong, without the line and link.
    #[must_use]
    pub fn description(&self) -> String {
        match &self.kind {
            InertiaIssueKind::Invalid(e) => format!("inertia: {e}"),
            InertiaIssueKind::ZeroMassMovingLink { joint } => format!(
                "moved by joint \"{joint}\" but it and its descendants have zero mass (singular \
                 mass matrix, ABA undefined)"
            ),
            InertiaIssueKind::HugeMass { mass } => format!(
                "mass {mass:e} kg is implausibly large (over {HUGE_MASS:e} kg); results may \
                 overflow"
            ),
        }
    }
}

impl std::fmt::Display for InertiaIssue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "line {}: link \"{}\": {}",
            self.line,
            self.link,
            self.description()
        )
    }
}

impl UrdfRobot {
    /// The link with this name.
    #[must_use]
    pub fn link(&self, name: &str) -> Option<&UrdfLink> {
        self.links.iter().find(|l| l.name == name)
    }

    /// The index (in `links`) of the link with this name.
    #[must_use]
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// The joint with this name.
    #[must_use]
    pub fn joint(&self, name: &str) -> Option<&UrdfJoint> {
        self.joints.iter().find(|j| j.name == name)
    }

    /// The mass of a link (0 without `<inertial>`).
    #[must_use]
    pub fn link_mass(&self, link: usize) -> f64 {
        self.links[link].inertial.as_ref().map_or(0.0, |i| i.mass)
    }

    /// The total mass of every link and of everything below it, indexed like `links`
    /// (computed leaves first, in linear time).
    #[must_use]
    pub fn subtree_masses(&self) -> Vec<f64> {
        // depth-first order from the root, then accumulate in reverse
        let mut order = Vec::with_capacity(self.links.len());
        let mut stack = vec![self.root];
        while let Some(l) = stack.pop() {
            order.push(l);
            stack.extend(self.children[l].iter().map(|&j| self.joints[j].child));
        }
        let mut m: Vec<f64> = (0..self.links.len()).map(|l| self.link_mass(l)).collect();
        for &l in order.iter().rev() {
            let below: f64 = self.children[l]
                .iter()
                .map(|&j| m[self.joints[j].child])
                .sum();
            m[l] += below;
        }
        m
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

    /// The spatial inertia of a link in its link frame: `<inertial>`'s mass, CoM at its origin,
    /// and inertia `R I Rᵀ` rotated from the inertial frame's axes into the link's (zero without
    /// `<inertial>`).
    #[must_use]
    pub fn link_inertia(&self, link: usize) -> SpatialInertia {
        self.links[link]
            .inertial
            .as_ref()
            .map_or_else(SpatialInertia::zero, UrdfInertial::spatial_inertia)
    }

    /// The inertia of the links welded to the root link (the root and every link fixed joints
    /// attach to it, directly or in a chain), in the root link's frame: what a fixed-base model
    /// welds to the world (Pinocchio's `model.inertias[0]`; rigid's model leaves it out, as it
    /// takes no part in the dynamics) and the body of a free-flyer root.
    ///
    /// ```
    /// let robot = rigid::io::urdf::parse_urdf_str(r#"<robot name="r">
    ///   <link name="base"><inertial><mass value="2"/>
    ///     <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    ///   <link name="plate"><inertial><mass value="1"/>
    ///     <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    ///   <joint name="weld" type="fixed"><parent link="base"/><child link="plate"/>
    ///     <origin xyz="0 0 0.3"/></joint></robot>"#).unwrap();
    /// let g = robot.welded_to_root_inertia();
    /// assert!((g.mass() - 3.0).abs() < 1e-12 && (g.com().z - 0.1).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn welded_to_root_inertia(&self) -> SpatialInertia {
        let mut total = self.link_inertia(self.root);
        let mut stack = vec![(self.root, Transform::identity())];
        while let Some((link, at)) = stack.pop() {
            for j in &self.joints {
                if j.parent == link && j.kind == UrdfJointKind::Fixed {
                    let t = at * j.origin;
                    total += self.link_inertia(j.child).transformed(&t);
                    stack.push((j.child, t));
                }
            }
        }
        total
    }

    /// Checks every link's inertial parameters ([`crate::mass::Consistency`]: mass, positive
    /// semi-definite inertia, triangle inequality, each beyond the round-off allowance) and finds
    /// the moving joints that carry no mass. Links in file order; an empty list means every
    /// inertia is fine.
    #[must_use]
    pub fn inertia_report(&self) -> Vec<InertiaIssue> {
        let mut issues = Vec::new();
        for (l, link) in self.links.iter().enumerate() {
            let Some(i) = &link.inertial else { continue };
            let c = Consistency::of(&self.link_inertia(l));
            let error = match c.verdict() {
                Verdict::BadMass => Some(InertiaError::BadMass { mass: i.mass }),
                Verdict::NotPositiveSemiDefinite => Some(InertiaError::NotPositiveSemiDefinite {
                    moment: c.principal_moments[0],
                }),
                Verdict::TriangleInequality => Some(InertiaError::TriangleInequality {
                    small_sum: c.principal_moments[0] + c.principal_moments[1],
                    largest: c.principal_moments[2],
                }),
                _ => None,
            };
            if let Some(e) = error {
                issues.push(InertiaIssue {
                    link: link.name.clone(),
                    line: i.line,
                    kind: InertiaIssueKind::Invalid(e),
                });
            }
            if i.mass > HUGE_MASS {
                issues.push(InertiaIssue {
                    link: link.name.clone(),
                    line: i.line,
                    kind: InertiaIssueKind::HugeMass { mass: i.mass },
                });
            }
        }
        let subtree = self.subtree_masses();
        for joint in &self.joints {
            if joint.kind != UrdfJointKind::Fixed && subtree[joint.child] == 0.0 {
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
