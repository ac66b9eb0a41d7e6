//! The free velocity of a lone free body in the time-stepping scheme: implicit midpoint on the
//! Newton–Euler equations in body axes, so that a passive body keeps its kinetic energy.
//!
//! A free-flyer joint at a root with no child (a box, a ball, a plate: one rigid body) has the
//! block `G` of the mass matrix to itself, and its equations in body axes are (lecture notes 1,
//! Newton–Euler in twist–wrench form)
//!
//! `G V̇ = adᵀ_V G V + F`,
//!
//! `F` the applied wrench (gravity, control, external) in body axes. Explicit Euler on the
//! gyroscopic term `adᵀ_V G V` gains energy every step (a box tumbling near its intermediate
//! axis gained 1.5 % in 20 s at 1 ms and 16 % at 10 ms). The step splits the two:
//!
//! 1. the torque-free flow by the implicit midpoint, `G (W − V)/h = adᵀ_{W_m} I W_m`,
//!    `W_m = (V + W)/2` (`I` the body's inertia, `G` with the joint's armature, if any), solved
//!    by Newton's method on the 6 unknowns: it keeps `½ Vᵀ G V` exactly
//!    (`W_mᵀ adᵀ_{W_m} I W_m = 0` and `W_mᵀ G (W − V) = ½ Wᵀ G W − ½ Vᵀ G V`);
//! 2. `W`, in the body axes after the turn `ΔR = exp(h ω_W)`, turned by `ΔR` into the axes of
//!    the step's start, where the time-stepping scheme holds every free-flyer's velocity, plus
//!    the kick `h G̃⁻¹ F` of the applied wrench (`G̃ = G + h K_d + h² K_p`, the control's
//!    implicit gains, see [`contact_step`](super::contact_step)).
//!
//! The contact impulses are then added as to every velocity, and the world-aligned update of
//! the configuration turns the velocity back to the new body axes: by exactly `ΔR` when no
//! wrench acts (`exp(h ΔR ω_W) = ΔR`), which gives back `W`. The energy is kept exactly; the
//! momentum in world axes to first order in `h` (the turn is `exp(h ω_W)`, not the midpoint's;
//! Simo & Wong 1991 give the energy–momentum variant). Gravity in the axes of the step's start keeps
//! a ball rolling down a slope at `5/7 g sin θ` (a kick in the turned axes was off by
//! `h ω / 2`, 1.6 % at 24 rad/s).

use crate::multibody::{JointType, Model};
use crate::spatial::so3;
use crate::spatial::{Mat6, Twist, Vec6, Wrench};

/// The lone free bodies of a model and the workspace of their step.
#[derive(Clone, Debug, Default)]
pub(crate) struct FreeBodies {
    /// Each one's joint index and first dof.
    joints: Vec<(usize, usize)>,
    /// Per body, `G` (the mass matrix block before the control's gains, armature included),
    /// the body's own inertia `I = G − diag(armature)` (the one of the gyroscopic term, as in
    /// RNEA) and the right-hand side `r = F` of this step.
    inertia: Vec<Mat6>,
    body: Vec<Mat6>,
    rhs: Vec<Vec6>,
}

/// Newton's iterations stop when the step is below this fraction of `‖V⁺‖ + ‖V‖ + 1`.
const TOLERANCE: f64 = 1e-14;
const MAX_ITERATIONS: usize = 30;

impl FreeBodies {
    /// The free-flyer joints of `model` at a root with no child.
    pub(crate) fn new(model: &Model) -> Self {
        let joints = model.joints();
        let found: Vec<(usize, usize)> = joints
            .iter()
            .enumerate()
            .filter(|(i, j)| {
                j.kind == JointType::FreeFlyer
                    && j.parent.is_none()
                    && !joints.iter().any(|c| c.parent.map(|p| p.0) == Some(*i))
            })
            .map(|(i, j)| (i, j.idx_v))
            .collect();
        Self {
            inertia: vec![Mat6::zeros(); found.len()],
            body: vec![Mat6::zeros(); found.len()],
            rhs: vec![Vec6::zeros(); found.len()],
            joints: found,
        }
    }

