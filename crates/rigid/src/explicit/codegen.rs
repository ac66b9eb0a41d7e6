//! Code from the tables: `mass_matrix(q)`, `coriolis_centrifugal(q, v)` (the vector `c(q, v)`),
//! `gravity(q)` and the constants, in Rust, C or Python, straight-line and allocation-free.
//!
//! Each function computes the sines and cosines it needs once (`sin_cos` per joint, the
//! cumulative angles of parallel joints by angle addition, `s23 = s2 c3 + c2 s3`), then every
//! monomial it needs once, each as the product of a shorter one and one factor (a trie of
//! prefixes: `C2·S23` and `C2·C23` share `c2`), then each entry as a sum of
//! `factor · constant · monomial` (a numeric factor times a named constant, folded by the
//! compiler). Long sums are accumulated in chunks of 32 terms, which keeps compilers' parse
//! trees shallow.

use super::paper::Monomial;
use super::tables::{EntryKind, Tables};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// A target language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// Rust: a module with `pub fn`s over fixed-size arrays.
    Rust,
    /// C99: functions writing into caller-supplied arrays.
    C,
    /// Python 3: a module using only `math`.
    Python,
}

/// One factor of a monomial: `c_v`, `s_v` or a prismatic `q_j`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Atom {
    Cos(usize),
    Sin(usize),
}

/// A node of the monomial trie: `parent · atom` (or the atom alone).
pub(crate) struct Node {
    pub parent: Option<usize>,
    pub atom: Atom,
    pub name: String,
}

/// Which function a body computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Output {
    /// `M[i][j]`, upper triangle (the caller mirrors it).
    Mass,
    /// `c[i] += b_ijk v_j v_k` and `c_ij v_j²`.
    Coriolis,
    /// `g[i]`.
    Gravity,
}

/// Above this many terms, a Rust or C function is written as tables and loops: compilers take
/// time growing faster than linearly with the size of one function (gcc -O1 needs 3 s for the
/// Panda's 3 300-term mass matrix as straight-line code and more than 3 minutes for its
/// 26 000-term Coriolis terms).
pub(crate) const TABLE_LIMIT: usize = 2000;

/// Writes code for one table set.
pub(crate) struct Emitter<'a> {
    pub t: &'a Tables,
    pub lang: Lang,
    pub out: String,
}

/// The name of a variable's sine or cosine (`s2`, `c23`, `s2m3`, `s9_10`), or of a prismatic
/// displacement (`q7`).
fn var_name(joints: &[(usize, i8)], prismatic: bool, sin: bool) -> String {
    let simple = joints.iter().all(|&(j, e)| j < 9 && e > 0);
    let mut s = String::from(if prismatic {
        "q"
    } else if sin {
        "s"
    } else {
        "c"
    });
    for (i, &(j, e)) in joints.iter().enumerate() {
        if i > 0 && !simple {
            s.push(if e > 0 { '_' } else { 'm' });
        }
        s.push_str(&(j + 1).to_string());
    }
    s
}

const CHUNK: usize = 32;

