//! The signed distance between two shapes at their world poses: Pinocchio's `computeDistance`
//! and `computeCollision` (hpp-fcl), here parry's GJK/EPA on the convex shapes (a mesh is its
//! convex hull, as everywhere in rigid's collision).

use super::shape::{from_parry, pose, Parry};
use super::{CollisionError, Shape};
use crate::spatial::{Transform, Vec3};

/// A shape made ready for queries: its parry counterpart (a mesh's convex hull) built once.
#[derive(Clone, Debug)]
pub struct Collider {
    parry: Parry,
}

impl Collider {
    /// `shape`, checked and prepared; `name` names it in an error.
    ///
    /// # Errors
    /// [`CollisionError::Shape`] for a non-positive or non-finite dimension, or points whose
    /// convex hull is flat.
    pub fn new(name: &str, shape: &Shape) -> Result<Self, CollisionError> {
        let fail = |message: String| CollisionError::Shape {
            geometry: name.to_string(),
            message,
        };
        shape.check().map_err(fail)?;
        Ok(Self {
            parry: Parry::of(shape).map_err(fail)?,
        })
    }
}

/// How near two shapes are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Proximity {
    /// The signed distance (m): positive apart, zero touching, negative the depth of the
    /// penetration (the shortest translation that separates them).
    pub distance: f64,
    /// The point of the first shape nearest the second (world; the deepest in it when they
    /// penetrate).
    pub point_a: Vec3,
    /// The point of the second shape nearest the first (world).
    pub point_b: Vec3,
    /// The unit normal out of the first shape, towards the second (world).
    pub normal: Vec3,
}

impl Proximity {
    /// Whether the shapes touch or overlap (`distance ≤ 0`): hpp-fcl's `isCollision` with no
    /// security margin.
    #[must_use]
    pub fn collides(&self) -> bool {
        self.distance <= 0.0
    }
}

/// The signed distance between `a` at the world pose `pa` and `b` at `pb`, with the nearest
/// points; `None` only where parry has no query for the pair (none of rigid's shapes, all
/// convex).
///
/// ```
/// use rigid::collision::{proximity, Collider, Shape};
/// use rigid::spatial::{Transform, Vec3};
/// let ball = Collider::new("ball", &Shape::Sphere { radius: 0.1 })?;
/// let cube = Collider::new("cube", &Shape::Box { size: Vec3::new(0.2, 0.2, 0.2) })?;
/// let at = Transform::from_translation(Vec3::new(0.5, 0.0, 0.0));
/// let p = proximity(&ball, &Transform::identity(), &cube, &at).unwrap();
/// assert!((p.distance - 0.3).abs() < 1e-9 && !p.collides());
/// assert!((p.point_b - Vec3::new(0.4, 0.0, 0.0)).norm() < 1e-9);
/// # Ok::<(), rigid::collision::CollisionError>(())
/// ```
#[must_use]
pub fn proximity(a: &Collider, pa: &Transform, b: &Collider, pb: &Transform) -> Option<Proximity> {
    let (pa, pb) = (*pa * a.parry.offset, *pb * b.parry.offset);
    let c = parry3d_f64::query::contact(
        &pose(&pa),
        &*a.parry.shape,
        &pose(&pb),
        &*b.parry.shape,
        f64::MAX,
    );
    let c = c.ok().flatten()?;
    Some(Proximity {
        distance: c.dist,
        point_a: from_parry(c.point1),
        point_b: from_parry(c.point2),
        normal: from_parry(c.normal1),
    })
}
