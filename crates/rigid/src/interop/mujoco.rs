//! MuJoCo's layout of the configuration and velocity vectors, so that `qpos`, `qvel`, `qacc`,
//! `qfrc` and the mass matrix pass between rigid and MuJoCo-based code unchanged.
//!
//! For the same joints in the same order (an MJCF file loaded by [`crate::io::mjcf`], whose joint
//! order is MuJoCo's), the layouts differ in three joint types:
//!
//! | joint | rigid `q` | MuJoCo `qpos` | rigid `v` | MuJoCo `qvel` |
//! | --- | --- | --- | --- | --- |
//! | hinge, slide | `θ` | `θ + ref` | `θ̇` | `θ̇` |
//! | ball | `(qx, qy, qz, qw)` | `(qw, qx, qy, qz)` | `ω_b` | `ω_b` |
//! | free | `(p, qx, qy, qz, qw)` | `(p, qw, qx, qy, qz)` | `(ω_b, v_b)`, `v_b = Rᵀ ṗ` | `(ṗ, ω_b)` |
//!
//! `ref` is the joint's reference configuration (MuJoCo's `qpos0`, at which the file describes
//! the bodies). The free joint's velocities are not a permutation of each other: MuJoCo's
//! linear velocity is in the world frame, so the map `v = T(q) u` from MuJoCo's `u = qvel` to
//! rigid's `v` depends on the orientation `R` of the body:
//!
//! `T = [[0, 1], [Rᵀ, 0]]` (rows `ω_b, v_b`; columns `ṗ, ω_b`), `T⁻¹ = [[0, R], [1, 0]]`.
//!
//! Everything else follows from `v = T u` (the power `τᵀ v` is the same in both, so forces map
//! by `Tᵀ`):
//!
//! - accelerations: `v̇ = T u̇ + Ṫ u`, with `Ṫ u = (0, d(Rᵀ)/dt ṗ) = (0, -[ω_b] Rᵀ ṗ) = (0, v_b × ω_b)`
//!   (as `Ṙ = R [ω_b]`): [`MujocoLayout::bias_acceleration`];
//! - generalised forces: `τ_mj = Tᵀ τ` (MuJoCo's free-joint force is the world force and the
//!   body torque), `τ = T⁻ᵀ τ_mj`;
//! - the mass matrix: `M_mj = Tᵀ M T` (congruence), Jacobians: `J_mj = J T`;
//! - the equations of motion `M v̇ + b = τ` become `Tᵀ M T u̇ + Tᵀ (M Ṫ u + b) = Tᵀ τ`, so
//!   MuJoCo's bias `qfrc_bias = Tᵀ (b + M Ṫ u)`, where `M` is without armature: MuJoCo adds its
//!   armature in its own coordinates (`M_mj = Tᵀ M T + diag(armature)`), so that rigid's armature
//!   `A` contributes `Tᵀ A T = A` (the same `a` on every dof of a free joint, as MuJoCo has, is
//!   unchanged by `T`) and nothing to the bias. Hence, with `c = Ṫ u`:
//!   `rnea_mj(q, u, u̇) = Tᵀ (rnea(q, T u, T u̇ + c) - A c)`, and `aba_mj` solves
//!   `τ = T⁻ᵀ τ_mj + A c` with rigid's ABA, then `u̇ = T⁻¹ (v̇ - c)`.
//!
//! These are checked against MuJoCo's `mj_fullM`, `qfrc_bias` and `mj_rne` on every MJCF file of
//! the description packages (`crates/rigid/tests/mjcf.rs`) and against finite differences here.
//!
//! ```
//! use rigid::interop::MujocoLayout;
//! use rigid::multibody::{JointType, ModelBuilder};
//! use rigid::mass::{RotationalInertia, SpatialInertia};
//! use rigid::spatial::{Transform, Vec3};
//! let g = SpatialInertia::from_com(2.0, Vec3::zeros(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
//! let mut b = ModelBuilder::new("brick");
//! b.add_joint(None, "free", JointType::FreeFlyer, Transform::identity(), g)?;
//! let model = b.build()?;
//! let layout = MujocoLayout::new(&model);
//! // MuJoCo's qpos: position, then the quaternion w first
//! let mut q = vec![0.0; 7];
//! layout.q_from_mujoco(&[1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0], &mut q)?;
//! assert_eq!(q, [1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0]);
//! // a free fall: MuJoCo's bias is the weight, in the world frame
//! let mut data = rigid::multibody::Data::new(&model);
//! let bias = layout.nonlinear_effects(&model, &mut data, &q, &[0.0; 6])?;
//! assert!((bias[2] - 2.0 * 9.81).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::error::DimensionError;
use crate::multibody::{self, Data, Model, MujocoCoords, MultibodyError};
use crate::spatial::{Mat3, Vec3};
use nalgebra::{DMatrix, DVector};

