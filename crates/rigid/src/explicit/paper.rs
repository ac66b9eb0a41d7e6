//! The tables' form of an expression: products of the sines and cosines of joint angles, where
//! consecutive parallel joints combine into one angle (`S23 = sin(θ2 + θ3)`), with squares and
//! products written `SS5 = sin² θ5`, `SC4 = sin θ4 cos θ4` as in Armstrong, Khatib & Burdick
//! (1986).
//!
//! The canonical [`Expr`] is a sum of harmonics `cos(k·θ)`, `sin(k·θ)`. A chain of parallel
//! revolute joints (a **block**, e.g. the PUMA's joints 2 and 3, the UR5's 2, 3 and 4) turns its
//! links in one plane, so the sums of their angles are the natural variables: for the joints
//! `j₁ < j₂ < … < j_r` of a block that one entry depends on, the variables are the cumulative
//! angles `φ_m = θ_{j₁} ± … ± θ_{j_m}` (a22 of the PUMA depends on θ3 alone and uses `S3`; g2
//! depends on θ2 and θ3 and uses `C2` and `S23`). A harmonic's frequencies become frequencies of
//! these variables (`a_m = ε_m k_{j_m} - ε_{m+1} k_{j_{m+1}}`), angle addition splits it over the
//! variables, and `cos aφ`, `sin aφ` become polynomials in `C = cos φ`, `S = sin φ` reduced by
//! `C² = 1 - S²`: every variable appears as `S^n` or `C S^n`. This basis is again canonical: one
//! representation per function.

use super::chain::Chain;
use super::expr::{Expr, Mono, MAX_JOINTS};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A variable of the tables: the angle `Σ ε_l θ_{j_l}` of consecutive parallel revolute joints
/// (one joint: `θ_j`), or the displacement `q_j` of a prismatic joint.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Var {
    /// The joints (0-based) and their signs `ε = ±1` (the first is `+1`).
    pub joints: Vec<(usize, i8)>,
    /// A prismatic joint's displacement (one joint).
    pub prismatic: bool,
}

impl Var {
    /// The label in the tables: `2`, `23`, `(2-3)`, `(9+10)` (joints numbered from 1).
    #[must_use]
    pub fn label(&self) -> String {
        if self.joints.len() == 1 {
            return (self.joints[0].0 + 1).to_string();
        }
        let simple = self.joints.iter().all(|&(j, e)| j < 9 && e > 0);
        if simple {
            return self
                .joints
                .iter()
                .map(|(j, _)| (j + 1).to_string())
                .collect();
        }
        let mut s = String::from("(");
        for (i, &(j, e)) in self.joints.iter().enumerate() {
            if i > 0 {
                s.push(if e > 0 { '+' } else { '-' });
            }
            s.push_str(&(j + 1).to_string());
        }
        s.push(')');
        s
    }
}

/// Exponents of one variable in a monomial: `C^c S^s` (`c ≤ 1`), or the power `s` of a
/// prismatic displacement (`c = 0`).
pub type Power = (u8, u8);

/// A monomial of the tables: `(variable index, exponents)`, by increasing variable index.
pub type Monomial = Vec<(usize, Power)>;

/// The block structure of a chain: per joint, the head of its block and its sign relative to
/// the head.
#[derive(Clone, Debug)]
pub(crate) struct Blocks {
    head: Vec<usize>,
    sign: Vec<i8>,
}

