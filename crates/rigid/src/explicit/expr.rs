//! The symbolic core: trigonometric polynomials in the joint angles (and polynomials in the
//! prismatic joints' displacements) whose coefficients are polynomials in the model's parameters,
//! stored flat and in canonical form.
//!
//! An [`Expr`] is a sum of [`Term`]s `c · h(q) · π₁ π₂ π₃`: a real number `c`, a **harmonic**
//! `h(q) = cos(k·q)` or `sin(k·q)` (the integer frequencies `k_j` of the revolute joints, times
//! `q_j^{k_j}` for the prismatic ones) and a **parameter monomial** of degree at most
//! [`MAX_DEGREE`] (masses, first moments, inertias, joint offsets, gravity; see
//! [`Parameters`](super::Parameters)).
//!
//! Canonical form: the harmonics `cos(k·q)`, `sin(k·q)` with the first non-zero revolute
//! frequency positive form a basis of the trigonometric polynomials, so every expression has one
//! representation: terms sorted by (frequencies, cos before sin, monomial), like terms merged,
//! zero coefficients dropped. `s² + c² = 1` needs no rewriting rule here: products go to sums
//! (`cos x cos y = ½ cos(x-y) + ½ cos(x+y)`, …), and `sin²q + cos²q` comes out as the constant
//! `1` because the `cos 2q` parts cancel exactly. Frequencies of parallel joints add
//! (`sin(q2+q3)`), which is how `S23` arises without a rule for it.

use std::cmp::Ordering;

/// Most joints an explicit model is derived for (the frequency vector is a fixed array).
pub const MAX_JOINTS: usize = 12;

/// Highest degree of a parameter monomial (`mass · length²`, `gravity · mass · length`).
pub const MAX_DEGREE: usize = 3;

/// Frequencies of the revolute joints and powers of the prismatic ones, by joint index.
pub type Freq = [i8; MAX_JOINTS];

/// A parameter monomial: up to [`MAX_DEGREE`] parameter indices `+ 1`, in decreasing order,
/// padded with zeros (`[0, 0, 0]` is the monomial `1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Mono(pub [u8; MAX_DEGREE]);

impl Mono {
    /// The monomial `1`.
    pub const ONE: Mono = Mono([0; MAX_DEGREE]);

    /// The monomial of one parameter (index `p`, at most 254).
    #[must_use]
    pub(crate) fn param(p: usize) -> Mono {
        let mut m = [0; MAX_DEGREE];
        m[0] = u8::try_from(p + 1).expect("at most 254 parameters");
        Mono(m)
    }

    /// The parameter indices of this monomial, with repetition.
    pub fn params(&self) -> impl Iterator<Item = usize> + '_ {
        self.0
            .iter()
            .take_while(|&&p| p != 0)
            .map(|&p| p as usize - 1)
    }

    /// The degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.params().count()
    }

    /// The product, or `None` above [`MAX_DEGREE`].
    #[must_use]
    pub(crate) fn mul(self, o: Mono) -> Option<Mono> {
        if o.0[0] == 0 {
            return Some(self);
        }
        if self.0[0] == 0 {
            return Some(o);
        }
        let mut all = [0u8; 2 * MAX_DEGREE];
        all[..MAX_DEGREE].copy_from_slice(&self.0);
        all[MAX_DEGREE..].copy_from_slice(&o.0);
        all.sort_unstable_by(|a, b| b.cmp(a));
        if all[MAX_DEGREE] != 0 {
            return None;
        }
        let mut m = [0; MAX_DEGREE];
        m.copy_from_slice(&all[..MAX_DEGREE]);
        Some(Mono(m))
    }

    /// The value for the parameter values `values`.
    #[must_use]
    pub fn eval(&self, values: &[f64]) -> f64 {
        self.params().map(|p| values[p]).product()
    }
}

/// Which joints of the chain are prismatic (their "frequency" is a power of `q_j`), and how many
/// joints there are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Space {
    /// Number of joints (at most [`MAX_JOINTS`]).
    pub n: usize,
    /// Bit `j` set: joint `j` is prismatic.
    pub prismatic: u16,
}

