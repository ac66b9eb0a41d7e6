//! MJCF import: MuJoCo's XML read into a multibody [`Model`] with MuJoCo's own compiled dynamics
//! (the same mass matrix `mj_fullM`, bias `qfrc_bias` and gravity forces, to round-off), plus the
//! geoms, sites, equality constraints and tendons kept in plain structs ([`MjcfModel`]).
//!
//! ```
//! use rigid::io::mjcf::load_mjcf_str;
//! use rigid::interop::MujocoLayout;
//! let mj = load_mjcf_str(r#"
//!   <mujoco model="pendulum">
//!     <worldbody>
//!       <body name="arm" pos="0 0 1">
//!         <joint name="hinge" type="hinge" axis="0 1 0" ref="30"/>
//!         <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.05" density="1000"/>
//!       </body>
//!     </worldbody>
//!   </mujoco>"#, std::path::Path::new(".")).unwrap();
//! assert_eq!((mj.model.nq(), mj.model.nv()), (1, 1));
//! // MuJoCo counts the hinge angle from its `ref` (30°): qpos = 30° is rigid's q = 0
//! let layout: MujocoLayout = mj.layout();
//! let mut q = [0.0];
//! layout.q_from_mujoco(&[30f64.to_radians()], &mut q).unwrap();
//! assert!(q[0].abs() < 1e-15);
//! ```
//!
//! # What is read, and how (MuJoCo's compiler, `src/user`, `src/xml`, at commit a725507)
//!
//! | MJCF | rigid |
//! | --- | --- |
//! | `<include file>` | replaced by the included file's elements (looked up next to the main file, then next to the including file); a file included twice or a loop is an error |
//! | `<compiler>` | `angle` (degrees by default), `eulerseq` (lower case: moving axes; upper case: fixed axes), `inertiafromgeom` (`auto`: only bodies without `<inertial>`), `inertiagrouprange`, `meshdir`/`assetdir`, `settotalmass` (every body's mass and inertia scaled, bodies fixed to the world included, as `mj_setTotalmass`), `boundmass`/`boundinertia`, `balanceinertia`, `alignfree` |
//! | `<default>`, `class`, `childclass` | [`defaults`]: nested classes, the element's `class`, else the nearest `childclass`, else `main` |
//! | `quat`, `axisangle`, `xyaxes`, `zaxis`, `euler`, `fromto` | [`orientation`]; `fromto` sets a capsule's, cylinder's, box's or ellipsoid's centre, axis and half-length |
//! | `<body>`, `<frame>` | every body under every `<worldbody>`; a body without joints is welded to its parent (its inertia merged, its name kept as a frame; fixed to the world: not part of the dynamics) |
//! | `<joint>` | `hinge` (revolute), `slide` (prismatic), `ball` (spherical), `free` (free-flyer); several joints in one body are a chain of joints with massless bodies between them, each in the frame moved by the previous ones, about its `pos`; `ref` is the configuration the body's pose describes (rigid's `q = qpos - ref`); `armature` is added to `M`, `damping` and `frictionloss` are the model's damping and friction; `range`, `stiffness`, `springref` are kept in [`MjcfJoint`] |
//! | `<freejoint>` | a free-flyer |
//! | `<inertial>` | `mass`, `pos`, `diaginertia` or `fullinertia`, its orientation |
//! | `<geom>` | inertia by MuJoCo's formulas ([`inertia`]), meshes ([`mesh`]: STL, OBJ, MSH; `legacy`, `exact` or `shell` rule), `mass` or `density`, `shellinertia`; kept in [`MjcfGeom`] |
//! | `<equality>` | kept in [`MjcfEquality`]; `connect`, `weld` and `joint` become constraint models ([`MjcfModel::constraint_models`]) |
//! | `<site>`, `<tendon>` | kept in [`MjcfSite`], [`MjcfTendon`] |
//! | `<option gravity>`, `<flag gravity="disable">` | the model's gravity |
//! | `<option timestep>` | kept in [`MjcfModel::timestep`] (the simulator's default step) |
//! | `<geom friction>`, `<contact><exclude>`, `<contact><pair>` | kept in [`MjcfGeom::friction`] and [`MjcfContact`] (the collision model of `rigid::io::collision::mjcf_world`) |
//! | `gravcomp` | kept in [`MjcfBody::gravcomp`] and reported |
//!
//! What rigid does not model (actuators, sensors, keyframes, cameras, lights,
//! textures, solver options) is read past with one warning per kind, naming the first line.
//! What it cannot load (`<composite>`, `<flexcomp>`, `<replicate>`, `<attach>`, a mesh whose
//! inertia needs the convex hull) is an error naming the element and line.
//!
//! # Errors
//!
//! Each error names the file (when it is not the main one), the line and the element: malformed
//! XML, an unknown default class, an include loop, a mesh file that cannot be read, a `fromto` of
//! zero length, a negative mass or density, a non-positive geom size, a zero axis, a number that
//! is not finite (or a compiled frame or inertia that is not: an angle given in radians where the
//! compiler reads degrees can overflow), the checks of MuJoCo's compiler (a free joint below the
//! top level, a moving body without mass, an inertia violating `A + B ≥ C`).

