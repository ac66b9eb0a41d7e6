//! How a contact between two geometries moves with their bodies: which side's flat face holds
//! the normal, or which features (ball centres, vertices, edges, capsule axes) it joins. The
//! derivatives of a step read it ([`rows`](crate::simulation::Simulator::step_derivatives)):
//! the normal of a face turns with that face's body; the normal between two features is their
//! common perpendicular, which turns and slides with both bodies. Anything else (edges crossing
//! inside a face's outline, a cylinder against anything but a face, a non-convex mesh's
//! triangle) is held: its normal's turn is not followed.

use super::shape::from_parry;
use crate::spatial::{Transform, Vec3};
use parry3d_f64::math::Vector;
use parry3d_f64::shape::Shape;

/// A feature fixed in a body that a contact's normal is perpendicular to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Feature {
    /// A point `a` (world): a vertex (`rho = 0`) or a ball's centre of radius `rho`.
    Point { a: Vec3, rho: f64 },
    /// A line through `a` (world, the feature's point nearest the other side) along the unit
    /// `e`: an edge (`rho = 0`) or a capsule's axis of radius `rho`.
    Line { a: Vec3, e: Vec3, rho: f64 },
    /// A circle (a cylinder's or a cone's rim) of centre `c`, unit axis `a` and radius `radius`
    /// (world), met at its point farthest towards the other side, which slides along it.
    Rim { c: Vec3, a: Vec3, radius: f64 },
}

/// How a contact's normal turns and its point moves with the bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Turn {
    /// A body on the ground: its point is a vertex or a ball's (the ground's own rules).
    Ground,
    /// A body on the ground at a point of a rim (a [`Feature::Rim`]), which slides along the
    /// rim as the body turns: the rim's point farthest along `−n`.
    Rim(Feature),
    /// The normal is the flat face's of side `face` (0: the contact's body 1, 1: body 2) and
    /// turns with that body; the other side meets it at `point`: a vertex, a ball (its centre
    /// fixed in its body) or a rim.
    Face { face: usize, point: Feature },
    /// The normal is the common perpendicular of two features (body 1's, body 2's).
    Features([Feature; 2]),
    /// Neither: the normal and the point are held fixed in the partials.
    Held,
}

/// What one side shows at a contact: whether the normal is one of its flat faces', and the
/// feature fixed in it that meets the other side.
struct Side {
    face: bool,
    feature: Option<Feature>,
}

/// Within this (relative) a normal is a face's, a point a vertex or on an edge, two
/// directions parallel.
const SAME: f64 = 1e-9;

/// Side `shape` (posed at `at`) at its contact point `p` (its frame), `n` its outward normal
/// there (its frame).
fn side(shape: &dyn Shape, at: &Transform, p: Vector, n: Vector) -> Side {
    let world = |x: Vector| at.act_point(&from_parry(x));
    let dir = |x: Vector| at.rotation * from_parry(x).normalize();
    let point = |a: Vector, rho: f64| Some(Feature::Point { a: world(a), rho });
    let line = |a: Vector, e: Vector, rho: f64| {
        Some(Feature::Line {
            a: world(a),
            e: dir(e),
            rho,
        })
    };
    if let Some(b) = shape.as_ball() {
        return Side {
            face: false,
            feature: point(Vector::ZERO, b.radius),
        };
    }
    if let Some(c) = shape.as_capsule() {
        // a point at the radius from an end's centre is that end's ball (parry takes a
        // capsule's points against a face as its ends' balls), else the axis
        let (r, a, b) = (c.radius, c.segment.a, c.segment.b);
        let tol = SAME * r.max(1e-3);
        let feature = if ((p - a).length() - r).abs() <= tol {
            point(a, r)
        } else if ((p - b).length() - r).abs() <= tol {
            point(b, r)
        } else {
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            line(a + (b - a) * t, b - a, r)
        };
        return Side {
            face: false,
            feature,
        };
    }
    if let Some(cb) = shape.as_cuboid() {
        let he = cb.half_extents;
        let tol = SAME * he.max_element();
        let on = (p.abs() - he).abs();
        let at_face = [on.x <= tol, on.y <= tol, on.z <= tol];
        let v = Vector::new(he.x.copysign(p.x), he.y.copysign(p.y), he.z.copysign(p.z));
        let feature = match at_face.iter().filter(|x| **x).count() {
            3 => point(v, 0.0),
            2 => {
                let k = at_face.iter().position(|x| !*x).unwrap_or(0);
                let mut e = Vector::ZERO;
                e[k] = 1.0;
                line(p, e, 0.0)
            }
            _ => None,
        };
        return Side {
            face: n.abs().max_element() >= 1.0 - SAME,
            feature,
        };
    }
    if let Some(poly) = shape.as_convex_polyhedron() {
        let pts = poly.points();
        let scale = pts.iter().fold(1e-3_f64, |a, x| a.max(x.length()));
        let tol = SAME * scale;
        let feature = if let Some(v) = pts.iter().find(|x| (**x - p).length() <= tol) {
            point(*v, 0.0)
        } else {
            poly.edges().iter().find_map(|e| {
                let (a, b) = (pts[e.vertices[0] as usize], pts[e.vertices[1] as usize]);
                let t = (p - a).dot(b - a) / (b - a).length_squared();
                let off = (a + (b - a) * t - p).length();
                ((0.0..=1.0).contains(&t) && off <= tol).then(|| line(p, b - a, 0.0))?
            })
        };
        return Side {
            face: poly.faces().iter().any(|f| f.normal.dot(n) >= 1.0 - SAME),
            feature,
        };
    }
    let normal = at.rotation * from_parry(n);
    Side {
        face: false,
        feature: rim(shape, at, &world(p), &normal),
    }
}

