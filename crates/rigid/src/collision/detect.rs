//! The workspace of a collision model and the contact points at a configuration.

use super::shape::{from_parry, pose, Parry, Walk};
use super::turn::{rim, turn, Turn};
use super::ContactPoint;
use super::{CollisionError, CollisionModel};
use crate::multibody::{JointId, Model};
use crate::spatial::{Transform, Vec3};
use parry3d_f64::query::{ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher};

/// The workspace of a [`CollisionModel`] on a [`Model`] (Pinocchio's `GeometryData`): parry's
/// shapes, the candidate pairs and their manifolds, the geometries' world poses.
#[derive(Clone, Debug)]
pub struct CollisionData {
    shapes: Vec<Parry>,
    /// The pairs of geometries that may collide (the ground aside).
    pairs: Vec<(usize, usize)>,
    manifolds: Vec<Vec<ContactManifold<(), ()>>>,
    /// Each geometry's world pose, at the last [`contacts`](Self::contacts).
    pub poses: Vec<Transform>,
    near: Vec<(Vec3, f64)>,
    /// The points of one body near the ground, each with its geometry.
    gathered: Vec<(Vec3, f64, usize)>,
    /// Per gathered point, the lowest gap of the kept points' triangles over it
    /// ([`add_under_envelope`]'s scratch).
    held: Vec<f64>,
    /// Each moving body and its geometries: a body meets the ground on at most four points
    /// over all its geometries.
    bodies: Vec<(JointId, Vec<usize>)>,
    /// Per geometry, its walk on its hull against the ground.
    walks: Vec<Walk>,
    /// Where each contact of the last [`contacts`](Self::contacts) came from (in its order):
    /// `(pair, manifold, point)`, `None` on the ground; [`turn`](Self::turn) reads it.
    sources: Vec<Option<(usize, usize, usize)>>,
    njoints: usize,
}

