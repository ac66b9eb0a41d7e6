//! The contact problem of one step: rows of `J`, the Delassus operator through the constraint
//! machinery's kernels, its islands, the solve (projected Gauss–Seidel in [`pgs`](super::pgs),
//! or ADMM), the energy safeguard and the position correction (see the [module](super)
//! documentation for the equations).
//!
//! Bilateral rows (closed loops, welds, MJCF equalities: a [`ConstraintData`]'s rows) come first
//! and are one block of the Gauss–Seidel sweep, solved whole at each sweep by the proximal step
//! `λ_B ← λ_B − (K_BB + ρ I)⁻¹ (σ_B − σ*_B)` (`ρ = 10⁻¹⁰ max diag K_BB`, so redundant rows such
//! as a planar loop's out-of-plane row need no care), with the target `σ*_B = 0`: `J_B v⁺ = 0`,
//! a hard constraint. Their position error is removed by the position correction with the
//! contacts' penetration (`σ*_B = −β e/h`).

use super::admm::Admm;
use super::pgs::{factor_bilateral, pgs, Islands};
use super::polish::Polish;
use super::residuals::ContactResiduals;
use super::{ContactSettings, ContactStats, Solver};
#[cfg(feature = "collision")]
use crate::collision::ContactPoint;
use crate::multibody::constraints::solver::{delassus_rows, primal_rows};
use crate::multibody::constraints::workspace::Support;
use crate::multibody::constraints::ConstraintData;
use crate::multibody::{Data, JointId, Model};
use crate::spatial::Vec3;
use nalgebra::DMatrix;

/// One row block of the problem: a contact (3 rows: normal, two tangents), a joint limit
/// (1 row) or a bilateral constraint (1, 3 or 6 rows).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Block {
    /// First row.
    pub(crate) row: usize,
    /// 3 (contact), 1 (limit), or the constraint's rows (bilateral).
    pub(crate) dim: usize,
    /// A bilateral constraint (its rows in the leading bilateral group).
    pub(crate) bilateral: bool,
    /// `μ` (0 for a limit).
    pub(crate) friction: f64,
    /// `e`.
    pub(crate) restitution: f64,
    /// `φ` (m or rad).
    pub(crate) gap: f64,
    /// The contact frame `(n, t1, t2)` in the world (a limit: unused).
    pub(crate) frame: [Vec3; 3],
    /// The impulse of the same contact at the last step (the warm start).
    pub(crate) warm: [f64; 6],
    /// The approach speed of an impact whose gap closed in the last step (0: none).
    pub(crate) impact: f64,
    /// The kinetic energy the rebound of that impact may give back (J): `e²` times what the
    /// contact took when its gap closed.
    pub(crate) credit: f64,
    /// The approach speed if the gap closes in this step (0: it does not).
    pub(crate) closing: f64,
    /// The normal target of this step's velocity solve: `−φ/h` (true), or a constant or a
    /// rebound (false).
    pub(crate) gap_target: bool,
    /// The normal target is the rebound `e |σ_n⁻|` of a contact found touching and approaching.
    pub(crate) rebound_target: bool,
}

/// What a contact of one step leaves to the next: the same pair of geometries (or the same
/// joint limit) near the same point is the same contact.
#[derive(Clone, Copy, Debug)]
struct Memory {
    key: (usize, usize),
    point: Vec3,
    lambda: [f64; 6],
    /// The speed at which its gap closed in that step (0: it did not).
    impact: f64,
    /// `e²` times the kinetic energy the contact took in that step if its gap closed (J).
    credit: f64,
}

/// Two contacts of successive steps with the same key are the same within this distance (m).
const SAME_CONTACT: f64 = 0.02;

