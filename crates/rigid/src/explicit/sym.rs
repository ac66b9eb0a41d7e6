//! Symbolic 3-vectors, 3x3 matrices, rigid transforms and spatial inertias over [`Expr`], the
//! few operations the derivations need (Lynch & Park §8.2; Featherstone 2008 §2).

use super::expr::{Expr, Overflow, Space};

/// A 3-vector of expressions.
pub(crate) type V3 = [Expr; 3];
/// A 3x3 matrix of expressions, `m[row][col]`.
pub(crate) type M3 = [[Expr; 3]; 3];

/// The zero vector.
pub(crate) fn zero_vec(space: Space) -> V3 {
    std::array::from_fn(|_| Expr::zero(space))
}

/// `a + b`.
pub(crate) fn add(a: &V3, b: &V3) -> V3 {
    std::array::from_fn(|i| a[i].add(&b[i]))
}

/// `a · b`.
pub(crate) fn dot(a: &V3, b: &V3) -> Result<Expr, Overflow> {
    let mut s = a[0].mul(&b[0])?;
    for i in 1..3 {
        s = s.add(&a[i].mul(&b[i])?);
    }
    Ok(s)
}

/// `a · b` for a numeric `a`.
pub(crate) fn dot_num(a: [f64; 3], b: &V3) -> Expr {
    let mut s = Expr::zero(b[0].space());
    for i in 0..3 {
        if a[i] != 0.0 {
            s = s.add_scaled(&b[i], a[i]);
        }
    }
    s
}

/// `a × b`.
pub(crate) fn cross(a: &V3, b: &V3) -> Result<V3, Overflow> {
    let c = |i: usize, j: usize| -> Result<Expr, Overflow> {
        Ok(a[i].mul(&b[j])?.sub(&a[j].mul(&b[i])?))
    };
    Ok([c(1, 2)?, c(2, 0)?, c(0, 1)?])
}

/// `a × b` for a numeric `a`.
pub(crate) fn cross_num(a: [f64; 3], b: &V3) -> V3 {
    let space = b[0].space();
    let c = |i: usize, j: usize| {
        let mut e = Expr::zero(space);
        if a[i] != 0.0 {
            e = e.add_scaled(&b[j], a[i]);
        }
        if a[j] != 0.0 {
            e = e.add_scaled(&b[i], -a[j]);
        }
        e
    };
    [c(1, 2), c(2, 0), c(0, 1)]
}

/// `s · a` for an expression `s`.
pub(crate) fn scale(s: &Expr, a: &V3) -> Result<V3, Overflow> {
    Ok([s.mul(&a[0])?, s.mul(&a[1])?, s.mul(&a[2])?])
}

/// `R v`.
pub(crate) fn mat_vec(r: &M3, v: &V3) -> Result<V3, Overflow> {
    let row = |i: usize| dot(&r[i], v);
    Ok([row(0)?, row(1)?, row(2)?])
}

/// `Rᵀ v`.
pub(crate) fn mat_t_vec(r: &M3, v: &V3) -> Result<V3, Overflow> {
    let col = |j: usize| -> Result<Expr, Overflow> {
        let mut s = r[0][j].mul(&v[0])?;
        for i in 1..3 {
            s = s.add(&r[i][j].mul(&v[i])?);
        }
        Ok(s)
    };
    Ok([col(0)?, col(1)?, col(2)?])
}

/// A rigid transform `T = (R, p)`: the pose of a child frame in its parent.
#[derive(Clone, Debug)]
pub(crate) struct SymTransform {
    /// Rotation `R`.
    pub r: M3,
    /// Translation `p`.
    pub p: V3,
}

/// A spatial inertia by its standard parameters about the frame origin: mass `m`, first moment
/// `h = m c`, rotational inertia `I_O` (symmetric, all nine entries kept).
#[derive(Clone, Debug)]
pub(crate) struct SymInertia {
    pub m: Expr,
    pub h: V3,
    pub i: M3,
}

