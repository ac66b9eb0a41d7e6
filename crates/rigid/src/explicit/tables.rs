//! The tables of the explicit model: every entry `a_ij`, `b_ijk`, `c_ij`, `g_i` in the tables'
//! form, its parameter polynomials abbreviated into numbered constants (`I_1, I_2, …` and, for the
//! gravity terms, `g_1, g_2, …`, in order of first use), its terms pruned by significance with a
//! proven bound on the error.
//!
//! **Abbreviation.** The coefficient of each monomial is a polynomial `P` in the parameters. It is
//! written `λ · K` with `K` a constant: `λ` is the most frequent coefficient magnitude in `P` (so
//! that `K = P/λ` has mostly unit coefficients) with the sign that makes `K`'s value positive;
//! polynomials equal up to such a factor share one constant (`b_ijk` reuse the constants of
//! `a_ij`, whose derivatives they are).
//!
//! **Pruning.** Each term's bound is `|λ K| · sup |monomial|` over the joint ranges
//! ([`bound`](super::bound)); a term whose bound is below `tolerance` times the largest bound of its
//! entry is dropped, and the entry's error is at most the sum of the dropped terms' bounds (the
//! triangle inequality). `tolerance = 0` drops nothing.

use super::bound::monomial_sup;
use super::chain::Chain;
use super::expr::Mono;
use super::paper::{expand, monomial_value, Blocks, Monomial, ParamPoly, Registry, Var};
use super::ExplicitModel;
use std::collections::HashMap;

/// What an entry of the tables is (indices 0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EntryKind {
    /// `a_ij = M_ij` (`i ≤ j`).
    Mass(usize, usize),
    /// `b_ijk` (`j < k`): coefficient of `q̇_j q̇_k` in `c_i`.
    Coriolis(usize, usize, usize),
    /// `c_ij`: coefficient of `q̇_j²` in `c_i`.
    Centrifugal(usize, usize),
    /// `g_i`.
    Gravity(usize),
}

impl EntryKind {
    /// The name in the tables, joints from 1: `a23`, `b123`, `c21`, `g2` (with commas when a
    /// joint number has two digits: `a2,10`).
    #[must_use]
    pub fn label(&self) -> String {
        let (letter, idx): (&str, Vec<usize>) = match *self {
            Self::Mass(i, j) => ("a", vec![i, j]),
            Self::Coriolis(i, j, k) => ("b", vec![i, j, k]),
            Self::Centrifugal(i, j) => ("c", vec![i, j]),
            Self::Gravity(i) => ("g", vec![i]),
        };
        let sep = if idx.iter().any(|&x| x >= 9) { "," } else { "" };
        let parts: Vec<String> = idx.iter().map(|x| (x + 1).to_string()).collect();
        format!("{letter}{}", parts.join(sep))
    }
}

/// An abbreviated constant `K = Σ coef · mono`.
#[derive(Clone, Debug, PartialEq)]
pub struct Constant {
    /// `I_5`, `g_2`.
    pub name: String,
    /// Its definition in the parameters.
    pub definition: ParamPoly,
    /// Its value.
    pub value: f64,
}

/// One term `factor · K · monomial` of an entry.
#[derive(Clone, Debug, PartialEq)]
pub struct TableTerm {
    /// The monomial in the tables' variables.
    pub monomial: Monomial,
    /// The numeric factor `λ`.
    pub factor: f64,
    /// The constant `K` (index into [`Tables::constants`]).
    pub constant: usize,
    /// A proven bound on the term's magnitude over the joint ranges.
    pub bound: f64,
}

/// One entry of the tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Which entry.
    pub kind: EntryKind,
    /// The terms kept, largest bound first.
    pub terms: Vec<TableTerm>,
    /// Number of terms dropped.
    pub dropped: usize,
    /// Proven bound on the error of the kept terms (0 when nothing was dropped).
    pub error_bound: f64,
}

/// How to write the tables.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TableOptions {
    /// Relative significance threshold (0: exact).
    pub tolerance: f64,
    /// Angle offsets per joint, `θ_j = q_j + o_j` (empty: none). The tables are written in `θ`.
    pub offsets: Vec<f64>,
}

