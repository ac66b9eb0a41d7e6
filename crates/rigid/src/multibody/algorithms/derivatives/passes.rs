//! The passes behind [`rnea_derivatives`](super::rnea_derivatives),
//! [`gravity_derivatives`](super::gravity_derivatives) and
//! [`aba_derivatives`](super::aba_derivatives) (the formulas are on `rnea_derivatives`), in the
//! frame {r} of each tree's root body frozen at `q`. The forward pass is split in two, velocity
//! terms then acceleration terms, so that forward dynamics can find `q̈` in between.

use super::Derivatives;
use crate::mass::SpatialInertia;
use crate::multibody::algorithms::parent_placement;
use crate::multibody::{Data, JointType, Model};
use crate::spatial::{mat3_tr_vec, Twist, Vec3, Wrench};

/// What the backward pass writes.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Output {
    /// `∂τ/∂q`, `∂τ/∂v`, `M` and `τ` (`rnea_derivatives`).
    Full,
    /// `∂τ/∂q` and `∂τ/∂v` (`aba_derivatives`, which has `τ` and needs no `M`).
    Aba,
    /// `∂g/∂q` into `dg_dq` and `g` into `data.g` (no velocity, no acceleration).
    Gravity,
}

/// The velocity terms, per joint `V_i`, the bias acceleration `A⁰_i = A⁰_λ + V_i × Σ J_k v_k`
/// (`a_g` at the root), `f⁰_i = G_i A⁰_i + V_i ×* G_i V_i - F_i^ext`, `h_i = G_i V_i` and the
/// symmetric part of `B_i`; per dof `∂V/∂q_k = V_λ × J_k` and `∂A/∂v_k = (V_i + V_λ) × J_k`.
/// Needs `data.dof_J`, `data.root_placements` and the root-frame inertias in
/// `data.root_frame_inertias` (`root_frame_bodies`). `v = None`: at rest.
pub(crate) fn forward_velocity(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: Option<&[f64]>,
    fext: Option<&[Wrench]>,
) {
    let d = &mut data.derivatives;
    let J = &data.dof_J;
    for i in 0..model.njoints() {
        let j = &model.joints()[i];
        let (Vp, Ap) = match j.parent {
            Some(p) => (d.vel[p.0], d.acc0[p.0]),
            None => {
                // the tree's frame {r}: its root body at q, where gravity is -Rᵀ g
                let oMr = parent_placement(model, i, q);
                let g = -mat3_tr_vec(&oMr.rotation, &model.gravity);
                d.gravity[i] = g;
                (Twist::zero(), Twist::new(Vec3::zeros(), g))
            }
        };
        let G = &data.root_frame_inertias[i];
        let dofs = j.idx_v..j.idx_v + j.nv;
        let Some(v) = v else {
            d.vel[i] = Twist::zero();
            d.acc0[i] = Ap;
            d.force[i] = G.momentum(&Ap);
            continue;
        };
        let mut vJ = Twist::zero();
        for k in dofs.clone() {
            vJ += J[k] * v[k];
        }
        let V = Vp + vJ;
        let A = Ap + V.cross(&vJ);
        let h = G.momentum(&V);
        let mut f = G.momentum(&A) - V.ad_transpose(&h);
        if let Some(fext) = fext {
            f -= data.root_placements[i].act_wrench(&fext[i]);
        }
        d.vel[i] = V;
        d.acc0[i] = A;
        d.force[i] = f;
        d.momentum[i] = h;
        d.sym[i] = variation_sym(G, &V);
        let W = V + Vp;
        for k in dofs {
            d.dv_dq[k] = Vp.cross(&J[k]);
            d.da_dv[k] = W.cross(&J[k]);
        }
    }
}

