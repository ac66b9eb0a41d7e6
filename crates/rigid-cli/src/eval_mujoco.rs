//! `rigid eval --layout mujoco`: a case read in MuJoCo's coordinates is evaluated in rigid's and
//! its results written back in MuJoCo's (`rigid::interop::MujocoLayout` documents the maps):
//! `q` from `qpos`; `v = T u`; `a = T u̇ + c`, `τ = T⁻ᵀ τ_mj + A c` with `c = Ṫ u` and `A` the
//! armature; then `rnea_mj = Tᵀ (rnea - A c)`, `M_mj = Tᵀ M T`, `qfrc_bias = Tᵀ (nle + (M - A) c)`,
//! `g_mj = Tᵀ g`, `u̇ = T⁻¹ (aba - c)`. Energies, the centre of mass and the placements do not
//! depend on the layout. Without a free joint `T = 1`, `c = 0`, and the derivatives are rigid's.

use super::CaseResult;
use rigid::interop::MujocoLayout;
use rigid::io::cases::Case;
use rigid::multibody::Model;

/// What a case's conversion leaves for the way back: `c = Ṫ u` in rigid's coordinates.
pub(super) struct Offset {
    c: Vec<f64>,
}

/// Converts a case read in MuJoCo's layout to rigid's, in place.
///
/// # Errors
/// A `qpos` of the wrong length or with a non-finite entry.
pub(super) fn case_from_mujoco(
    l: &MujocoLayout,
    model: &Model,
    c: &mut Case,
) -> Result<Offset, String> {
    let mut q = vec![0.0; model.nq()];
    l.q_from_mujoco(&c.q, &mut q)
        .map_err(|e| format!("\"q\": {e}"))?;
    c.q = q;
    let mut off = vec![0.0; model.nv()];
    l.bias_acceleration(&c.q, &c.v, &mut off);
    l.v_from_mujoco(&c.q, &mut c.v);
    l.v_from_mujoco(&c.q, &mut c.a);
    l.force_from_mujoco(&c.q, &mut c.tau);
    let arm = model.armature();
    for k in 0..model.nv() {
        c.a[k] += off[k];
        c.tau[k] += arm[k] * off[k];
    }
    Ok(Offset { c: off })
}

/// A result in MuJoCo's layout (`c` the case in rigid's layout).
pub(super) fn result_to_mujoco(
    l: &MujocoLayout,
    model: &Model,
    c: &Case,
    off: &Offset,
    r: &mut CaseResult,
) {
    let q = &c.q;
    let n = model.nv();
    let arm = model.armature();
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| r.mass_matrix[i][j]);
    for k in 0..n {
        r.rnea[k] -= arm[k] * off.c[k];
        let mc: f64 = (0..n).map(|j| m[(k, j)] * off.c[j]).sum();
        r.nonlinear_effects[k] += mc - arm[k] * off.c[k];
    }
    l.force_to_mujoco(q, &mut r.rnea);
    l.force_to_mujoco(q, &mut r.nonlinear_effects);
    l.force_to_mujoco(q, &mut r.gravity_torques);
    if let Some(a) = &mut r.aba {
        a.iter_mut().zip(&off.c).for_each(|(x, c)| *x -= c);
        l.v_to_mujoco(q, a);
    }
    if let Some(d) = &mut r.constraint_dynamics {
        d.convert_to_mujoco(l, q, &off.c);
    }
    if let Some(d) = &mut r.impulse_dynamics {
        d.convert_to_mujoco(l, q);
    }
    let mm = l.matrix_to_mujoco(q, &m);
    r.mass_matrix = (0..n)
        .map(|i| (0..n).map(|j| mm[(i, j)]).collect())
        .collect();
}