impl Emitter<'_> {
    pub fn line(&mut self, s: &str) {
        let end = if self.lang == Lang::Python { "" } else { ";" };
        let _ = writeln!(self.out, "    {s}{end}");
    }

    pub fn declare(&mut self, name: &str, e: &str, mutable: bool) {
        let s = match (self.lang, mutable) {
            (Lang::Rust, false) => format!("let {name} = {e}"),
            (Lang::Rust, true) => format!("let mut {name} = {e}"),
            (Lang::C, false) => format!("const double {name} = {e}"),
            (Lang::C, true) => format!("double {name} = {e}"),
            (Lang::Python, _) => format!("{name} = {e}"),
        };
        self.line(&s);
    }

    pub(crate) fn atom_name(&self, a: Atom) -> String {
        let (v, sin) = match a {
            Atom::Cos(v) => (v, false),
            Atom::Sin(v) => (v, true),
        };
        var_name(&self.t.vars[v].joints, self.t.vars[v].prismatic, sin)
    }

    /// Declares the sines and cosines the atoms need: of each joint angle (`s{j}`, `c{j}`, one
    /// `sin_cos` when both are needed), then of the cumulative angles by angle addition, then
    /// the prismatic displacements.
    fn trig(&mut self, atoms: &BTreeSet<Atom>) {
        // (joints of an angle, sine?) needed, closed under angle addition's inputs
        let mut need: BTreeSet<(Vec<(usize, i8)>, bool)> = BTreeSet::new();
        let mut prismatic = BTreeSet::new();
        for &a in atoms {
            let (v, sin) = match a {
                Atom::Cos(v) => (v, false),
                Atom::Sin(v) => (v, true),
            };
            let var = &self.t.vars[v];
            if var.prismatic {
                prismatic.insert(v);
            } else {
                need.insert((var.joints.clone(), sin));
            }
        }
        let longest = need.iter().map(|x| x.0.len()).max().unwrap_or(0);
        for len in (2..=longest).rev() {
            let heads: Vec<Vec<(usize, i8)>> = need
                .iter()
                .filter(|x| x.0.len() == len)
                .map(|x| x.0.clone())
                .collect();
            for p in heads {
                let (head, last) = (p[..len - 1].to_vec(), p[len - 1]);
                for sin in [true, false] {
                    need.insert((head.clone(), sin));
                    need.insert((vec![(last.0, 1)], sin));
                }
            }
        }
        let name = |joints: &[(usize, i8)], sin: bool| var_name(joints, false, sin);
        for len in 1..=longest {
            let angles: BTreeSet<Vec<(usize, i8)>> = need
                .iter()
                .filter(|x| x.0.len() == len)
                .map(|x| x.0.clone())
                .collect();
            for p in angles {
                let (want_s, want_c) = (
                    need.contains(&(p.clone(), true)),
                    need.contains(&(p.clone(), false)),
                );
                let (s, c) = (name(&p, true), name(&p, false));
                if len == 1 {
                    let j = p[0].0;
                    let o = self.t.options.offsets.get(j).copied().unwrap_or(0.0);
                    let angle = if o == 0.0 {
                        format!("q[{j}]")
                    } else {
                        format!("(q[{j}] + {})", literal(o))
                    };
                    let stmt = match (self.lang, want_s, want_c) {
                        (Lang::Rust, true, true) => format!("let ({s}, {c}) = {angle}.sin_cos()"),
                        (Lang::Rust, true, false) => format!("let {s} = {angle}.sin()"),
                        (Lang::Rust, _, _) => format!("let {c} = {angle}.cos()"),
                        (Lang::C, true, true) => {
                            format!("const double {s} = sin({angle}), {c} = cos({angle})")
                        }
                        (Lang::C, true, false) => format!("const double {s} = sin({angle})"),
                        (Lang::C, _, _) => format!("const double {c} = cos({angle})"),
                        (Lang::Python, true, true) => {
                            format!("{s}, {c} = math.sin({angle}), math.cos({angle})")
                        }
                        (Lang::Python, true, false) => format!("{s} = math.sin({angle})"),
                        (Lang::Python, _, _) => format!("{c} = math.cos({angle})"),
                    };
                    self.line(&stmt);
                    continue;
                }
                let (head, last) = (&p[..len - 1], p[len - 1]);
                let (sh, ch) = (name(head, true), name(head, false));
                let (sj, cj) = (format!("s{}", last.0 + 1), format!("c{}", last.0 + 1));
                let (pm, mp) = if last.1 > 0 { ("+", "-") } else { ("-", "+") };
                // sin(A ± B) = sA cB ± cA sB, cos(A ± B) = cA cB ∓ sA sB
                if want_s {
                    self.declare(&s, &format!("{sh} * {cj} {pm} {ch} * {sj}"), false);
                }
                if want_c {
                    self.declare(&c, &format!("{ch} * {cj} {mp} {sh} * {sj}"), false);
                }
            }
        }
        for v in prismatic {
            let j = self.t.vars[v].joints[0].0;
            let n = var_name(&self.t.vars[v].joints, true, true);
            self.declare(&n, &format!("q[{j}]"), false);
        }
    }

    /// The trie of every monomial of `monomials`: nodes `(prefix, parent node, last atom)` in
    /// creation order (a parent before its children; single atoms are nodes without a parent),
    /// and each monomial's node.
    fn trie(&self, monomials: &BTreeSet<Monomial>) -> (Vec<Node>, BTreeMap<Monomial, usize>) {
        let atoms = |m: &Monomial| -> Vec<Atom> {
            let mut a = Vec::new();
            for &(v, (c, s)) in m {
                if c == 1 {
                    a.push(Atom::Cos(v));
                }
                a.extend(std::iter::repeat_n(Atom::Sin(v), usize::from(s)));
            }
            a
        };
        let mut index: BTreeMap<Vec<Atom>, usize> = BTreeMap::new();
        let mut nodes: Vec<Node> = Vec::new();
        let mut out = BTreeMap::new();
        for m in monomials {
            let a = atoms(m);
            if a.is_empty() {
                continue;
            }
            for r in 1..=a.len() {
                if index.contains_key(&a[..r]) {
                    continue;
                }
                let parent = (r > 1).then(|| index[&a[..r - 1]]);
                let name = match parent {
                    None => self.atom_name(a[0]),
                    // named by its factors: s23_s4_s5
                    Some(p) => format!("{}_{}", nodes[p].name, self.atom_name(a[r - 1])),
                };
                nodes.push(Node {
                    parent,
                    atom: a[r - 1],
                    name,
                });
                index.insert(a[..r].to_vec(), nodes.len() - 1);
            }
            out.insert(m.clone(), index[&a]);
        }
        (nodes, out)
    }

    /// The terms of an entry as strings `± 2.0 * I_5 * m3` (first without a leading `+`).
    fn terms(
        &self,
        kind: EntryKind,
        monos: &BTreeMap<Monomial, usize>,
        nodes: &[Node],
    ) -> Vec<String> {
        let e = self.t.entry(kind).expect("every entry exists");
        e.terms
            .iter()
            .filter(|t| self.t.constants[t.constant].value != 0.0)
            .map(|t| {
                let k = &self.t.constants[t.constant].name;
                let mut body = if t.factor.abs() == 1.0 {
                    k.clone()
                } else {
                    format!("{} * {k}", literal(t.factor.abs()))
                };
                if let Some(&m) = monos.get(&t.monomial) {
                    body = format!("{body} * {}", nodes[m].name);
                }
                format!("{}{body}", if t.factor < 0.0 { "-" } else { "+" })
            })
            .collect()
    }

    /// `target = Σ terms` (declared as a new variable if `declare`), in chunks.
    pub fn sum(&mut self, target: &str, terms: &[String], declare: bool) {
        let join = |c: &[String]| -> String {
            let mut s = String::new();
            for (i, t) in c.iter().enumerate() {
                let (sign, body) = t.split_at(1);
                match (i, sign) {
                    (0, "+") => s.push_str(body),
                    (0, _) => {
                        s.push('-');
                        s.push_str(body);
                    }
                    (_, _) => {
                        let _ = write!(s, " {sign} {body}");
                    }
                }
            }
            if s.is_empty() {
                s.push_str("0.0");
            }
            s
        };
        let mut chunks = terms.chunks(CHUNK);
        let first = join(chunks.next().unwrap_or(&[]));
        let rest: Vec<&[String]> = chunks.collect();
        if declare {
            self.declare(target, &first, !rest.is_empty());
        } else {
            self.line(&format!("{target} = {first}"));
        }
        for c in rest {
            self.line(&format!("{target} += {}", join(c)));
        }
    }

    /// The monomials used by some entries (terms with a zero constant left out).
    fn needs(&self, kinds: &[EntryKind]) -> BTreeSet<Monomial> {
        let mut monos = BTreeSet::new();
        for &k in kinds {
            let terms = &self.t.entry(k).expect("exists").terms;
            for t in terms
                .iter()
                .filter(|t| self.t.constants[t.constant].value != 0.0)
            {
                monos.insert(t.monomial.clone());
            }
        }
        monos
    }
}

