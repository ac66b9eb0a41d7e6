//! The tables as text or LaTeX, laid out like Armstrong, Khatib & Burdick (1986): each entry as
//! an expression in the abbreviated constants, then `≈` its numeric form with three significant
//! digits, then the proven bound on what pruning dropped; the constants with their definitions
//! and values; the parameters.

use super::paper::{Monomial, ParamPoly};
use super::tables::{EntryKind, Tables};
use std::fmt::Write;

/// Text or LaTeX.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Style {
    Text,
    Latex,
}

/// `x` with `digits` significant digits: `6.82`, `0.771`, `-2.50e-3` (LaTeX `2.50 \times 10^{-3}`).
pub(crate) fn number(x: f64, digits: usize, style: Style) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let e = x.abs().log10().floor() as i32;
    if (-2..4).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        return format!("{x:.decimals$}");
    }
    let m = format!("{:.*e}", digits - 1, x);
    let (mant, exp) = m.split_once('e').unwrap_or((&m, "0"));
    match style {
        Style::Text => format!("{mant}e{exp}"),
        Style::Latex => format!("{mant} \\times 10^{{{exp}}}"),
    }
}

/// A factor or coefficient: up to 6 significant digits, trailing zeros trimmed (`2`, `0.5`,
/// `1.41421`, `2.5e-7`).
pub(crate) fn coefficient(x: f64, style: Style) -> String {
    let s = number(x, 6, style);
    let trim = |m: &str| -> String {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m.to_string()
        }
    };
    match s.split_once(['e', ' ']) {
        Some((mant, rest)) => {
            let sep = if s.contains(' ') { " " } else { "e" };
            format!("{}{sep}{rest}", trim(mant))
        }
        None => trim(&s),
    }
}

fn superscript(p: usize, style: Style) -> String {
    match (style, p) {
        (_, 1) => String::new(),
        (Style::Text, 2) => "²".into(),
        (Style::Text, 3) => "³".into(),
        (Style::Text, _) => format!("^{p}"),
        (Style::Latex, _) => format!("^{{{p}}}"),
    }
}

impl Tables {
    /// The tables as text, laid out like the 1986 paper's (see the module documentation).
    #[must_use]
    pub fn to_text(&self) -> String {
        self.write(Style::Text)
    }

    /// The tables as a LaTeX document (`amsmath`).
    #[must_use]
    pub fn to_latex(&self) -> String {
        self.write(Style::Latex)
    }

    /// A monomial as the text tables write it: `C2·S23`, `SS5`, `SC4` (empty for `1`).
    #[must_use]
    pub fn monomial_label(&self, m: &Monomial) -> String {
        self.monomial_text(m, Style::Text)
    }

    /// A monomial: `C2·S23`, `SS5`, `SC4`, `S5^3`, `q7²` (LaTeX `\mathrm{C}_{2} \mathrm{S}_{23}`).
    pub(crate) fn monomial_text(&self, m: &Monomial, style: Style) -> String {
        let factor = |name: &str, label: &str, power: usize| match style {
            Style::Text => format!("{name}{label}{}", superscript(power, style)),
            Style::Latex => format!(
                "\\mathrm{{{name}}}_{{{label}}}{}",
                superscript(power, style)
            ),
        };
        let parts: Vec<String> = m
            .iter()
            .map(|&(v, (c, s))| {
                let label = self.vars[v].label();
                let s = usize::from(s);
                if self.vars[v].prismatic {
                    return match style {
                        Style::Text => format!("q{label}{}", superscript(s, style)),
                        Style::Latex => format!("q_{{{label}}}{}", superscript(s, style)),
                    };
                }
                match (c, s) {
                    (1, 0) => factor("C", &label, 1),
                    (0, 2) => factor("SS", &label, 1),
                    (1, 1) => factor("SC", &label, 1),
                    (0, s) => factor("S", &label, s),
                    (_, s) => {
                        let sep = if style == Style::Text { "·" } else { " " };
                        format!("{}{sep}{}", factor("C", &label, 1), factor("S", &label, s))
                    }
                }
            })
            .collect();
        let sep = if style == Style::Text { "·" } else { " " };
        parts.join(sep)
    }