mod attrs;
mod build;
mod compile;
pub mod defaults;
pub mod equality;
pub mod inertia;
pub mod mesh;
pub mod orientation;
mod parse;
mod tree;
mod xml;

pub use build::{load_mjcf, load_mjcf_str};
pub use mesh::MeshInertia;

use crate::interop::MujocoLayout;
use crate::multibody::{JointId, Model};
use crate::spatial::{Transform, Vec3};
use std::path::PathBuf;
use thiserror::Error;

/// A model read from MJCF: the multibody [`Model`] and what MuJoCo's file says besides.
#[derive(Clone, Debug)]
pub struct MjcfModel {
    /// The kinematic tree: one rigid joint per MuJoCo joint, in MuJoCo's order.
    pub model: Model,
    /// MuJoCo's joints, indexed like the model's joints.
    pub joints: Vec<MjcfJoint>,
    /// MuJoCo's bodies, world first, in MuJoCo's (depth-first) order.
    pub bodies: Vec<MjcfBody>,
    /// Every geom, in MuJoCo's order.
    pub geoms: Vec<MjcfGeom>,
    /// Every site, in MuJoCo's order.
    pub sites: Vec<MjcfSite>,
    /// The equality constraints.
    pub equalities: Vec<MjcfEquality>,
    /// The tendons.
    pub tendons: Vec<MjcfTendon>,
    /// `<option timestep>`, if the file gives one (s).
    pub timestep: Option<f64>,
    /// `<contact>`: the excluded body pairs and the explicit geom pairs.
    pub contact: MjcfContact,
    /// MuJoCo's `qpos0` (its layout): each free joint's body pose at load, each ball joint
    /// `(1, 0, 0, 0)`, each hinge or slide its `ref`.
    pub qpos0: Vec<f64>,
    /// What was tolerated, each with its line.
    pub warnings: Vec<MjcfWarning>,
    /// The file it was read from (`None` for text).
    pub path: Option<PathBuf>,
}

impl MjcfModel {
    /// MuJoCo's layout of this model's vectors (each hinge and slide counted from its `ref`).
    #[must_use]
    pub fn layout(&self) -> MujocoLayout {
        let reference: Vec<f64> = self.joints.iter().map(|j| j.reference).collect();
        MujocoLayout::with_reference(&self.model, &reference)
            .expect("one reference per joint, finite")
    }
}

/// MuJoCo's joint types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MjcfJointKind {
    /// Six degrees of freedom.
    Free,
    /// Three rotational degrees of freedom.
    Ball,
    /// Translation along an axis.
    Slide,
    /// Rotation about an axis.
    Hinge,
}

impl MjcfJointKind {
    /// MuJoCo's name: `free`, `ball`, `slide`, `hinge`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Free => "free",
            Self::Ball => "ball",
            Self::Slide => "slide",
            Self::Hinge => "hinge",
        }
    }
}

/// A MuJoCo joint, with the attributes rigid keeps (angles in radians).
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfJoint {
    /// Its name in the model (MuJoCo's, or `BODY_jntK` for an unnamed one).
    pub name: String,
    /// Its type.
    pub kind: MjcfJointKind,
    /// The rigid joint.
    pub id: JointId,
    /// The index of its body in [`MjcfModel::bodies`].
    pub body: usize,
    /// `ref` (rad or m): MuJoCo's `qpos0`; rigid's `q` is `qpos - ref`.
    pub reference: f64,
    /// `springref` (rad or m).
    pub springref: f64,
    /// `stiffness` (N·m/rad or N/m).
    pub stiffness: f64,
    /// `damping` (also the model's [`damping`](Model::damping)).
    pub damping: f64,
    /// `frictionloss` (also the model's [`friction`](Model::friction)).
    pub frictionloss: f64,
    /// `armature` (also the model's [`armature`](Model::armature)).
    pub armature: f64,
    /// `range` when the joint is limited (rad or m, MuJoCo's coordinates).
    pub range: Option<[f64; 2]>,
    /// Line of the element.
    pub line: u32,
}

