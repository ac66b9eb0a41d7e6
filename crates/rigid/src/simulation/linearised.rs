//! The linearised problem of a step's derivatives (`step_derivatives.rs`): each row's kind from
//! the mode the solver left it in, the targets' partials, and the solve for `δλ`, with the rows
//! at a switch as per-column complementarity rows.

use super::contact::{Block, ContactSolver};
use super::step_derivatives::ContactMode;
use nalgebra::DMatrix;

/// A row's part in the linearised problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Row {
    /// `δλ = 0`.
    Free,
    /// `δσ = δσ*`, with the target's kind.
    Equal(Target),
    /// The first tangent row of a sliding contact (its normal row `n`; the second tangent
    /// follows): `û`, `μ`, `κ = μ λ_n/‖σ_t‖`.
    Slide {
        n: usize,
        u: [f64; 2],
        mu: f64,
        kappa: f64,
    },
    /// The second tangent row of a sliding contact (written with the first).
    SlideSecond,
    /// A normal row at a switch (touching without pushing): per column, `δλ ≥ 0` and
    /// `δσ ≥ δσ*`, complementary; active, it is `Equal` and its `tangents` rows stick, or
    /// slide along `slide = (û, μ)` when the contact slips (`δλ_t = −μ û δλ_n`).
    Switch {
        target: Target,
        tangents: usize,
        slide: Option<Slip>,
    },
    /// A tangent row of a `Switch` contact.
    SwitchTangent,
}

/// A slipping contact's direction `û` and friction coefficient `μ`.
pub(super) type Slip = ([f64; 2], f64);

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Target {
    Constant,
    /// `σ* = −(open · max(δφ, 0) + closed · min(δφ, 0))/h`, `δφ = J_n δq`: `1` in the velocity
    /// solve for an open gap, `β` in the position correction for a penetration; a contact
    /// touching (`φ = 0`) takes `open` and `closed` of either side.
    Gap {
        open: f64,
        closed: f64,
    },
    /// `σ* = −e J v`.
    Rebound(f64),
}

impl Target {
    /// The same share of the gap on either side.
    pub(super) fn gap(s: f64) -> Self {
        Self::Gap { open: s, closed: s }
    }
}