    /// A parameter polynomial: `ZZ1 + YY2 + 2·px3·MX3 + M3·px3²`.
    pub(crate) fn poly_text(&self, p: &ParamPoly, style: Style) -> String {
        let mut out = String::new();
        for (i, (mono, c)) in p.iter().enumerate() {
            let mut names: Vec<(String, usize)> = Vec::new();
            for q in mono.params() {
                let name = self.parameters.get(q).name.clone();
                match names.last_mut() {
                    Some(last) if last.0 == name => last.1 += 1,
                    _ => names.push((name, 1)),
                }
            }
            let sep = if style == Style::Text { "·" } else { " " };
            let body: Vec<String> = names
                .iter()
                .map(|(n, k)| match style {
                    Style::Text => format!("{n}{}", superscript(*k, style)),
                    Style::Latex => format!("\\mathit{{{n}}}{}", superscript(*k, style)),
                })
                .collect();
            signed(&mut out, *c, &body.join(sep), i == 0, style);
        }
        if out.is_empty() {
            out.push('0');
        }
        out
    }

    /// A constant's name: `I_5` (LaTeX `I_{5}`).
    pub(crate) fn constant_name(&self, k: usize, style: Style) -> String {
        let name = &self.constants[k].name;
        match style {
            Style::Text => name.clone(),
            Style::Latex => {
                let (a, b) = name.split_once('_').unwrap_or((name, ""));
                format!("{a}_{{{b}}}")
            }
        }
    }

    fn entry_label(kind: EntryKind, style: Style) -> String {
        let l = kind.label();
        match style {
            Style::Text => l,
            Style::Latex => format!("{}_{{{}}}", &l[..1], &l[1..]),
        }
    }

    /// The tables, as text (`Style::Text`) or as a LaTeX document.
    pub(crate) fn write(&self, style: Style) -> String {
        let mut o = String::new();
        let latex = style == Style::Latex;
        if latex {
            o.push_str("\\documentclass{article}\n\\usepackage{amsmath}\n\\usepackage[margin=2cm]{geometry}\n\\allowdisplaybreaks\n\\begin{document}\n");
        }
        for line in self.preamble() {
            if latex {
                let _ = writeln!(o, "{}\n", latex_escape(&line));
            } else {
                let _ = writeln!(o, "{line}");
            }
        }
        type Select = fn(&EntryKind) -> bool;
        let sections: [(&str, Select); 4] = [
            (
                "The kinetic-energy matrix a_ij = M_ij (i ≤ j; a_ji = a_ij)",
                |k| matches!(k, EntryKind::Mass(..)),
            ),
            (
                "The Coriolis terms b_ijk (j < k): c_i(q, q̇) = Σ b_ijk q̇_j q̇_k + Σ c_ij q̇_j²",
                |k| matches!(k, EntryKind::Coriolis(..)),
            ),
            ("The centrifugal terms c_ij", |k| {
                matches!(k, EntryKind::Centrifugal(..))
            }),
            ("The gravity terms g_i", |k| {
                matches!(k, EntryKind::Gravity(..))
            }),
        ];
        for (t, (title, select)) in sections.iter().enumerate() {
            self.write_section(&mut o, style, t + 1, title, *select);
        }
        self.write_constants(&mut o, style, sections.len() + 1);
        if latex {
            o.push_str("\\end{document}\n");
        }
        o
    }

    /// `θ2 = q2 + π`, one per non-zero angle offset (`theta` names the angle).
    pub(crate) fn offsets_text(&self, theta: &str, angle: fn(f64) -> String) -> Vec<String> {
        let offsets = self.options.offsets.iter().enumerate();
        offsets
            .filter(|(_, &o)| o != 0.0)
            .map(|(j, &o)| format!("{theta}{} = q{} + {}", j + 1, j + 1, angle(o)))
            .collect()
    }