/// The workspace of the contact problem, reused from step to step. It allocates only when a
/// step has more contact rows than any before it.
#[derive(Clone, Debug)]
pub(crate) struct ContactSolver {
    nv: usize,
    /// Per joint: the dofs of its chain to the root, ascending.
    chains: Vec<Vec<usize>>,
    pub(crate) blocks: Vec<Block>,
    /// The contact points given, in block order (limits excluded).
    #[cfg(feature = "collision")]
    pub(crate) points: Vec<ContactPoint>,
    /// The impulse (N·s, world axes) of each of `points` on its body 1, as last solved.
    pub(crate) impulses: Vec<Vec3>,
    /// First row of each block, and the total at the end.
    pub(crate) rows: Vec<usize>,
    /// Per block, its support (a pool: only the first `blocks.len()` are in use).
    pub(crate) support: Vec<Support>,
    /// Rows of `J` (capacity x nv); only each block's support columns are written.
    pub(crate) jacobian: DMatrix<f64>,
    z: Vec<f64>,
    delassus: Vec<f64>,
    sigma_free: Vec<f64>,
    sigma_before: Vec<f64>,
    pub(crate) target: Vec<f64>,
    pub(crate) lambda: Vec<f64>,
    pub(crate) sigma: Vec<f64>,
    /// The position correction's impulses and contact velocities (`lambda` keeps the velocity
    /// solve's).
    pub(crate) mu: Vec<f64>,
    pub(crate) sigma_mu: Vec<f64>,
    pub(crate) target_mu: Vec<f64>,
    x: Vec<f64>,
    /// The rows of the bilateral group (the leading rows), and the Cholesky factor of
    /// `K_BB + ρ I` (`None` until a step has bilateral rows).
    pub(crate) bilateral_rows: usize,
    bilateral_factor: DMatrix<f64>,
    /// The bilateral rows' errors `e` at this step's `q`, and their largest `‖e‖∞`.
    bilateral_e: Vec<f64>,
    bilateral_error: f64,
    /// Scratch of the bilateral group's step (length: its rows).
    bilateral_step: Vec<f64>,
    /// The bilateral rows that move nothing (`K_rr` ≤ 1e-9 of the largest: a planar loop's
    /// out-of-plane row); their impulse stays 0.
    pub(crate) bilateral_idle: Vec<bool>,
    /// Per block, the row ranges of the blocks it shares a dof with (its own included): the
    /// nonzero columns of its rows of `K`; `coupled[first[b]..first[b + 1]]`.
    coupled: Vec<(usize, usize)>,
    coupled_first: Vec<usize>,
    /// Per dof, the blocks whose support holds it (scratch of `couple`), and marks.
    dof_blocks: Vec<Vec<usize>>,
    marks: Vec<usize>,
    near: Vec<usize>,
    /// The step's islands (blocks coupled through `K`), each solved on its own.
    islands: Islands,
    /// The contacts of the last step, and of this one (for the next).
    memory: Vec<Memory>,
    next_memory: Vec<Memory>,
    keys: Vec<((usize, usize), Vec3)>,
    /// The second solver's workspace.
    admm: Admm,
    /// The sweep's active-set polish.
    polish: Polish,
    /// What the last solve did.
    pub(crate) stats: ContactStats,
}

impl ContactSolver {
    /// The workspace of `model`.
    pub(crate) fn new(model: &Model) -> Self {
        let nv = model.nv();
        let chains = (0..model.njoints())
            .map(|j| {
                let mut dofs = Vec::new();
                let mut at = Some(JointId(j));
                while let Some(i) = at {
                    let joint = model.joint(i);
                    dofs.extend(joint.dofs());
                    at = joint.parent;
                }
                dofs.sort_unstable();
                dofs
            })
            .collect();
        let mut s = Self {
            nv,
            chains,
            blocks: Vec::new(),
            #[cfg(feature = "collision")]
            points: Vec::new(),
            impulses: Vec::new(),
            rows: vec![0],
            support: Vec::new(),
            jacobian: DMatrix::zeros(0, nv),
            z: Vec::new(),
            delassus: Vec::new(),
            sigma_free: Vec::new(),
            sigma_before: Vec::new(),
            target: Vec::new(),
            lambda: Vec::new(),
            sigma: Vec::new(),
            mu: Vec::new(),
            sigma_mu: Vec::new(),
            target_mu: Vec::new(),
            x: vec![0.0; nv],
            bilateral_rows: 0,
            bilateral_factor: DMatrix::zeros(0, 0),
            bilateral_e: Vec::new(),
            bilateral_error: 0.0,
            bilateral_step: Vec::new(),
            bilateral_idle: Vec::new(),
            coupled: Vec::new(),
            coupled_first: Vec::new(),
            dof_blocks: vec![Vec::new(); nv],
            marks: Vec::new(),
            near: Vec::new(),
            islands: Islands::default(),
            memory: Vec::new(),
            next_memory: Vec::new(),
            keys: Vec::new(),
            admm: Admm::default(),
            polish: Polish::default(),
            stats: ContactStats::default(),
        };
        s.reserve(24);
        s
    }

