//! The rows of the contact problem as functions of the configuration, for the derivatives of a
//! step ([`step_derivatives`](crate::simulation::Simulator::step_derivatives)): the dense `J`,
//! `∂(J(q) x)/∂q` at a fixed velocity `x` and `∂(J(q)ᵀ λ)/∂q` at fixed impulses, each along
//! `q ⊕ δ`.
//!
//! A contact row is `J_d x = Σ_b s_b d · (v_b + ω_b × p)` over the contact's bodies (`s = +1`
//! for body 1, `−1` for body 2), `(ω_b, v_b) = S_b x` the spatial twist of body b (world axes,
//! at the world origin), `p` the contact point and `d` one of the frame's directions `(n, t₁,
//! t₂)`. With `∂(S_b x)/∂q_k` from [`joint_kinematics_derivatives`] and `u_k = ∂p/∂q_k`:
//!
//! `∂(J_d x)/∂q_k = Σ_b s_b (d · ∂v_b/∂q_k + (p × d) · ∂ω_b/∂q_k + d · (ω_b × u_k))`.
//!
//! The generalised force of the world force `f = Σ_d λ_d d` at `p` is `Q_k = Σ_b s_b S_kᵀ F`,
//! `F = (p × f, f)`, and (Carpentier & Mansard 2018, §III: `∂S_k/∂q_j = S_j × S_k` for `j` on
//! `k`'s chain up to `k`'s own joint)
//!
//! `∂Q_k/∂q_j = Σ_b s_b (S_kᵀ (u_j × f, 0) + [j ⪯ k] (S_j × S_k)ᵀ F)`.
//!
//! How the point moves, `u_k`, and the frame turns, `θ_k` (each direction `d` of the frame
//! turns with the normal, `∂d/∂q_k = θ_k × d`, which adds `θ_k · (d × v_rel(p))` to the rows
//! and `(p × δf, δf)`, `δf = θ_k × f`, to the forces), per
//! [`Turn`](crate::collision::Turn):
//!
//! - **a body on the ground**: `p = x − (φ/2) n`, `x` the shape's point nearest the plane and
//!   `φ = n·x − height`, so `u = u_x − ½ (n·u_x) n`, `θ = 0`; `x` is a vertex fixed in the body
//!   (a box, a mesh's hull) or, for a ball of radius `ρ` (a sphere, a capsule's end),
//!   `c − ρ n` with the centre `c` fixed in the body: `u_x = S_k.v + S_k.w × a`, `a = x + ρ n`.
//!   A cylinder's or cone's rim (centre `c`, unit axis `a`, radius `R`) meets it at its point
//!   farthest along `−n`, `x = c + R d`, `d = −m/|m|`, `m = n − a (a·n)`, which slides along
//!   the rim as the body turns: `δa = θ × a`, `δm = −δa (a·n) − a (δa·n)`,
//!   `δd = −(I − m̂ m̂ᵀ) δm/|m|`, `u_x = u(c) + R δd` (a cap flat on the ground: its points as
//!   vertices).
//! - **a flat face** of one side against a vertex or a ball (centre `a`, radius `ρ`) of the
//!   other: `θ` the face body's `S_k.ω`, `δn = θ × n`; with the point on body 1 (`s = 1`; on
//!   body 2 `s = −1`) `x = a − s ρ n`, `δx = u(a) − s ρ δn` (against a rim, the rim's point
//!   farthest along `−s n`, as on the ground with the normal turning), `φ = n·(x₁ − x₂)`,
//!   `δφ = s n·(δx − u_face(x − s φ n))`, `p = x − s (φ/2) n`:
//!   `u = δx − s (½ δφ n + (φ/2) δn)`.
//! - **two features** (ball centres and vertices `Point`s, edges and capsule axes `Line`s of
//!   direction `e`, radius `ρ`; their nearest points `x₁`, `x₂`, `w = x₁ − x₂`): a `Line`
//!   slides by `δt_i` along itself so that `w` stays perpendicular to it,
//!   `δw·e_i + w·(θ_i × e_i) = 0` with `δw = u₁(x₁) − u₂(x₂) + δt₁ e₁ − δt₂ e₂`; the normal is
//!   `w/|w|` (`δn = (I − n nᵀ) δw/|w|`) or, between two lines, `e₁ × e₂/|e₁ × e₂|`
//!   (`δn = (I − n nᵀ)((θ₁ × e₁) × e₂ + e₁ × (θ₂ × e₂))/|e₁ × e₂|`); `θ = n × δn`, and
//!   `p = ½ (x₁ + x₂ + (ρ₂ − ρ₁) n)`: `u = ½ (δx₁ + δx₂ + (ρ₂ − ρ₁) δn)`.
//! - **anything else** (edges crossing inside a face's outline, a cylinder against anything but
//!   a face, a non-convex mesh's triangle): the point fixed in a moving body, the frame in the
//!   world,
//!   `θ = 0` (`StepDerivatives::held_normal` names those contacts).
//!
//! Joint limits' rows are constant.