/// A MuJoCo body.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfBody {
    /// Its name (`world` for the world, `bodyK` for an unnamed one).
    pub name: String,
    /// Its parent body (`None` for the world).
    pub parent: Option<usize>,
    /// The rigid joint whose frame it is fixed in (`None`: the world).
    pub joint: Option<JointId>,
    /// The body frame in that joint's frame (in the world's, for `None`).
    pub placement: Transform,
    /// The compiled mass (kg), after `boundmass` and `settotalmass`.
    pub mass: f64,
    /// The compiled centre of mass and principal axes in the body frame, and principal moments
    /// (MuJoCo's `body_ipos`, `body_iquat` as a rotation, `body_inertia`).
    pub inertial: (Transform, Vec3),
    /// The `<inertial>` the file gives, if any (as written: before `boundmass` and
    /// `settotalmass`; for the doctor).
    pub given: Option<MjcfInertial>,
    /// `gravcomp`: the fraction of its weight MuJoCo cancels by a passive force (not in
    /// `qfrc_bias`).
    pub gravcomp: f64,
    /// `mocap="true"`.
    pub mocap: bool,
    /// Line of the element (0 for the world).
    pub line: u32,
}

/// An `<inertial>` as the file writes it.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfInertial {
    /// `mass` (kg).
    pub mass: f64,
    /// `pos` and the orientation of the axes `inertia` is written in, in the body frame.
    pub frame: Transform,
    /// `diaginertia` (diagonal) or `fullinertia` (kg·m²) in those axes.
    pub inertia: crate::mass::RotationalInertia,
    /// The numbers as written: `mass`, then `ixx, iyy, izz, ixy, ixz, iyz` (the products `0`
    /// for `diaginertia`).
    pub text: [String; 7],
    /// Line of the element.
    pub line: u32,
}

/// A geom's shape, with MuJoCo's sizes (half-lengths).
#[derive(Clone, Debug, PartialEq)]
pub enum MjcfShape {
    /// A plane (half-sizes in x and y; 0 means infinite).
    Plane {
        /// Half-sizes in x and y.
        half: [f64; 2],
    },
    /// A sphere.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// A capsule along z.
    Capsule {
        /// Radius.
        radius: f64,
        /// Half-length of the cylindrical part.
        half_length: f64,
    },
    /// A cylinder along z.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Half-length.
        half_length: f64,
    },
    /// An ellipsoid.
    Ellipsoid {
        /// Semi-axes.
        radii: Vec3,
    },
    /// A box.
    Box {
        /// Half-sizes.
        half: Vec3,
    },
    /// A mesh: the file's vertices `v` appear at `scale ∘ (R(refquat)ᵀ (v - refpos))` in the geom
    /// frame.
    Mesh {
        /// The asset's name.
        name: String,
        /// The file (empty when the mesh is given in the XML).
        file: PathBuf,
        /// The mesh given in the XML (`vertex`, `face`; its convex hull's triangles without
        /// `face`) instead of a file, before `refpos`, `refquat` and `scale`.
        inline: Option<crate::mass::TriMesh>,
        /// `scale`.
        scale: Vec3,
        /// `refpos`.
        refpos: Vec3,
        /// `refquat` as a rotation.
        refrot: crate::spatial::Mat3,
    },
    /// A height field (its asset's name).
    Hfield {
        /// The asset's name.
        name: String,
    },
}

impl MjcfShape {
    /// For a mesh given by its file: the frame, in the geom frame, in which MuJoCo draws the
    /// file's vertices scaled, `scale ∘ (Rᵀ (v − refpos)) = T (scale ∘ v)` with `T = (Rᵀ,
    /// −Rᵀ (scale ∘ refpos))` (`R` of `refquat`). `None` for another shape, a mesh given by its
    /// vertices, or one both turned and scaled unevenly (no rigid frame then).
    #[must_use]
    pub fn mesh_file_frame(&self) -> Option<Transform> {
        let Self::Mesh {
            inline: None,
            scale,
            refpos,
            refrot,
            ..
        } = self
        else {
            return None;
        };
        let uniform = (scale.x - scale.y).abs() < 1e-12 && (scale.x - scale.z).abs() < 1e-12;
        let turned = (refrot - crate::spatial::Mat3::identity()).norm() > 1e-12;
        if turned && !uniform {
            return None;
        }
        let rt = refrot.transpose();
        Some(Transform::new(rt, -(rt * refpos.component_mul(scale))))
    }
}

