//! The collision shapes, their parry counterparts, and their points nearest a plane.

use crate::spatial::{Transform, Vec3};
use parry3d_f64::math::{Pose, Rot3, Vector};
use parry3d_f64::shape::{PolygonalFeature, SharedShape};

/// A collision shape in its own frame: the shapes of URDF `<collision>`, of MJCF geoms and of
/// `rigid mass` parts, with their conventions (axes along z, centred, a cone's origin at its
/// centroid).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A ball.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// A box, centred.
    Box {
        /// Edge lengths along x, y, z (m).
        size: Vec3,
    },
    /// A cylinder along z, centred.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Length (m).
        length: f64,
    },
    /// A capsule along z, centred: a cylinder of `length` capped by two half balls.
    Capsule {
        /// Radius (m).
        radius: f64,
        /// Length of the cylindrical part (m).
        length: f64,
    },
    /// A cone along z, the origin at its centroid: base (radius `radius`) at `z = −h/4`, apex
    /// at `z = 3h/4` (the convention of `rigid mass`).
    Cone {
        /// Radius of the base (m).
        radius: f64,
        /// Height (m).
        height: f64,
    },
    /// An ellipsoid, centred (collides as the convex hull of 162 points of its surface).
    Ellipsoid {
        /// Semi-axes along x, y, z (m).
        semi_axes: Vec3,
    },
    /// The convex hull of points (a mesh's vertices, already scaled), in the shape frame.
    ConvexHull {
        /// The points (m).
        points: Vec<Vec3>,
    },
}

impl Shape {
    /// Checks the dimensions.
    pub(crate) fn check(&self) -> Result<(), String> {
        let pos = |what: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(format!("{what} must be positive and finite, got {x}"))
            }
        };
        match self {
            Self::Sphere { radius } => pos("radius", *radius),
            Self::Box { size } => size.iter().try_for_each(|x| pos("size", *x)),
            Self::Cylinder { radius, length } | Self::Capsule { radius, length } => {
                pos("radius", *radius)?;
                pos("length", *length)
            }
            Self::Cone { radius, height } => {
                pos("radius", *radius)?;
                pos("height", *height)
            }
            Self::Ellipsoid { semi_axes } => {
                semi_axes.iter().try_for_each(|x| pos("semi axis", *x))
            }
            Self::ConvexHull { points } => {
                if points.len() < 4 || points.iter().any(|p| !p.iter().all(|x| x.is_finite())) {
                    Err(format!(
                        "a convex hull needs at least 4 finite points, got {}",
                        points.len()
                    ))
                } else {
                    Ok(())
                }
            }
        }
    }

    /// The name: `sphere`, `box`, `cylinder`, `capsule`, `cone`, `ellipsoid`, `convex hull`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Sphere { .. } => "sphere",
            Self::Box { .. } => "box",
            Self::Cylinder { .. } => "cylinder",
            Self::Capsule { .. } => "capsule",
            Self::Cone { .. } => "cone",
            Self::Ellipsoid { .. } => "ellipsoid",
            Self::ConvexHull { .. } => "convex hull",
        }
    }
}

/// A shape as parry has it: the parry shape, its pose in our shape frame (parry's cylinders and
/// cones are along y, its cone centred at mid-height), the points tested against a plane, and a
/// bounding sphere.
#[derive(Clone)]
pub(crate) struct Parry {
    pub shape: SharedShape,
    /// The parry shape's frame in the shape frame.
    pub offset: Transform,
    /// How the shape meets a plane.
    pub kind: PlaneTest,
    /// Bounding sphere: centre (shape frame) and radius.
    pub center: Vec3,
    pub radius: f64,
}

/// How a shape's points nearest a plane are found.
#[derive(Clone, Debug)]
pub(crate) enum PlaneTest {
    /// Balls of this radius at these centres (a sphere, a capsule's two ends), shape frame.
    Balls(f64, [Vec3; 2], usize),
    /// These vertices (a box's corners, a hull's vertices), shape frame.
    Vertices(Vec<Vec3>),
    /// parry's support feature and point (cylinder, cone), in the parry shape's frame.
    Feature,
}

impl std::fmt::Debug for Parry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Parry")
            .field("shape", &self.shape.shape_type())
            .field("offset", &self.offset)
            .field("radius", &self.radius)
            .finish_non_exhaustive()
    }
}

/// Our vector as parry's.
pub(crate) fn to_parry(v: &Vec3) -> Vector {
    Vector::new(v.x, v.y, v.z)
}

/// parry's vector as ours.
pub(crate) fn from_parry(v: Vector) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

/// Our rigid transform as a parry pose.
pub(crate) fn pose(t: &Transform) -> Pose {
    let r = &t.rotation;
    let m = parry3d_f64::math::Mat3::from_cols(
        to_parry(&r.column(0).into()),
        to_parry(&r.column(1).into()),
        to_parry(&r.column(2).into()),
    );
    Pose::from_parts(to_parry(&t.translation), Rot3::from_mat3(&m).normalize())
}

/// The rotation taking parry's y axis to our z axis (a quarter turn about x).
fn y_to_z() -> Transform {
    Transform::from_rotation(crate::spatial::so3::exp(&Vec3::new(
        std::f64::consts::FRAC_PI_2,
        0.0,
        0.0,
    )))
}

/// 162 unit vectors: the icosphere of two subdivisions (vertices of a regular icosahedron
/// split twice, normalised).
fn sphere_points() -> Vec<Vec3> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut faces: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..2 {
        let mut mids = std::collections::HashMap::new();
        let mut mid = |a: usize, b: usize, v: &mut Vec<Vec3>| -> usize {
            *mids.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a] + v[b]) * 0.5).normalize());
                v.len() - 1
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let (ab, bc, ca) = (mid(a, b, &mut v), mid(b, c, &mut v), mid(c, a, &mut v));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    v
}