use super::solver::ContactSolver;
use crate::collision::{Feature, Turn};
use crate::multibody::{
    joint_kinematics_derivatives, Data, JointId, Model, MultibodyError, ReferenceFrame,
};
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::DMatrix;

/// The spatial Jacobian `S` (6 x nv, its chain's columns) of a body, and `∂(S x)/∂q` for one `x`.
#[derive(Clone, Debug)]
struct Body {
    joint: JointId,
    S: DMatrix<f64>,
    dV: DMatrix<f64>,
    V: Twist,
}

fn col(m: &DMatrix<f64>, k: usize) -> Twist {
    let c = m.column(k);
    Twist::new(Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]))
}

/// A contact block's geometry: first row, frame, point, gap, how it turns, its bodies and, on
/// the ground, `rho` the ball radius of its geometry (0 for a vertex).
struct Contact {
    row: usize,
    frame: [Vec3; 3],
    p: Vec3,
    gap: f64,
    rho: f64,
    turn: Turn,
    bodies: [(Option<JointId>, f64); 2],
}

/// The contacts of a solver's rows and the bodies they touch, loaded at one `(q, x)`: what
/// [`ContactSolver::rows_dq`] and [`ContactSolver::force_dq`] read (the latter only the bodies'
/// Jacobians, which do not depend on `x`).
pub(crate) struct RowsAt {
    contacts: Vec<Contact>,
    bodies: Vec<Body>,
}

impl RowsAt {
    fn find(&self, j: Option<JointId>) -> Option<&Body> {
        j.and_then(|j| self.bodies.iter().find(|b| b.joint == j))
    }
}

impl ContactSolver {
    /// The contacts and their bodies at `(q, x)` (`radius(g)` the ball radius of geometry `g`,
    /// 0 for a vertex); `data` a scratch workspace.
    pub(crate) fn rows_at(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
        x: &[f64],
        (radius, turns): (&dyn Fn(usize) -> f64, &[Turn]),
    ) -> Result<RowsAt, MultibodyError> {
        let contacts = self.contact_geometry(radius, turns);
        let bodies = Self::bodies(&contacts, model, data, q, x)?;
        Ok(RowsAt { contacts, bodies })
    }

    /// The dense rows of `J` (m x nv) into `out`.
    pub(crate) fn dense_jacobian(&self, out: &mut DMatrix<f64>) {
        let (m, nv) = (self.m(), self.jacobian.ncols());
        *out = DMatrix::zeros(m, nv);
        for (b, block) in self.blocks.iter().enumerate() {
            for r in block.row..block.row + block.dim {
                for &(k, _, _) in &self.support[b].cols {
                    out[(r, k)] = self.jacobian[(r, k)];
                }
            }
        }
    }