/// The explicit model as tables (see the module documentation).
#[derive(Clone, Debug)]
pub struct Tables {
    /// The model's name.
    pub model_name: String,
    /// Joint names.
    pub joint_names: Vec<String>,
    /// Which joints are prismatic.
    pub prismatic: Vec<bool>,
    /// The options used.
    pub options: TableOptions,
    /// The tables' variables.
    pub vars: Vec<Var>,
    /// The constants, `I_k` then `g_k`, each in order of first use.
    pub constants: Vec<Constant>,
    /// The symbols and their values.
    pub parameters: super::Parameters,
    /// `a_ij` (`i ≤ j`, row by row), `b_ijk`, `c_ij`, `g_i`: every entry, zero ones included.
    pub entries: Vec<Entry>,
}

/// `P = λ K`: `(λ, K)` with `λ` the most frequent coefficient magnitude, `K`'s value ≥ 0.
fn normalize(p: &ParamPoly, values: &[f64]) -> (f64, ParamPoly, f64) {
    let round = |x: f64| f64::from_bits((x.abs().to_bits() + (1 << 11)) & !((1u64 << 12) - 1));
    let mut counts: Vec<(u64, usize, f64)> = Vec::new();
    for &(_, c) in p {
        let r = round(c).to_bits();
        match counts.iter_mut().find(|x| x.0 == r) {
            Some(x) => x.1 += 1,
            None => counts.push((r, 1, c.abs())),
        }
    }
    let mut lambda = counts
        .iter()
        .fold(
            (0, 1.0),
            |best, x| if x.1 > best.0 { (x.1, x.2) } else { best },
        )
        .1;
    let mut k: ParamPoly = p.iter().map(|&(m, c)| (m, c / lambda)).collect();
    let mut value: f64 = k.iter().map(|(m, c)| c * m.eval(values)).sum();
    if value < 0.0 {
        lambda = -lambda;
        value = -value;
        for x in &mut k {
            x.1 = -x.1;
        }
    }
    (lambda, k, value)
}

/// The interval of each joint's `θ` (`None`: unbounded, or a full turn).
fn ranges(chain: &Chain, offsets: &[f64]) -> Vec<Option<(f64, f64)>> {
    (0..chain.n())
        .map(|j| {
            let (lo, hi) = (chain.lower[j], chain.upper[j]);
            (lo.is_finite() && hi.is_finite()).then(|| {
                let o = offsets.get(j).copied().unwrap_or(0.0);
                (lo + o, hi + o)
            })
        })
        .collect()
}

