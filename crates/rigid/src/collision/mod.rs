//! Collision geometry and contact points, on parry3d-f64 (the `collision` feature, on by
//! default): the shapes fixed in the bodies of a multibody [`Model`](crate::multibody::Model), a ground plane, and the
//! contact points between them at a configuration, for the contact dynamics of
//! [`simulation::contact`](crate::simulation::contact).
//!
//! A [`CollisionModel`] is constant (Pinocchio's `GeometryModel`): geometries, each a
//! [`Shape`] placed in a joint's frame, a [`Ground`], and the rules of which pairs collide; a
//! [`CollisionData`] is its workspace (`GeometryData`): parry's shapes (a mesh becomes its convex
//! hull, as in MuJoCo), the candidate pairs and their manifolds. [`CollisionData::contacts`]
//! finds the contacts at the world poses of the joints.
//!
//! | pair | how | source |
//! | --- | --- | --- |
//! | shape–ground | the shape's points nearest the plane: a ball's centre, a capsule's two centres, a box's or hull's vertices, a cylinder's or cone's support feature (parry's `PolygonalFeatureMap`) and support point; at most 4 kept, the deepest and the widest (largest area) | parry shapes; the reduction of Bullet's manifolds |
//! | shape–shape | parry's contact manifolds (`DefaultQueryDispatcher::contact_manifolds`: SAT for boxes, GJK/EPA and clipping for convex shapes) | parry |
//!
//! Which pairs: every geometry with the ground; two geometries when both are on moving bodies
//! that differ and are not parent and child, [`CollisionModel::self_collision`] is on, and
//! their bit masks match (MJCF's `contype & conaffinity`); geometries fixed in the world meet the
//! moving ones. A pair is skipped cheaply when the bounding spheres are farther apart than the
//! margin.
//!
//! Which pairs besides: [`CollisionModel::excluded`] pairs never, [`CollisionModel::included`]
//! pairs always (MJCF's `<contact><exclude>` and `<pair>`).
//!
//! Friction and restitution of a contact: the larger of the two sides' (MuJoCo's rule for
//! friction), the ground's for the ground when the geometry gives none, else the model's
//! default.
//!
//! ```
//! use rigid::collision::{CollisionData, CollisionModel, Geometry, Ground, Shape};
//! use rigid::multibody::{JointId, JointType, ModelBuilder};
//! use rigid::mass::{RotationalInertia, SpatialInertia};
//! use rigid::spatial::{Transform, Vec3};
//! let mut b = ModelBuilder::new("ball");
//! let g = SpatialInertia::from_com(1.0, Vec3::zeros(), RotationalInertia::diagonal(0.004, 0.004, 0.004));
//! b.add_joint(None, "ball", JointType::FreeFlyer, Transform::identity(), g).unwrap();
//! let model = b.build().unwrap();
//! let mut cm = CollisionModel::new(Ground::horizontal(0.0, 0.8));
//! cm.geometries.push(Geometry::new("ball", Some(JointId(0)), Transform::identity(), Shape::Sphere { radius: 0.1 }));
//! let mut cd = CollisionData::new(&model, &cm)?;
//! let at = [Transform::from_translation(Vec3::new(0.0, 0.0, 0.098))];
//! let mut contacts = Vec::new();
//! cd.contacts(&cm, &at, &mut contacts);
//! assert_eq!(contacts.len(), 1);
//! assert!((contacts[0].gap + 0.002).abs() < 1e-12 && contacts[0].normal == Vec3::z());
//! # Ok::<(), rigid::collision::CollisionError>(())
//! ```

mod detect;
mod proximity;
mod shape;
mod turn;

pub use detect::CollisionData;
pub(crate) use detect::RESTING_FACE;
pub use proximity::{proximity, Collider, Proximity};
pub(crate) use shape::hull_triangles;
pub use shape::Shape;
pub(crate) use turn::{Feature, Turn};

use crate::multibody::JointId;
use crate::spatial::{Transform, Vec3};
use thiserror::Error;

/// A shape fixed in a body (or in the world).
#[derive(Clone, Debug, PartialEq)]
pub struct Geometry {
    /// A name, for messages (the URDF link, the part).
    pub name: String,
    /// The body it moves with (`None`: fixed in the world).
    pub body: Option<JointId>,
    /// The shape's frame in the joint frame of `body` (in the world for `None`).
    pub placement: Transform,
    /// The shape.
    pub shape: Shape,
    /// Its friction coefficient (`None`: the model's default).
    pub friction: Option<f64>,
    /// Its restitution (`None`: the model's default).
    pub restitution: Option<f64>,
    /// MJCF's `contype` bit mask (1 by default).
    pub contype: u32,
    /// MJCF's `conaffinity` bit mask (1 by default): two geometries collide when
    /// `contype₁ & conaffinity₂` or `contype₂ & conaffinity₁` is not zero.
    pub conaffinity: u32,
}

