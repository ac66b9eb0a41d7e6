//! How a contact between two geometries moves with their bodies: which side's flat face holds
//! the normal, or which two ball centres it joins. The derivatives of a step read it
//! ([`rows`](crate::simulation::Simulator::step_derivatives)): the normal of a face turns with
//! that face's body, `δn = δθ_face × n`; the normal between two balls of centres `a₁`, `a₂`
//! (radii `ρ₁`, `ρ₂`) is `n = (a₁ − a₂)/|a₁ − a₂|`, `δn = (I − n nᵀ)(δa₁ − δa₂)/|a₁ − a₂|`.
//! Anything else (an edge across an edge, a capsule's side, a cylinder's rim, a mesh's
//! triangle) is held: its normal's turn is not followed.

use super::shape::from_parry;
use crate::spatial::{Transform, Vec3};
use parry3d_f64::math::Vector;
use parry3d_f64::shape::Shape;

/// How a contact's normal turns and its point moves with the bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Turn {
    /// A body on the ground: its point is a vertex or a ball's (the ground's own rules).
    Ground,
    /// The normal is the flat face's of side `face` (0: the contact's body 1, 1: body 2) and
    /// turns with that body; the other side meets it at `a` (world), a vertex (`rho = 0`) or a
    /// ball's centre of radius `rho`, fixed in its body.
    Face { face: usize, a: Vec3, rho: f64 },
    /// The normal joins two ball centres `a` (world; `rho` their radii, one may be a vertex),
    /// each fixed in its body.
    Centres { a: [Vec3; 2], rho: [f64; 2] },
    /// Neither: the normal and the point are held fixed in the partials.
    Held,
}

/// What one side shows at a contact: whether the normal is one of its flat faces', and the
/// point fixed in it that meets the other side (a vertex, or a ball's centre and radius).
struct Side {
    face: bool,
    point: Option<(Vec3, f64)>,
}

/// Within this (relative) a normal is a face's and a point a vertex.
const SAME: f64 = 1e-9;

/// Side `shape` (posed at `at`) at its contact point `p` (its frame), `n` its outward normal
/// there (its frame).
fn side(shape: &dyn Shape, at: &Transform, p: Vector, n: Vector) -> Side {
    let world = |x: Vector| at.act_point(&from_parry(x));
    if let Some(b) = shape.as_ball() {
        return Side {
            face: false,
            point: Some((world(Vector::ZERO), b.radius)),
        };
    }
    if let Some(c) = shape.as_capsule() {
        // a point at the radius from an end's centre is that end's ball (parry takes a
        // capsule's points against a face as its ends' balls); one along the axis slides
        let r = c.radius;
        let end = [c.segment.a, c.segment.b]
            .into_iter()
            .find(|e| ((p - *e).length() - r).abs() <= SAME * r.max(1e-3));
        return Side {
            face: false,
            point: end.map(|e| (world(e), r)),
        };
    }
    if let Some(cb) = shape.as_cuboid() {
        let he = cb.half_extents;
        let face = n.abs().max_element() >= 1.0 - SAME;
        let tol = SAME * he.max_element();
        let corner = (p.abs() - he).abs().max_element() <= tol;
        let v = Vector::new(he.x.copysign(p.x), he.y.copysign(p.y), he.z.copysign(p.z));
        return Side {
            face,
            point: corner.then(|| (world(v), 0.0)),
        };
    }
    if let Some(poly) = shape.as_convex_polyhedron() {
        let face = poly.faces().iter().any(|f| f.normal.dot(n) >= 1.0 - SAME);
        let scale = poly.points().iter().fold(0.0_f64, |a, x| a.max(x.length()));
        let vertex = poly
            .points()
            .iter()
            .find(|x| (**x - p).length() <= SAME * scale.max(1e-3));
        return Side {
            face,
            point: vertex.map(|v| (world(*v), 0.0)),
        };
    }
    Side {
        face: false,
        point: None,
    }
}

/// The turn of a contact between geometry 1 (`shape1` at `at1`, its point `p1` and outward
/// normal `n1` in its frame) and geometry 2 (the same).
pub(crate) fn turn(
    (shape1, at1, p1, n1): (&dyn Shape, &Transform, Vector, Vector),
    (shape2, at2, p2, n2): (&dyn Shape, &Transform, Vector, Vector),
) -> Turn {
    let (s1, s2) = (side(shape1, at1, p1, n1), side(shape2, at2, p2, n2));
    match (s1.point, s2.point) {
        (_, Some((a, rho))) if s1.face => Turn::Face { face: 0, a, rho },
        (Some((a, rho)), _) if s2.face => Turn::Face { face: 1, a, rho },
        (Some((a1, r1)), Some((a2, r2))) if r1 + r2 > 0.0 && (a1 - a2).norm() > SAME => {
            Turn::Centres {
                a: [a1, a2],
                rho: [r1, r2],
            }
        }
        _ => Turn::Held,
    }
}