impl Blocks {
    /// Joint `j` joins its parent's block when both are revolute, `j` is the parent's first child
    /// to do so, and `j`'s axis, seen in the parent's frame, is parallel to the parent's.
    pub fn new(chain: &Chain) -> Blocks {
        let n = chain.n();
        let (mut head, mut sign) = ((0..n).collect::<Vec<_>>(), vec![1i8; n]);
        let mut taken = vec![false; n];
        for (j, cj) in chain.joints.iter().enumerate() {
            let Some(p) = cj.parent else { continue };
            let cp = &chain.joints[p];
            if cj.prismatic || cp.prismatic || taken[p] {
                continue;
            }
            let a: [f64; 3] =
                std::array::from_fn(|r| (0..3).map(|c| cj.rot[r][c] * cj.axis[c]).sum());
            let d: f64 = (0..3).map(|k| a[k] * cp.axis[k]).sum();
            if (d.abs() - 1.0).abs() < 1e-12 {
                taken[p] = true;
                head[j] = head[p];
                sign[j] = if d > 0.0 { sign[p] } else { -sign[p] };
            }
        }
        Blocks { head, sign }
    }
}

/// Registry of the variables used by all entries.
#[derive(Clone, Debug, Default)]
pub(crate) struct Registry {
    pub vars: Vec<Var>,
    index: HashMap<Var, usize>,
}

impl Registry {
    fn id(&mut self, v: Var) -> usize {
        if let Some(&i) = self.index.get(&v) {
            return i;
        }
        self.vars.push(v.clone());
        self.index.insert(v, self.vars.len() - 1);
        self.vars.len() - 1
    }
}

/// A polynomial in the parameters: `Σ coef · mono`.
pub type ParamPoly = Vec<(Mono, f64)>;

/// One variable's part of a monomial, packed: `c << 5 | s` (prismatic: the power).
type Slots = [u8; MAX_JOINTS];

/// A polynomial in one variable's `C` and `S`: `(exponents, coefficient)`.
type Univariate = Vec<(Power, f64)>;

/// `cos aφ` and `sin aφ` (`a ≥ 0`) in the basis `S^n`, `C S^n`, as `(c, s) → coefficient`.
fn chebyshev(a: u8) -> (Univariate, Univariate) {
    let mut cos = vec![((0u8, 0u8), 1.0)];
    let mut sin: Vec<(Power, f64)> = Vec::new();
    // times C: C^1 S^n -> S^n - S^(n+2); times S: n + 1
    let times_c = |p: &[(Power, f64)]| -> Vec<(Power, f64)> {
        let mut out = Vec::new();
        for &((c, s), x) in p {
            if c == 0 {
                out.push(((1, s), x));
            } else {
                out.push(((0, s), x));
                out.push(((0, s + 2), -x));
            }
        }
        out
    };
    let times_s = |p: &[(Power, f64)]| -> Vec<(Power, f64)> {
        p.iter().map(|&((c, s), x)| ((c, s + 1), x)).collect()
    };
    for _ in 0..a {
        let mut c2 = times_c(&cos);
        c2.extend(times_s(&sin).into_iter().map(|(p, x)| (p, -x)));
        let mut s2 = times_c(&sin);
        s2.extend(times_s(&cos));
        cos = merge(c2);
        sin = merge(s2);
    }
    (cos, sin)
}

fn merge<K: Ord + Copy>(mut v: Vec<(K, f64)>) -> Vec<(K, f64)> {
    v.sort_unstable_by_key(|a| a.0);
    let mut out: Vec<(K, f64)> = Vec::with_capacity(v.len());
    for (k, x) in v {
        match out.last_mut() {
            Some(last) if last.0 == k => last.1 += x,
            _ => out.push((k, x)),
        }
    }
    out.retain(|p| p.1 != 0.0);
    out
}

/// `(slots, monomial)` as one integer, in their order.
fn pack(slots: &Slots, mono: Mono) -> u128 {
    let mut k = 0u128;
    for &b in slots.iter().chain(&mono.0) {
        k = k << 8 | u128::from(b);
    }
    k
}

fn unpack(mut k: u128) -> (Slots, Mono) {
    let mut mono = [0u8; super::expr::MAX_DEGREE];
    for m in mono.iter_mut().rev() {
        *m = (k & 0xff) as u8;
        k >>= 8;
    }
    let mut slots = [0u8; MAX_JOINTS];
    for b in slots.iter_mut().rev() {
        *b = (k & 0xff) as u8;
        k >>= 8;
    }
    (slots, Mono(mono))
}