impl Space {
    /// Whether joint `j` is prismatic.
    #[must_use]
    pub fn is_prismatic(&self, j: usize) -> bool {
        self.prismatic >> j & 1 == 1
    }
}

/// One term `coef · (cos|sin)(k·q) · Π q_prismatic^k · mono`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term {
    /// Frequencies (revolute joints) and powers (prismatic joints).
    pub freq: Freq,
    /// `sin(k·q)` rather than `cos(k·q)`.
    pub sin: bool,
    /// The parameter monomial.
    pub mono: Mono,
    /// The numeric coefficient.
    pub coef: f64,
}

impl Term {
    /// The key `(freq, sin, mono)` as one integer with the same order: the frequencies as
    /// biased bytes in bits 127..32, `sin` in bit 24, the monomial in bits 23..0.
    fn pack(&self) -> u128 {
        let mut k: u128 = 0;
        for &f in &self.freq {
            k = k << 8 | u128::from((f as u8) ^ 0x80);
        }
        k = k << 8 | u128::from(self.sin);
        for &m in &self.mono.0 {
            k = k << 8 | u128::from(m);
        }
        k
    }

    fn unpack(mut k: u128, coef: f64) -> Term {
        let mut mono = [0u8; MAX_DEGREE];
        for m in mono.iter_mut().rev() {
            *m = (k & 0xff) as u8;
            k >>= 8;
        }
        let sin = k & 1 == 1;
        k >>= 8;
        let mut freq = [0i8; MAX_JOINTS];
        for f in freq.iter_mut().rev() {
            *f = ((k & 0xff) as u8 ^ 0x80) as i8;
            k >>= 8;
        }
        Term {
            freq,
            sin,
            mono: Mono(mono),
            coef,
        }
    }

    fn key_cmp(&self, o: &Term) -> Ordering {
        (self.freq, self.sin, self.mono).cmp(&(o.freq, o.sin, o.mono))
    }
}

/// Error of an operation whose result would leave the representation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overflow;

/// A trigonometric polynomial with parameter-polynomial coefficients, in canonical form
/// (see the module documentation).
///
/// ```
/// use rigid::explicit::ExplicitModel;
/// use rigid::multibody::pendulum;
/// // the pendulum's gravity torque: one term, g·MX1-like constant times sin q
/// let ex = ExplicitModel::derive(&pendulum())?;
/// let g = ex.gravity(0);
/// let values = ex.parameters().values();
/// assert_eq!(g.len(), 1);
/// assert!(g.terms()[0].sin && g.terms()[0].freq[0] == 1);
/// assert!((g.eval(&[0.5], &values) - 4.905 * 0.5f64.sin()).abs() < 1e-12);
/// assert!(g.sub(g).is_empty());
/// # Ok::<(), rigid::explicit::ExplicitError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    space: Space,
    terms: Vec<Term>,
}

/// `sign · k` on the revolute joints (prismatic powers add in both `x + y` and `x - y`).
fn combine(space: Space, a: &Freq, b: &Freq, minus: bool) -> Result<Freq, Overflow> {
    let mut k = [0i8; MAX_JOINTS];
    for j in 0..space.n {
        let r = if minus && !space.is_prismatic(j) {
            a[j].checked_sub(b[j])
        } else {
            a[j].checked_add(b[j])
        };
        k[j] = r.ok_or(Overflow)?;
    }
    Ok(k)
}

/// Whether a frequency vector is constant in the angles (every revolute frequency zero).
fn trig_free(space: Space, k: &Freq) -> bool {
    (0..space.n).all(|j| space.is_prismatic(j) || k[j] == 0)
}

impl Expr {
    /// The zero expression.
    #[must_use]
    pub(crate) fn zero(space: Space) -> Self {
        Self {
            space,
            terms: Vec::new(),
        }
    }

    /// The constant `c`.
    #[must_use]
    pub(crate) fn constant(space: Space, c: f64) -> Self {
        Self::from_terms(
            space,
            vec![Term {
                freq: [0; MAX_JOINTS],
                sin: false,
                mono: Mono::ONE,
                coef: c,
            }],
        )
    }