/// Solves the linearised rows for `δλ` (m x cols): `A δλ = B` with `A`, `B` from the rows'
/// kinds, `G = J M̃⁻¹ Jᵀ`, `JE` the rows' response to the inputs at `δλ = 0` (plus their own
/// `∂(J x)/∂q` in its first `nv` columns) and the targets' partials `T`.
///
/// The columns come in groups of `group` of one kind (`q`, `v`, `τ`); each column's residuals
/// and impulses are measured against its group's largest, so that a column that barely moves
/// the rows does not switch on round-off. The active set of a column is found in at most
/// `switches + 1` passes (redundant rows can make it cycle: the last pass is kept).
pub(super) fn solve_rows(
    rows: &[Row],
    (g, je, t): (&DMatrix<f64>, &DMatrix<f64>, &DMatrix<f64>),
    group: usize,
) -> DMatrix<f64> {
    let mut out = solve_fixed(rows, g, je, t);
    let switches: Vec<(usize, usize, Option<Slip>)> = (0..rows.len())
        .filter_map(|r| match rows[r] {
            Row::Switch {
                tangents, slide, ..
            } => Some((r, tangents, slide)),
            _ => None,
        })
        .collect();
    if switches.is_empty() || group == 0 {
        return out;
    }
    // each column its own active set among the switches: the one-sided derivative along it
    let amax = |m: &DMatrix<f64>, k: usize| {
        let g0 = k / group * group;
        m.columns(g0, group.min(m.ncols() - g0)).amax()
    };
    for k in 0..je.ncols() {
        let scale = amax(je, k).max(amax(t, k));
        let lscale = amax(&out, k);
        if scale == 0.0 {
            continue;
        }
        let mut active = vec![false; rows.len()];
        for _ in 0..=switches.len() {
            let x = out.column(k);
            let mut changed = false;
            for &(r, _, _) in &switches {
                let gap = (g.row(r) * x)[0] + je[(r, k)] - t[(r, k)];
                if !active[r] && gap < -1e-9 * scale {
                    active[r] = true;
                    changed = true;
                } else if active[r] && x[r] < -1e-9 * lscale {
                    active[r] = false;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
            let mut rk = rows.to_vec();
            for &(r, tangents, slide) in &switches {
                let on = if active[r] {
                    Row::Equal(Target::Constant)
                } else {
                    Row::Free
                };
                for row in &mut rk[r..=r + tangents] {
                    *row = on;
                }
                if let (true, 2, Some((u, mu))) = (active[r], tangents, slide) {
                    // slipping as it touches: the friction on the cone's edge, κ = 0 (λ_n = 0)
                    rk[r + 1] = Row::Slide {
                        n: r,
                        u,
                        mu,
                        kappa: 0.0,
                    };
                    rk[r + 2] = Row::SlideSecond;
                }
            }
            let x = solve_fixed(
                &rk,
                g,
                &je.columns(k, 1).into_owned(),
                &t.columns(k, 1).into_owned(),
            );
            out.set_column(k, &x.column(0));
        }
    }
    out
}

/// [`solve_rows`] with the switches held free.
pub(super) fn solve_fixed(
    rows: &[Row],
    g: &DMatrix<f64>,
    je: &DMatrix<f64>,
    t: &DMatrix<f64>,
) -> DMatrix<f64> {
    let (m, cols) = (rows.len(), je.ncols());
    // the unknowns: the rows not held at δλ = 0
    let live: Vec<usize> = (0..m)
        .filter(|&r| !matches!(rows[r], Row::Free | Row::Switch { .. } | Row::SwitchTangent))
        .collect();
    let at = |r: usize| live.binary_search(&r).ok();
    let na = live.len();
    let mut a = DMatrix::zeros(na, na);
    let mut b = DMatrix::zeros(na, cols);
    let copy_g = |a: &mut DMatrix<f64>, i: usize, r: usize, s: f64| {
        for (j, &c) in live.iter().enumerate() {
            a[(i, j)] += s * g[(r, c)];
        }
    };
    for (i, &r) in live.iter().enumerate() {
        match rows[r] {
            Row::Free | Row::SlideSecond | Row::Switch { .. } | Row::SwitchTangent => {}
            Row::Equal(_) => {
                copy_g(&mut a, i, r, 1.0);
                let x = t.row(r) - je.row(r);
                b.row_mut(i).copy_from(&x);
            }
            Row::Slide { n, u, mu, kappa } => {
                // (I − ûûᵀ) applied to the two tangent rows
                let p = [
                    [1.0 - u[0] * u[0], -u[0] * u[1]],
                    [-u[1] * u[0], 1.0 - u[1] * u[1]],
                ];
                let ni = at(n).expect("a sliding contact's normal row pushes");
                for k in 0..2 {
                    let ik = i + k;
                    a[(ik, ik)] += 1.0;
                    a[(ik, ni)] += mu * u[k];
                    for j in 0..2 {
                        let s = kappa * p[k][j];
                        copy_g(&mut a, ik, r + j, s);
                        let jr = je.row(r + j) * (-s);
                        let mut br = b.row_mut(ik);
                        br += jr;
                    }
                }
            }
        }
    }
    let mut out = DMatrix::zeros(m, cols);
    if na == 0 {
        return out;
    }
    let scale = a.amax().max(1e-300);
    if let Ok(x) = a.svd(true, true).solve(&b, 1e-12 * scale) {
        for (i, &r) in live.iter().enumerate() {
            out.row_mut(r).copy_from(&x.row(i));
        }
    }
    out
}

/// The target of a row that holds one.
pub(super) fn target_of(row: &Row) -> Option<Target> {
    match *row {
        Row::Equal(t) | Row::Switch { target: t, .. } => Some(t),
        _ => None,
    }
}

/// Row `r` of the targets' `q` columns for `σ* = −(open · max(δφ, 0) + closed · min(δφ, 0))/h`
/// with `δφ = J_n δq` along each column (`∂φ/∂q = J_n`): per column, the side of the switch
/// that the perturbation moves to.
pub(super) fn gap_target(
    t: &mut DMatrix<f64>,
    r: usize,
    jm: &DMatrix<f64>,
    h: f64,
    open: f64,
    closed: f64,
) {
    for k in 0..jm.ncols() {
        let dphi = jm[(r, k)];
        t[(r, k)] = -(if dphi > 0.0 { open } else { closed }) * dphi / h;
    }
}

/// Whether a gap (m, or rad for a limit) is zero within round-off: a contact or limit
/// touching, at the switch between closing its gap in the velocity solve (`φ > 0`) and being
/// corrected (`φ < 0`).
pub(super) fn at_zero(gap: f64) -> bool {
    gap.abs() <= 1e-12
}

/// Each row's kind from the solution `lambda` of the velocity solve, with the modes of the
/// contacts and limits and those at a switch.
pub(super) fn classify(
    solver: &ContactSolver,
    lambda: &[f64],
    modes: &mut Vec<ContactMode>,
    at_switch: &mut Vec<usize>,
) -> Vec<Row> {
    let m = lambda.len();
    let mut rows = vec![Row::Free; m];
    // the bilateral rows hold J v⁺ = 0 (an idle row, which moves nothing, keeps λ = 0)
    for r in (0..solver.bilateral_rows).filter(|&r| !solver.bilateral_idle[r]) {
        rows[r] = Row::Equal(Target::Constant);
    }
    let sigma = &solver.sigma[..m];
    let target = &solver.target[..m];
    // contacts first (the order of `contacts()`), then limits
    let (contacts, limits): (Vec<&Block>, Vec<&Block>) = solver
        .blocks
        .iter()
        .filter(|b| !b.bilateral)
        .partition(|b| b.dim == 3);
    let scale = lambda
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
        .max(1e-300);
    let vscale = sigma.iter().fold(1e-3_f64, |a, x| a.max(x.abs()));
    for b in contacts.into_iter().chain(limits) {
        let r = b.row;
        let index = modes.len();
        let normal = if b.rebound_target {
            Target::Rebound(b.restitution)
        } else if at_zero(b.gap) {
            // touching: an opening perturbation is closed in this step, a penetration is
            // left to the correction
            Target::Gap {
                open: 1.0,
                closed: 0.0,
            }
        } else if b.gap_target {
            Target::gap(1.0)
        } else {
            Target::Constant
        };
        if lambda[r] <= 1e-12 * scale {
            modes.push(ContactMode::Separated);
            // touching without pushing: the normal velocity meets its target, and a
            // perturbation that presses the contact makes it push (sticking)
            if (sigma[r] - target[r]).abs() <= 1e-9 * vscale {
                at_switch.push(index);
                // it sticks as it touches, or slips along its tangential velocity
                let friction = b.dim == 3 && b.friction > 0.0;
                let (st, sn) = if friction {
                    let st = [sigma[r + 1], sigma[r + 2]];
                    (st, st[0].hypot(st[1]))
                } else {
                    ([0.0; 2], 0.0)
                };
                rows[r] = Row::Switch {
                    target: normal,
                    tangents: if friction { 2 } else { 0 },
                    slide: (sn > 1e-9 * vscale).then(|| ([st[0] / sn, st[1] / sn], b.friction)),
                };
                for row in &mut rows[r + 1..r + b.dim] {
                    *row = Row::SwitchTangent;
                }
            }
            continue;
        }
        rows[r] = Row::Equal(normal);
        // pushing at φ = 0: each side has its own target (see `Target::Gap`)
        let touching = at_zero(b.gap);
        if touching {
            at_switch.push(index);
        }
        if b.dim == 1 || b.friction == 0.0 {
            modes.push(ContactMode::Sticking);
            continue;
        }
        let (lt, st) = ((lambda[r + 1], lambda[r + 2]), (sigma[r + 1], sigma[r + 2]));
        let (ln, sn) = (lt.0.hypot(lt.1), st.0.hypot(st.1));
        let edge = ln >= b.friction * lambda[r] * (1.0 - 1e-7);
        if edge && sn > 1e-9 * vscale {
            modes.push(ContactMode::Sliding);
            rows[r + 1] = Row::Slide {
                n: r,
                u: [st.0 / sn, st.1 / sn],
                mu: b.friction,
                kappa: b.friction * lambda[r] / sn,
            };
            rows[r + 2] = Row::SlideSecond;
        } else {
            modes.push(ContactMode::Sticking);
            rows[r + 1] = Row::Equal(Target::Constant);
            rows[r + 2] = Row::Equal(Target::Constant);
            if edge && !touching {
                at_switch.push(index);
            }
        }
    }
    rows
}