    /// Room for `m` rows.
    fn reserve(&mut self, m: usize) {
        let cap = self.jacobian.nrows();
        if m <= cap {
            return;
        }
        let cap = m.max(2 * cap);
        let nv = self.nv;
        let mut jacobian = DMatrix::zeros(cap, nv);
        let used = self.rows[self.blocks.len()];
        jacobian
            .rows_mut(0, used)
            .copy_from(&self.jacobian.rows(0, used));
        self.jacobian = jacobian;
        self.z.resize(nv * cap, 0.0);
        self.delassus.resize(cap * cap, 0.0);
        for v in [
            &mut self.sigma_free,
            &mut self.sigma_before,
            &mut self.target,
            &mut self.lambda,
            &mut self.sigma,
            &mut self.mu,
            &mut self.sigma_mu,
            &mut self.target_mu,
        ] {
            v.resize(cap, 0.0);
        }
    }

    /// The memory of `other`'s last step (warm starts, impacts), for a solve of the same step
    /// from a copy.
    #[cfg(feature = "collision")]
    pub(crate) fn copy_memory(&mut self, other: &Self) {
        self.next_memory.clone_from(&other.next_memory);
    }

    /// Forgets the contacts of past steps (warm starts, impacts): the next step starts cold.
    pub(crate) fn forget(&mut self) {
        self.memory.clear();
        self.next_memory.clear();
    }

    /// Forgets the blocks of the last step (remembering their impulses and impacts for the
    /// warm start of this one).
    pub(crate) fn clear(&mut self) {
        std::mem::swap(&mut self.memory, &mut self.next_memory);
        self.next_memory.clear();
        self.keys.clear();
        self.blocks.clear();
        #[cfg(feature = "collision")]
        self.points.clear();
        self.impulses.clear();
        self.rows.truncate(1);
        self.bilateral_rows = 0;
        self.bilateral_e.clear();
        self.bilateral_error = 0.0;
        self.stats = ContactStats::default();
    }

    /// The rows so far.
    pub(crate) fn m(&self) -> usize {
        self.rows[self.blocks.len()]
    }

    /// A new block of `dim` rows, `key` and `point` naming it from step to step; returns its
    /// first row (its support cleared).
    fn push_block(&mut self, block: Block, key: (usize, usize), point: Vec3) -> usize {
        let found = self
            .memory
            .iter()
            .filter(|m| m.key == key && (m.point - point).norm() < SAME_CONTACT)
            .min_by(|a, b| {
                (a.point - point)
                    .norm()
                    .total_cmp(&(b.point - point).norm())
            });
        let (warm, impact, credit) =
            found.map_or(([0.0; 6], 0.0, 0.0), |m| (m.lambda, m.impact, m.credit));
        let block = Block {
            warm,
            impact,
            credit,
            closing: 0.0,
            ..block
        };
        self.keys.push((key, point));
        let row = self.m();
        self.reserve(row + block.dim);
        let n = self.blocks.len();
        if self.support.len() == n {
            self.support.push(Support {
                cols: Vec::with_capacity(self.nv),
            });
        }
        self.support[n].cols.clear();
        self.blocks.push(Block { row, ..block });
        self.rows.push(row + block.dim);
        row
    }