    fn preamble(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "Explicit dynamic model of \"{}\" ({} joints), derived by rigid explicit.",
            self.model_name,
            self.n()
        )];
        let offsets = self.offsets_text("θ", angle_text);
        let angles = if offsets.is_empty() {
            "Angles θj = qj (the model's joint coordinates)".to_string()
        } else {
            format!("Angles θj = qj except {}", offsets.join(", "))
        };
        lines.push(format!(
            "{angles}; Cj = cos θj, Sj = sin θj, S23 = sin(θ2 + θ3) (consecutive parallel joints), SSj = sin² θj, SCj = sin θj cos θj; qj of a prismatic joint is its displacement. SI units."
        ));
        if self.options.tolerance > 0.0 {
            lines.push(format!(
                "Tolerance {}: a term is dropped when its largest magnitude over the joint ranges is below {} times the largest term of its entry; |error| ≤ the bound printed with the entry (proven: the sum of the dropped terms' largest magnitudes).",
                self.options.tolerance, self.options.tolerance
            ));
        } else {
            lines.push("Exact: every term is kept.".into());
        }
        lines
    }

    fn write_section(
        &self,
        o: &mut String,
        style: Style,
        number_: usize,
        title: &str,
        select: fn(&EntryKind) -> bool,
    ) {
        let latex = style == Style::Latex;
        if latex {
            let _ = writeln!(o, "\\section*{{Table {number_}. {}}}", latex_escape(title));
            o.push_str("\\begin{align*}\n");
        } else {
            let _ = writeln!(o, "\nTable {number_}. {title}");
        }
        let mut zeros = Vec::new();
        for e in self.entries.iter().filter(|e| select(&e.kind)) {
            if e.terms.is_empty() && e.dropped == 0 {
                zeros.push(Self::entry_label(e.kind, style));
                continue;
            }
            let label = Self::entry_label(e.kind, style);
            let mut sym = String::new();
            let mut num = String::new();
            for (i, t) in e.terms.iter().enumerate() {
                let mono = self.monomial_text(&t.monomial, style);
                let k = self.constant_name(t.constant, style);
                let sep = if latex { " " } else { "·" };
                let mag = t.factor.abs();
                let body_sym = match (mag == 1.0, mono.is_empty()) {
                    (true, true) => k,
                    (true, false) => format!("{k}{sep}{mono}"),
                    (false, true) => format!("{}{sep}{k}", coefficient(mag, style)),
                    (false, false) => format!("{}{sep}{k}{sep}{mono}", coefficient(mag, style)),
                };
                signed_body(&mut sym, t.factor < 0.0, &body_sym, i == 0);
                let value = t.factor * self.constants[t.constant].value;
                let n = number(value.abs(), 3, style);
                let body_num = if mono.is_empty() {
                    n
                } else {
                    format!("{n}{sep}{mono}")
                };
                signed_body(&mut num, value < 0.0, &body_num, i == 0);
                if latex && i % 5 == 4 && i + 1 < e.terms.len() {
                    sym.push_str(" \\\\\n  &\\quad ");
                    num.push_str(" \\\\\n  &\\quad ");
                }
            }
            if sym.is_empty() {
                sym.push('0');
                num.push('0');
            }
            let bound = if e.dropped > 0 {
                format!(
                    "|error| ≤ {} ({} terms dropped)",
                    number(e.error_bound, 2, Style::Text),
                    e.dropped
                )
            } else {
                String::new()
            };
            if latex {
                let _ = writeln!(o, "{label} &= {sym} \\\\\n  &\\approx {num} \\\\");
                if !bound.is_empty() {
                    let _ = writeln!(o, "  &\\quad \\text{{{}}} \\\\", latex_escape(&bound));
                }
            } else {
                let _ = writeln!(o, "{label} = {sym};");
                let pad = " ".repeat(label.chars().count());
                let _ = writeln!(
                    o,
                    "{pad} ≈ {num}{}{bound}",
                    if bound.is_empty() { "" } else { "      " }
                );
            }
        }
        if latex {
            o.push_str("\\end{align*}\n");
            if !zeros.is_empty() {
                let _ = writeln!(o, "Zero: ${}$.\n", zeros.join(", "));
            }
        } else if !zeros.is_empty() {
            let _ = writeln!(o, "zero: {}", zeros.join(", "));
        }
    }

    fn write_constants(&self, o: &mut String, style: Style, number_: usize) {
        let title = "The abbreviated constants, in order of first use (definition = value)";
        let latex = style == Style::Latex;
        if latex {
            let _ = writeln!(
                o,
                "\\section*{{Table {number_}. {}}}\n\\begin{{align*}}",
                latex_escape(title)
            );
        } else {
            let _ = writeln!(o, "\nTable {number_}. {title}");
        }
        for (k, c) in self.constants.iter().enumerate() {
            let name = self.constant_name(k, style);
            let def = self.poly_text(&c.definition, style);
            let value = coefficient(c.value, style);
            if latex {
                let _ = writeln!(o, "{name} &= {def} = {value} \\\\");
            } else {
                let _ = writeln!(o, "{name} = {def} = {value}");
            }
        }
        if latex {
            o.push_str("\\end{align*}\n");
            let _ = writeln!(
                o,
                "\\section*{{Table {}. The parameters}}\n\\begin{{align*}}",
                number_ + 1
            );
        } else {
            let _ = writeln!(
                o,
                "\nTable {}. The parameters (zero ones are not symbols)",
                number_ + 1
            );
        }
        for p in self.parameters.list() {
            if latex {
                let _ = writeln!(
                    o,
                    "\\mathit{{{}}} &= {} \\ \\mathrm{{{}}} \\\\",
                    p.name,
                    p.value,
                    latex_escape(p.unit())
                );
            } else {
                let _ = writeln!(o, "{} = {} {}", p.name, p.value, p.unit());
            }
        }
        if latex {
            o.push_str("\\end{align*}\n");
        }
    }
}