/// The turn of a contact between geometry 1 (`shape1` at `at1`, its point `p1` and outward
/// normal `n1` in its frame) and geometry 2 (the same); `normal` the contact's (world, from
/// body 2 towards body 1).
pub(crate) fn turn(
    (shape1, at1, p1, n1): (&dyn Shape, &Transform, Vector, Vector),
    (shape2, at2, p2, n2): (&dyn Shape, &Transform, Vector, Vector),
    normal: &Vec3,
) -> Turn {
    let (s1, s2) = (side(shape1, at1, p1, n1), side(shape2, at2, p2, n2));
    match (s1.feature, s2.feature) {
        (_, Some(point @ (Feature::Point { .. } | Feature::Rim { .. }))) if s1.face => {
            Turn::Face { face: 0, point }
        }
        (Some(point @ (Feature::Point { .. } | Feature::Rim { .. })), _) if s2.face => {
            Turn::Face { face: 1, point }
        }
        // a face's normal with anything but a point or a rim on the other side (two faces'
        // clipped edges crossing, a capsule's axis over a face's edge): not followed
        (Some(f1), Some(f2)) if !s1.face && !s2.face && perpendicular(&f1, &f2, normal) => {
            Turn::Features([f1, f2])
        }
        _ => Turn::Held,
    }
}

/// Whether `normal` is the common perpendicular of the two features, well defined: along the
/// line between two points (at least one a ball), across a point and a line (the same), or
/// along the cross product of two lines at least 1 mrad from parallel (nearer, the slides
/// along them are ill-conditioned: held).
fn perpendicular(f1: &Feature, f2: &Feature, normal: &Vec3) -> bool {
    use Feature::{Line, Point};
    let along = |w: Vec3| w.norm() > SAME && w.normalize().dot(normal).abs() >= 1.0 - 1e-6;
    match (f1, f2) {
        (Point { a: a1, rho: r1 }, Point { a: a2, rho: r2 }) => r1 + r2 > 0.0 && along(a1 - a2),
        (Point { a, rho: rp }, Line { a: b, e, rho: rl })
        | (Line { a: b, e, rho: rl }, Point { a, rho: rp }) => {
            let w = a - b;
            rp + rl > 0.0 && along(w - e * e.dot(&w))
        }
        (Line { e: e1, .. }, Line { e: e2, .. }) => {
            e1.cross(e2).norm() >= 1e-3 && along(e1.cross(e2))
        }
        _ => false,
    }
}

/// The rim of a cylinder or a cone (posed at `at`, parry's frame: the axis along y, a cone's
/// base at `−h/2`) whose point farthest along `out` (the shape's outward normal at the
/// contact, not along the axis: a flat cap rests on its rim's points as vertices) is the world
/// point `x`: that point slides along the rim as the body turns. Other points of a rim (the
/// corners of parry's square for a cap facing the other side) and points inside a side's line
/// of contact (parry adds its deepest point anywhere along the line) are not.
pub(crate) fn rim(shape: &dyn Shape, at: &Transform, x: &Vec3, out: &Vec3) -> Option<Feature> {
    let (hh, rims): (f64, &[(f64, f64)]) = if let Some(c) = shape.as_cylinder() {
        (c.half_height, &[(-1.0, c.radius), (1.0, c.radius)][..])
    } else if let Some(c) = shape.as_cone() {
        (c.half_height, &[(-1.0, c.radius)][..])
    } else {
        return None;
    };
    let a = at.rotation * Vec3::y();
    let m = out - a * a.dot(out);
    if m.norm() < 1e-6 {
        return None;
    }
    rims.iter().find_map(|&(side, radius)| {
        let c = at.act_point(&Vec3::new(0.0, side * hh, 0.0));
        let farthest = c + m.normalize() * radius;
        ((x - farthest).norm() <= 1e-6 * radius).then_some(Feature::Rim { c, a, radius })
    })
}