/// The acceleration terms: `A_i = A⁰_i + Σ_{k ⪯ i} J_k a_k`, `f_i += G_i (A_i - A⁰_i)` and
/// `∂A/∂q_k = A_λ × J_k + V_λ × ∂V/∂q_k` (`a = None`: zero acceleration). After
/// [`forward_velocity`].
pub(crate) fn forward_acceleration(model: &Model, data: &mut Data, a: Option<&[f64]>) {
    let d = &mut data.derivatives;
    let J = &data.dof_J;
    for i in 0..model.njoints() {
        let j = &model.joints()[i];
        let (Ap, Aap, Vp) = match j.parent {
            Some(p) => (d.acc[p.0], d.acc_a[p.0], d.vel[p.0]),
            None => (
                Twist::new(Vec3::zeros(), d.gravity[i]),
                Twist::zero(),
                Twist::zero(),
            ),
        };
        let dofs = j.idx_v..j.idx_v + j.nv;
        let mut Aa = Aap;
        if let Some(a) = a {
            for k in dofs.clone() {
                Aa += J[k] * a[k];
            }
            d.force[i] += data.root_frame_inertias[i].momentum(&Aa);
        }
        d.acc_a[i] = Aa;
        d.acc[i] = d.acc0[i] + Aa;
        if Vp == Twist::zero() {
            for k in dofs {
                d.da_dq[k] = Ap.cross(&J[k]);
            }
        } else {
            for k in dofs {
                d.da_dq[k] = Ap.cross(&J[k]) + Vp.cross(&d.dv_dq[k]);
            }
        }
    }
}

/// `J_kᵀ Σ_{j ⪰ i} f⁰_j` for every dof, into `d.tau_bias` (the bias forces of
/// [`forward_velocity`] carried to the joints: `c + g - Jᵀ F^ext`), leaving `d.force` alone.
pub(crate) fn bias_torques(model: &Model, data: &mut Data) {
    let d = &mut data.derivatives;
    d.bias.copy_from_slice(&d.force);
    for i in (0..model.njoints()).rev() {
        let j = &model.joints()[i];
        let F = d.bias[i];
        for k in j.idx_v..j.idx_v + j.nv {
            d.tau_bias[k] = data.dof_J[k].dot(&F);
        }
        if let Some(p) = j.parent {
            d.bias[p.0] += F;
        }
    }
}

/// The symmetric part of the angular block of `B` for a body of inertia `G = (m, c, I)` (about
/// the frame origin, `c = m·com`) moving with `V = (ω, v)`:
/// `[ω]I - I[ω] - [c][v] - [v][c] = K + Kᵀ - c vᵀ - v cᵀ + 2 (c·v) 1` with `K = [ω] I` (the
/// columns of `I` crossed with `ω`; `I[ω] = -([ω]I)ᵀ`), stored `xx yy zz xy xz yz`.
#[inline]
fn variation_sym(G: &SpatialInertia, V: &Twist) -> [f64; 6] {
    let I = G.inertia_origin_matrix();
    let (c, w, v) = (G.first_moment(), V.w, V.v);
    let k0 = w.cross(&I.column(0).into_owned());
    let k1 = w.cross(&I.column(1).into_owned());
    let k2 = w.cross(&I.column(2).into_owned());
    let cv2 = 2.0 * c.dot(&v);
    [
        2.0 * (k0.x - c.x * v.x) + cv2,
        2.0 * (k1.y - c.y * v.y) + cv2,
        2.0 * (k2.z - c.z * v.z) + cv2,
        k1.x + k0.y - c.x * v.y - v.x * c.y,
        k2.x + k0.z - c.x * v.z - v.x * c.z,
        k2.y + k1.z - c.y * v.z - v.y * c.z,
    ]
}

/// `S x` for a symmetric 3x3 stored `xx yy zz xy xz yz`.
#[inline(always)]
fn sym_mul(s: &[f64; 6], x: &Vec3) -> Vec3 {
    Vec3::new(
        s[0] * x.x + s[3] * x.y + s[4] * x.z,
        s[3] * x.x + s[1] * x.y + s[5] * x.z,
        s[4] * x.x + s[5] * x.y + s[2] * x.z,
    )
}

