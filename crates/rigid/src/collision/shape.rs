//! The collision shapes, their parry counterparts, and their points nearest a plane.

use crate::spatial::{Transform, Vec3};
use parry3d_f64::math::{Pose, Rot3, Vector};
use parry3d_f64::shape::{PolygonalFeature, SharedShape};
use parry3d_f64::transformation::try_convex_hull;

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

    /// How deep the deepest of a convex hull's points lies inside their hull (m): 0, to
    /// round-off, for the vertices of a convex mesh, which all lie on its surface; the depth of
    /// its deepest dent for a non-convex one, whose hull fills the dents (and collides in its
    /// place). The distance of a point to the surface is `min over the hull's faces of
    /// (d − n·p)`, `n·x = d` a face's plane, `n` outward. 0 for the other shapes.
    #[must_use]
    pub fn concavity(&self) -> f64 {
        let Self::ConvexHull { points } = self else {
            return 0.0;
        };
        let pts: Vec<Vector> = points.iter().map(to_parry).collect();
        let Ok((vertices, triangles)) = try_convex_hull(&pts) else {
            return 0.0;
        };
        let vertices: Vec<Vec3> = vertices.into_iter().map(from_parry).collect();
        let centre = vertices.iter().sum::<Vec3>() / vertices.len().max(1) as f64;
        let planes: Vec<(Vec3, f64)> = triangles
            .iter()
            .filter_map(|t| {
                let [a, b, c] = t.map(|i| vertices[i as usize]);
                let n = (b - a).cross(&(c - a)).try_normalize(1e-300)?;
                let n = if n.dot(&(a - centre)) < 0.0 { -n } else { n };
                Some((n, n.dot(&a)))
            })
            .collect();
        let mut deepest: f64 = 0.0;
        for p in points {
            // the point's depth, no deeper than the deepest so far once a face shows it
            let mut depth = f64::INFINITY;
            for (n, d) in &planes {
                depth = depth.min(d - n.dot(p));
                if depth <= deepest {
                    break;
                }
            }
            if depth.is_finite() {
                deepest = deepest.max(depth);
            }
        }
        deepest
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
    /// These vertices (a box's corners), shape frame.
    Vertices(Vec<Vec3>),
    /// A convex hull's vertices, walked along its edges.
    Hull(HullGraph),
    /// parry's support feature and point (cylinder, cone), in the parry shape's frame.
    Feature,
}

/// A convex hull's vertices and, for each, its neighbours along the hull's edges (compressed
/// rows): the graph on which a linear function is minimised by descent, as MuJoCo's mesh
/// support (`mjc_support` with `graphadr`) and libccd's hill-climbing do. On a convex polytope
/// every local minimum of a linear function over the vertices is global, and the vertices under
/// any level are connected on the edges (from each, an edge path descends to the minimum), so
/// [`lowest`](Self::lowest) and [`below`](Self::below) visit only the vertices they return and
/// their neighbours, never every vertex.
#[derive(Clone, Debug)]
pub(crate) struct HullGraph {
    /// The vertices (shape frame).
    pub points: Vec<Vec3>,
    /// `adjacent[first[i]..first[i + 1]]`: the neighbours of vertex i.
    first: Vec<u32>,
    adjacent: Vec<u32>,
}

/// The state of walks on one hull: where the last descent ended (the next one starts there: a
/// body moves little in a step), and the marks of the vertices seen.
#[derive(Clone, Debug, Default)]
pub(crate) struct Walk {
    start: usize,
    seen: Marks,
}

/// Marks of visited vertices, cleared in O(1) by a new epoch.
#[derive(Clone, Debug, Default)]
pub(crate) struct Marks {
    epoch: u32,
    mark: Vec<u32>,
    stack: Vec<u32>,
}