/// Appends `± body` (`-body` or `body` first).
fn signed_body(out: &mut String, negative: bool, body: &str, first: bool) {
    match (first, negative) {
        (true, false) => out.push_str(body),
        (true, true) => {
            out.push('-');
            out.push_str(body);
        }
        (false, false) => {
            out.push_str(" + ");
            out.push_str(body);
        }
        (false, true) => {
            out.push_str(" - ");
            out.push_str(body);
        }
    }
}

/// Appends `c·body` with its sign, the factor omitted when `|c| = 1`.
fn signed(out: &mut String, c: f64, body: &str, first: bool, style: Style) {
    let sep = if style == Style::Text { "·" } else { " " };
    let b = if c.abs() == 1.0 {
        body.to_string()
    } else if body.is_empty() {
        coefficient(c.abs(), style)
    } else {
        format!("{}{sep}{body}", coefficient(c.abs(), style))
    };
    signed_body(out, c < 0.0, &b, first);
}

/// `π`, `π/2`, `-π/2` or the number.
pub(crate) fn angle_text(o: f64) -> String {
    let r = o / std::f64::consts::FRAC_PI_2;
    if (r - r.round()).abs() < 1e-12 {
        match r.round() as i64 {
            1 => return "π/2".into(),
            2 => return "π".into(),
            -1 => return "-π/2".into(),
            -2 => return "-π".into(),
            3 => return "3π/2".into(),
            -3 => return "-3π/2".into(),
            _ => {}
        }
    }
    format!("{o}")
}

/// Plain text for LaTeX's text mode (math symbols in `$…$`).
fn latex_escape(s: &str) -> String {
    let mut out = String::new();
    for ch in s.replace("q̇", "$\\dot q$").chars() {
        match ch {
            '_' => out.push_str("\\_"),
            '&' | '%' | '#' => {
                out.push('\\');
                out.push(ch);
            }
            'θ' => out.push_str("$\\theta$"),
            'π' => out.push_str("$\\pi$"),
            'Σ' => out.push_str("$\\Sigma$"),
            '≤' => out.push_str("$\\le$"),
            '²' => out.push_str("$^2$"),
            '·' => out.push_str("$\\cdot$"),
            '|' => out.push_str("$|$"),
            _ => out.push(ch),
        }
    }
    out
}