    /// Adds a contact; its rows of `J` from the spatial Jacobian `data.jacobian` (world axes,
    /// angular rows first, at the world origin: the velocity of a point `p` of the body of dof k
    /// is `v_k + ω_k × p`).
    #[cfg(feature = "collision")]
    pub(crate) fn push_contact(&mut self, data: &Data, c: &ContactPoint) {
        let n = c.normal;
        let t1 = tangent(&n);
        let t2 = n.cross(&t1);
        let frame = [n, t1, t2];
        let block = Block {
            row: 0,
            dim: 3,
            bilateral: false,
            friction: c.friction,
            restitution: c.restitution,
            gap: c.gap,
            frame,
            warm: [0.0; 6],
            impact: 0.0,
            credit: 0.0,
            closing: 0.0,
            gap_target: false,
            rebound_target: false,
        };
        let key = (c.geometries.0, c.geometries.1.unwrap_or(usize::MAX));
        let row = self.push_block(block, key, c.point);
        let b = self.blocks.len() - 1;
        let cols = &mut self.support[b].cols;
        merge_chains(
            c.body1.map(|j| self.chains[j.0].as_slice()),
            c.body2.map(|j| self.chains[j.0].as_slice()),
            cols,
        );
        let p = c.point;
        let pd = [p.cross(&n), p.cross(&t1), p.cross(&t2)];
        for &(k, on1, on2) in cols.iter() {
            let s = f64::from(i8::from(on1) - i8::from(on2));
            let col = data.jacobian.column(k);
            let w = Vec3::new(col[0], col[1], col[2]);
            let v = Vec3::new(col[3], col[4], col[5]);
            for (i, d) in frame.iter().enumerate() {
                self.jacobian[(row + i, k)] = s * (d.dot(&v) + pd[i].dot(&w));
            }
        }
        self.points.push(*c);
    }

    /// The normal speed of contact `c` at the generalized velocity `x`: `n · (v₁ − v₂)` of its
    /// point on its two bodies (negative: closing), from the spatial Jacobian `data.jacobian` as
    /// in [`push_contact`](Self::push_contact).
    #[cfg(feature = "collision")]
    pub(crate) fn normal_speed(&self, data: &Data, c: &ContactPoint, x: &[f64]) -> f64 {
        let (n, pn) = (c.normal, c.point.cross(&c.normal));
        let speed = |body: Option<JointId>| {
            body.map_or(0.0, |j| {
                self.chains[j.0]
                    .iter()
                    .map(|&k| {
                        let col = data.jacobian.column(k);
                        let w = Vec3::new(col[0], col[1], col[2]);
                        let v = Vec3::new(col[3], col[4], col[5]);
                        (n.dot(&v) + pn.dot(&w)) * x[k]
                    })
                    .sum::<f64>()
            })
        };
        speed(c.body1) - speed(c.body2)
    }

    /// Adds the limit of the 1-dof joint `joint` (its dof `dof`): `sign = +1` for a lower limit
    /// (`q − lower ≥ 0`), `−1` for an upper one, at the distance `gap` from it.
    pub(crate) fn push_limit(&mut self, joint: JointId, dof: usize, sign: f64, gap: f64) {
        let block = Block {
            row: 0,
            dim: 1,
            bilateral: false,
            friction: 0.0,
            restitution: 0.0,
            gap,
            frame: [Vec3::zeros(); 3],
            warm: [0.0; 6],
            impact: 0.0,
            credit: 0.0,
            closing: 0.0,
            gap_target: false,
            rebound_target: false,
        };
        let key = (usize::MAX - 1, 2 * dof + usize::from(sign > 0.0));
        let row = self.push_block(block, key, Vec3::zeros());
        let b = self.blocks.len() - 1;
        let cols = &mut self.support[b].cols;
        merge_chains(Some(self.chains[joint.0].as_slice()), None, cols);
        for &(k, _, _) in cols.iter() {
            self.jacobian[(row, k)] = if k == dof { sign } else { 0.0 };
        }
    }