impl HullGraph {
    /// The graph of parry's hull: its points, and the two ends of each of its edges (the edges
    /// parry merged inside a flat face included: chords of a face keep the properties above).
    fn new(poly: &parry3d_f64::shape::ConvexPolyhedron) -> Self {
        let points: Vec<Vec3> = poly.points().iter().map(|&x| from_parry(x)).collect();
        let n = points.len();
        let mut count = vec![0u32; n + 1];
        for e in poly.edges() {
            count[e.vertices[0] as usize + 1] += 1;
            count[e.vertices[1] as usize + 1] += 1;
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut adjacent = vec![0u32; count[n] as usize];
        for e in poly.edges() {
            let [a, b] = e.vertices;
            adjacent[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
            adjacent[fill[b as usize] as usize] = a;
            fill[b as usize] += 1;
        }
        Self {
            points,
            first: count,
            adjacent,
        }
    }

    fn neighbours(&self, i: usize) -> &[u32] {
        &self.adjacent[self.first[i] as usize..self.first[i + 1] as usize]
    }

    /// The vertex minimising `dir · p`, by steepest descent along the edges from `start`.
    pub(crate) fn lowest(&self, dir: &Vec3, start: usize) -> usize {
        let mut at = start.min(self.points.len() - 1);
        let mut value = dir.dot(&self.points[at]);
        loop {
            let mut next = at;
            for &j in self.neighbours(at) {
                let v = dir.dot(&self.points[j as usize]);
                if v < value {
                    (value, next) = (v, j as usize);
                }
            }
            if next == at {
                return at;
            }
            at = next;
        }
    }

    /// Calls `f` on every vertex `p` with `dir · p ≤ level`, walking the edges from `lowest`
    /// (the minimiser); nothing if it is above the level.
    pub(crate) fn below(
        &self,
        dir: &Vec3,
        level: f64,
        lowest: usize,
        marks: &mut Marks,
        mut f: impl FnMut(&Vec3),
    ) {
        if dir.dot(&self.points[lowest]) > level {
            return;
        }
        if marks.mark.len() != self.points.len() {
            marks.mark = vec![0; self.points.len()];
            marks.epoch = 0;
        }
        marks.epoch = marks.epoch.wrapping_add(1);
        if marks.epoch == 0 {
            marks.mark.fill(0);
            marks.epoch = 1;
        }
        let epoch = marks.epoch;
        marks.stack.clear();
        marks.stack.push(lowest as u32);
        marks.mark[lowest] = epoch;
        while let Some(i) = marks.stack.pop() {
            let i = i as usize;
            f(&self.points[i]);
            for &j in self.neighbours(i) {
                let j = j as usize;
                if marks.mark[j] != epoch {
                    marks.mark[j] = epoch;
                    if dir.dot(&self.points[j]) <= level {
                        marks.stack.push(j as u32);
                    }
                }
            }
        }
    }
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

/// The convex hull of `points`: its vertices and its triangles (outward, counter-clockwise),
/// or `None` when parry makes fewer than 4 triangles (fewer than 4 points, or collinear ones);
/// flat points with 4 or more on their outline give a two-sided polygon (no volume).
pub(crate) fn hull_triangles(points: &[Vec3]) -> Option<(Vec<Vec3>, Vec<[usize; 3]>)> {
    let pts: Vec<Vector> = points.iter().map(to_parry).collect();
    let (vertices, triangles) = try_convex_hull(&pts).ok()?;
    (triangles.len() >= 4).then(|| {
        (
            vertices.into_iter().map(from_parry).collect(),
            triangles.iter().map(|t| t.map(|i| i as usize)).collect(),
        )
    })
}

impl Parry {
    /// The parry shape of `shape`.
    ///
    /// # Errors
    /// A convex hull that parry cannot make (flat or degenerate points).
    pub(crate) fn of(shape: &Shape) -> Result<Self, String> {
        let zero = Vec3::zeros();
        let id = Transform::identity();
        let hull = |points: &[Vec3]| -> Result<(SharedShape, HullGraph), String> {
            let pts: Vec<Vector> = points.iter().map(to_parry).collect();
            let s = SharedShape::convex_hull(&pts)
                .ok_or("the convex hull of its points is flat or degenerate")?;
            let graph = s
                .as_convex_polyhedron()
                .map(HullGraph::new)
                .ok_or("the convex hull of its points is flat or degenerate")?;
            Ok((s, graph))
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
                let (s, graph) = hull(&pts)?;
                Self {
                    shape: s,
                    offset: id,
                    radius: bound(&graph.points),
                    kind: PlaneTest::Hull(graph),
                    center: zero,
                }
            }
            Shape::ConvexHull { points } => {
                let (s, graph) = hull(points)?;
                let verts = &graph.points;
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
                    kind: PlaneTest::Hull(graph),
                    center,
                    radius,
                }
            }
        })
    }

    /// The shape's points within `margin` of the plane `nᵀ x = height` (or below it), with the
    /// shape at the world pose `pose` (of the shape frame): each the point of the shape and its
    /// signed distance to the plane, into `out`. With `face = Some(f)`, a hull gives only its
    /// vertices within `f` of its deepest one, and the result says whether it may have left
    /// others within the margin out (the face's level is below the margin's).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn near_plane(
        &self,
        pose: &Transform,
        n: &Vec3,
        height: f64,
        margin: f64,
        face: Option<f64>,
        walk: &mut Walk,
        out: &mut Vec<(Vec3, f64)>,
    ) -> bool {
        let mut cut = false;
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
            PlaneTest::Hull(g) => {
                // d(p) = (Rᵀn)·p + n·t − height over the hull's vertices p
                let dir = pose.rotation.tr_mul(n);
                let mut level = height - n.dot(&pose.translation) + margin;
                let lowest = g.lowest(&dir, walk.start);
                walk.start = lowest;
                if let Some(f) = face {
                    let top = dir.dot(&g.points[lowest]) + f;
                    cut = top < level;
                    level = level.min(top);
                }
                g.below(&dir, level, lowest, &mut walk.seen, |p| {
                    test(pose.act_point(p), 0.0)
                });
            }
            PlaneTest::Feature => {
                let world = *pose * self.offset;
                let dir = to_parry(&world.rotation.tr_mul(&(-n)));
                let Some((pfm, _)) = self.shape.as_polygonal_feature_map() else {
                    return false;
                };
                let support = self
                    .shape
                    .as_support_map()
                    .map(|s| s.local_support_point(dir));
                let mut f = PolygonalFeature::default();
                let hint = support.unwrap_or(Vector::ZERO);
                pfm.local_support_feature_toward(dir, hint, &mut f);
                for v in &f.vertices[..f.num_vertices] {
                    test(world.act_point(&from_parry(*v)), 0.0);
                }
                // the support point, unless it is one of the feature's vertices
                if let Some(s) = support {
                    if f.vertices[..f.num_vertices]
                        .iter()
                        .all(|v| (*v - s).length() >= 1e-9)
                    {
                        test(world.act_point(&from_parry(s)), 0.0);
                    }
                }
            }
        }
        cut
    }
}