/// A geom: its shape placed in a body, and what contact and drawing need.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfGeom {
    /// `name`, if any.
    pub name: Option<String>,
    /// The index of its body in [`MjcfModel::bodies`].
    pub body: usize,
    /// The rigid joint whose frame it is fixed in (`None`: the world).
    pub parent: Option<JointId>,
    /// The geom frame (as the file writes it, before MuJoCo re-centres a mesh) in that joint's
    /// frame.
    pub placement: Transform,
    /// The shape.
    pub shape: MjcfShape,
    /// `group`.
    pub group: i32,
    /// `contype`.
    pub contype: i32,
    /// `conaffinity`.
    pub conaffinity: i32,
    /// The sliding friction, the first number of `friction` (MuJoCo's default 1).
    pub friction: f64,
    /// Colour: `rgba`, else its material's, else MuJoCo's grey.
    pub rgba: [f64; 4],
    /// The mass it gives its body (0 when its inertia is not taken from geoms).
    pub mass: f64,
    /// Line of the element.
    pub line: u32,
}

/// A site: a named frame with a shape, for sensors and tendons.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfSite {
    /// `name`, if any.
    pub name: Option<String>,
    /// The index of its body in [`MjcfModel::bodies`].
    pub body: usize,
    /// The rigid joint whose frame it is fixed in.
    pub parent: Option<JointId>,
    /// The site frame in that joint's frame.
    pub placement: Transform,
    /// Its shape (for drawing).
    pub shape: MjcfShape,
    /// `group`.
    pub group: i32,
    /// Line of the element.
    pub line: u32,
}

/// What an equality constraint ties together.
#[derive(Clone, Debug, PartialEq)]
pub enum MjcfEqualityKind {
    /// `<connect>`: a point of `body1` (`anchor`, in its frame) kept on `body2` (the world when
    /// absent); or the sites `site1`, `site2` kept together.
    Connect {
        /// The two bodies (or sites, when `sites`).
        targets: [Option<String>; 2],
        /// Whether `targets` names sites.
        sites: bool,
        /// `anchor` in `body1`'s frame.
        anchor: Vec3,
    },
    /// `<weld>`: two frames kept at a relative pose.
    Weld {
        /// The two bodies (or sites).
        targets: [Option<String>; 2],
        /// Whether `targets` names sites.
        sites: bool,
        /// `anchor` in `body2`'s frame.
        anchor: Vec3,
        /// `relpose` as `(pos, quat w x y z)`, when given.
        relpose: Option<[f64; 7]>,
        /// `torquescale`.
        torquescale: f64,
    },
    /// `<joint>`: `q2 = poly(q1)` (`polycoef`, five coefficients), or `joint1` fixed when
    /// `joint2` is absent.
    Joint {
        /// `joint1`, `joint2`.
        joints: [Option<String>; 2],
        /// `polycoef`.
        polycoef: [f64; 5],
    },
    /// `<tendon>`: two tendon lengths tied by a polynomial.
    Tendon {
        /// `tendon1`, `tendon2`.
        tendons: [Option<String>; 2],
        /// `polycoef`.
        polycoef: [f64; 5],
    },
    /// Another kind (`flex`, ...), by its tag.
    Other(String),
}

/// The `<contact>` section: which body pairs never collide, and which geom pairs collide
/// whatever their masks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MjcfContact {
    /// `<exclude body1 body2>`.
    pub excludes: Vec<MjcfExclude>,
    /// `<pair geom1 geom2>`.
    pub pairs: Vec<MjcfPair>,
}

/// `<exclude body1 body2>`: the two bodies' geoms never collide.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfExclude {
    /// The first body's name.
    pub body1: String,
    /// The second body's name.
    pub body2: String,
    /// Line of the element.
    pub line: u32,
}

/// `<pair geom1 geom2 friction>`: the two geoms collide whatever their masks.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfPair {
    /// The first geom's name.
    pub geom1: String,
    /// The second geom's name.
    pub geom2: String,
    /// The pair's sliding friction (its `friction`'s first number), if given.
    pub friction: Option<f64>,
    /// Line of the element.
    pub line: u32,
}

