//! Centres of mass of every subtree (position, velocity, acceleration), the Jacobian of the
//! centre of mass, and the centroidal momentum and its matrix (Orin, Goswami & Lee, "Centroidal
//! dynamics of a humanoid robot", Autonomous Robots 35, 2013; Pinocchio's `centerOfMass`,
//! `jacobianCenterOfMass`, `ccrba`, `computeCentroidalMomentum`).
//!
//! Everything here is in the world frame, angular first: a subtree's centre of mass
//! `c = Σ mᵢ cᵢ / Σ mᵢ` over the moving bodies of the subtree (`cᵢ = oMᵢ · leverᵢ`), its velocity
//! `ċ` and classical acceleration `c̈`; the centroidal momentum `h_G = (L_G, p)` (angular momentum
//! about the centre of mass, then linear momentum `p = m ċ`); `A_G` with `h_G = A_G v`.

use super::jacobian::compute_joint_jacobians;
use super::kinematics::{forward_kinematics, forward_kinematics_qv, placements_unchecked};
use crate::mass::SpatialInertia;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::DMatrix;

/// How far [`subtree_centers_of_mass`] differentiates (Pinocchio's `KinematicLevel`): positions
/// only, or also velocities (given `v`), or also accelerations (given `v` and `a`).
#[derive(Clone, Copy, Debug)]
pub enum KinematicLevel<'a> {
    /// Positions: `q` only.
    Position,
    /// Positions and velocities.
    Velocity {
        /// Joint velocities (nv).
        v: &'a [f64],
    },
    /// Positions, velocities and accelerations.
    Acceleration {
        /// Joint velocities (nv).
        v: &'a [f64],
        /// Joint accelerations (nv).
        a: &'a [f64],
    },
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Level {
    Position,
    Velocity,
    Acceleration,
}