/// `Bc x = ((S - [L]) x_ω, -2 p × x_ω)` for the composite `S`, momentum `(L, p)` (`x_v` does not
/// enter).
#[inline(always)]
fn b_times(s: &[f64; 6], h: &Wrench, xw: &Vec3) -> Wrench {
    Wrench::new(sym_mul(s, xw) - h.m.cross(xw), -2.0 * h.f.cross(xw))
}

/// The six numbers `(m, f)`.
#[inline(always)]
fn array(w: &Wrench) -> [f64; 6] {
    [w.m.x, w.m.y, w.m.z, w.f.x, w.f.y, w.f.z]
}

/// The backward pass: the composite sums `Ic`, `Bc` (as `S`, `H`), `F`, then the rows and
/// columns of each joint's dofs. Column-major outputs: entry (row r, column c) at `c nv + r`.
pub(crate) fn backward(model: &Model, data: &mut Data, a: Option<&[f64]>, out: Output) {
    let nv = model.nv;
    // the composites start as the bodies' own root-frame inertias and are summed in place
    data.composite_inertias
        .copy_from_slice(&data.root_frame_inertias);
    let Data {
        derivatives: d,
        dof_J: J,
        composite_inertias: Ic,
        mass_matrix,
        tau,
        g,
        ..
    } = data;
    let Derivatives {
        dtau_dq,
        dtau_dv,
        dg_dq,
        force,
        momentum,
        sym,
        vel,
        gravity,
        dv_dq,
        da_dq,
        da_dv,
        yj,
        bj,
        df_dq,
        df_dv,
        dof_end,
        ..
    } = d;
    let (full, moving) = (out == Output::Full, out != Output::Gravity);
    let dq = if moving {
        dtau_dq.as_mut_slice()
    } else {
        dg_dq.as_mut_slice()
    };
    let tau = if moving {
        tau.as_mut_slice()
    } else {
        g.as_mut_slice()
    };
    let dv = dtau_dv.as_mut_slice();
    let M = mass_matrix.as_mut_slice();
    for i in (0..model.njoints()).rev() {
        let j = &model.joints()[i];
        let (Y, F) = (Ic[i], force[i]);
        let (iv, own) = (j.idx_v, j.idx_v + j.nv);
        let end = dof_end[iv];
        let (S, H) = (sym[i], momentum[i]);
        for k in iv..own {
            let Jk = J[k];
            if out != Output::Aba {
                tau[k] = Jk.dot(&F) + a.map_or(0.0, |a| model.armature[k] * a[k]);
            }
            yj[k] = Y.momentum(&Jk);
            df_dq[k] = Y.momentum(&da_dq[k]);
            if moving {
                bj[k] = sym_mul(&S, &Jk.w) + H.m.cross(&Jk.w) + 2.0 * H.f.cross(&Jk.v);
                df_dq[k] += b_times(&S, &H, &dv_dq[k].w);
                df_dv[k] = Y.momentum(&da_dv[k]) + b_times(&S, &H, &Jk.w);
            }
        }
        if j.parent.is_none() && j.kind == JointType::FreeFlyer {
            // J_k = e_k in the root's own frame: row k of the root is component k, and the
            // root's columns need one product per descendant row
            let root = Root {
                yj,
                bj,
                df_dq,
                df_dv,
                gravity: gravity[i],
                twist: vel[i],
                armature: &model.armature[iv..own],
            };
            free_flyer_root(nv, iv, end, dq, dv, M, out, &root);
            continue;
        }
        // rows of the joint's dofs, columns of its subtree (M into both triangles)
        for k in iv..own {
            let Jk = J[k];
            for c in iv..end {
                dq[c * nv + k] = Jk.dot(&df_dq[c]);
            }
            if moving {
                for c in iv..end {
                    dv[c * nv + k] = Jk.dot(&df_dv[c]);
                }
            }
            if full {
                for c in iv..end {
                    let m = Jk.dot(&yj[c]);
                    M[c * nv + k] = m;
                    M[k * nv + c] = m;
                }
                M[k * nv + k] += model.armature[k];
            }
        }
        // columns of the joint's dofs, rows of its strict subtree
        for k in iv..own {
            let col = k * nv;
            let daq = da_dq[k];
            if moving {
                let (dvq, dav, Jw) = (dv_dq[k].w, da_dv[k], J[k].w);
                for c in own..end {
                    dq[col + c] = daq.dot(&yj[c]) + bj[c].dot(&dvq);
                    dv[col + c] = dav.dot(&yj[c]) + bj[c].dot(&Jw);
                }
            } else {
                for c in own..end {
                    dq[col + c] = daq.dot(&yj[c]);
                }
            }
        }
        // J_k ×* F for the ancestors' rows (it cancels the turning of J_k in the own block)
        for k in iv..own {
            df_dq[k] -= J[k].ad_transpose(&F);
        }
        if let Some(p) = j.parent {
            Ic[p.0] += Y;
            force[p.0] += F;
            if moving {
                momentum[p.0] += H;
                for (x, y) in sym[p.0].iter_mut().zip(S) {
                    *x += y;
                }
            }
        }
    }
}