    /// Before the control's gains are added to the mass matrix `m`: `G`, `I`, and `−adᵀ_V I V`
    /// at the step's velocity `v` (RNEA's bias of a lone body, `c = −adᵀ_V I V`).
    pub(crate) fn prepare(&mut self, model: &Model, m: &nalgebra::DMatrix<f64>, v: &[f64]) {
        for (n, &(_, d)) in self.joints.iter().enumerate() {
            let g: Mat6 = m.fixed_view::<6, 6>(d, d).into();
            let mut i = g;
            for k in 0..6 {
                i[(k, k)] -= model.armature[d + k];
            }
            let vb = Twist::from_slice(&v[d..d + 6]);
            self.inertia[n] = g;
            self.body[n] = i;
            self.rhs[n] = -vb
                .ad_transpose(&Wrench::from_vector(&(i * vb.to_vector())))
                .to_vector();
        }
    }

    /// The applied wrench `r = F = a − adᵀ_V I V` from the step's `a = τ − c − g` (the gains'
    /// terms in it), which holds `F + adᵀ_V I V` for these dofs.
    pub(crate) fn forces(&mut self, a: &[f64]) {
        for (n, &(_, d)) in self.joints.iter().enumerate() {
            self.rhs[n] += Vec6::from_column_slice(&a[d..d + 6]);
        }
    }

    /// The free velocity of each lone body into `v_free` (which holds the explicit step on
    /// entry), by the implicit midpoint: `m_tilde` the mass matrix with the gains, `v` the
    /// velocity at the start of the step. The result is in the body axes of the step's start,
    /// as every free-flyer's free velocity in the time-stepping scheme.
    pub(crate) fn free_velocity(
        &self,
        m_tilde: &nalgebra::DMatrix<f64>,
        v: &[f64],
        h: f64,
        v_free: &mut [f64],
    ) {
        for (n, &(_, d)) in self.joints.iter().enumerate() {
            let f = &self.rhs[n];
            let v0 = Vec6::from_column_slice(&v[d..d + 6]);
            let x = self.midpoint(n, &v0, h);
            // W is in the body axes after the turn ΔR = exp(h ω_W); turned by ΔR into the axes
            // of the step's start (which the world-aligned configuration update turns back by
            // the same ΔR when nothing else acts: exp(h ΔR ω_W) = ΔR), with the kick of the
            // applied wrench there, h G̃⁻¹ F
            let turn = so3::exp(&(x.fixed_rows::<3>(0) * h));
            let gt: Mat6 = m_tilde.fixed_view::<6, 6>(d, d).into();
            // a principal block of M̃, which `ltl_factor` has factored: positive definite
            let kick = gt.cholesky().map_or(Vec6::zeros(), |c| c.solve(f) * h);
            let w = turn * x.fixed_rows::<3>(0) + kick.fixed_rows::<3>(0);
            let l = turn * x.fixed_rows::<3>(3) + kick.fixed_rows::<3>(3);
            v_free[d..d + 3].copy_from_slice(w.as_slice());
            v_free[d + 3..d + 6].copy_from_slice(l.as_slice());
        }
    }

    /// The torque-free flow of body `n` over `h` from `v0`: `G (W − V)/h = adᵀ_{W_m} I W_m`,
    /// `W_m = (V + W)/2`, by Newton's method from `W = V`.
    fn midpoint(&self, n: usize, v0: &Vec6, h: f64) -> Vec6 {
        let (g, i) = (&self.inertia[n], &self.body[n]);
        let mut x = *v0;
        for _ in 0..MAX_ITERATIONS {
            let vm = Twist::from_vector(&((v0 + x) * 0.5));
            let p = Wrench::from_vector(&(i * vm.to_vector()));
            let residual = g * (x - v0) - vm.ad_transpose(&p).to_vector() * h;
            // ∂/∂x of adᵀ_{W_m} I W_m = ½ (adᵀ_{W_m} I + C(I W_m)), with adᵀ_u w = C(w) u
            let jac = g - (vm.ad().transpose() * i + coad(&p)) * (0.5 * h);
            let Some(step) = jac.lu().solve(&residual) else {
                break;
            };
            x -= step;
            if step.norm() <= TOLERANCE * (x.norm() + v0.norm() + 1.0) {
                break;
            }
        }
        x
    }