/// A multiply-fold hash for packed keys (the standard SipHash is several times slower here and
/// its protection against adversarial keys is not needed).
#[derive(Default)]
struct PackedHasher(u64);

impl Hasher for PackedHasher {
    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 31)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(5) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    fn write_u128(&mut self, x: u128) {
        let h = (x as u64) ^ ((x >> 64) as u64).rotate_left(29);
        self.0 = h.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// A complex coefficient `(re, im)`.
type Complex = (f64, f64);

type Accumulator = HashMap<u128, Complex, BuildHasherDefault<PackedHasher>>;

fn accumulate(acc: &mut Accumulator, key: u128, z: Complex) {
    let e = acc.entry(key).or_insert((0.0, 0.0));
    e.0 += z.0;
    e.1 += z.1;
}

/// `expr` in the tables' form: `(monomial, parameter polynomial)` pairs, monomials in the
/// registry's variables.
///
/// Method: each harmonic is the real part of an exponential, `cos θ = Re e^{iθ}`,
/// `sin θ = Re(-i e^{iθ})` (`θ = Σ_v a_v φ_v` in this entry's variables), and
/// `e^{iθ} = Π_v e^{i a_v φ_v}` is a tensor product: the change of basis
/// `e^{i a φ} = cos aφ + i sin aφ` → `C^c S^s` acts on one variable at a time, merging like terms
/// after each, so the work grows with the sizes of the expressions rather than with
/// `2^(number of variables)` per harmonic. The monomials being real, the real parts of the
/// final coefficients are the answer.
pub(crate) fn expand(
    expr: &Expr,
    chain: &Chain,
    blocks: &Blocks,
    registry: &mut Registry,
) -> Vec<(Monomial, ParamPoly)> {
    let space = expr.space();
    let present = expr.joints();
    // this entry's variables: per block, the cumulative angles of its present joints
    let mut vars: Vec<Var> = Vec::new();
    // per block head: the present joints of the block and their signs
    let mut members: Vec<Vec<(usize, i8)>> = vec![Vec::new(); space.n];
    for j in (0..space.n).filter(|&j| present >> j & 1 == 1) {
        members[blocks.head[j]].push((j, blocks.sign[j]));
    }
    let mut block_slots: Vec<Vec<usize>> = vec![Vec::new(); space.n];
    for h in 0..space.n {
        let m = &members[h];
        let e0 = m.first().map_or(1, |x| x.1);
        for r in 1..=m.len() {
            block_slots[h].push(vars.len());
            vars.push(Var {
                joints: m[..r].iter().map(|&(j, e)| (j, e * e0)).collect(),
                prismatic: chain.joints[m[0].0].prismatic,
            });
        }
    }
    // 1. the exponential form: slots hold a_v + 128 (revolute) or the power (prismatic)
    let mut acc = Accumulator::default();
    for t in expr.terms() {
        let mut plus = [0u8; MAX_JOINTS];
        for h in 0..space.n {
            let m = &members[h];
            if m.is_empty() {
                continue;
            }
            if chain.joints[m[0].0].prismatic {
                let v = block_slots[h][0];
                plus[v] = t.freq[m[0].0] as u8;
                continue;
            }
            let e0 = m[0].1;
            let eps = |l: usize| if l < m.len() { m[l].1 * e0 } else { 1 };
            let k = |l: usize| if l < m.len() { t.freq[m[l].0] } else { 0 };
            for (l, &v) in block_slots[h].iter().enumerate() {
                // a_m = ε_m k_{j_m} - ε_{m+1} k_{j_{m+1}}
                let a = i16::from(eps(l)) * i16::from(k(l))
                    - i16::from(eps(l + 1)) * i16::from(k(l + 1));
                plus[v] = (a + 128) as u8;
            }
        }
        let z = if t.sin { (0.0, -t.coef) } else { (t.coef, 0.0) };
        accumulate(&mut acc, pack(&plus, t.mono), z);
    }
    // 2. one revolute variable at a time: e^{i a φ} = cos aφ + i sin aφ in C^c S^s
    let cheb: Vec<_> = (0..=16).map(chebyshev).collect();
    for (v, var) in vars.iter().enumerate() {
        if var.prismatic {
            continue;
        }
        let shift = 8 * (MAX_JOINTS - 1 - v) + 8 * super::expr::MAX_DEGREE;
        let mut next = Accumulator::default();
        next.reserve(acc.len());
        for (key, z) in acc {
            let code = ((key >> shift) & 0xff) as i16 - 128;
            let base = key & !(0xffu128 << shift);
            let (c, s) = &cheb[code.unsigned_abs() as usize];
            let sg = if code < 0 { -1.0 } else { 1.0 };
            for &((pc, ps), w) in c {
                let k = base | u128::from(pc << 5 | ps) << shift;
                accumulate(&mut next, k, (z.0 * w, z.1 * w));
            }
            for &((pc, ps), w) in s {
                // times i sg w
                let k = base | u128::from(pc << 5 | ps) << shift;
                accumulate(&mut next, k, (-z.1 * sg * w, z.0 * sg * w));
            }
        }
        acc = next;
    }
    // 3. the real parts, grouped by monomial, the slots mapped to registry variables
    let mut acc: Vec<(u128, f64)> = acc
        .into_iter()
        .filter(|x| x.1 .0 != 0.0)
        .map(|(k, z)| (k, z.0))
        .collect();
    acc.sort_unstable_by_key(|a| a.0);
    let ids: Vec<usize> = vars.into_iter().map(|v| registry.id(v)).collect();
    let mut out: Vec<(Monomial, ParamPoly)> = Vec::new();
    let mut last: Option<Slots> = None;
    for (key, x) in acc {
        let (slots, mono) = unpack(key);
        if last != Some(slots) {
            let mut m: Monomial = (0..ids.len())
                .filter(|&v| slots[v] != 0)
                .map(|v| (ids[v], (slots[v] >> 5, slots[v] & 31)))
                .collect();
            m.sort_unstable();
            out.push((m, Vec::new()));
            last = Some(slots);
        }
        out.last_mut().expect("pushed").1.push((mono, x));
    }
    out
}

/// The value of a monomial: `Π C_v^c S_v^s` (prismatic: `q^s`) at the angles `theta`.
pub(crate) fn monomial_value(m: &Monomial, vars: &[Var], theta: &[f64]) -> f64 {
    m.iter()
        .map(|&(v, (c, s))| {
            let var = &vars[v];
            let x: f64 = var
                .joints
                .iter()
                .map(|&(j, e)| f64::from(e) * theta[j])
                .sum();
            if var.prismatic {
                x.powi(i32::from(s))
            } else {
                x.cos().powi(i32::from(c)) * x.sin().powi(i32::from(s))
            }
        })
        .product()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_matches_the_double_and_triple_angle_formulas() {
        let (c2, s2) = chebyshev(2);
        // cos 2x = 1 - 2 S², sin 2x = 2 S C
        assert_eq!(c2, vec![((0, 0), 1.0), ((0, 2), -2.0)]);
        assert_eq!(s2, vec![((1, 1), 2.0)]);
        let (c3, s3) = chebyshev(3);
        let x: f64 = 0.37;
        let ev = |p: &[(Power, f64)]| -> f64 {
            p.iter()
                .map(|&((c, s), k)| k * x.cos().powi(i32::from(c)) * x.sin().powi(i32::from(s)))
                .sum()
        };
        assert!((ev(&c3) - (3.0 * x).cos()).abs() < 1e-15);
        assert!((ev(&s3) - (3.0 * x).sin()).abs() < 1e-15);
    }
}