impl Geometry {
    /// A geometry with the model's friction and restitution and the default masks.
    #[must_use]
    pub fn new(
        name: impl Into<String>,
        body: Option<JointId>,
        placement: Transform,
        shape: Shape,
    ) -> Self {
        Self {
            name: name.into(),
            body,
            placement,
            shape,
            friction: None,
            restitution: None,
            contype: 1,
            conaffinity: 1,
        }
    }
}

/// One contact between two bodies (or a body and the world), the output of collision detection and the contact solver's input ([`simulation::contact`](crate::simulation::contact)): where, along
/// which normal, how far apart, with which friction and restitution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint {
    /// The body pushed along `+normal` (`None`: the world).
    pub body1: Option<JointId>,
    /// The other body (`None`: the world, as for the ground).
    pub body2: Option<JointId>,
    /// The contact point in the world (m): the middle of the two closest points.
    pub point: Vec3,
    /// The unit contact normal in the world, from body 2 towards body 1.
    pub normal: Vec3,
    /// The signed distance along `normal` (m): positive apart, negative penetrating.
    pub gap: f64,
    /// Coulomb's friction coefficient `μ ≥ 0`.
    pub friction: f64,
    /// Newton's restitution coefficient `e ∈ [0, 1]`.
    pub restitution: f64,
    /// The collision geometries in contact (indices into the collision model; `None` for the
    /// ground), for reports.
    pub geometries: (usize, Option<usize>),
}

/// The ground: the half-space `nᵀ x ≤ height` (its surface the plane `nᵀ x = height`), with its
/// friction and restitution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ground {
    /// The plane's offset along the normal (m): for `n = z`, the height of the ground.
    pub height: f64,
    /// The unit normal, pointing out of the ground (default `z`: up, against gravity).
    pub normal: Vec3,
    /// Coulomb's friction coefficient of every contact with the ground.
    pub friction: f64,
    /// Newton's restitution of every contact with the ground (0: no bounce).
    pub restitution: f64,
}

impl Ground {
    /// The horizontal ground `z = height` with friction `friction` and no restitution.
    #[must_use]
    pub fn horizontal(height: f64, friction: f64) -> Self {
        Self {
            height,
            normal: Vec3::z(),
            friction,
            restitution: 0.0,
        }
    }
}

/// The friction coefficient assumed when none is given (`rigid simulate --friction`, Python's
/// `friction`): 0.8, between rubber on concrete (≈ 1) and MuJoCo's default (1), for robot feet
/// on a floor.
pub const DEFAULT_FRICTION: f64 = 0.8;

/// The distance (m) under which two shapes are contact candidates (speculative contacts: the
/// solver lets them close the gap but no more); 1 cm, more than a body at 10 m/s moves in a
/// 1 ms step.
pub const DEFAULT_MARGIN: f64 = 0.01;

/// The collision geometry of a model: the geometries, the ground, and which pairs collide.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionModel {
    /// The geometries.
    pub geometries: Vec<Geometry>,
    /// The ground, if any.
    pub ground: Option<Ground>,
    /// Whether geometries on different moving bodies collide with each other (not parent with
    /// child). Off, only the ground and geometries fixed in the world are met.
    pub self_collision: bool,
    /// Friction of a pair of geometries that give none ([`DEFAULT_FRICTION`]).
    pub friction: f64,
    /// Restitution of a pair of geometries that give none (0).
    pub restitution: f64,
    /// Contact candidates are the pairs closer than this (m, [`DEFAULT_MARGIN`]).
    pub margin: f64,
    /// Pairs of geometries (indices into `geometries`) that never collide (MJCF's
    /// `<contact><exclude>`, an SRDF's disabled pairs).
    pub excluded: Vec<(usize, usize)>,
    /// Pairs of geometries that collide whatever the other rules say (MJCF's
    /// `<contact><pair>`).
    pub included: Vec<(usize, usize)>,
}

impl CollisionModel {
    /// No geometry yet, `ground` (if any), self-collision on, the default friction and margin,
    /// no restitution.
    #[must_use]
    pub fn new(ground: impl Into<Option<Ground>>) -> Self {
        Self {
            geometries: Vec::new(),
            ground: ground.into(),
            self_collision: true,
            friction: DEFAULT_FRICTION,
            restitution: 0.0,
            margin: DEFAULT_MARGIN,
            excluded: Vec::new(),
            included: Vec::new(),
        }
    }