/// The local of a Coriolis or centrifugal entry: `b_123`, `c_21`, `b_1_2_10` (never a trigonometric
/// name such as `c23`).
fn temp_name(k: EntryKind) -> String {
    let l = k.label().replace(',', "_");
    format!("{}_{}", &l[..1], &l[1..])
}

/// A float literal valid in Rust, C and Python (`2.0`, `1e-5`, `-0.5`).
pub(crate) fn literal(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

impl Emitter<'_> {
    /// The non-zero entries an output function computes.
    fn kinds(&self, out: Output) -> Vec<EntryKind> {
        let n = self.t.n();
        let mut k = Vec::new();
        for i in 0..n {
            match out {
                Output::Mass => k.extend((i..n).map(|j| EntryKind::Mass(i, j))),
                Output::Gravity => k.push(EntryKind::Gravity(i)),
                Output::Coriolis => {
                    for j in 0..n {
                        k.extend((j + 1..n).map(|l| EntryKind::Coriolis(i, j, l)));
                        k.push(EntryKind::Centrifugal(i, j));
                    }
                }
            }
        }
        k.retain(|&x| !self.is_zero(x));
        k
    }

    /// Whether an output function depends on `q` (has a non-constant term).
    pub fn uses_q(&self, out: Output) -> bool {
        self.needs(&self.kinds(out)).iter().any(|m| !m.is_empty())
    }

    /// Whether an output function has no non-zero entry.
    pub fn is_empty(&self, out: Output) -> bool {
        self.kinds(out).is_empty()
    }

    /// The statements of an output function (after its outputs are zeroed): the sines and
    /// cosines, the monomials, each entry's sum and where it goes. Straight-line code, or tables
    /// and loops above [`TABLE_LIMIT`] terms (Rust and C).
    pub fn function_body(&mut self, out: Output) {
        let kinds = self.kinds(out);
        let monos = self.needs(&kinds);
        let (nodes, index) = self.trie(&monos);
        self.trig(&nodes.iter().map(|n| n.atom).collect());
        let total: usize = kinds
            .iter()
            .map(|&k| self.t.entry(k).map_or(0, |e| e.terms.len()))
            .sum();
        if self.lang != Lang::Python && total > TABLE_LIMIT {
            self.table_body(out, &kinds, &nodes, &index);
            return;
        }
        for n in &nodes {
            if let Some(p) = n.parent {
                let e = format!("{} * {}", nodes[p].name, self.atom_name(n.atom));
                self.declare(&n.name, &e, false);
            }
        }
        for &k in &kinds {
            let terms = self.terms(k, &index, &nodes);
            match k {
                EntryKind::Mass(i, j) => {
                    self.sum(&format!("{}[{i}][{j}]", self.mass_name()), &terms, false)
                }
                EntryKind::Gravity(i) => self.sum(&format!("g[{i}]"), &terms, false),
                EntryKind::Coriolis(i, j, l) => {
                    let name = temp_name(k);
                    self.sum(&name, &terms, true);
                    self.line(&format!("c[{i}] += {name} * v[{j}] * v[{l}]"));
                }
                EntryKind::Centrifugal(i, j) => {
                    let name = temp_name(k);
                    self.sum(&name, &terms, true);
                    self.line(&format!("c[{i}] += {name} * v[{j}] * v[{j}]"));
                }
            }
        }
    }

    /// The mass matrix's name: `M` in C, `m` otherwise.
    pub fn mass_name(&self) -> &'static str {
        if self.lang == Lang::C {
            "M"
        } else {
            "m"
        }
    }

    /// Whether an entry has no term (or only terms whose constant is zero).
    pub fn is_zero(&self, k: EntryKind) -> bool {
        self.t.entry(k).is_none_or(|e| {
            e.terms
                .iter()
                .all(|t| self.t.constants[t.constant].value == 0.0)
        })
    }
}

impl Tables {
    /// The model as code in `lang` (see the module documentation); `command` is quoted in the
    /// header as the command that generated it.
    #[must_use]
    pub fn to_code(&self, lang: Lang, command: &str) -> String {
        let mut e = Emitter {
            t: self,
            lang,
            out: String::new(),
        };
        super::langs::write(&mut e, command);
        e.out
    }
}