#[cfg(test)]
mod tests {
    use super::{Parry, PlaneTest, Shape, Walk};
    use crate::multibody::configuration::Rng;
    use crate::spatial::Vec3;

    /// Descent and flood on the hull's edges give what a loop over every vertex gives: random
    /// clouds (a ball's, a flat box's with coplanar faces, a sole's uneven by 0.5 mm), random
    /// directions and levels, walks started where the last one ended.
    #[test]
    fn hull_walks_find_what_every_vertex_finds() {
        let mut rng = Rng::new(7);
        let dir = |rng: &mut Rng| Vec3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
        let clouds: Vec<Vec<Vec3>> = vec![
            (0..300).map(|_| dir(&mut rng)).collect(),
            (0..200)
                .map(|_| {
                    let c = |rng: &mut Rng| if rng.next_f64() < 0.5 { -1.0 } else { 1.0 };
                    let mut p = Vec3::new(
                        rng.uniform(-1.0, 1.0),
                        rng.uniform(-1.0, 1.0),
                        c(&mut rng) * 0.1,
                    );
                    let k = (rng.next_u64() % 3) as usize;
                    p[k] = c(&mut rng) * if k == 2 { 0.1 } else { 1.0 };
                    p
                })
                .collect(),
            (0..400)
                .map(|_| {
                    let (x, y) = (rng.uniform(-0.1, 0.1), rng.uniform(-0.05, 0.05));
                    let z = if rng.next_f64() < 0.5 {
                        rng.uniform(0.0, 5e-4)
                    } else {
                        0.02
                    };
                    Vec3::new(x, y, z)
                })
                .collect(),
        ];
        for points in clouds {
            let parry = Parry::of(&Shape::ConvexHull { points }).unwrap();
            let PlaneTest::Hull(g) = &parry.kind else {
                panic!("a hull walks its graph")
            };
            let mut walk = Walk::default();
            for _ in 0..200 {
                let d = dir(&mut rng);
                let values: Vec<f64> = g.points.iter().map(|p| d.dot(p)).collect();
                let min = values.iter().copied().fold(f64::INFINITY, f64::min);
                let lowest = g.lowest(&d, walk.start);
                walk.start = lowest;
                assert_eq!(values[lowest], min);
                let level = min + rng.uniform(0.0, 0.3);
                let mut found = Vec::new();
                g.below(&d, level, lowest, &mut walk.seen, |p| found.push(*p));
                let mut all: Vec<Vec3> = g
                    .points
                    .iter()
                    .filter(|p| d.dot(p) <= level)
                    .copied()
                    .collect();
                let key = |p: &Vec3| (p.x, p.y, p.z);
                found.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
                all.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
                assert_eq!(found, all);
            }
        }
    }

    /// A convex mesh's vertices lie on their hull (depth 0 to round-off); points inside a box
    /// with its corners lie as deep as their distance to its nearest face, `min(h − |x_i|)`.
    #[test]
    fn concavity_is_the_depth_of_the_deepest_point_inside_the_hull() {
        let mut rng = Rng::new(11);
        let ball: Vec<Vec3> = (0..200)
            .map(|_| 0.3 * Vec3::new(rng.normal(), rng.normal(), rng.normal()).normalize())
            .collect();
        let ball = Shape::ConvexHull { points: ball }.concavity();
        assert!(ball < 1e-12, "a ball's surface points: {ball:e}");
        let h = Vec3::new(0.2, 0.1, 0.05);
        let mut points: Vec<Vec3> = (0..8)
            .map(|i| {
                let s = |b: usize| if i & (1 << b) == 0 { -1.0 } else { 1.0 };
                Vec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
            })
            .collect();
        let mut expected: f64 = 0.0;
        for _ in 0..50 {
            let x = Vec3::new(
                rng.uniform(-h.x, h.x),
                rng.uniform(-h.y, h.y),
                rng.uniform(-h.z, h.z),
            );
            expected = expected.max((h - x.abs()).min());
            points.push(x);
        }
        let depth = Shape::ConvexHull { points }.concavity();
        assert!(
            (depth - expected).abs() < 1e-12,
            "{depth} against {expected}"
        );
        assert_eq!(Shape::Sphere { radius: 1.0 }.concavity(), 0.0);
    }
}
