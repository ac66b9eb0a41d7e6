//! The workspace of the algorithms: every buffer, allocated once by [`Data::new`].

use super::Model;
use crate::mass::SpatialInertia;
use crate::spatial::{Mat6, Transform, Twist, Vec3, Wrench};
use nalgebra::{DMatrix, DVector};

/// Buffers and results of the multibody algorithms for one [`Model`] (Pinocchio's `Data`).
/// Per-body quantities are indexed by joint and expressed in the body's own (moved joint) frame
/// unless said otherwise. Which algorithm fills which field is stated on the field.
#[derive(Clone, Debug)]
pub struct Data {
    /// `liMi`: pose of body i's frame in its parent's frame (world for a root), `X_T X_J(q)`.
    /// Filled by every algorithm that takes `q`.
    pub parent_placements: Vec<Transform>,
    /// `oMi`: world pose of each joint frame as moved by the joint. Forward kinematics,
    /// Jacobians, energies, CoM (not CRBA and `M⁻¹`, which work in the root body's frame).
    pub placements: Vec<Transform>,
    /// `oMf`: world pose of each named frame ([`update_frame_placements`](super::update_frame_placements)).
    pub frame_placements: Vec<Transform>,
    /// Body twist `V_i` of each body in its own frame. Forward kinematics, RNEA, ABA.
    pub velocities: Vec<Twist>,
    /// Body acceleration `A_i` (spatial acceleration `V̇_i`, no gravity) in its own frame.
    /// Forward kinematics (second order).
    pub accelerations: Vec<Twist>,
    /// `A_i - a_g`: acceleration with gravity as a fictitious base acceleration (RNEA, ABA).
    pub accelerations_gravity: Vec<Twist>,
    /// Wrench `F_i` transmitted from the parent to body i through joint i, in body i's frame
    /// (RNEA).
    pub forces: Vec<Wrench>,
    /// Composite rigid-body inertia of each subtree, in the frame of its tree's root body (CRBA,
    /// and the RNEA derivatives, which compute them on the way).
    pub composite_inertias: Vec<SpatialInertia>,
    /// Generalised forces `τ` (RNEA).
    pub tau: DVector<f64>,
    /// Nonlinear effects `c(q, v) + g(q) = rnea(q, v, 0)`.
    pub nle: DVector<f64>,
    /// Generalised gravity `g(q) = rnea(q, 0, 0)`.
    pub g: DVector<f64>,
    /// Joint accelerations `q̈` (ABA, Cholesky forward dynamics).
    pub ddq: DVector<f64>,
    /// Joint-space mass matrix `M(q)`, full symmetric, armature on the diagonal (CRBA).
    pub mass_matrix: DMatrix<f64>,
    /// Inverse joint-space mass matrix `M(q)⁻¹`, full symmetric, armature included: the inverse
    /// of [`mass_matrix`](Self::mass_matrix) ([`compute_minverse`](super::compute_minverse)).
    pub minv: DMatrix<f64>,
    /// Coriolis matrix `C(q, v)`, `c = C v`, `Ṁ - 2C` skew ([`coriolis_matrix`](super::coriolis_matrix)).
    pub coriolis: DMatrix<f64>,
    /// Spatial (world-frame) Jacobian of all joints, column k = `[Ad_{oMi}] S_k` (6 x nv).
    pub jacobian: DMatrix<f64>,
    /// Its time derivative, column k = `V^s_i × J_k` (6 x nv).
    pub jacobian_dot: DMatrix<f64>,
    /// Output buffer of the frame and joint Jacobians (6 x nv).
    pub frame_jacobian: DMatrix<f64>,
    /// Output buffer of the frame and joint Jacobian derivatives (6 x nv).
    pub frame_jacobian_dot: DMatrix<f64>,
    /// Centre of mass of the moving bodies in the world (CoM).
    pub com: Vec3,
    /// Mass of the moving bodies.
    pub mass: f64,
    /// Mass of each subtree: the moving bodies of joint i's subtree
    /// ([`subtree_centers_of_mass`](super::subtree_centers_of_mass), [`jacobian_center_of_mass`](super::jacobian_center_of_mass)).
    pub subtree_masses: Vec<f64>,
    /// Centre of mass of each subtree, world frame (zero for a massless subtree).
    pub subtree_coms: Vec<Vec3>,
    /// Velocity of each subtree's centre of mass, world frame
    /// ([`subtree_centers_of_mass`](super::subtree_centers_of_mass) with `v`).
    pub subtree_com_velocities: Vec<Vec3>,
    /// Classical acceleration of each subtree's centre of mass, world frame (with `v` and `a`).
    pub subtree_com_accelerations: Vec<Vec3>,
    /// Velocity `ċ` of the centre of mass of the moving bodies, world frame.
    pub com_velocity: Vec3,
    /// Classical acceleration `c̈` of the centre of mass, world frame.
    pub com_acceleration: Vec3,
    /// Jacobian of the centre of mass, `ċ = J_c v` (3 x nv, world frame;
    /// [`jacobian_center_of_mass`](super::jacobian_center_of_mass)).
    pub com_jacobian: DMatrix<f64>,
    /// Centroidal momentum matrix `A_G` (6 x nv, angular rows first;
    /// [`centroidal_momentum_matrix`](super::centroidal_momentum_matrix)).
    pub centroidal_map: DMatrix<f64>,
    /// Centroidal momentum `h_G = (L_G, p)`: angular momentum about the centre of mass and linear
    /// momentum, world axes ([`centroidal_momentum`](super::centroidal_momentum),
    /// [`centroidal_momentum_matrix`](super::centroidal_momentum_matrix)).
    pub centroidal_momentum: Wrench,
    /// Composite inertia of the moving bodies about their centre of mass, world axes (Pinocchio's
    /// `Ig`; [`centroidal_momentum_matrix`](super::centroidal_momentum_matrix)).
    pub centroidal_inertia: SpatialInertia,
    /// Outputs and buffers of the analytical derivatives ([`rnea_derivatives`](super::rnea_derivatives),
    /// [`aba_derivatives`](super::aba_derivatives), the kinematics derivatives).
    pub derivatives: super::Derivatives,
    // --- internal workspaces ---
    /// The motion-subspace columns `S_k(q)` (child frames) at the `q` of the last algorithm:
    /// constant columns set once here, the others rewritten by each algorithm
    /// (`update_subspaces`).
    pub(crate) S: Vec<Twist>,
    /// Articulated inertias (`M⁻¹`, in each tree's root-body frame).
    pub(crate) ia: Vec<Mat6>,
    pub(crate) c_bias: Vec<Twist>,
    /// ABA: `D⁻¹` of each one-dof joint, per dof.
    pub(crate) d_inv_1: Vec<f64>,
    /// ABA's workspace: the batch kernel's pack of one state (`batch::aba_one`).
    pub(crate) one: super::batch::Pack<1>,
    pub(crate) crba_forces: Vec<Wrench>,
    /// Placements `rMi` in the frame of each tree's root body (CRBA, `M⁻¹`).
    pub(crate) root_placements: Vec<Transform>,
    pub(crate) dof_J: Vec<Twist>,
    /// `[sin q_k, cos q_k]` for the entries `k` of `q` listed in `Model::chain_angles`, written
    /// by the first pass of CRBA, `M⁻¹` and the RNEA derivatives (the other entries are unused).
    pub(crate) sin_cos: Vec<[f64; 2]>,
    /// The joints of the model this was made for (`Plan::joints_key`), checked by every call.
    pub(crate) joints_key: u64,
    pub(crate) spatial_velocities: Vec<Twist>,
    /// Composite inertias in the world frame (the Coriolis matrix).
    pub(crate) world_inertias: Vec<SpatialInertia>,
    /// Each body's own inertia `rG_i` in the frame of its tree's root body (the first pass of
    /// `M⁻¹` and of the analytical derivatives).
    pub(crate) root_frame_inertias: Vec<SpatialInertia>,
    pub(crate) world_b: Vec<Mat6>,
    pub(crate) chol: DMatrix<f64>,
    /// `compute_minverse`: `U_i D_i⁻¹` per dof (world), the bias forces `P` for every unit
    /// torque per dof, a depth stack of the accelerations `A` for every unit torque (`n` rows of
    /// `nv` columns, row = depth of the joint), and the depth of each joint. It also uses `ia`
    /// (world articulated inertias) and `dof_J` (world joint columns).
    pub(crate) minv_ud: Vec<Wrench>,
    pub(crate) minv_p: Vec<Wrench>,
    pub(crate) minv_a: Vec<Twist>,
    pub(crate) minv_depth: Vec<usize>,
    /// Parent dof `λ(k)` of each dof (`usize::MAX` at the root), for the sparse `Lᵀ L`.
    pub(crate) dof_parent: Vec<usize>,
}