/// The centres of mass of every subtree and of the whole model, in the world frame:
///
/// - `cᵢ = oMᵢ · leverᵢ`, `m_s(i) = Σ_{k ∈ subtree(i)} m_k`, `c_s(i) = Σ m_k c_k / m_s(i)`;
/// - at [`KinematicLevel::Velocity`]: `ċ_k = R_k (v_k + ω_k × lever_k)` from the body twist `(ω_k, v_k)`, and
///   `ċ_s(i) = Σ m_k ċ_k / m_s(i)`;
/// - at [`KinematicLevel::Acceleration`]: the classical acceleration of the point,
///   `c̈_k = R_k (v̇_k + ω̇_k × lever_k + ω_k × (v_k + ω_k × lever_k))` from the body acceleration
///   `(ω̇_k, v̇_k)` (no gravity), and `c̈_s(i) = Σ m_k c̈_k / m_s(i)`.
///
/// Fills `data.subtree_masses`, `subtree_coms`, `subtree_com_velocities`,
/// `subtree_com_accelerations` (per joint; a massless subtree gets zeros) and the whole model's
/// `data.mass`, `com`, `com_velocity`, `com_acceleration` (the sum over the roots); also the
/// placements (and twists, accelerations) of forward kinematics. Returns `data.com`. Pinocchio's
/// `centerOfMass(model, data, q[, v[, a]])`, whose subtree values for `i > 0` are these expressed in
/// joint i's frame (`oMᵢ⁻¹ c_s(i)`, `R_iᵀ ċ_s(i)`, `R_iᵀ c̈_s(i)`).
///
/// # Errors
/// Wrong lengths, non-finite entries or a non-unit quaternion.
///
/// ```
/// use rigid::multibody::{builtin, subtree_centers_of_mass, Data, KinematicLevel};
/// let model = builtin("double_pendulum").unwrap();
/// let mut data = Data::new(&model);
/// let c = subtree_centers_of_mass(&model, &mut data, &[0.3, -0.2], KinematicLevel::Position)?;
/// // the whole model's centre of mass is the mass-weighted mean of the subtrees' of the roots
/// assert!((c - data.subtree_coms[0]).norm() < 1e-15);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn subtree_centers_of_mass(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    level: KinematicLevel<'_>,
) -> Result<Vec3, MultibodyError> {
    let level = match level {
        KinematicLevel::Position => {
            check_q(model, q)?;
            check_data(model, data)?;
            placements_unchecked(model, data, q);
            Level::Position
        }
        KinematicLevel::Velocity { v } => {
            forward_kinematics_qv(model, data, q, v)?;
            Level::Velocity
        }
        KinematicLevel::Acceleration { v, a } => {
            forward_kinematics(model, data, q, v, a)?;
            Level::Acceleration
        }
    };
    let n = model.njoints();
    // first moments m c, m ċ, m c̈ of each body, world frame
    for i in 0..n {
        let G = &model.inertias()[i];
        let oMi = &data.placements[i];
        let (m, h) = (G.mass(), G.first_moment());
        data.subtree_masses[i] = m;
        data.subtree_coms[i] = oMi.rotation * h + oMi.translation * m;
        if level >= Level::Velocity {
            let V = &data.velocities[i];
            let mv = V.v * m + V.w.cross(&h); // m (v + ω × lever)
            data.subtree_com_velocities[i] = oMi.rotation * mv;
            if level >= Level::Acceleration {
                let A = &data.accelerations[i];
                let ma = A.v * m + A.w.cross(&h) + V.w.cross(&mv);
                data.subtree_com_accelerations[i] = oMi.rotation * ma;
            }
        }
    }
    let (mut mass, mut c, mut dc, mut ddc) = (0.0, Vec3::zeros(), Vec3::zeros(), Vec3::zeros());
    for i in (0..n).rev() {
        match model.joints()[i].parent {
            Some(p) => {
                let p = p.0;
                data.subtree_masses[p] += data.subtree_masses[i];
                let x = data.subtree_coms[i];
                data.subtree_coms[p] += x;
                if level >= Level::Velocity {
                    let x = data.subtree_com_velocities[i];
                    data.subtree_com_velocities[p] += x;
                }
                if level >= Level::Acceleration {
                    let x = data.subtree_com_accelerations[i];
                    data.subtree_com_accelerations[p] += x;
                }
            }
            None => {
                mass += data.subtree_masses[i];
                c += data.subtree_coms[i];
                if level >= Level::Velocity {
                    dc += data.subtree_com_velocities[i];
                }
                if level >= Level::Acceleration {
                    ddc += data.subtree_com_accelerations[i];
                }
            }
        }
        let m = data.subtree_masses[i];
        let scale = if m > 0.0 { 1.0 / m } else { 0.0 };
        data.subtree_coms[i] *= scale;
        if level >= Level::Velocity {
            data.subtree_com_velocities[i] *= scale;
        }
        if level >= Level::Acceleration {
            data.subtree_com_accelerations[i] *= scale;
        }
    }
    let scale = if mass > 0.0 { 1.0 / mass } else { 0.0 };
    data.mass = mass;
    data.com = c * scale;
    data.com_velocity = if level >= Level::Velocity {
        dc * scale
    } else {
        Vec3::zeros()
    };
    data.com_acceleration = if level >= Level::Acceleration {
        ddc * scale
    } else {
        Vec3::zeros()
    };
    Ok(data.com)
}

/// The Jacobian of the centre of mass, `ċ = J_c v` (3 x nv, world frame): with `J_k = (ω_k, v_k)`
/// the spatial (world-frame) column of dof k, `i` its joint, `m_s(i)` and `h_s(i) = m_s(i) c_s(i)`
/// the mass and first moment of the subtree it moves, and `m` the total mass,
///
/// `J_c[:, k] = (m_s(i) v_k + ω_k × h_s(i)) / m`
///
/// (the velocity `v_k + ω_k × x` of each point `x` of the subtree, mass-weighted). Returns
/// `data.com_jacobian`; also fills the subtree centres of mass of
/// [`subtree_centers_of_mass`] (positions), `data.com`, `data.mass` and the spatial Jacobian of
/// [`compute_joint_jacobians`]. Pinocchio's `jacobianCenterOfMass`. A massless model has
/// `J_c = 0`.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn jacobian_center_of_mass<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    compute_joint_jacobians(model, data, q)?;
    subtree_centers_of_mass(model, data, q, KinematicLevel::Position)?;
    let scale = if data.mass > 0.0 {
        1.0 / data.mass
    } else {
        0.0
    };
    for k in 0..model.nv() {
        let i = model.dof_joint(k).0;
        let (m, h) = (
            data.subtree_masses[i],
            data.subtree_coms[i] * data.subtree_masses[i],
        );
        let c = data.jacobian.column(k);
        let (w, v) = (Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]));
        let x = (v * m + w.cross(&h)) * scale;
        data.com_jacobian[(0, k)] = x.x;
        data.com_jacobian[(1, k)] = x.y;
        data.com_jacobian[(2, k)] = x.z;
    }
    Ok(&data.com_jacobian)
}