    /// Checks the numbers: finite placements, shapes with positive dimensions, friction `≥ 0`,
    /// restitution in `[0, 1]`, a unit ground normal, a positive margin.
    ///
    /// # Errors
    /// The first bad one.
    pub fn check(&self, njoints: usize) -> Result<(), CollisionError> {
        let friction = |x: f64| x.is_finite() && x >= 0.0;
        let restitution = |x: f64| (0.0..=1.0).contains(&x);
        if !friction(self.friction) || !restitution(self.restitution) {
            return Err(CollisionError::Material {
                what: "the model's default".into(),
            });
        }
        if !(self.margin.is_finite() && self.margin > 0.0) {
            return Err(CollisionError::Margin(self.margin));
        }
        if let Some(g) = &self.ground {
            let unit = (g.normal.norm() - 1.0).abs() < 1e-9;
            if !(unit && g.height.is_finite()) {
                return Err(CollisionError::Ground);
            }
            if !friction(g.friction) || !restitution(g.restitution) {
                return Err(CollisionError::Material {
                    what: "the ground".into(),
                });
            }
        }
        let n = self.geometries.len();
        if let Some(&(i, j)) = self
            .excluded
            .iter()
            .chain(&self.included)
            .find(|(i, j)| *i >= n || *j >= n || i == j)
        {
            return Err(CollisionError::Pair {
                first: i,
                second: j,
            });
        }
        for g in &self.geometries {
            if g.body.is_some_and(|j| j.0 >= njoints) {
                return Err(CollisionError::Body {
                    geometry: g.name.clone(),
                });
            }
            let p = &g.placement;
            let finite = p.rotation.iter().chain(p.translation.iter());
            if !finite.copied().all(f64::is_finite) {
                return Err(CollisionError::Placement {
                    geometry: g.name.clone(),
                });
            }
            g.shape.check().map_err(|message| CollisionError::Shape {
                geometry: g.name.clone(),
                message,
            })?;
            if !g.friction.is_none_or(friction) || !g.restitution.is_none_or(restitution) {
                return Err(CollisionError::Material {
                    what: format!("geometry \"{}\"", g.name),
                });
            }
        }
        Ok(())
    }
}

/// What is wrong with a collision model.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CollisionError {
    /// A friction that is negative or not finite, or a restitution outside `[0, 1]`.
    #[error("{what}: friction must be finite and >= 0, restitution in [0, 1]")]
    Material {
        /// Whose.
        what: String,
    },
    /// A ground normal that is not a unit vector, or a height that is not finite.
    #[error("the ground's normal must be a unit vector and its height finite")]
    Ground,
    /// A margin that is not positive and finite.
    #[error("the contact margin must be positive and finite, got {0}")]
    Margin(f64),
    /// A geometry on a joint the model does not have.
    #[error("geometry \"{geometry}\" is on a joint the model does not have")]
    Body {
        /// The geometry.
        geometry: String,
    },
    /// An excluded or included pair that names a geometry the model does not have, or one
    /// geometry twice.
    #[error("the pair of geometries ({first}, {second}) is not two of the model's geometries")]
    Pair {
        /// The first index.
        first: usize,
        /// The second index.
        second: usize,
    },
    /// A placement with a non-finite entry.
    #[error("geometry \"{geometry}\": the placement is not finite")]
    Placement {
        /// The geometry.
        geometry: String,
    },
    /// A configuration that is not one of the model's.
    #[error("the configuration has {got} numbers or is not valid; the model has nq = {expected}")]
    Configuration {
        /// `nq`.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A shape with a bad dimension, or a mesh whose convex hull cannot be made.
    #[error("geometry \"{geometry}\": {message}")]
    Shape {
        /// The geometry.
        geometry: String,
        /// What is wrong.
        message: String,
    },
}

/// Sets a floating robot down on the ground: moves its first free-flyer joint along the ground's
/// normal so that the lowest geometry just touches the ground at `q` (gap 0), and returns the
/// distance moved (m, positive up). `None` when there is no ground, no free-flyer, or no
/// geometry that meets the ground.
///
/// # Errors
/// A bad collision model, a configuration of the wrong length.
pub fn place_on_ground(
    model: &crate::multibody::Model,
    cm: &CollisionModel,
    q: &mut [f64],
) -> Result<Option<f64>, CollisionError> {
    use crate::multibody::{forward_kinematics_q, Data, JointType};
    let Some(ground) = cm.ground else {
        return Ok(None);
    };
    let Some(root) = model
        .joints()
        .iter()
        .find(|j| j.kind == JointType::FreeFlyer && j.parent.is_none())
    else {
        return Ok(None);
    };
    if q.len() != model.nq() {
        return Err(CollisionError::Configuration {
            expected: model.nq(),
            got: q.len(),
        });
    }
    let far = CollisionModel {
        margin: 1e6,
        self_collision: false,
        ..cm.clone()
    };
    let mut data = Data::new(model);
    forward_kinematics_q(model, &mut data, q).map_err(|_| CollisionError::Configuration {
        expected: model.nq(),
        got: q.len(),
    })?;
    let mut cd = CollisionData::new(model, &far)?;
    let mut contacts = Vec::new();
    cd.contacts(&far, &data.placements, &mut contacts);
    let low = contacts
        .iter()
        .filter(|c| c.geometries.1.is_none())
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min);
    if !low.is_finite() {
        return Ok(None);
    }
    for (k, n) in ground.normal.iter().enumerate() {
        q[root.idx_q + k] -= low * n;
    }
    Ok(Some(-low))
}