impl SymInertia {
    /// `self + o` (both in the same frame).
    pub fn add(&self, o: &SymInertia) -> SymInertia {
        SymInertia {
            m: self.m.add(&o.m),
            h: add(&self.h, &o.h),
            i: std::array::from_fn(|r| add(&self.i[r], &o.i[r])),
        }
    }

    /// This inertia, given in a child frame, expressed in the parent frame where the child has
    /// pose `t = (R, p)` (as `SpatialInertia::transformed`): with `u = R h`,
    /// `h' = u + m p`, `I' = R I Rᵀ - (p uᵀ + u pᵀ) + 2 (p·u) 1 - m (p pᵀ - (p·p) 1)`
    /// (`[a][b] = b aᵀ - (a·b) 1`).
    pub fn transformed(&self, t: &SymTransform) -> Result<SymInertia, Overflow> {
        let (r, p) = (&t.r, &t.p);
        let u = mat_vec(r, &self.h)?;
        let h = add(&u, &scale(&self.m, p)?);
        // R I
        let mut ri: Vec<Vec<Expr>> = Vec::with_capacity(3);
        for row in r {
            let mut out = Vec::with_capacity(3);
            for c in 0..3 {
                let col: V3 = std::array::from_fn(|k| self.i[k][c].clone());
                out.push(dot(row, &col)?);
            }
            ri.push(out);
        }
        let pu = dot(p, &u)?;
        let pp = dot(p, p)?;
        let mut i: M3 = std::array::from_fn(|_| zero_vec(self.m.space()));
        for a in 0..3 {
            for b in a..3 {
                // (R I Rᵀ)_ab = Σ_k (R I)_ak R_bk
                let mut e = ri[a][0].mul(&r[b][0])?;
                for k in 1..3 {
                    e = e.add(&ri[a][k].mul(&r[b][k])?);
                }
                e = e.sub(&p[a].mul(&u[b])?).sub(&u[a].mul(&p[b])?);
                e = e.sub(&self.m.mul(&p[a].mul(&p[b])?)?);
                if a == b {
                    e = e.add(&pu.scale(2.0)).add(&self.m.mul(&pp)?);
                }
                i[a][b] = e.clone();
                i[b][a] = e;
            }
        }
        Ok(SymInertia {
            m: self.m.clone(),
            h,
            i,
        })
    }

    /// The first moment `h' = R h + m p` of [`transformed`](Self::transformed) alone.
    pub fn transformed_first_moment(&self, t: &SymTransform) -> Result<V3, Overflow> {
        Ok(add(&mat_vec(&t.r, &self.h)?, &scale(&self.m, &t.p)?))
    }

    /// The momentum `G S = (I_O ω + h × v, m v - h × ω)` of a constant twist `S = (ω, v)`.
    pub fn momentum(&self, w: [f64; 3], v: [f64; 3]) -> (V3, V3) {
        // h × v = -(v × h); m v - h × ω = m v + ω × h
        let vh = cross_num(v, &self.h);
        let n: V3 = std::array::from_fn(|k| dot_num(w, &self.i[k]).sub(&vh[k]));
        let wh = cross_num(w, &self.h);
        let f: V3 = std::array::from_fn(|k| self.m.scale(v[k]).add(&wh[k]));
        (n, f)
    }
}

/// A wrench `(n, f)` given in a child frame, expressed in the parent where the child has pose
/// `t = (R, p)`: `f' = R f`, `n' = R n + p × f'`.
pub(crate) fn wrench_to_parent(t: &SymTransform, n: &V3, f: &V3) -> Result<(V3, V3), Overflow> {
    let f2 = mat_vec(&t.r, f)?;
    let n2 = add(&mat_vec(&t.r, n)?, &cross(&t.p, &f2)?);
    Ok((n2, f2))
}