/// The centroidal momentum matrix `A_G` (6 x nv, angular rows first) with `h_G = A_G v`, by the
/// composite rigid-body inertias in the world frame (Orin, Goswami & Lee 2013; Pinocchio's
/// `ccrba`):
///
/// - `oG_i = [Ad_{oMᵢ⁻¹}]ᵀ G_i [Ad_{oMᵢ⁻¹}]`, `oG^c_i = Σ_{k ∈ subtree(i)} oG_k`;
/// - column k of dof k of joint i: `(L_O, p) = oG^c_i J_k` (the momentum about the world origin
///   of the subtree moving with the spatial twist `J_k`), moved to the centre of mass
///   `c`: `A_G[:, k] = (L_O - c × p, p)`.
///
/// Also sets `data.centroidal_momentum = A_G v` (`h_G = (L_G, p)`), `data.centroidal_inertia`
/// (the composite inertia of the whole model about its centre of mass, world axes: Pinocchio's
/// `Ig`), `data.com`, `data.mass`, the spatial Jacobian and the placements. Returns
/// `data.centroidal_map`.
///
/// # Errors
/// Wrong lengths, non-finite entries or a non-unit quaternion.
pub fn centroidal_momentum_matrix<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_v(model, "v", v)?;
    compute_joint_jacobians(model, data, q)?;
    let n = model.njoints();
    for i in 0..n {
        data.world_inertias[i] = model.inertias()[i].transformed(&data.placements[i]);
    }
    let mut total = SpatialInertia::zero();
    for i in (0..n).rev() {
        let Gc = data.world_inertias[i];
        match model.joints()[i].parent {
            Some(p) => data.world_inertias[p.0] += Gc,
            None => total += Gc,
        }
    }
    let c = total.com();
    for k in 0..model.nv() {
        let i = model.dof_joint(k).0;
        let col = data.jacobian.column(k);
        let Jk = Twist::new(
            Vec3::new(col[0], col[1], col[2]),
            Vec3::new(col[3], col[4], col[5]),
        );
        let P = data.world_inertias[i].momentum(&Jk);
        let L = P.m - c.cross(&P.f);
        let mut out = data.centroidal_map.column_mut(k);
        out[0] = L.x;
        out[1] = L.y;
        out[2] = L.z;
        out[3] = P.f.x;
        out[4] = P.f.y;
        out[5] = P.f.z;
    }
    let h = &data.centroidal_map * nalgebra::DVector::from_column_slice(v);
    data.centroidal_momentum =
        Wrench::new(Vec3::new(h[0], h[1], h[2]), Vec3::new(h[3], h[4], h[5]));
    data.centroidal_inertia = total.transformed(&crate::spatial::Transform::from_translation(-c));
    data.mass = total.mass();
    data.com = c;
    Ok(&data.centroidal_map)
}

/// The centroidal momentum `h_G = (L_G, p)`: the sum of the bodies' momenta `G_i V_i` moved to the
/// world frame (`[Ad_{oMᵢ⁻¹}]ᵀ`), its moment then taken about the centre of mass `c`,
/// `L_G = L_O - c × p` (Pinocchio's `computeCentroidalMomentum`, which returns it linear
/// first). Also sets `data.centroidal_momentum`, `data.com`, `data.mass` and
/// `data.com_velocity = p / m`, and the placements and twists of forward kinematics.
///
/// # Errors
/// Wrong lengths, non-finite entries or a non-unit quaternion.
pub fn centroidal_momentum(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<Wrench, MultibodyError> {
    forward_kinematics_qv(model, data, q, v)?;
    let (mut h, mut m, mut first) = (Wrench::zero(), 0.0, Vec3::zeros());
    for (i, G) in model.inertias().iter().enumerate() {
        let oMi = &data.placements[i];
        h += oMi.act_wrench(&G.momentum(&data.velocities[i]));
        m += G.mass();
        first += oMi.rotation * G.first_moment() + oMi.translation * G.mass();
    }
    let scale = if m > 0.0 { 1.0 / m } else { 0.0 };
    let c = first * scale;
    let hg = Wrench::new(h.m - c.cross(&h.f), h.f);
    data.centroidal_momentum = hg;
    data.com = c;
    data.mass = m;
    data.com_velocity = h.f * scale;
    Ok(hg)
}