/// How one joint's coordinates differ from rigid's.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Coords {
    /// Hinge or slide: `qpos = q + reference`.
    Scalar(f64),
    /// Ball: the quaternion written `w` first.
    Ball,
    /// Free: the quaternion `w` first and the velocity map `T(q)`.
    Free,
    /// Any other rigid joint (planar): the same coordinates.
    Same,
}

#[derive(Clone, Copy, Debug)]
struct JointMap {
    coords: Coords,
    idx_q: usize,
    nq: usize,
    idx_v: usize,
}

/// The map between rigid's layout of a [`Model`]'s vectors and MuJoCo's (see the
/// [module](crate::interop) documentation). Made once per model.
#[derive(Clone, Debug)]
pub struct MujocoLayout {
    joints: Vec<JointMap>,
    nq: usize,
    nv: usize,
}

impl MujocoLayout {
    /// The layout of `model` with every `ref` zero (a model not read from MJCF: a URDF's joint
    /// angles are MuJoCo's when it loads the URDF).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        Self::with_reference(model, &vec![0.0; model.njoints()])
            .expect("one zero reference per joint")
    }

    /// The layout of `model` whose joint `i` has MuJoCo's `ref = reference[i]` (ignored but for
    /// revolute and prismatic joints): [`MjcfModel::layout`](crate::io::mjcf::MjcfModel::layout).
    ///
    /// # Errors
    /// A length other than the number of joints, or a non-finite reference.
    pub fn with_reference(model: &Model, reference: &[f64]) -> Result<Self, MultibodyError> {
        DimensionError::check("reference", model.njoints(), reference.len())?;
        if let Some(index) = reference.iter().position(|x| !x.is_finite()) {
            return Err(MultibodyError::NonFinite {
                what: "reference",
                index,
            });
        }
        let joints = model
            .joints()
            .iter()
            .zip(reference)
            .map(|(j, &r)| JointMap {
                coords: match j.kind.mujoco_coords() {
                    MujocoCoords::Scalar => Coords::Scalar(r),
                    MujocoCoords::Ball => Coords::Ball,
                    MujocoCoords::Free => Coords::Free,
                    MujocoCoords::Same => Coords::Same,
                },
                idx_q: j.idx_q,
                nq: j.nq,
                idx_v: j.idx_v,
            })
            .collect();
        Ok(Self {
            joints,
            nq: model.nq(),
            nv: model.nv(),
        })
    }

    /// `nq` (the same in both layouts).
    #[must_use]
    pub fn nq(&self) -> usize {
        self.nq
    }

    /// `nv` (the same in both layouts).
    #[must_use]
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// Whether every conversion is a copy (no free, ball or offset joint).
    #[must_use]
    pub fn is_identity(&self) -> bool {
        self.joints
            .iter()
            .all(|j| matches!(j.coords, Coords::Same | Coords::Scalar(0.0)))
    }

    /// Whether the velocity map `T` depends on `q` (a free joint).
    #[must_use]
    pub fn has_free_joint(&self) -> bool {
        self.joints.iter().any(|j| j.coords == Coords::Free)
    }

    /// Rigid's `q` from MuJoCo's `qpos`.
    ///
    /// # Errors
    /// A wrong length or a non-finite entry (its index).
    pub fn q_from_mujoco(&self, qpos: &[f64], q: &mut [f64]) -> Result<(), MultibodyError> {
        DimensionError::check("q", self.nq, qpos.len())?;
        if let Some(index) = qpos.iter().position(|x| !x.is_finite()) {
            return Err(MultibodyError::NonFinite { what: "q", index });
        }
        for j in &self.joints {
            let (s, d) = (
                &qpos[j.idx_q..j.idx_q + j.nq],
                &mut q[j.idx_q..j.idx_q + j.nq],
            );
            match j.coords {
                Coords::Scalar(r) => d[0] = s[0] - r,
                Coords::Ball => d.copy_from_slice(&[s[1], s[2], s[3], s[0]]),
                Coords::Free => d.copy_from_slice(&[s[0], s[1], s[2], s[4], s[5], s[6], s[3]]),
                Coords::Same => d.copy_from_slice(s),
            }
        }
        Ok(())
    }

    /// MuJoCo's `qpos` from rigid's `q`.
    ///
    /// # Panics
    /// If a slice is shorter than `nq`.
    pub fn q_to_mujoco(&self, q: &[f64], qpos: &mut [f64]) {
        for j in &self.joints {
            let (s, d) = (
                &q[j.idx_q..j.idx_q + j.nq],
                &mut qpos[j.idx_q..j.idx_q + j.nq],
            );
            match j.coords {
                Coords::Scalar(r) => d[0] = s[0] + r,
                Coords::Ball => d.copy_from_slice(&[s[3], s[0], s[1], s[2]]),
                Coords::Free => d.copy_from_slice(&[s[0], s[1], s[2], s[6], s[3], s[4], s[5]]),
                Coords::Same => d.copy_from_slice(s),
            }
        }
    }

    /// The rotation `R` (body to world) of a free joint at `q` (rigid's layout).
    fn rotation(q: &[f64], j: &JointMap) -> Mat3 {
        let x = &q[j.idx_q + 3..j.idx_q + 7];
        let n = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]).sqrt();
        crate::spatial::quat_to_rot(x[0] / n, x[1] / n, x[2] / n, x[3] / n)
    }

    /// Applies `f(R, (first, second))` to each free joint's two halves of `x`.
    fn each_free(&self, q: &[f64], x: &mut [f64], f: impl Fn(&Mat3, Vec3, Vec3) -> (Vec3, Vec3)) {
        for j in self.joints.iter().filter(|j| j.coords == Coords::Free) {
            let r = Self::rotation(q, j);
            let o = j.idx_v;
            let a = Vec3::new(x[o], x[o + 1], x[o + 2]);
            let b = Vec3::new(x[o + 3], x[o + 4], x[o + 5]);
            let (a, b) = f(&r, a, b);
            x[o..o + 3].copy_from_slice(a.as_slice());
            x[o + 3..o + 6].copy_from_slice(b.as_slice());
        }
    }

    /// Rigid's `v = T(q) u` from MuJoCo's `u` (`qvel`, or an acceleration without `Ṫ u`), in
    /// place; `q` in rigid's layout.
    pub fn v_from_mujoco(&self, q: &[f64], x: &mut [f64]) {
        self.each_free(q, x, |r, pdot, w| (w, r.transpose() * pdot));
    }

    /// MuJoCo's `u = T⁻¹ v` from rigid's `v`, in place.
    pub fn v_to_mujoco(&self, q: &[f64], x: &mut [f64]) {
        self.each_free(q, x, |r, w, vb| (r * vb, w));
    }

    /// MuJoCo's generalised force `Tᵀ τ` from rigid's `τ`, in place.
    pub fn force_to_mujoco(&self, q: &[f64], x: &mut [f64]) {
        self.each_free(q, x, |r, m, f| (r * f, m));
    }

    /// Rigid's generalised force `T⁻ᵀ τ_mj` from MuJoCo's, in place.
    pub fn force_from_mujoco(&self, q: &[f64], x: &mut [f64]) {
        self.each_free(q, x, |r, f, m| (m, r.transpose() * f));
    }

    /// `Tᵀ M T` from rigid's `nv × nv` matrix `M` (also for `M⁻¹`'s inverse map use
    /// [`matrix_inverse_to_mujoco`](Self::matrix_inverse_to_mujoco)).
    #[must_use]
    pub fn matrix_to_mujoco(&self, q: &[f64], m: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = m.clone();
        self.congruence(q, &mut out, Self::force_to_mujoco);
        out
    }

    /// `T⁻¹ M⁻¹ T⁻ᵀ`, the inverse of MuJoCo's mass matrix, from rigid's `M⁻¹`.
    #[must_use]
    pub fn matrix_inverse_to_mujoco(&self, q: &[f64], minv: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = minv.clone();
        self.congruence(q, &mut out, Self::v_to_mujoco);
        out
    }

    /// `X m Xᵀ` where `f` applies `X` to a vector in place.
    fn congruence(&self, q: &[f64], m: &mut DMatrix<f64>, f: fn(&Self, &[f64], &mut [f64])) {
        let n = m.nrows();
        let mut col = vec![0.0; n];
        for c in 0..m.ncols() {
            col.iter_mut().enumerate().for_each(|(r, x)| *x = m[(r, c)]);
            f(self, q, &mut col);
            col.iter().enumerate().for_each(|(r, x)| m[(r, c)] = *x);
        }
        let mut row = vec![0.0; m.ncols()];
        for r in 0..n {
            row.iter_mut().enumerate().for_each(|(c, x)| *x = m[(r, c)]);
            f(self, q, &mut row);
            row.iter().enumerate().for_each(|(c, x)| m[(r, c)] = *x);
        }
    }

    /// `J T`: a Jacobian's columns in MuJoCo's velocity coordinates (rows unchanged).
    #[must_use]
    pub fn jacobian_to_mujoco(&self, q: &[f64], j: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = j.clone();
        let mut row = vec![0.0; j.ncols()];
        for r in 0..j.nrows() {
            row.iter_mut().enumerate().for_each(|(c, x)| *x = j[(r, c)]);
            self.force_to_mujoco(q, &mut row);
            row.iter().enumerate().for_each(|(c, x)| out[(r, c)] = *x);
        }
        out
    }

    /// `c = Ṫ u` in rigid's coordinates, for rigid's `q` and MuJoCo's `u`: zero but on each
    /// free joint's linear rows, `v_b × ω_b` with `v_b = Rᵀ ṗ`.
    pub fn bias_acceleration(&self, q: &[f64], u: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|x| *x = 0.0);
        for j in self.joints.iter().filter(|j| j.coords == Coords::Free) {
            let r = Self::rotation(q, j);
            let o = j.idx_v;
            let vb = r.transpose() * Vec3::new(u[o], u[o + 1], u[o + 2]);
            let w = Vec3::new(u[o + 3], u[o + 4], u[o + 5]);
            out[o + 3..o + 6].copy_from_slice(vb.cross(&w).as_slice());
        }
    }

    /// Checks a MuJoCo-layout velocity-space input (length `nv`, finite).
    fn check(&self, what: &'static str, x: &[f64]) -> Result<(), MultibodyError> {
        DimensionError::check(what, self.nv, x.len())?;
        match x.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(MultibodyError::NonFinite { what, index }),
            None => Ok(()),
        }
    }

    /// MuJoCo's inverse dynamics `mj_rne` plus the armature term:
    /// `τ_mj = M_mj u̇ + qfrc_bias` at rigid's `q` and MuJoCo's `u = qvel`, `u̇ = qacc`.
    ///
    /// # Errors
    /// Bad inputs (as [`rnea`](crate::multibody::rnea)).
    pub fn rnea(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
        u: &[f64],
        udot: &[f64],
    ) -> Result<DVector<f64>, MultibodyError> {
        self.check("v", u)?;
        self.check("a", udot)?;
        let mut c = vec![0.0; self.nv];
        self.bias_acceleration(q, u, &mut c);
        let mut v = u.to_vec();
        self.v_from_mujoco(q, &mut v);
        let mut a = udot.to_vec();
        self.v_from_mujoco(q, &mut a);
        a.iter_mut().zip(&c).for_each(|(x, c)| *x += c);
        let mut tau = multibody::rnea(model, data, q, &v, &a)?.clone();
        for (k, c) in c.iter().enumerate() {
            tau[k] -= model.armature()[k] * c;
        }
        self.force_to_mujoco(q, tau.as_mut_slice());
        Ok(tau)
    }

    /// MuJoCo's `qfrc_bias = Tᵀ (b + M Ṫ u)`: Coriolis, centrifugal and gravity forces.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn nonlinear_effects(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
        u: &[f64],
    ) -> Result<DVector<f64>, MultibodyError> {
        self.rnea(model, data, q, u, &vec![0.0; self.nv])
    }

    /// The gravity forces in MuJoCo's coordinates, `Tᵀ g(q)`.
    ///
    /// # Errors
    /// As [`gravity_torques`](crate::multibody::gravity_torques).
    pub fn gravity_torques(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
    ) -> Result<DVector<f64>, MultibodyError> {
        let mut g = multibody::gravity_torques(model, data, q)?.clone();
        self.force_to_mujoco(q, g.as_mut_slice());
        Ok(g)
    }

    /// MuJoCo's mass matrix `M_mj = Tᵀ M T` (armature included: `mj_fullM`).
    ///
    /// # Errors
    /// As [`crba`](crate::multibody::crba).
    pub fn mass_matrix(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
    ) -> Result<DMatrix<f64>, MultibodyError> {
        let m = multibody::crba(model, data, q)?;
        Ok(self.matrix_to_mujoco(q, m))
    }

    /// Forward dynamics in MuJoCo's coordinates: `u̇` with `M_mj u̇ + qfrc_bias = τ_mj`.
    ///
    /// # Errors
    /// As [`aba`](crate::multibody::aba).
    pub fn aba(
        &self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
        u: &[f64],
        tau_mj: &[f64],
    ) -> Result<DVector<f64>, MultibodyError> {
        self.check("v", u)?;
        self.check("tau", tau_mj)?;
        let mut c = vec![0.0; self.nv];
        self.bias_acceleration(q, u, &mut c);
        let mut v = u.to_vec();
        self.v_from_mujoco(q, &mut v);
        let mut tau = tau_mj.to_vec();
        self.force_from_mujoco(q, &mut tau);
        for (k, c) in c.iter().enumerate() {
            tau[k] += model.armature()[k] * c;
        }
        let mut a = multibody::aba(model, data, q, &v, &tau)?.clone();
        a.iter_mut().zip(&c).for_each(|(x, c)| *x -= c);
        self.v_to_mujoco(q, a.as_mut_slice());
        Ok(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mass::{RotationalInertia, SpatialInertia};
    use crate::multibody::{random_configuration, JointType, ModelBuilder, Rng};
    use crate::spatial::Transform;

    /// A free base with an armature, a ball joint and an offset hinge.
    fn model() -> (Model, MujocoLayout) {
        let g = |m: f64, c: [f64; 3]| {
            SpatialInertia::from_com(
                m,
                Vec3::from(c),
                RotationalInertia::new(0.3, 0.2, 0.4, 0.01, 0.02, -0.03),
            )
        };
        let mut b = ModelBuilder::new("m");
        let base = b
            .add_joint(
                None,
                "free",
                JointType::FreeFlyer,
                Transform::identity(),
                g(3.0, [0.1, 0.0, -0.1]),
            )
            .unwrap();
        b.set_armature(base, &[0.05; 6]).unwrap();
        let off = Transform::from_translation(Vec3::new(0.2, 0.1, 0.0));
        let ball = b
            .add_joint(
                Some(base),
                "ball",
                JointType::Spherical,
                off,
                g(1.0, [0.0, 0.3, 0.0]),
            )
            .unwrap();
        b.add_joint(
            Some(ball),
            "hinge",
            JointType::Revolute { axis: Vec3::x() },
            off,
            g(0.5, [0.0, 0.0, 0.2]),
        )
        .unwrap();
        let model = b.build().unwrap();
        let layout = MujocoLayout::with_reference(&model, &[0.0, 0.0, 0.7]).unwrap();
        (model, layout)
    }

    fn random(n: usize, rng: &mut Rng) -> Vec<f64> {
        (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect()
    }

    #[test]
    fn configurations_and_velocities_survive_the_round_trip() {
        let (model, l) = model();
        let mut rng = Rng::new(1);
        let q = random_configuration(&model, &mut rng);
        let mut qpos = vec![0.0; model.nq()];
        l.q_to_mujoco(&q, &mut qpos);
        assert_eq!(qpos[7..11], [q[10], q[7], q[8], q[9]]);
        assert!((qpos[11] - q[11] - 0.7).abs() < 1e-15);
        let mut back = vec![0.0; model.nq()];
        l.q_from_mujoco(&qpos, &mut back).unwrap();
        assert!(back.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-15));
        let u = random(model.nv(), &mut rng);
        let mut v = u.clone();
        l.v_from_mujoco(&q, &mut v);
        l.v_to_mujoco(&q, &mut v);
        assert!(v.iter().zip(&u).all(|(a, b)| (a - b).abs() < 1e-14));
    }

    #[test]
    fn mujoco_dynamics_are_consistent_and_invert() {
        let (model, l) = model();
        let mut data = Data::new(&model);
        let mut rng = Rng::new(2);
        let q = random_configuration(&model, &mut rng);
        let (u, udot) = (random(model.nv(), &mut rng), random(model.nv(), &mut rng));
        let m = l.mass_matrix(&model, &mut data, &q).unwrap();
        let b = l.nonlinear_effects(&model, &mut data, &q, &u).unwrap();
        let tau = l.rnea(&model, &mut data, &q, &u, &udot).unwrap();
        let want = &m * DVector::from_column_slice(&udot) + &b;
        assert!(
            (&tau - &want).norm() < 1e-12 * want.norm(),
            "{tau} vs {want}"
        );
        let back = l.aba(&model, &mut data, &q, &u, tau.as_slice()).unwrap();
        assert!((back - DVector::from_column_slice(&udot)).norm() < 1e-10);
        // the armature is added in MuJoCo's coordinates: the same 0.05 on the free joint's diagonal
        let mut bare = model.clone();
        bare.set_armature(&vec![0.0; model.nv()]).unwrap();
        let m0 = l.mass_matrix(&bare, &mut data, &q).unwrap();
        for k in 0..6 {
            assert!((m[(k, k)] - m0[(k, k)] - 0.05).abs() < 1e-12);
        }
    }

    /// MuJoCo's bias is `d/dt(M u) - ∂K/∂q` in its coordinates; here checked as the momentum
    /// balance of one free body: `qfrc_bias` linear part is the weight only (no `ω × v` term),
    /// and the angular part is `ω × I ω` (with the CoM at the origin).
    #[test]
    fn free_body_bias_has_no_coriolis_force_in_world_coordinates() {
        let g = SpatialInertia::from_com(
            2.0,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 2.0, 3.0),
        );
        let mut b = ModelBuilder::new("free");
        b.add_joint(None, "f", JointType::FreeFlyer, Transform::identity(), g)
            .unwrap();
        let model = b.build().unwrap();
        let l = MujocoLayout::new(&model);
        let mut data = Data::new(&model);
        let q = random_configuration(&model, &mut Rng::new(5));
        let u = [0.3, -0.2, 0.5, 1.0, -2.0, 0.7];
        let bias = l.nonlinear_effects(&model, &mut data, &q, &u).unwrap();
        assert!((bias[0]).abs() < 1e-12 && (bias[1]).abs() < 1e-12);
        assert!((bias[2] - 2.0 * 9.81).abs() < 1e-12);
        let w = Vec3::new(1.0, -2.0, 0.7);
        let gyro = w.cross(&Vec3::new(1.0 * w.x, 2.0 * w.y, 3.0 * w.z));
        assert!((Vec3::new(bias[3], bias[4], bias[5]) - gyro).norm() < 1e-12);
    }
}