impl Parry {
    /// The parry shape of `shape`.
    ///
    /// # Errors
    /// A convex hull that parry cannot make (flat or degenerate points).
    pub(crate) fn of(shape: &Shape) -> Result<Self, String> {
        let zero = Vec3::zeros();
        let id = Transform::identity();
        let hull = |points: &[Vec3]| -> Result<(SharedShape, Vec<Vec3>), String> {
            let pts: Vec<Vector> = points.iter().map(to_parry).collect();
            let s = SharedShape::convex_hull(&pts)
                .ok_or("the convex hull of its points is flat or degenerate")?;
            let verts = s
                .as_convex_polyhedron()
                .map(|p| p.points().iter().map(|&x| from_parry(x)).collect())
                .unwrap_or_default();
            Ok((s, verts))
        };
        let bound = |pts: &[Vec3]| pts.iter().map(|p| p.norm()).fold(0.0, f64::max);
        Ok(match shape {
            Shape::Sphere { radius } => Self {
                shape: SharedShape::ball(*radius),
                offset: id,
                kind: PlaneTest::Balls(*radius, [zero, zero], 1),
                center: zero,
                radius: *radius,
            },
            Shape::Capsule { radius, length } => {
                let a = Vec3::new(0.0, 0.0, 0.5 * length);
                Self {
                    shape: SharedShape::capsule_z(0.5 * length, *radius),
                    offset: id,
                    kind: PlaneTest::Balls(*radius, [a, -a], 2),
                    center: zero,
                    radius: 0.5 * length + radius,
                }
            }
            Shape::Box { size } => {
                let h = size * 0.5;
                let corners = (0..8)
                    .map(|i| {
                        let s = |b: usize| if i & (1 << b) == 0 { -1.0 } else { 1.0 };
                        Vec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
                    })
                    .collect();
                Self {
                    shape: SharedShape::cuboid(h.x, h.y, h.z),
                    offset: id,
                    kind: PlaneTest::Vertices(corners),
                    center: zero,
                    radius: h.norm(),
                }
            }
            Shape::Cylinder { radius, length } => Self {
                shape: SharedShape::cylinder(0.5 * length, *radius),
                offset: y_to_z(),
                kind: PlaneTest::Feature,
                center: zero,
                radius: radius.hypot(0.5 * length),
            },
            Shape::Cone { radius, height } => Self {
                shape: SharedShape::cone(0.5 * height, *radius),
                offset: Transform::from_translation(Vec3::new(0.0, 0.0, 0.25 * height)) * y_to_z(),
                kind: PlaneTest::Feature,
                center: Vec3::new(0.0, 0.0, 0.25 * height),
                radius: radius.hypot(0.5 * height),
            },
            Shape::Ellipsoid { semi_axes } => {
                let pts: Vec<Vec3> = sphere_points()
                    .iter()
                    .map(|u| u.component_mul(semi_axes))
                    .collect();
                let (s, verts) = hull(&pts)?;
                Self {
                    shape: s,
                    offset: id,
                    radius: bound(&verts),
                    kind: PlaneTest::Vertices(verts),
                    center: zero,
                }
            }
            Shape::ConvexHull { points } => {
                let (s, verts) = hull(points)?;
                let lo = verts
                    .iter()
                    .fold(Vec3::repeat(f64::INFINITY), |a, p| a.inf(p));
                let hi = verts
                    .iter()
                    .fold(Vec3::repeat(-f64::INFINITY), |a, p| a.sup(p));
                let center = (lo + hi) * 0.5;
                let radius = verts
                    .iter()
                    .map(|p| (p - center).norm())
                    .fold(0.0, f64::max);
                Self {
                    shape: s,
                    offset: id,
                    kind: PlaneTest::Vertices(verts),
                    center,
                    radius,
                }
            }
        })
    }

    /// The shape's points within `margin` of the plane `nᵀ x = height` (or below it), with the
    /// shape at the world pose `pose` (of the shape frame): each the point of the shape and its
    /// signed distance to the plane, into `out`.
    pub(crate) fn near_plane(
        &self,
        pose: &Transform,
        n: &Vec3,
        height: f64,
        margin: f64,
        out: &mut Vec<(Vec3, f64)>,
    ) {
        out.clear();
        let mut test = |x: Vec3, r: f64| {
            let d = n.dot(&x) - height - r;
            if d <= margin {
                out.push((x - n * r, d));
            }
        };
        match &self.kind {
            PlaneTest::Balls(r, centres, k) => {
                for c in &centres[..*k] {
                    test(pose.act_point(c), *r);
                }
            }
            PlaneTest::Vertices(v) => {
                for p in v {
                    test(pose.act_point(p), 0.0);
                }
            }
            PlaneTest::Feature => {
                let world = *pose * self.offset;
                let dir = to_parry(&world.rotation.tr_mul(&(-n)));
                let Some((pfm, _)) = self.shape.as_polygonal_feature_map() else {
                    return;
                };
                let support = self
                    .shape
                    .as_support_map()
                    .map(|s| s.local_support_point(dir));
                let mut f = PolygonalFeature::default();
                let hint = support.unwrap_or(Vector::ZERO);
                pfm.local_support_feature_toward(dir, hint, &mut f);
                for v in f.vertices[..f.num_vertices].iter().chain(support.iter()) {
                    test(world.act_point(&from_parry(*v)), 0.0);
                }
            }
        }
    }
}