    /// The contact blocks (limits and bilateral rows left out), `radius(g)` the ball radius of
    /// geometry `g` against the ground (0 for a vertex), `turns` how each of `points` turns
    /// with its bodies (empty: held).
    fn contact_geometry(&self, radius: &dyn Fn(usize) -> f64, turns: &[Turn]) -> Vec<Contact> {
        let mut out = Vec::new();
        let mut points = self.points.iter().enumerate();
        for b in self.blocks.iter().filter(|b| !b.bilateral && b.dim == 3) {
            let Some((i, c)) = points.next() else { break };
            let ground = c.geometries.1.is_none();
            let rho = if ground { radius(c.geometries.0) } else { 0.0 };
            let turn = match turns.get(i) {
                Some(t) => *t,
                None if ground => Turn::Ground,
                None => Turn::Held,
            };
            out.push(Contact {
                row: b.row,
                frame: b.frame,
                p: c.point,
                gap: c.gap,
                rho,
                turn,
                bodies: [(c.body1, 1.0), (c.body2, -1.0)],
            });
        }
        out
    }

    /// The bodies the contacts touch, loaded at `(q, x)`.
    fn bodies(
        contacts: &[Contact],
        model: &Model,
        data: &mut Data,
        q: &[f64],
        x: &[f64],
    ) -> Result<Vec<Body>, MultibodyError> {
        let mut out: Vec<Body> = Vec::new();
        let zeros = vec![0.0; model.nv];
        for c in contacts {
            for (j, _) in c.bodies {
                let Some(j) = j else { continue };
                if out.iter().any(|b| b.joint == j) {
                    continue;
                }
                let d = joint_kinematics_derivatives(
                    model,
                    data,
                    q,
                    x,
                    &zeros,
                    j,
                    ReferenceFrame::Spatial,
                )?;
                let (S, dV) = (d.velocity_dv.clone(), d.velocity_dq.clone());
                let V = data.placements[j.0].act_twist(&data.velocities[j.0]);
                out.push(Body { joint: j, S, dV, V });
            }
        }
        Ok(out)
    }

    /// How a contact moves along `q_k`: its point's `u_k = ∂p/∂q_k` and its frame's turn
    /// `θ_k` (`∂d/∂q_k = θ_k × d`), see the [module](self) documentation.
    fn motion(c: &Contact, at: &RowsAt, k: usize) -> (Vec3, Vec3) {
        let body = |side: usize| at.find(c.bodies[side].0).map(|b| col(&b.S, k));
        // the velocity of the point `x` fixed in side's body
        let carried =
            |side: usize, x: &Vec3| body(side).map_or(Vec3::zeros(), |S| S.v + S.w.cross(x));
        let n = c.frame[0];
        let phi = c.gap;
        match c.turn {
            Turn::Ground => {
                let Some(S) = body(0) else {
                    return (Vec3::zeros(), Vec3::zeros());
                };
                let rho = c.rho;
                // the nearest point x = p + (φ/2) n and its anchor x + ρ n
                let a = c.p + n * (0.5 * phi + rho);
                let ux = S.v + S.w.cross(&a);
                (ux - n * (0.5 * n.dot(&ux)), Vec3::zeros())
            }
            Turn::Rim(rim) => {
                // the rim's point farthest along −n, the ground's normal fixed
                let dx = Self::rim_rate(&rim, n, Vec3::zeros(), -1.0, &|x| carried(0, x));
                (dx - n * (0.5 * n.dot(&dx)), Vec3::zeros())
            }
            Turn::Face { face, point } => {
                let theta = body(face).map_or(Vec3::zeros(), |S| S.w);
                let dn = theta.cross(&n);
                let (sign, side) = if face == 1 { (1.0, 0) } else { (-1.0, 1) };
                // sign = +1 with the point on body 1: its nearest point x (a ball's centre
                // less sign ρ n, a rim's point farthest along −sign n), the face's point
                // x − sign φ n (φ = n·(x₁ − x₂)), p = x − sign (φ/2) n
                let (x, dx) = match point {
                    Feature::Point { a, rho } => {
                        (a - n * (sign * rho), carried(side, &a) - dn * (sign * rho))
                    }
                    Feature::Rim { .. } => (
                        c.p + n * (sign * 0.5 * phi),
                        Self::rim_rate(&point, n, dn, -sign, &|x| carried(side, x)),
                    ),
                    // not made by `turn` (a line against a face is held); as held
                    Feature::Line { .. } => (c.p, carried(side, &c.p)),
                };
                let xf = x - n * (sign * phi);
                let dphi = sign * n.dot(&(dx - carried(face, &xf)));
                (
                    dx - n * (sign * 0.5 * dphi) - dn * (sign * 0.5 * phi),
                    theta,
                )
            }
            Turn::Features(f) => Self::features_motion(&f, n, &body, &carried),
            Turn::Held => {
                // the point fixed in a moving body, the frame in the world
                let side = usize::from(c.bodies[0].0.is_none());
                (carried(side, &c.p), Vec3::zeros())
            }
        }
    }