/// An `<equality>` constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfEquality {
    /// `name`, if any.
    pub name: Option<String>,
    /// What it ties.
    pub kind: MjcfEqualityKind,
    /// `active`.
    pub active: bool,
    /// Line of the element.
    pub line: u32,
}

/// A tendon's path.
#[derive(Clone, Debug, PartialEq)]
pub enum MjcfTendonKind {
    /// `<fixed>`: a linear combination of joint coordinates (`joint`, `coef`).
    Fixed(Vec<(String, f64)>),
    /// `<spatial>`: a path through sites, wrapped around geoms, with pulleys: each element's tag
    /// and target (`site`, `geom` or the pulley's `divisor`).
    Spatial(Vec<(String, String)>),
}

/// A `<tendon>`.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfTendon {
    /// `name`, if any.
    pub name: Option<String>,
    /// Its path.
    pub kind: MjcfTendonKind,
    /// `stiffness`, `damping`, `frictionloss`, `armature`.
    pub stiffness: f64,
    /// `damping`.
    pub damping: f64,
    /// `frictionloss`.
    pub frictionloss: f64,
    /// `armature`.
    pub armature: f64,
    /// `range`, when limited.
    pub range: Option<[f64; 2]>,
    /// Line of the element.
    pub line: u32,
}

/// Something in an MJCF file that was tolerated: the model loads, the user should know.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MjcfWarning {
    /// The file, when it is not the main one.
    pub file: Option<String>,
    /// Line (1-based).
    pub line: u32,
    /// The element: `geom "foot"`, `<actuator>`.
    pub element: String,
    /// What was tolerated and how.
    pub message: String,
}

impl std::fmt::Display for MjcfWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(file) = &self.file {
            write!(f, "{file}: ")?;
        }
        write!(f, "line {}: {}: {}", self.line, self.element, self.message)
    }
}

/// Why an MJCF file could not be read or turned into a model. Every variant says where.
#[derive(Debug, Error)]
pub enum MjcfError {
    /// The file could not be read.
    #[error("cannot read MJCF file {path}: {source}")]
    Io {
        /// The path given.
        path: String,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// Not well-formed XML.
    #[error(
        "{}malformed XML at line {line}, column {column}: {message}",
        prefix(file)
    )]
    Xml {
        /// The file, when it is not the main one.
        file: Option<String>,
        /// Line (1-based).
        line: u32,
        /// Column (1-based).
        column: u32,
        /// The XML parser's message.
        message: String,
    },
    /// Well-formed XML that is not a model rigid can build.
    #[error("{}line {line}: {element}: {message}", prefix(file))]
    Invalid {
        /// The file, when it is not the main one.
        file: Option<String>,
        /// Line (1-based).
        line: u32,
        /// The element: `geom "foot"`, `body "torso"`, `<include>`.
        element: String,
        /// What is wrong.
        message: String,
    },
    /// The multibody model refused it.
    #[error("building the model from MJCF: {0}")]
    Model(String),
}

fn prefix(file: &Option<String>) -> String {
    file.as_ref().map_or_else(String::new, |f| format!("{f}: "))
}

impl MjcfError {
    /// The line the error points at, if any.
    #[must_use]
    pub fn line(&self) -> Option<u32> {
        match self {
            Self::Xml { line, .. } | Self::Invalid { line, .. } => Some(*line),
            Self::Io { .. } | Self::Model(_) => None,
        }
    }
}

/// Reading context shared by the passes: the files (for messages) and the warnings.
pub(crate) struct Reader {
    sources: xml::Sources,
    warnings: Vec<MjcfWarning>,
}

impl Reader {
    /// `geom "name"` or `<geom>`.
    fn label(e: &xml::Element) -> String {
        match e.attr("name") {
            Some(n) => format!("{} \"{n}\"", e.tag),
            None => format!("<{}>", e.tag),
        }
    }

    /// An error at element `e`.
    fn invalid(&self, e: &xml::Element, message: String) -> MjcfError {
        MjcfError::Invalid {
            file: self.sources.name(e.file),
            line: e.line,
            element: Self::label(e),
            message,
        }
    }

    /// A warning at element `e`.
    fn warn(&mut self, e: &xml::Element, message: String) {
        self.warnings.push(MjcfWarning {
            file: self.sources.name(e.file),
            line: e.line,
            element: Self::label(e),
            message,
        });
    }
}