    /// Adds every constraint of `cd` as a bilateral block, from its rows of `J` and its error
    /// (`constraint_rows` at this step's `q`); an error within `tolerance` (the projection's)
    /// asks no position correction. Called first in a step, before any contact or limit: the
    /// bilateral rows lead.
    pub(crate) fn push_bilateral(&mut self, cd: &ConstraintData, tolerance: f64) {
        debug_assert!(self.blocks.iter().all(|b| b.bilateral));
        for i in 0..cd.constraints.len() {
            let rows = cd.rows_of(i);
            let block = Block {
                row: 0,
                dim: rows.len(),
                bilateral: true,
                friction: 0.0,
                restitution: 0.0,
                gap: 0.0,
                frame: [Vec3::zeros(); 3],
                warm: [0.0; 6],
                impact: 0.0,
                credit: 0.0,
                closing: 0.0,
                gap_target: false,
                rebound_target: false,
            };
            let row = self.push_block(block, (usize::MAX - 2, i), Vec3::zeros());
            let b = self.blocks.len() - 1;
            self.support[b].cols.clear();
            self.support[b].cols.extend_from_slice(&cd.support[i].cols);
            for (r, src) in rows.enumerate() {
                for &(k, _, _) in &cd.support[i].cols {
                    self.jacobian[(row + r, k)] = cd.jacobian[(src, k)];
                }
                self.bilateral_e.push(cd.error[src]);
                if cd.error[src].abs() > tolerance {
                    self.bilateral_error = self.bilateral_error.max(cd.error[src].abs());
                }
            }
            self.bilateral_rows = row + self.blocks[b].dim;
        }
        let mb = self.bilateral_rows;
        if self.bilateral_factor.nrows() < mb {
            self.bilateral_factor = DMatrix::zeros(mb, mb);
            self.bilateral_step.resize(mb, 0.0);
            self.bilateral_idle.resize(mb, false);
        }
    }