impl CollisionData {
    /// The workspace of `cm` on `model`: checks `cm`, makes parry's shapes (convex hulls of
    /// meshes) and the list of candidate pairs.
    ///
    /// # Errors
    /// [`CollisionModel::check`]'s, or a convex hull parry cannot make.
    pub fn new(model: &Model, cm: &CollisionModel) -> Result<Self, CollisionError> {
        cm.check(model.njoints())?;
        let shapes = cm
            .geometries
            .iter()
            .map(|g| {
                Parry::of(&g.shape).map_err(|message| CollisionError::Shape {
                    geometry: g.name.clone(),
                    message,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let parent = |j: JointId| model.joint(j).parent;
        let mut pairs = Vec::new();
        for (i, a) in cm.geometries.iter().enumerate() {
            for (j, b) in cm.geometries.iter().enumerate().skip(i + 1) {
                let masks = (a.contype & b.conaffinity) | (b.contype & a.conaffinity) != 0;
                let meet = match (a.body, b.body) {
                    (None, None) => false,
                    (Some(_), None) | (None, Some(_)) => true,
                    (Some(x), Some(y)) => {
                        cm.self_collision && x != y && parent(x) != Some(y) && parent(y) != Some(x)
                    }
                };
                let listed = |l: &[(usize, usize)]| l.contains(&(i, j)) || l.contains(&(j, i));
                let moving = a.body.is_some() || b.body.is_some();
                if (masks && meet && !listed(&cm.excluded)) || (moving && listed(&cm.included)) {
                    pairs.push((i, j));
                }
            }
        }
        let mut bodies: Vec<(JointId, Vec<usize>)> = Vec::new();
        for (k, g) in cm.geometries.iter().enumerate() {
            let Some(body) = g.body else { continue };
            match bodies.iter_mut().find(|(b, _)| *b == body) {
                Some((_, group)) => group.push(k),
                None => bodies.push((body, vec![k])),
            }
        }
        Ok(Self {
            gathered: Vec::new(),
            held: Vec::new(),
            bodies,
            manifolds: vec![Vec::new(); pairs.len()],
            poses: vec![Transform::identity(); shapes.len()],
            shapes,
            pairs,
            near: Vec::new(),
            walks: vec![Walk::default(); cm.geometries.len()],
            sources: Vec::new(),
            njoints: model.njoints(),
        })
    }

    /// The number of candidate pairs of geometries (the ground aside).
    #[must_use]
    pub fn pairs(&self) -> usize {
        self.pairs.len()
    }

    /// The contacts at the joints' world poses `oMi` (`Data::placements`), into `out`
    /// (cleared first): every pair closer than the margin, with its gap, normal, friction and
    /// restitution.
    ///
    /// # Panics
    /// If `oMi` has fewer entries than the model has joints.
    pub fn contacts(
        &mut self,
        cm: &CollisionModel,
        oMi: &[Transform],
        out: &mut Vec<ContactPoint>,
    ) {
        assert!(oMi.len() >= self.njoints, "one placement per joint");
        out.clear();
        for (k, g) in cm.geometries.iter().enumerate() {
            self.poses[k] = match g.body {
                Some(j) => oMi[j.0] * g.placement,
                None => g.placement,
            };
        }
        let margin = cm.margin;
        if let Some(ground) = &cm.ground {
            let n = ground.normal;
            for (body, group) in &self.bodies {
                // the resting face first: `reduce` takes points beyond it only when the face
                // has fewer than four that spread
                let mut face = Some(RESTING_FACE);
                loop {
                    self.gathered.clear();
                    let mut cut = false;
                    for &k in group {
                        let s = &self.shapes[k];
                        let c = self.poses[k].act_point(&s.center);
                        if n.dot(&c) - ground.height - s.radius > margin {
                            continue;
                        }
                        cut |= s.near_plane(
                            &self.poses[k],
                            &n,
                            ground.height,
                            margin,
                            face,
                            &mut self.walks[k],
                            &mut self.near,
                        );
                        self.gathered
                            .extend(self.near.iter().map(|&(x, d)| (x, d, k)));
                    }
                    let beyond = reduce(&mut self.gathered, &n, &mut self.held);
                    if !(cut && beyond && face.is_some()) {
                        break;
                    }
                    face = None;
                }
                for &(x, d, k) in &self.gathered {
                    let g = &cm.geometries[k];
                    out.push(ContactPoint {
                        body1: Some(*body),
                        body2: None,
                        point: x - n * (0.5 * d),
                        normal: n,
                        gap: d,
                        friction: g
                            .friction
                            .map_or(ground.friction, |f| f.max(ground.friction)),
                        restitution: g
                            .restitution
                            .map_or(ground.restitution, |e| e.max(ground.restitution)),
                        geometries: (k, None),
                    });
                }
            }
        }
        // in the order of the geometries, whichever body they are on (the Gauss–Seidel sweeps
        // take the contacts in this order)
        out.sort_by_key(|c| c.geometries.0);
        self.sources.clear();
        self.sources.resize(out.len(), None);
        let dispatcher = DefaultQueryDispatcher;
        for (p, &(i, j)) in self.pairs.iter().enumerate() {
            let (si, sj) = (&self.shapes[i], &self.shapes[j]);
            let (ci, cj) = (
                self.poses[i].act_point(&si.center),
                self.poses[j].act_point(&sj.center),
            );
            if (ci - cj).norm() - si.radius - sj.radius > margin {
                self.manifolds[p].clear();
                continue;
            }
            let (pi, pj) = (self.poses[i] * si.offset, self.poses[j] * sj.offset);
            let pos12 = pose(&pi).inv_mul(&pose(&pj));
            let found = dispatcher.contact_manifolds(
                &pos12,
                &*si.shape,
                &*sj.shape,
                margin,
                &mut self.manifolds[p],
                &mut None,
            );
            if found.is_err() {
                continue;
            }
            let (a, b) = (&cm.geometries[i], &cm.geometries[j]);
            let pick = |x: Option<f64>, y: Option<f64>, default: f64| match (x, y) {
                (None, None) => default,
                (x, y) => x.unwrap_or(0.0).max(y.unwrap_or(0.0)),
            };
            let friction = pick(a.friction, b.friction, cm.friction);
            let restitution = pick(a.restitution, b.restitution, cm.restitution);
            let first = out.len();
            for (mi, m) in self.manifolds[p].iter().enumerate() {
                // the normal out of shape i, towards j: body i is pushed along its opposite
                let n1 = pi.rotation * from_parry(m.local_n1);
                for (ci, c) in m.points.iter().enumerate() {
                    if c.dist > margin {
                        continue;
                    }
                    let (x1, x2) = (
                        pi.act_point(&from_parry(c.local_p1)),
                        pj.act_point(&from_parry(c.local_p2)),
                    );
                    let point = (x1 + x2) * 0.5;
                    // two manifolds of one pair may hold the same point (a capsule's segment
                    // against a face): a duplicate makes the contact problem singular
                    if out[first..]
                        .iter()
                        .any(|o: &ContactPoint| (o.point - point).norm() < SAME_POINT)
                    {
                        continue;
                    }
                    self.sources.push(Some((p, mi, ci)));
                    out.push(ContactPoint {
                        body1: a.body,
                        body2: b.body,
                        point,
                        normal: -n1,
                        gap: c.dist,
                        friction,
                        restitution,
                        geometries: (i, Some(j)),
                    });
                }
            }
        }
    }

    /// What `other` (a workspace of the same collision model) carries from one call to the
    /// next: parry's persistent manifolds and each hull walk's start, so that a copy finds the
    /// contacts `other` would.
    pub(crate) fn copy_warm_from(&mut self, other: &Self) {
        self.manifolds.clone_from(&other.manifolds);
        self.walks.clone_from(&other.walks);
    }

    /// Keeps the contacts of the last [`contacts`](Self::contacts) (`out`) for which `keep`
    /// holds, in their order, with what [`turn`](Self::turn) reads of each.
    pub(crate) fn retain(
        &mut self,
        out: &mut Vec<ContactPoint>,
        mut keep: impl FnMut(&ContactPoint) -> bool,
    ) {
        debug_assert_eq!(out.len(), self.sources.len(), "one source per contact");
        let mut k = 0;
        for i in 0..out.len() {
            if keep(&out[i]) {
                out.swap(k, i);
                self.sources.swap(k, i);
                k += 1;
            }
        }
        out.truncate(k);
        self.sources.truncate(k);
    }

    /// Forgets what past calls carry to the next (parry's persistent manifolds, the hull
    /// walks' starts): the next call starts cold.
    pub(crate) fn forget(&mut self) {
        for m in &mut self.manifolds {
            m.clear();
        }
        for w in &mut self.walks {
            *w = Walk::default();
        }
    }

    /// How contact `k` of the last [`contacts`](Self::contacts) turns with its bodies (for
    /// the derivatives of a step; see [`Turn`]).
    pub(crate) fn turn(&self, k: usize, contact: &ContactPoint) -> Turn {
        let normal = &contact.normal;
        let Some(Some((p, mi, ci))) = self.sources.get(k).copied() else {
            // on the ground: a rim's point slides, any other is a vertex or a ball's
            let g = contact.geometries.0;
            let s = &self.shapes[g];
            let x = contact.point + normal * (0.5 * contact.gap);
            return rim(&*s.shape, &(self.poses[g] * s.offset), &x, &-normal)
                .map_or(Turn::Ground, Turn::Rim);
        };
        let (i, j) = self.pairs[p];
        let m = &self.manifolds[p][mi];
        let c = &m.points[ci];
        let (si, sj) = (&self.shapes[i], &self.shapes[j]);
        let (pi, pj) = (self.poses[i] * si.offset, self.poses[j] * sj.offset);
        turn(
            (&*si.shape, &pi, c.local_p1, m.local_n1),
            (&*sj.shape, &pj, c.local_p2, m.local_n2),
            normal,
        )
    }

    /// The radius of the balls geometry `k` meets the ground with (a sphere, a capsule's ends:
    /// its points nearest the plane are `c − ρ n`, `c` fixed in the body); 0 for the shapes
    /// that meet it at vertices.
    pub(crate) fn ball_radius(&self, k: usize) -> f64 {
        match self.shapes[k].kind {
            super::shape::PlaneTest::Balls(r, _, _) => r,
            _ => 0.0,
        }
    }
}

/// Two contact points of one pair of geometries closer than this (m) are one.
const SAME_POINT: f64 = 1e-6;

/// Points of a shape within this height (m) of its deepest one are its resting face: a mesh's
/// flat sole is uneven by a fraction of a millimetre.
pub(crate) const RESTING_FACE: f64 = 1e-3;

/// Keeps four of the points near a plane of normal `n`, as Bullet's manifold reduction
/// (the deepest, the farthest from it, the one making the largest triangle with those two, and
/// the one making the largest triangle on the other side of their line), each taken first from
/// the resting face (the points within [`RESTING_FACE`] of the deepest) and from the others
/// only when the face has no point that spreads the set: a flat sole rests on its four widest
/// points, not on its deepest one and three corners raised by its rounded edges; a box landing
/// on one corner keeps the other corners as speculative contacts. When the points touching the
/// plane (within [`TOUCHING`] of the deepest) spread (the first of them, the farthest from it
/// and a third: [`spans_triangle`]), the body rests on a face of its hull and the four are taken
/// first from those points. Then the points of the resting face under the envelope of the four
/// (at most [`MOST_POINTS`] in all): an uneven sole settles on points the widest four may miss.
/// When all four touch, no point is under their envelope by more than [`TOUCHING`] (none is
/// deeper than the deepest) and that search is skipped.
///
/// Returns whether the resting face alone did not fill the set (points beyond it were wanted).
fn reduce(pts: &mut Vec<(Vec3, f64, usize)>, n: &Vec3, held: &mut Vec<f64>) -> bool {
    if pts.len() <= 4 {
        // all kept: beyond the face only if they are fewer than four, or two coincide (within
        // 0.1 mm: overlapping geometries of one body)
        let close = (0..pts.len()).any(|i| (0..i).any(|j| (pts[i].0 - pts[j].0).norm() <= 1e-4));
        return pts.len() < 4 || close;
    }
    let mut beyond = false;
    let deepest = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let on_face = |p: &(Vec3, f64, usize)| p.1 <= deepest + RESTING_FACE;
    let area = |a: &Vec3, b: &Vec3, c: &Vec3| n.dot(&(b - a).cross(&(c - a)));
    let touching = |p: &(Vec3, f64, usize)| p.1 <= deepest + TOUCHING;
    let flat = spans_triangle(pts.iter().filter(|p| touching(p)).map(|p| &p.0), n);
    // where a point is taken from: 0 the touching face (when flat), 1 the resting face, 2 beyond
    let tier = |p: &(Vec3, f64, usize)| {
        if flat && touching(p) {
            0
        } else if on_face(p) {
            1
        } else {
            2
        }
    };
    let mut keep: Vec<(Vec3, f64, usize)> = Vec::with_capacity(4);
    let mut side = 0.0;
    while keep.len() < 4 {
        // how much a point spreads the kept set (slot 0: its depth)
        let score = |p: &(Vec3, f64, usize)| match keep.len() {
            0 => -p.1,
            1 => (p.0 - keep[0].0).norm(),
            2 => area(&keep[0].0, &keep[1].0, &p.0).abs(),
            _ => -side * area(&keep[0].0, &keep[1].0, &p.0),
        };
        // a point spreads the set if it is 0.1 mm away from it (or 1e-8 m² of triangle)
        let spreads = |s: f64| keep.is_empty() || s > if keep.len() == 1 { 1e-4 } else { 1e-8 };
        let best = |t: u8| {
            pts.iter()
                .filter(|p| tier(p) == t)
                .map(|p| (score(p), *p))
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .filter(|b| spreads(b.0))
        };
        let on = best(0).or_else(|| best(1));
        beyond |= on.is_none();
        let Some((_, p)) = on.or_else(|| best(2)) else {
            break;
        };
        if keep.len() == 2 {
            side = area(&keep[0].0, &keep[1].0, &p.0).signum();
        }
        keep.push(p);
    }
    if !(flat && keep.iter().all(touching)) {
        add_under_envelope(&mut keep, pts, n, deepest, held);
    }
    pts.clear();
    pts.extend(keep);
    beyond
}

/// The most ground points a body keeps: the four widest, and those of its resting face under
/// their envelope ([`add_under_envelope`]).
const MOST_POINTS: usize = 8;

/// A point within this of the deepest (m) touches the ground as much as the deepest does.
const TOUCHING: f64 = 1e-6;

/// Adds to `keep` the points of `pts` on the resting face (within [`RESTING_FACE`] of the
/// deepest) that lie under the kept points' envelope when two points 0.1 mm apart or more touch
/// (within [`TOUCHING`] of the deepest: the body rests on a line or a face, not on a rounded
/// point, which the four widest hold as it rolls): a point inside a triangle of kept points
/// (seen along `n`) whose gap is below the gaps of its corners interpolated there by more than
/// 1 µm would touch before them as the body settles onto them (a mesh sole uneven by a fraction
/// of a millimetre rests on its hull's lowest facet, which the four widest points may miss), and
/// a point outside them within [`TOUCHING`] of the deepest. The deepest such point first, then
/// again against the grown set, at most [`MOST_POINTS`] kept.
fn add_under_envelope(
    keep: &mut Vec<(Vec3, f64, usize)>,
    pts: &[(Vec3, f64, usize)],
    n: &Vec3,
    deepest: f64,
    held: &mut Vec<f64>,
) {
    // on one point (a ball, a rounded foot) the four widest hold the body as it rolls; on a
    // line or a face the others may have to as it settles
    let low = pts
        .iter()
        .find(|p| p.1 == deepest)
        .map_or(Vec3::zeros(), |p| p.0);
    let line = pts
        .iter()
        .any(|p| p.1 <= deepest + TOUCHING && (p.0 - low).norm() > 1e-4);
    if !line {
        return;
    }
    // held[i]: the lowest gap at point i of the kept points' triangles that contain it, kept up
    // to date as points are added (the new triangles are those with the newest point)
    held.clear();
    held.resize(pts.len(), f64::INFINITY);
    for k in 3..=keep.len() {
        lower_newest(held, pts, &keep[..k], n);
    }
    while keep.len() < MOST_POINTS {
        let mut worst: Option<(f64, usize)> = None;
        // the envelope is nowhere above the highest kept point: a point not 1 µm below it is
        // under no triangle, and wanted only if it touches
        let highest = keep.iter().map(|k| k.1).fold(f64::NEG_INFINITY, f64::max);
        for (i, p) in pts.iter().enumerate() {
            let touches = p.1 <= deepest + TOUCHING;
            if p.1 > deepest + RESTING_FACE
                || (!touches && p.1 >= highest - 1e-6)
                || keep.iter().any(|k| (k.0 - p.0).norm_squared() <= 1e-8)
            {
                continue;
            }
            // outside every kept triangle: wanted if it touches (it extends the support)
            let under = if held[i].is_finite() {
                held[i] - p.1
            } else if touches {
                deepest + RESTING_FACE - p.1
            } else {
                continue;
            };
            if under > 1e-6 && worst.is_none_or(|(w, _)| under > w) {
                worst = Some((under, i));
            }
        }
        let Some((_, i)) = worst else {
            return;
        };
        keep.push(pts[i]);
        lower_newest(held, pts, keep, n);
    }
}

/// Lowers `held` by the triangles of `keep` that have its last point as a corner: with those of
/// `keep[..k]` for each `k` up to its length, every triangle of `keep` once.
fn lower_newest(
    held: &mut [f64],
    pts: &[(Vec3, f64, usize)],
    keep: &[(Vec3, f64, usize)],
    n: &Vec3,
) {
    let Some((newest, rest)) = keep.split_last() else {
        return;
    };
    for (a, pa) in rest.iter().enumerate() {
        for pb in &rest[a + 1..] {
            lower(held, pts, [pa, pb, newest], n);
        }
    }
}

/// Lowers `held[i]` to the gap at point `i` (seen along `n`) of the triangle `t` of kept points
/// when `t` contains it, interpolated linearly from its corners' gaps. The barycentric
/// coordinates are linear in the point's offset from `p_a` (exact far from the origin): with
/// `r = x − p_a`, `w_b = r·((p_c − p_a) × n) / A`, `w_c = r·(n × (p_b − p_a)) / A` and
/// `w_a = 1 − w_b − w_c`, `A = n·((p_b − p_a) × (p_c − p_a))`.
fn lower(held: &mut [f64], pts: &[(Vec3, f64, usize)], t: [&(Vec3, f64, usize); 3], n: &Vec3) {
    let [(pa, ga, _), (pb, gb, _), (pc, gc, _)] = t;
    let (ab, ac) = (pb - pa, pc - pa);
    let area = n.dot(&ab.cross(&ac));
    if area.abs() < 1e-10 {
        return;
    }
    let (ub, uc) = (ac.cross(n) / area, n.cross(&ab) / area);
    for (low, (x, _, _)) in held.iter_mut().zip(pts) {
        let r = x - pa;
        let (wb, wc) = (r.dot(&ub), r.dot(&uc));
        let wa = 1.0 - wb - wc;
        if wa < -1e-9 || wb < -1e-9 || wc < -1e-9 {
            continue;
        }
        *low = low.min(wa * ga + wb * gb + wc * gc);
    }
}

/// Whether `points` spread over a face seen along `n`: the first of them, the farthest from it
/// (0.1 mm away or more) and some third span a parallelogram of 1e-8 m² or more (a quick test
/// from one corner, not a search of every triple).
fn spans_triangle<'a>(mut points: impl Iterator<Item = &'a Vec3> + Clone, n: &Vec3) -> bool {
    let Some(a) = points.next() else {
        return false;
    };
    let far = |p: &&Vec3| (*p - a).norm();
    let Some(b) = points.clone().max_by(|p, q| far(p).total_cmp(&far(q))) else {
        return false;
    };
    (b - a).norm() > 1e-4 && points.any(|c| n.dot(&(b - a).cross(&(c - a))).abs() > 1e-8)
}

/// The lowest gap at `x` (seen along `n`) of the triangles of kept points that contain it,
/// interpolated linearly from their corners' gaps; `None` when no triangle contains it: the
/// direct form [`lower`] keeps up to date point by point (the test's oracle).
#[cfg(test)]
fn envelope(keep: &[(Vec3, f64, usize)], x: &Vec3, n: &Vec3) -> Option<f64> {
    let k = keep.len();
    let mut lowest: Option<f64> = None;
    for a in 0..k {
        for b in a + 1..k {
            for c in b + 1..k {
                let (pa, pb, pc) = (&keep[a], &keep[b], &keep[c]);
                // barycentric coordinates in the plane normal to n
                let area = n.dot(&(pb.0 - pa.0).cross(&(pc.0 - pa.0)));
                if area.abs() < 1e-10 {
                    continue;
                }
                let wa = n.dot(&(pb.0 - x).cross(&(pc.0 - x))) / area;
                let wb = n.dot(&(pc.0 - x).cross(&(pa.0 - x))) / area;
                let wc = 1.0 - wa - wb;
                if wa < -1e-9 || wb < -1e-9 || wc < -1e-9 {
                    continue;
                }
                let g = wa * pa.1 + wb * pb.1 + wc * pc.1;
                lowest = Some(lowest.map_or(g, |l: f64| l.min(g)));
            }
        }
    }
    lowest
}

#[cfg(test)]
mod tests {
    use super::{envelope, lower_newest, Vec3};
    use crate::multibody::configuration::Rng;

    /// The envelope kept up to date triangle by triangle as points are added equals the direct
    /// minimum over every triangle of the kept points, at random points inside and outside
    /// them, on tilted planes, at the origin and 100 m from it.
    #[test]
    fn the_envelope_kept_up_to_date_is_the_direct_one() {
        let mut rng = Rng::new(3);
        let mut inside = 0;
        for k in 0..100 {
            let n = Vec3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
            let at = if k % 2 == 0 {
                Vec3::zeros()
            } else {
                Vec3::new(100.0, -70.0, 30.0)
            };
            let point = |rng: &mut Rng| {
                let x = Vec3::new(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0.0);
                (at + x, rng.uniform(0.0, 1e-3), 0)
            };
            let pts: Vec<_> = (0..40).map(|_| point(&mut rng)).collect();
            let mut keep: Vec<_> = (0..3).map(|_| point(&mut rng)).collect();
            let mut held = vec![f64::INFINITY; pts.len()];
            lower_newest(&mut held, &pts, &keep, &n);
            for _ in 3..8 {
                keep.push(point(&mut rng));
                lower_newest(&mut held, &pts, &keep, &n);
                for (h, p) in held.iter().zip(&pts) {
                    match envelope(&keep, &p.0, &n) {
                        Some(e) => {
                            assert!((h - e).abs() < 1e-13, "{h} vs {e}");
                            inside += 1;
                        }
                        None => assert!(h.is_infinite(), "{h} outside every triangle"),
                    }
                }
            }
        }
        assert!(inside > 2000, "{inside} points under a triangle");
    }
}