    /// `c · π_p`, a parameter times a number.
    #[must_use]
    pub(crate) fn param(space: Space, p: usize, c: f64) -> Self {
        Self::from_terms(
            space,
            vec![Term {
                freq: [0; MAX_JOINTS],
                sin: false,
                mono: Mono::param(p),
                coef: c,
            }],
        )
    }

    /// `c · cos q_j` (`sin` false) or `c · sin q_j` (true) of a revolute joint, or `c · q_j` of a
    /// prismatic one (`sin` ignored).
    #[must_use]
    pub(crate) fn joint(space: Space, j: usize, sin: bool, c: f64) -> Self {
        let mut freq = [0; MAX_JOINTS];
        freq[j] = 1;
        Self::from_terms(
            space,
            vec![Term {
                freq,
                sin: sin && !space.is_prismatic(j),
                mono: Mono::ONE,
                coef: c,
            }],
        )
    }

    /// An expression from any terms: canonicalises signs, sorts, merges, drops zeros.
    #[must_use]
    pub(crate) fn from_terms(space: Space, mut terms: Vec<Term>) -> Self {
        for t in &mut terms {
            canonical_sign(space, t);
        }
        // sort on one packed integer per term (the canonical order), then merge equal keys
        let mut packed: Vec<(u128, f64)> = terms
            .iter()
            .filter(|t| t.coef != 0.0)
            .map(|t| (t.pack(), t.coef))
            .collect();
        packed.sort_unstable_by_key(|x| x.0);
        let mut out: Vec<(u128, f64)> = Vec::with_capacity(packed.len());
        for (k, c) in packed {
            match out.last_mut() {
                Some(last) if last.0 == k => last.1 += c,
                _ => out.push((k, c)),
            }
        }
        let terms = out
            .into_iter()
            .filter(|x| x.1 != 0.0)
            .map(|(k, c)| Term::unpack(k, c))
            .collect();
        Self { space, terms }
    }

    /// The terms, in canonical order.
    #[must_use]
    pub fn terms(&self) -> &[Term] {
        &self.terms
    }

    /// The joint space.
    #[must_use]
    pub(crate) fn space(&self) -> Space {
        self.space
    }

    /// Number of terms.
    #[must_use]
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether this is the zero expression (no terms).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// `self + o`.
    #[must_use]
    pub fn add(&self, o: &Expr) -> Expr {
        self.add_scaled(o, 1.0)
    }

    /// `self - o`.
    #[must_use]
    pub fn sub(&self, o: &Expr) -> Expr {
        self.add_scaled(o, -1.0)
    }