    /// Whether there is nothing to solve.
    pub(crate) fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }

    /// `J x` over the supports into `out`.
    fn times(&self, x: &[f64], out: &mut [f64]) {
        for (b, block) in self.blocks.iter().enumerate() {
            for r in block.row..block.row + block.dim {
                out[r] = self.support[b]
                    .cols
                    .iter()
                    .map(|&(k, _, _)| self.jacobian[(r, k)] * x[k])
                    .sum();
            }
        }
    }

    /// The row ranges each block's rows of `K` may be nonzero on (`coupled`): the blocks whose
    /// supports share a dof with it (two contacts on bodies of different trees never couple).
    fn couple(&mut self) {
        let n = self.blocks.len();
        for list in &mut self.dof_blocks {
            list.clear();
        }
        for (b, s) in self.support[..n].iter().enumerate() {
            for &(k, _, _) in &s.cols {
                self.dof_blocks[k].push(b);
            }
        }
        self.marks.clear();
        self.marks.resize(n, usize::MAX);
        self.coupled.clear();
        self.coupled_first.clear();
        let mut near = std::mem::take(&mut self.near);
        for b in 0..n {
            self.coupled_first.push(self.coupled.len());
            near.clear();
            for &(k, _, _) in &self.support[b].cols {
                for &c in &self.dof_blocks[k] {
                    if self.marks[c] != b {
                        self.marks[c] = b;
                        near.push(c);
                    }
                }
            }
            near.sort_unstable();
            let start = self.coupled.len();
            for &c in &near {
                let (lo, hi) = (self.rows[c], self.rows[c + 1]);
                match self.coupled[start..].last_mut() {
                    Some(last) if last.1 == lo => last.1 = hi,
                    _ => self.coupled.push((lo, hi)),
                }
            }
        }
        self.coupled_first.push(self.coupled.len());
        self.near = near;
    }

    /// Solves the step's contact problem: `v` the velocity at the start of the step, `v_free`
    /// the free velocity, overwritten with `v⁺`; `data` holds the factor `M = LᵀL`
    /// (`ltl_factor`). Fills [`stats`](Self::stats).
    pub(crate) fn solve(
        &mut self,
        data: &Data,
        v: &[f64],
        v_free: &mut [f64],
        h: f64,
        settings: &ContactSettings,
    ) {
        let nblocks = self.blocks.len();
        let m = self.m();
        self.stats.candidates = self.blocks.iter().filter(|b| !b.bilateral).count();
        if nblocks == 0 {
            return;
        }
        self.couple();
        // only the coupled pairs of rows where they are fewer than half of all (free bodies
        // apart, several robots); on one robot's tree every pair is
        let pairs: usize = (0..nblocks)
            .map(|b| {
                let ranges = &self.coupled[self.coupled_first[b]..self.coupled_first[b + 1]];
                self.blocks[b].dim * ranges.iter().map(|(lo, hi)| hi - lo).sum::<usize>()
            })
            .sum();
        let coupled = (2 * pairs < m * m).then_some((&self.coupled[..], &self.coupled_first[..]));
        delassus_rows(
            data,
            &self.rows,
            &self.support[..nblocks],
            &self.jacobian,
            coupled,
            &mut self.z,
            &mut self.delassus,
        );
        self.islands
            .find(&self.blocks, (&self.coupled, &self.coupled_first));
        let mut sigma_free = std::mem::take(&mut self.sigma_free);
        let mut sigma_before = std::mem::take(&mut self.sigma_before);
        self.times(v_free, &mut sigma_free);
        self.times(v, &mut sigma_before);
        self.sigma_free = sigma_free;
        self.sigma_before = sigma_before;
        // the normal targets σ*_n (the tangent rows aim at 0): a gap φ > 0 may close in this
        // step and no more (a contact that closes lands at φ = 0, and its approach speed is
        // remembered); touching, an impact of the last step (or a contact found approaching)
        // rebounds at e times its speed
        let mut penetration: f64 = 0.0;
        let mut credit = 0.0;
        for b in &mut self.blocks {
            let r = b.row;
            if b.bilateral {
                self.target[r..r + b.dim].fill(0.0);
                continue;
            }
            penetration = penetration.max(-b.gap);
            let rebound = |speed: f64| {
                if speed > settings.restitution_speed {
                    b.restitution * speed
                } else {
                    0.0
                }
            };
            b.gap_target = true;
            b.rebound_target = false;
            let target = if b.impact > 0.0 {
                // the gap closed in the last step: the impact happens now
                credit += b.credit;
                let r = rebound(b.impact);
                b.gap_target = -b.gap / h >= r;
                r.max(-b.gap / h)
            } else if b.gap > 0.0 {
                let (s0, s1) = (self.sigma_before[r], self.sigma_free[r]);
                if b.gap + h * s1 < 0.0 && b.restitution > 0.0 {
                    // the speed when the gap closes, the approach accelerating uniformly from
                    // σ_n⁻ to σ_{f,n} over the step: v² = σ_n⁻² − 2 a φ, a = (σ_{f,n} − σ_n⁻)/h
                    let v2 = s0 * s0 - 2.0 * (s1 - s0) / h * b.gap;
                    b.closing = v2.max(0.0).sqrt().clamp(s0.abs().min(-s1), -s1);
                }
                -b.gap / h
            } else {
                let r = rebound(-self.sigma_before[r]);
                b.gap_target = false;
                b.rebound_target = r > 0.0;
                r
            };
            self.target[r] = target;
            for i in 1..b.dim {
                self.target[r + i] = 0.0;
            }
        }
        self.stats.penetration = penetration;
        let K = &self.delassus[..m * m];
        let (lambda, sigma) = (&mut self.lambda[..m], &mut self.sigma[..m]);
        let mb = self.bilateral_rows;
        let idle = &mut self.bilateral_idle[..mb];
        if mb > 0 {
            factor_bilateral(K, m, &mut self.bilateral_factor, idle);
        }
        // warm start: the impulses of the same contacts at the last step, σ = σ_f + K λ
        for b in &self.blocks {
            lambda[b.row..b.row + b.dim].copy_from_slice(&b.warm[..b.dim]);
        }
        for (l, _) in lambda.iter_mut().zip(idle.iter()).filter(|(_, i)| **i) {
            *l = 0.0;
        }
        sigma.copy_from_slice(&self.sigma_free[..m]);
        for s in 0..m {
            if lambda[s] != 0.0 {
                let col = &K[s * m..(s + 1) * m];
                for (x, k) in sigma.iter_mut().zip(col) {
                    *x += k * lambda[s];
                }
            }
        }
        let (iterations, converged) = match settings.solver {
            Solver::Pgs => pgs(
                &self.blocks,
                &self.islands,
                (&self.coupled, &self.coupled_first),
                K,
                (&self.bilateral_factor, &mut self.bilateral_step[..mb], idle),
                &self.target[..m],
                lambda,
                sigma,
                (settings, &mut self.polish),
                true,
            ),
            Solver::Admm => self.admm.solve(
                &self.blocks,
                &self.islands,
                K,
                idle,
                &self.target[..m],
                lambda,
                sigma,
                settings,
                true,
            ),
        };
        // ΔK = λᵀ σ_f + ½ λᵀ G λ, with G λ = σ − σ_f; at most the credit of the rebounds
        let (mut lsf, mut lgl) = (0.0, 0.0);
        for r in 0..m {
            lsf += lambda[r] * self.sigma_free[r];
            lgl += lambda[r] * (sigma[r] - self.sigma_free[r]);
        }
        let mut dk = lsf + 0.5 * lgl;
        let scale = lsf.abs().max(lgl.abs());
        let mut scaled = false;
        if dk > credit + 1e-12 * scale {
            // the largest α ∈ [0, 1] with α λᵀσ_f + ½ α² λᵀGλ ≤ credit
            let alpha = if lgl > 0.0 {
                ((-lsf + (lsf * lsf + 2.0 * lgl * credit).sqrt()) / lgl).clamp(0.0, 1.0)
            } else {
                0.0
            };
            for r in 0..m {
                lambda[r] *= alpha;
                sigma[r] = self.sigma_free[r] + alpha * (sigma[r] - self.sigma_free[r]);
            }
            dk = alpha * lsf + 0.5 * alpha * alpha * lgl;
            scaled = true;
        }
        for (i, b) in self.blocks.iter().enumerate() {
            let mut l = [0.0; 6];
            l[..b.dim].copy_from_slice(&lambda[b.row..b.row + b.dim]);
            // the block's share of ΔK: ½ λ_bᵀ (σ_f + σ)_b
            let share: f64 = (b.row..b.row + b.dim)
                .map(|r| 0.5 * lambda[r] * (self.sigma_free[r] + sigma[r]))
                .sum();
            let (key, point) = self.keys[i];
            self.next_memory.push(Memory {
                key,
                point,
                lambda: l,
                impact: b.closing,
                credit: if b.closing > 0.0 {
                    b.restitution * b.restitution * (-share).max(0.0)
                } else {
                    0.0
                },
            });
        }
        // v⁺ = v_f + M⁻¹ Jᵀ λ = v_f + L⁻¹ Z λ
        self.x.fill(0.0);
        primal_rows(
            data,
            &self.rows,
            &self.support[..nblocks],
            &self.z,
            &self.lambda[..m],
            &mut self.x,
        );
        for (v, dv) in v_free.iter_mut().zip(&self.x) {
            *v += dv;
        }
        // the impulses' work over the step, λᵀ J (v + v⁺)/2: with `M` constant over the step,
        // K(v⁺) − K(v) = (v + v⁺)ᵀ M (v⁺ − v)/2 is the smooth forces' work at the mean velocity
        // plus this; zero for a body at rest
        let work: f64 = (0..m)
            .map(|r| 0.5 * self.lambda[r] * (self.sigma_before[r] + self.sigma[r]))
            .sum();
        let (mut active, mut normal) = (0, 0.0);
        let unilateral = self.blocks.iter().filter(|b| !b.bilateral).count();
        for b in self.blocks.iter().filter(|b| !b.bilateral) {
            let l = &self.lambda[b.row..b.row + b.dim];
            if l[0] > 0.0 {
                active += 1;
            }
            if b.dim == 3 {
                normal += l[0];
                let f = b.frame;
                self.impulses.push(f[0] * l[0] + f[1] * l[1] + f[2] * l[2]);
            }
        }
        let residuals = ContactResiduals::of(
            &self.blocks,
            &self.target[..m],
            &self.lambda[..m],
            &self.sigma[..m],
            true,
        );
        self.stats = ContactStats {
            candidates: unilateral,
            active,
            iterations,
            converged,
            residuals,
            scaled,
            kinetic_change: dk,
            work,
            normal_impulse: normal,
            penetration,
        };
    }

    /// The position correction after [`solve`](Self::solve): normal impulses `μ ≥ 0` with
    /// `G_nn μ ≥ β max(0, −φ)/h` and bilateral ones with `(G μ)_B = −β e/h`, and
    /// `dq = h M⁻¹ Jᵀ μ` into `dq` (zero when nothing penetrates and every bilateral error is
    /// zero).
    pub(crate) fn correction(
        &mut self,
        data: &Data,
        h: f64,
        settings: &ContactSettings,
        dq: &mut [f64],
    ) {
        dq.fill(0.0);
        let beta = settings.stabilization;
        let m = self.m();
        self.mu[..m].fill(0.0);
        if (self.stats.penetration <= 0.0 && self.bilateral_error == 0.0) || beta == 0.0 {
            return;
        }
        for b in &self.blocks {
            if b.bilateral {
                continue; // set by `set_bilateral_targets`
            }
            self.target_mu[b.row] = beta * (-b.gap).max(0.0) / h;
            for i in 1..b.dim {
                self.target_mu[b.row + i] = 0.0;
            }
        }
        for (r, e) in self.bilateral_e.iter().enumerate() {
            self.target_mu[r] = -beta * e / h;
        }
        let (lambda, sigma) = (&mut self.mu[..m], &mut self.sigma_mu[..m]);
        lambda.fill(0.0);
        sigma.fill(0.0);
        // the polish is PGS's: under ADMM the correction's sweep goes without it
        let correction = ContactSettings {
            polish: settings.polish && settings.solver == Solver::Pgs,
            ..*settings
        };
        // the sweep whichever the solver: without friction the rows are a plain LCP, where it
        // converges in a few sweeps (ADMM's split converges slowly on the tiny targets of a
        // resting stack's redundant corners)
        pgs(
            &self.blocks,
            &self.islands,
            (&self.coupled, &self.coupled_first),
            &self.delassus[..m * m],
            (
                &self.bilateral_factor,
                &mut self.bilateral_step[..self.bilateral_rows],
                &self.bilateral_idle[..self.bilateral_rows],
            ),
            &self.target_mu[..m],
            lambda,
            sigma,
            (&correction, &mut self.polish),
            false,
        );
        primal_rows(
            data,
            &self.rows,
            &self.support[..self.blocks.len()],
            &self.z,
            &self.mu[..m],
            dq,
        );
        for x in dq.iter_mut() {
            *x *= h;
        }
    }
}

/// A unit vector orthogonal to the unit vector `n`.
#[cfg(feature = "collision")]
fn tangent(n: &Vec3) -> Vec3 {
    let a = if n.x.abs() < 0.6 {
        Vec3::x()
    } else if n.y.abs() < 0.6 {
        Vec3::y()
    } else {
        Vec3::z()
    };
    n.cross(&a).normalize()
}

/// The union of two chains of dofs (ascending), each dof with the chains it is on.
fn merge_chains(a: Option<&[usize]>, b: Option<&[usize]>, out: &mut Vec<(usize, bool, bool)>) {
    out.clear();
    let (a, b) = (a.unwrap_or(&[]), b.unwrap_or(&[]));
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) if x == y => {
                out.push((x, true, true));
                i += 1;
                j += 1;
            }
            (Some(&x), Some(&y)) if x < y => {
                out.push((x, true, false));
                i += 1;
            }
            (Some(&x), None) => {
                out.push((x, true, false));
                i += 1;
            }
            (_, Some(&y)) => {
                out.push((y, false, true));
                j += 1;
            }
            (None, None) => break,
        }
    }
}