/// What the free-flyer root's rows and columns read.
struct Root<'a> {
    yj: &'a [Wrench],
    bj: &'a [Vec3],
    df_dq: &'a [Wrench],
    df_dv: &'a [Wrench],
    /// `g'` with `a_g = (0, g')`, so that `∂A/∂q_k = a_g × e_k`.
    gravity: Vec3,
    /// The root's twist `V` (`∂A/∂v_k = V × e_k`).
    twist: Twist,
    armature: &'a [f64],
}

/// The rows and columns of a free-flyer root at dofs `iv..iv + 6` of a tree whose dofs end at
/// `end`, where `J_k = e_k`, `V_λ = 0`, `A_λ = a_g = (0, g')`:
/// - rows: `∂τ_k/∂q_c = e_kᵀ ∂F/∂q_c` (component k), likewise `∂τ/∂v` and `M`;
/// - columns, for each descendant row c with `y = Ic J_c`, `b = (Bcᵀ J_c)_ω`:
///   `∂τ_c/∂q_k = yᵀ (a_g × e_k)`, the components of `y_f × g'` for k < 3 and zero after;
///   `∂τ_c/∂v_k = yᵀ (V × e_k) + bᵀ (e_k)_ω`, the components of `[ad_V]ᵀ y + (b, 0)`.
#[allow(clippy::too_many_arguments)]
fn free_flyer_root(
    nv: usize,
    iv: usize,
    end: usize,
    dq: &mut [f64],
    dv: &mut [f64],
    M: &mut [f64],
    out: Output,
    r: &Root<'_>,
) {
    let moving = out != Output::Gravity;
    for c in iv..end {
        let rows = c * nv + iv..c * nv + iv + 6;
        dq[rows.clone()].copy_from_slice(&array(&r.df_dq[c]));
        if moving {
            dv[rows.clone()].copy_from_slice(&array(&r.df_dv[c]));
        }
        if out == Output::Full {
            let y = array(&r.yj[c]);
            M[rows].copy_from_slice(&y);
            for (k, x) in y.iter().enumerate() {
                M[(iv + k) * nv + c] = *x;
            }
        }
    }
    if out == Output::Full {
        for (k, arm) in r.armature.iter().enumerate() {
            M[(iv + k) * (nv + 1)] += arm;
        }
    }
    for c in iv + 6..end {
        let y = &r.yj[c];
        let t = y.f.cross(&r.gravity);
        for k in 0..3 {
            dq[(iv + k) * nv + c] = t[k];
            dq[(iv + 3 + k) * nv + c] = 0.0;
        }
        if moving {
            let mut u = array(&r.twist.ad_transpose(y));
            let b = &r.bj[c];
            u[0] += b.x;
            u[1] += b.y;
            u[2] += b.z;
            for (k, x) in u.iter().enumerate() {
                dv[(iv + k) * nv + c] = *x;
            }
        }
    }
}