    /// The rate of a rim's point farthest along `s n` (`s = ±1`), `x = c + R d`, `d = s m̂`,
    /// `m = n − a (a·n)`, as its body turns (`δa = ω × a`, `carried(x)` the velocity of the
    /// body's point at `x`) and the normal turns by `δn`:
    /// `δm = δn − δa (a·n) − a (δa·n + a·δn)`, `δx = u(c) + s R (I − m̂ m̂ᵀ) δm/|m|`.
    fn rim_rate(rim: &Feature, n: Vec3, dn: Vec3, s: f64, carried: &dyn Fn(&Vec3) -> Vec3) -> Vec3 {
        let Feature::Rim { c, a, radius } = *rim else {
            return Vec3::zeros();
        };
        let uc = carried(&c);
        let da = carried(&(c + a)) - uc;
        let m = n - a * a.dot(&n);
        let (mn, mh) = (m.norm(), m.normalize());
        let dm = dn - da * a.dot(&n) - a * (da.dot(&n) + a.dot(&dn));
        uc + (dm - mh * mh.dot(&dm)) * (s * radius / mn)
    }

    /// [`motion`](Self::motion) of a contact along the common perpendicular of two features
    /// (see the [module](self) documentation): their nearest points `x_i` (`Line`s slide by
    /// `δt_i` along `e_i`, keeping `w = x₁ − x₂` perpendicular to them), the normal `n` along
    /// `w` or, between two lines, along `e₁ × e₂`.
    fn features_motion(
        f: &[Feature; 2],
        n: Vec3,
        body: &dyn Fn(usize) -> Option<Twist>,
        carried: &dyn Fn(usize, &Vec3) -> Vec3,
    ) -> (Vec3, Vec3) {
        let parts = |i: usize| match f[i] {
            Feature::Point { a, rho } => (a, None, rho),
            Feature::Line { a, e, rho } => (a, Some(e), rho),
            Feature::Rim { c, .. } => (c, None, 0.0), // not paired (see `turn`)
        };
        let ((x1, e1, r1), (x2, e2, r2)) = (parts(0), parts(1));
        let (u1, u2) = (carried(0, &x1), carried(1, &x2));
        let turn = |i: usize, e: &Vec3| body(i).map_or(Vec3::zeros(), |S| S.w.cross(e));
        let w = x1 - x2;
        let delta = u1 - u2;
        // the slides: for each line, δw·e_i + w·δe_i = 0, δw = Δ + δt₁ e₁ − δt₂ e₂
        let (dt1, dt2) = match (e1, e2) {
            (Some(e1), Some(e2)) => {
                let c = e1.dot(&e2);
                let b1 = -delta.dot(&e1) - w.dot(&turn(0, &e1));
                let b2 = -delta.dot(&e2) - w.dot(&turn(1, &e2));
                // [1 −c; c −1] (δt₁, δt₂) = (b₁, b₂)
                let det = c * c - 1.0;
                ((c * b2 - b1) / det, (b2 - c * b1) / det)
            }
            (Some(e1), None) => (-delta.dot(&e1) - w.dot(&turn(0, &e1)), 0.0),
            (None, Some(e2)) => (0.0, delta.dot(&e2) + w.dot(&turn(1, &e2))),
            (None, None) => (0.0, 0.0),
        };
        let (e1v, e2v) = (e1.unwrap_or_default(), e2.unwrap_or_default());
        let dx1 = u1 + e1v * dt1;
        let dx2 = u2 + e2v * dt2;
        let project = |x: Vec3| x - n * n.dot(&x);
        let dn = match (e1, e2) {
            (Some(e1), Some(e2)) => {
                let m = e1.cross(&e2);
                let dm = turn(0, &e1).cross(&e2) + e1.cross(&turn(1, &e2));
                project(dm) * (n.dot(&m).signum() / m.norm())
            }
            _ => project(dx1 - dx2) * (n.dot(&w).signum() / w.norm()),
        };
        ((dx1 + dx2 + dn * (r2 - r1)) * 0.5, n.cross(&dn))
    }