impl Tables {
    pub(crate) fn new(model: &ExplicitModel, options: &TableOptions) -> Tables {
        let chain = &model.chain;
        let n = chain.n();
        let values = chain.params.values();
        let blocks = Blocks::new(chain);
        let mut registry = Registry::default();
        let offsets: Vec<f64> = (0..n)
            .map(|j| options.offsets.get(j).copied().unwrap_or(0.0))
            .collect();
        let ranges = ranges(chain, &offsets);
        let mut kinds = Vec::new();
        for i in 0..n {
            for j in i..n {
                kinds.push(EntryKind::Mass(i, j));
            }
        }
        for i in 0..n {
            for j in 0..n {
                for k in j + 1..n {
                    kinds.push(EntryKind::Coriolis(i, j, k));
                }
            }
        }
        for i in 0..n {
            for j in 0..n {
                kinds.push(EntryKind::Centrifugal(i, j));
            }
        }
        kinds.extend((0..n).map(EntryKind::Gravity));
        // provisional constants, keyed by their rounded definition
        let mut provisional: Vec<(ParamPoly, f64)> = Vec::new();
        let mut index: HashMap<Vec<(Mono, u64)>, usize> = HashMap::new();
        let key = |k: &ParamPoly| -> Vec<(Mono, u64)> {
            k.iter()
                .map(|&(m, c)| (m, (c.to_bits() + (1 << 11)) & !((1u64 << 12) - 1)))
                .collect()
        };
        let mut entries = Vec::with_capacity(kinds.len());
        for kind in kinds {
            let expr = match kind {
                EntryKind::Mass(i, j) => model.mass(i, j),
                EntryKind::Coriolis(i, j, k) => model.coriolis(i, j, k),
                EntryKind::Centrifugal(i, j) => model.centrifugal(i, j),
                EntryKind::Gravity(i) => model.gravity(i),
            };
            let shifted = expr.shifted(&offsets);
            let mut terms: Vec<TableTerm> = expand(&shifted, chain, &blocks, &mut registry)
                .into_iter()
                .map(|(monomial, poly)| {
                    let (factor, k, value) = normalize(&poly, &values);
                    let constant = *index.entry(key(&k)).or_insert_with(|| {
                        provisional.push((k, value));
                        provisional.len() - 1
                    });
                    let sup = monomial_sup(&monomial, &registry.vars, &ranges);
                    TableTerm {
                        monomial,
                        factor,
                        constant,
                        bound: (factor * value).abs() * sup,
                    }
                })
                .collect();
            terms.sort_by(|a, b| b.bound.total_cmp(&a.bound));
            let largest = terms
                .iter()
                .map(|t| t.bound)
                .filter(|b| b.is_finite())
                .fold(0.0, f64::max);
            let cut = options.tolerance * largest;
            // with a tolerance, terms that vanish at the parameters' values go too
            let keep =
                |t: &TableTerm| t.bound >= cut && (options.tolerance == 0.0 || t.bound > 0.0);
            let (kept, dropped): (Vec<_>, Vec<_>) = terms.into_iter().partition(keep);
            let error_bound = dropped.iter().map(|t| t.bound).sum::<f64>() * (1.0 + 1e-12);
            entries.push(Entry {
                kind,
                terms: kept,
                dropped: dropped.len(),
                error_bound,
            });
        }
        // number the constants in order of first use, I_k then g_k
        let gravity_param = chain.gravity;
        let is_gravity = |k: &ParamPoly| {
            gravity_param.is_some_and(|g| k.iter().any(|(m, _)| m.params().any(|p| p == g)))
        };
        let mut renumber: Vec<Option<usize>> = vec![None; provisional.len()];
        let mut constants = Vec::new();
        for pass_gravity in [false, true] {
            let mut count = 0;
            for e in &mut entries {
                for t in &mut e.terms {
                    let (k, value) = &provisional[t.constant];
                    if is_gravity(k) != pass_gravity {
                        continue;
                    }
                    if renumber[t.constant].is_none() {
                        count += 1;
                        let prefix = if pass_gravity { "g" } else { "I" };
                        constants.push(Constant {
                            name: format!("{prefix}_{count}"),
                            definition: k.clone(),
                            value: *value,
                        });
                        renumber[t.constant] = Some(constants.len() - 1);
                    }
                }
            }
        }
        for e in &mut entries {
            for t in &mut e.terms {
                t.constant = renumber[t.constant].expect("numbered");
            }
        }
        Tables {
            model_name: chain.model_name.clone(),
            joint_names: chain.joints.iter().map(|j| j.name.clone()).collect(),
            prismatic: chain.joints.iter().map(|j| j.prismatic).collect(),
            options: TableOptions {
                tolerance: options.tolerance,
                offsets,
            },
            vars: registry.vars,
            constants,
            parameters: chain.params.clone(),
            entries,
        }
    }

    /// Number of joints.
    #[must_use]
    pub fn n(&self) -> usize {
        self.joint_names.len()
    }

    /// The entry of a kind.
    #[must_use]
    pub fn entry(&self, kind: EntryKind) -> Option<&Entry> {
        self.entries.iter().find(|e| e.kind == kind)
    }

    /// The value of an entry (its kept terms) at the joint coordinates `q` (the model's, not
    /// the offset angles).
    #[must_use]
    pub fn eval(&self, entry: &Entry, q: &[f64]) -> f64 {
        let theta: Vec<f64> = q
            .iter()
            .zip(&self.options.offsets)
            .map(|(q, o)| q + o)
            .collect();
        entry
            .terms
            .iter()
            .map(|t| {
                t.factor
                    * self.constants[t.constant].value
                    * monomial_value(&t.monomial, &self.vars, &theta)
            })
            .sum()
    }
}