    /// The first dof of each lone body.
    #[cfg(feature = "collision")]
    pub(crate) fn first_dofs(&self) -> impl Iterator<Item = usize> + '_ {
        self.joints.iter().map(|&(_, d)| d)
    }

    /// `∂(ΔR W)/∂V` of each lone body (6 x 6, written at its dofs of `out`): the derivative of
    /// its torque-free free velocity with respect to the velocity at the step's start, the
    /// implicit function theorem on the midpoint rule, `∂W/∂V = (G − ½h D)⁻¹ (G + ½h D)`,
    /// `D = adᵀ_{W_m} I + C(I W_m)`, then the turn `ΔR = exp(h ω_W)`:
    /// `∂(ΔR u) = ΔR ∂u − h ΔR [u]× J_r(h ω_W) ∂ω_W` for each half `u` of `W`.
    #[cfg(feature = "collision")]
    pub(crate) fn velocity_jacobian(&self, v: &[f64], h: f64, out: &mut nalgebra::DMatrix<f64>) {
        for (n, &(_, d)) in self.joints.iter().enumerate() {
            let (g, i) = (&self.inertia[n], &self.body[n]);
            let v0 = Vec6::from_column_slice(&v[d..d + 6]);
            let x = self.midpoint(n, &v0, h);
            let vm = Twist::from_vector(&((v0 + x) * 0.5));
            let p = Wrench::from_vector(&(i * vm.to_vector()));
            let dd = (vm.ad().transpose() * i + coad(&p)) * (0.5 * h);
            let dx = (g - dd)
                .lu()
                .solve(&(g + dd))
                .unwrap_or_else(Mat6::identity);
            let w = x.fixed_rows::<3>(0).into_owned();
            let turn = so3::exp(&(w * h));
            let jr = crate::multibody::se3_right_jacobian(&Twist::new(
                w * h,
                crate::spatial::Vec3::zeros(),
            ))
            .fixed_view::<3, 3>(0, 0)
            .into_owned();
            let mut dy = Mat6::zeros();
            for half in [0, 3] {
                let u = x.fixed_rows::<3>(half).into_owned();
                dy.fixed_view_mut::<3, 3>(half, half).copy_from(&turn);
                let rot = -(turn * u.cross_matrix() * jr) * h;
                let mut b = dy.fixed_view_mut::<3, 3>(half, 0);
                b += rot;
            }
            let phi = dy * dx;
            out.view_mut((d, d), (6, 6)).copy_from(&phi);
        }
    }
}

/// `C(F)` with `adᵀ_u F = C(F) u` for every twist `u` (angular first): `[[m̂, f̂], [f̂, 0]]`.
fn coad(p: &Wrench) -> Mat6 {
    let (m, f) = (p.m.cross_matrix(), p.f.cross_matrix());
    let mut c = Mat6::zeros();
    c.fixed_view_mut::<3, 3>(0, 0).copy_from(&m);
    c.fixed_view_mut::<3, 3>(0, 3).copy_from(&f);
    c.fixed_view_mut::<3, 3>(3, 0).copy_from(&f);
    c
}

#[cfg(test)]
mod tests {
    use super::coad;
    use crate::spatial::{Twist, Vec6, Wrench};

    /// `adᵀ_u F = C(F) u`.
    #[test]
    fn coad_is_the_transpose_action_read_the_other_way() {
        let u = Twist::from_vector(&Vec6::new(0.3, -1.2, 0.7, 2.0, 0.1, -0.4));
        let f = Wrench::from_vector(&Vec6::new(-0.5, 0.9, 1.1, 0.2, -3.0, 0.6));
        let a = u.ad_transpose(&f).to_vector();
        let b = coad(&f) * u.to_vector();
        assert!((a - b).norm() < 1e-14, "{a} {b}");
    }
}