    /// `∂(J(q) x)/∂q` (m x nv) into `out`, for the `x` of `at`.
    pub(crate) fn rows_dq(&self, at: &RowsAt, nv: usize, out: &mut DMatrix<f64>) {
        *out = DMatrix::zeros(self.m(), nv);
        let find = |j: Option<JointId>| at.find(j);
        for c in &at.contacts {
            // the bodies' relative velocity at the point
            let mut rel = Vec3::zeros();
            for (j, s) in c.bodies {
                if let Some(b) = find(j) {
                    rel += (b.V.v + b.V.w.cross(&c.p)) * s;
                }
            }
            for k in 0..nv {
                let (u, theta) = Self::motion(c, at, k);
                for (i, d) in c.frame.iter().enumerate() {
                    let pd = c.p.cross(d);
                    let mut t = theta.dot(&d.cross(&rel));
                    for (j, s) in c.bodies {
                        let Some(b) = find(j) else { continue };
                        let dV = col(&b.dV, k);
                        t += s * (d.dot(&dV.v) + pd.dot(&dV.w) + d.dot(&b.V.w.cross(&u)));
                    }
                    out[(c.row + i, k)] = t;
                }
            }
        }
    }

    /// `∂(J(q)ᵀ λ)/∂q` (nv x nv) into `out` for the impulses `lambda` (one per row).
    pub(crate) fn force_dq(
        &self,
        at: &RowsAt,
        model: &Model,
        lambda: &[f64],
        out: &mut DMatrix<f64>,
    ) {
        let nv = model.nv;
        *out = DMatrix::zeros(nv, nv);
        let find = |j: Option<JointId>| at.find(j);
        for c in &at.contacts {
            let l = &lambda[c.row..c.row + 3];
            let f = c.frame[0] * l[0] + c.frame[1] * l[1] + c.frame[2] * l[2];
            if f == Vec3::zeros() {
                continue;
            }
            let F = Wrench::new(c.p.cross(&f), f);
            let motions: Vec<(Vec3, Vec3)> = (0..nv).map(|j| Self::motion(c, at, j)).collect();
            for (jb, s) in c.bodies {
                let Some(b) = find(jb) else { continue };
                for (j, (u, theta)) in motions.iter().enumerate() {
                    // the point's move and the frame's turn (δf = θ × f)
                    let df = theta.cross(&f);
                    let dF = Wrench::new(u.cross(&f) + c.p.cross(&df), df);
                    let Sj = col(&b.S, j);
                    let on_j = Sj.w != Vec3::zeros() || Sj.v != Vec3::zeros();
                    for k in 0..nv {
                        let Sk = col(&b.S, k);
                        if Sk.w == Vec3::zeros() && Sk.v == Vec3::zeros() {
                            continue;
                        }
                        let mut t = Sk.dot(&dF);
                        if on_j && (j <= k || model.dof_joint(j) == model.dof_joint(k)) {
                            t += Sj.cross(&Sk).dot(&F);
                        }
                        out[(k, j)] += s * t;
                    }
                }
            }
        }
    }
}