    /// `self + s · o`, by a merge of the two sorted term lists.
    #[must_use]
    pub(crate) fn add_scaled(&self, o: &Expr, s: f64) -> Expr {
        let (a, b) = (&self.terms, &o.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            let ord = match (a.get(i), b.get(j)) {
                (Some(x), Some(y)) => x.key_cmp(y),
                (Some(_), None) => Ordering::Less,
                _ => Ordering::Greater,
            };
            match ord {
                Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                Ordering::Greater => {
                    let mut t = b[j];
                    t.coef *= s;
                    out.push(t);
                    j += 1;
                }
                Ordering::Equal => {
                    let mut t = a[i];
                    t.coef += s * b[j].coef;
                    if t.coef != 0.0 {
                        out.push(t);
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.retain(|t| t.coef != 0.0);
        Expr {
            space: self.space,
            terms: out,
        }
    }

    /// `s · self`.
    #[must_use]
    pub(crate) fn scale(&self, s: f64) -> Expr {
        if s == 0.0 {
            return Expr::zero(self.space);
        }
        let mut e = self.clone();
        for t in &mut e.terms {
            t.coef *= s;
        }
        e
    }

    /// `self · o`, products of harmonics turned into sums:
    /// `cos x cos y = ½[cos(x-y) + cos(x+y)]`, `sin x sin y = ½[cos(x-y) - cos(x+y)]`,
    /// `sin x cos y = ½[sin(x+y) + sin(x-y)]`, `cos x sin y = ½[sin(x+y) - sin(x-y)]`.
    ///
    /// # Errors
    /// A parameter monomial above [`MAX_DEGREE`] or a frequency beyond ±127.
    pub(crate) fn mul(&self, o: &Expr) -> Result<Expr, Overflow> {
        let space = self.space;
        let mut out = Vec::with_capacity(2 * self.len() * o.len());
        for a in &self.terms {
            let a_const = trig_free(space, &a.freq);
            for b in &o.terms {
                let mono = a.mono.mul(b.mono).ok_or(Overflow)?;
                let c = a.coef * b.coef;
                let sum = combine(space, &a.freq, &b.freq, false)?;
                if a_const || trig_free(space, &b.freq) {
                    // one factor has no angle: the product is one harmonic
                    out.push(Term {
                        freq: sum,
                        sin: a.sin || b.sin,
                        mono,
                        coef: c,
                    });
                    continue;
                }
                let diff = combine(space, &a.freq, &b.freq, true)?;
                let h = 0.5 * c;
                let (plus, minus, sin) = match (a.sin, b.sin) {
                    (false, false) => (h, h, false),
                    (true, true) => (-h, h, false),
                    (true, false) => (h, h, true),
                    (false, true) => (h, -h, true),
                };
                out.push(Term {
                    freq: sum,
                    sin,
                    mono,
                    coef: plus,
                });
                out.push(Term {
                    freq: diff,
                    sin,
                    mono,
                    coef: minus,
                });
            }
        }
        Ok(Expr::from_terms(space, out))
    }

    /// `∂/∂q_j`: `-k_j sin(k·q)` from `cos(k·q)`, `k_j cos(k·q)` from `sin(k·q)`, and
    /// `p q^{p-1}` for a prismatic joint.
    #[must_use]
    pub(crate) fn derivative(&self, j: usize) -> Expr {
        let prismatic = self.space.is_prismatic(j);
        let terms = self
            .terms
            .iter()
            .filter(|t| t.freq[j] != 0)
            .map(|t| {
                let k = f64::from(t.freq[j]);
                let mut d = *t;
                if prismatic {
                    d.freq[j] -= 1;
                    d.coef *= k;
                } else {
                    d.sin = !t.sin;
                    d.coef *= if t.sin { k } else { -k };
                }
                d
            })
            .collect();
        Expr::from_terms(self.space, terms)
    }

    /// The value at the joint values `q` and the parameter values `values`.
    #[must_use]
    pub fn eval(&self, q: &[f64], values: &[f64]) -> f64 {
        self.terms
            .iter()
            .map(|t| t.coef * harmonic(self.space, t, q) * t.mono.eval(values))
            .sum()
    }

    /// The largest absolute coefficient value `|coef · mono(values)|` (0 for zero).
    #[must_use]
    pub fn max_abs(&self, values: &[f64]) -> f64 {
        self.terms
            .iter()
            .map(|t| (t.coef * t.mono.eval(values)).abs())
            .fold(0.0, f64::max)
    }

    /// The same function written in the angles `θ_j = q_j + o_j`: `cos(k·q) = cos(k·θ - φ)`
    /// `= cos(k·θ) cos φ + sin(k·θ) sin φ` and `sin(k·q) = sin(k·θ) cos φ - cos(k·θ) sin φ`
    /// with `φ = k·o` (`cos φ`, `sin φ` exact at multiples of π/2). Offsets of prismatic joints
    /// must be zero.
    #[must_use]
    pub(crate) fn shifted(&self, offsets: &[f64]) -> Expr {
        let mut out = Vec::with_capacity(2 * self.len());
        for t in &self.terms {
            let phi: f64 = (0..self.space.n)
                .filter(|&j| !self.space.is_prismatic(j))
                .map(|j| f64::from(t.freq[j]) * offsets[j])
                .sum();
            if phi == 0.0 {
                out.push(*t);
                continue;
            }
            let (s, c) = (super::chain::snap(phi.sin()), super::chain::snap(phi.cos()));
            let (same, other) = if t.sin { (c, -s) } else { (c, s) };
            out.push(Term {
                coef: t.coef * same,
                ..*t
            });
            out.push(Term {
                sin: !t.sin,
                coef: t.coef * other,
                ..*t
            });
        }
        Expr::from_terms(self.space, out)
    }

    /// The joints the expression depends on, as a bit set.
    #[must_use]
    pub(crate) fn joints(&self) -> u16 {
        self.terms.iter().fold(0, |acc, t| {
            (0..self.space.n)
                .filter(|&j| t.freq[j] != 0)
                .fold(acc, |a, j| a | 1 << j)
        })
    }
}

/// `cos(k·q)` or `sin(k·q)` times the prismatic powers.
fn harmonic(space: Space, t: &Term, q: &[f64]) -> f64 {
    let mut angle = 0.0;
    let mut power = 1.0;
    for (j, (&k, &x)) in t.freq.iter().zip(q).enumerate().take(space.n) {
        if space.is_prismatic(j) {
            power *= x.powi(i32::from(k));
        } else if k != 0 {
            angle += f64::from(k) * x;
        }
    }
    power * if t.sin { angle.sin() } else { angle.cos() }
}

/// Makes the first non-zero revolute frequency positive (`cos(-x) = cos x`,
/// `sin(-x) = -sin x`); `sin 0` becomes a zero coefficient.
fn canonical_sign(space: Space, t: &mut Term) {
    let first = (0..space.n).find(|&j| !space.is_prismatic(j) && t.freq[j] != 0);
    match first {
        None => {
            if t.sin {
                t.coef = 0.0;
                t.sin = false;
            }
        }
        Some(j) if t.freq[j] < 0 => {
            for i in 0..space.n {
                if !space.is_prismatic(i) {
                    t.freq[i] = -t.freq[i];
                }
            }
            if t.sin {
                t.coef = -t.coef;
            }
        }
        Some(_) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const S2: Space = Space { n: 2, prismatic: 0 };

    #[test]
    fn sin_squared_plus_cos_squared_is_one() {
        let c = Expr::joint(S2, 0, false, 1.0);
        let s = Expr::joint(S2, 0, true, 1.0);
        let one = c.mul(&c).unwrap().add(&s.mul(&s).unwrap());
        assert_eq!(one, Expr::constant(S2, 1.0));
    }

    #[test]
    fn angle_addition_gives_one_harmonic() {
        // sin q0 cos q1 + cos q0 sin q1 = sin(q0 + q1)
        let (c0, s0) = (
            Expr::joint(S2, 0, false, 1.0),
            Expr::joint(S2, 0, true, 1.0),
        );
        let (c1, s1) = (
            Expr::joint(S2, 1, false, 1.0),
            Expr::joint(S2, 1, true, 1.0),
        );
        let e = s0.mul(&c1).unwrap().add(&c0.mul(&s1).unwrap());
        assert_eq!(e.len(), 1);
        let t = e.terms()[0];
        assert!(t.sin && t.freq[..2] == [1, 1] && t.coef == 1.0);
        let q = [0.3, -1.1];
        assert!((e.eval(&q, &[]) - (q[0] + q[1]).sin()).abs() < 1e-15);
        // its derivative in q1 is cos(q0 + q1)
        let d = e.derivative(1);
        assert!((d.eval(&q, &[]) - (q[0] + q[1]).cos()).abs() < 1e-15);
    }

    #[test]
    fn prismatic_powers_multiply_and_differentiate() {
        let sp = Space {
            n: 2,
            prismatic: 0b10,
        };
        let x = Expr::joint(sp, 1, false, 2.0);
        let c = Expr::joint(sp, 0, false, 1.0);
        let e = x.mul(&x).unwrap().mul(&c).unwrap(); // 4 x² cos q0
        let q = [0.7, 0.3];
        assert!((e.eval(&q, &[]) - 4.0 * 0.09 * 0.7f64.cos()).abs() < 1e-15);
        let d = e.derivative(1); // 8 x cos q0
        assert!((d.eval(&q, &[]) - 8.0 * 0.3 * 0.7f64.cos()).abs() < 1e-15);
    }

    #[test]
    fn parameter_monomials_multiply_up_to_the_degree() {
        let p = Expr::param(S2, 4, 1.0);
        let p3 = p.mul(&p).unwrap().mul(&p).unwrap();
        assert_eq!(p3.terms()[0].mono.degree(), 3);
        assert!(p3.mul(&p).is_err());
        assert_eq!(p3.eval(&[0.0, 0.0], &[0.0, 0.0, 0.0, 0.0, 2.0]), 8.0);
    }
}