impl Data {
    /// All buffers for `model`.
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let n = model.njoints();
        let nv = model.nv();
        let nf = model.frames().len();
        Self {
            parent_placements: vec![Transform::identity(); n],
            placements: vec![Transform::identity(); n],
            frame_placements: vec![Transform::identity(); nf],
            velocities: vec![Twist::zero(); n],
            accelerations: vec![Twist::zero(); n],
            accelerations_gravity: vec![Twist::zero(); n],
            forces: vec![Wrench::zero(); n],
            composite_inertias: vec![SpatialInertia::zero(); n],
            tau: DVector::zeros(nv),
            nle: DVector::zeros(nv),
            g: DVector::zeros(nv),
            ddq: DVector::zeros(nv),
            mass_matrix: DMatrix::zeros(nv, nv),
            minv: DMatrix::zeros(nv, nv),
            coriolis: DMatrix::zeros(nv, nv),
            jacobian: DMatrix::zeros(6, nv),
            jacobian_dot: DMatrix::zeros(6, nv),
            frame_jacobian: DMatrix::zeros(6, nv),
            frame_jacobian_dot: DMatrix::zeros(6, nv),
            com: Vec3::zeros(),
            mass: model.total_mass(),
            subtree_masses: vec![0.0; n],
            subtree_coms: vec![Vec3::zeros(); n],
            subtree_com_velocities: vec![Vec3::zeros(); n],
            subtree_com_accelerations: vec![Vec3::zeros(); n],
            com_velocity: Vec3::zeros(),
            com_acceleration: Vec3::zeros(),
            com_jacobian: DMatrix::zeros(3, nv),
            centroidal_map: DMatrix::zeros(6, nv),
            centroidal_momentum: Wrench::zero(),
            centroidal_inertia: SpatialInertia::zero(),
            derivatives: super::Derivatives::new(model),
            S: (0..nv).map(|k| model.motion_subspace(k)).collect(),
            ia: vec![Mat6::zeros(); n],
            c_bias: vec![Twist::zero(); n],
            d_inv_1: vec![0.0; nv],
            one: super::batch::Pack::new(model),
            crba_forces: vec![Wrench::zero(); nv],
            root_placements: vec![Transform::identity(); n],
            dof_J: vec![Twist::zero(); nv],
            sin_cos: vec![[0.0; 2]; model.nq()],
            joints_key: model.plan().joints_key,
            spatial_velocities: vec![Twist::zero(); n],
            world_inertias: vec![SpatialInertia::zero(); n],
            root_frame_inertias: vec![SpatialInertia::zero(); n],
            world_b: vec![Mat6::zeros(); n],
            chol: DMatrix::zeros(nv, nv),
            minv_ud: vec![Wrench::zero(); nv],
            minv_p: vec![Wrench::zero(); nv],
            minv_a: vec![Twist::zero(); n * nv],
            minv_depth: vec![0; n],
            dof_parent: vec![usize::MAX; nv],
        }
    }
}
