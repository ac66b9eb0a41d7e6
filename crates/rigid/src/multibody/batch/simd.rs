//! The lane kernels compiled for the vector unit the CPU has, chosen at run time: 8 doubles
//! with AVX-512, 4 with AVX2, 2 with SSE2 (the x86-64 baseline, and the width elsewhere).
//!
//! The kernels are written once, generic over the width `W` ([`super::lanes`]), and compiled
//! into a function per instruction set with `#[target_feature]`; everything they call is
//! `#[inline(always)]`, so the whole pack is compiled with the wider registers. This is
//! `core::arch`-style run-time dispatch (as [`trig`](crate::spatial::trig)'s `sin_cos` does)
//! rather than the `wide` crate, because `wide` fixes its width when the crate is compiled
//! (`-C target-cpu`), and a binary built for any x86-64 must still use AVX2 where it runs.

use super::aba::aba;
use super::crba::crba;
use super::derivatives::rnea_derivatives;
use super::pack::Pack;
use super::rnea::rnea;
use super::rows::{prefetch_rows, symmetric_out, transpose_in, transpose_out};
use crate::multibody::{Model, MultibodyError};

/// Which batch entry point a pack computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Algo {
    /// `τ = rnea(q, v, a)`: `nv` numbers per state.
    Rnea,
    /// `q̈ = aba(q, v, τ)`: `nv` numbers per state.
    Aba,
    /// `M(q)`, the full `nv x nv` matrix per state.
    Crba,
    /// `M(q)`'s lower triangle packed by columns, `nv (nv + 1) / 2` numbers per state.
    CrbaLower,
    /// `∂τ/∂q` and `∂τ/∂v` at `(q, v, a)`: two outputs, each the `nv x nv` matrix per state,
    /// row-major.
    RneaDerivatives,
}

/// The algorithms as the const parameter `A` of [`packs`], so that each (width, algorithm)
/// pair is a function of its own: the kernels are `#[inline(always)]`, and one function holding
/// them all took LLVM far longer to compile than the sum of its parts.
const RNEA: u8 = 0;
const ABA: u8 = 1;
const CRBA: u8 = 2;
const CRBA_LOWER: u8 = 3;
const RNEA_DERIVATIVES: u8 = 4;

impl Algo {
    /// The code of this algorithm for [`packs`].
    const fn code(self) -> u8 {
        match self {
            Self::Rnea => RNEA,
            Self::Aba => ABA,
            Self::Crba => CRBA,
            Self::CrbaLower => CRBA_LOWER,
            Self::RneaDerivatives => RNEA_DERIVATIVES,
        }
    }

    /// Numbers written per state (to each output: the derivatives have two).
    pub(crate) fn per_state(self, nv: usize) -> usize {
        match self {
            Self::Rnea | Self::Aba => nv,
            Self::Crba | Self::RneaDerivatives => nv * nv,
            Self::CrbaLower => nv * (nv + 1) / 2,
        }
    }
}

/// The lanes a [`Batch::new`](super::Batch::new) uses: `RIGID_LANES` (2, 4 or 8) when the
/// environment sets it, else [`native_width`]. Read once per process; a value other than 2, 4
/// or 8 is reported on stderr, naming the variable, and the native width is used.
pub(crate) fn default_width() -> usize {
    static WIDTH: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *WIDTH.get_or_init(|| {
        let value = std::env::var_os("RIGID_LANES").map(|v| v.to_string_lossy().into_owned());
        lanes_from(value.as_deref())
            .unwrap_or_else(|bad| {
                eprintln!(
                    "rigid: RIGID_LANES={bad:?} is not 2, 4 or 8: using the CPU's {} lanes",
                    native_width()
                );
                None
            })
            .unwrap_or_else(native_width)
    })
}

/// `RIGID_LANES`'s value: `None` when unset or empty, the width for `2`, `4` or `8`
/// (surrounding blanks allowed), else the value as given.
pub(crate) fn lanes_from(value: Option<&str>) -> Result<Option<usize>, String> {
    match value.map(str::trim) {
        None | Some("") => Ok(None),
        Some(v @ ("2" | "4" | "8")) => Ok(v.parse().ok()),
        Some(v) => Err(v.to_string()),
    }
}

/// The widest lanes this CPU runs natively: 8 with AVX-512F, 4 with AVX2, else 2.
#[must_use]
pub(crate) fn native_width() -> usize {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            return 8;
        }
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            return 4;
        }
    }
    2
}

/// One task's workspace, of the width chosen when it was made.
#[derive(Clone, Debug)]
pub(crate) enum Lanes {
    W2(Box<Pack<2>>),
    W4(Box<Pack<4>>),
    W8(Box<Pack<8>>),
}

impl Lanes {
    /// A workspace of `width` lanes (2, 4 or 8; anything else is 2) for `model`.
    pub(crate) fn new(model: &Model, width: usize) -> Self {
        match width {
            8 => Self::W8(Box::new(Pack::new(model))),
            4 => Self::W4(Box::new(Pack::new(model))),
            _ => Self::W2(Box::new(Pack::new(model))),
        }
    }

    /// The number of lanes.
    pub(crate) fn width(&self) -> usize {
        match self {
            Self::W2(_) => 2,
            Self::W4(_) => 4,
            Self::W8(_) => 8,
        }
    }

    /// Whether the workspace was made for a model of `model`'s shape.
    pub(crate) fn fits(&self, model: &Model) -> bool {
        match self {
            Self::W2(p) => p.fits(model),
            Self::W4(p) => p.fits(model),
            Self::W8(p) => p.fits(model),
        }
    }

    /// `algo` for the `count` states from `first` on of the row-major inputs (`xs` is `a` or
    /// `τ`, and with `vs` empty for CRBA), written to `out` (`count` blocks of
    /// [`Algo::per_state`]; the derivatives' `∂τ/∂v` to `out2`, empty for the others), a pack
    /// of states at a time, in the widest instructions the CPU has for this width. The inputs
    /// were checked. Never inlined (one call per chunk of states, [`super::CHUNK`]):
    /// bench/flops.py counts the operations executed inside it.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(crate) fn run(
        &mut self,
        algo: Algo,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        xs: &[f64],
        first: usize,
        out: &mut [f64],
        out2: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let io = Io {
            qs,
            vs,
            xs,
            first,
            native: false,
        };
        match algo.code() {
            RNEA => self.run_as::<RNEA>(model, io, out, out2),
            ABA => self.run_as::<ABA>(model, io, out, out2),
            CRBA => self.run_as::<CRBA>(model, io, out, out2),
            CRBA_LOWER => self.run_as::<CRBA_LOWER>(model, io, out, out2),
            _ => self.run_as::<RNEA_DERIVATIVES>(model, io, out, out2),
        }
    }

    /// [`Lanes::run`] for the algorithm of code `A`, in the widest instructions the CPU has for
    /// this width.
    #[inline(always)]
    fn run_as<const A: u8>(
        &mut self,
        model: &Model,
        mut io: Io,
        out: &mut [f64],
        out2: &mut [f64],
    ) -> Result<(), MultibodyError> {
        match self {
            #[cfg(target_arch = "x86_64")]
            Self::W8(p) if std::arch::is_x86_feature_detected!("avx512f") => {
                io.native = true;
                // SAFETY: the CPU has AVX-512F (checked above).
                unsafe { avx512::<A>(p, model, &io, out, out2) }
            }
            #[cfg(target_arch = "x86_64")]
            Self::W4(p)
                if std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma") =>
            {
                io.native = true;
                // SAFETY: the CPU has AVX2 and FMA (checked above).
                unsafe { avx2::<A>(p, model, &io, out, out2) }
            }
            Self::W2(p) => generic::<2, A>(p, model, &io, out, out2),
            Self::W4(p) => generic::<4, A>(p, model, &io, out, out2),
            Self::W8(p) => generic::<8, A>(p, model, &io, out, out2),
        }
    }
}

/// The row-major inputs, the index of the first state of a chunk, and whether the pack runs in
/// the CPU's own instructions for its width (AVX-512F for 8 lanes, AVX2 for 4): then the
/// transpositions into the lanes (full packs) and out of them (the full CRBA matrices too,
/// when `nv ≥ 4`) run in registers.
pub(super) struct Io<'a> {
    pub(super) qs: &'a [f64],
    pub(super) vs: &'a [f64],
    pub(super) xs: &'a [f64],
    pub(super) first: usize,
    pub(super) native: bool,
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn avx512<const A: u8>(
    p: &mut Pack<8>,
    model: &Model,
    io: &Io,
    out: &mut [f64],
    out2: &mut [f64],
) -> Result<(), MultibodyError> {
    packs::<8, A>(p, model, io, out, out2)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn avx2<const A: u8>(
    p: &mut Pack<4>,
    model: &Model,
    io: &Io,
    out: &mut [f64],
    out2: &mut [f64],
) -> Result<(), MultibodyError> {
    packs::<4, A>(p, model, io, out, out2)
}

/// The kernels in the baseline instruction set (SSE2 on x86-64), for widths the CPU has no
/// wider instructions for (and the tests' forced widths).
#[inline(never)]
fn generic<const W: usize, const A: u8>(
    p: &mut Pack<W>,
    model: &Model,
    io: &Io,
    out: &mut [f64],
    out2: &mut [f64],
) -> Result<(), MultibodyError> {
    packs::<W, A>(p, model, io, out, out2)
}

/// The task's states `W` at a time: transposed into the lanes (the last pack's missing lanes
/// repeat its last state, so that every lane computes a valid state), computed, and the lanes
/// that hold states transposed back out (the derivatives' second output to `out2`).
#[inline(always)]
fn packs<const W: usize, const A: u8>(
    p: &mut Pack<W>,
    model: &Model,
    io: &Io,
    out: &mut [f64],
    out2: &mut [f64],
) -> Result<(), MultibodyError> {
    let algo = match A {
        RNEA => Algo::Rnea,
        ABA => Algo::Aba,
        CRBA => Algo::Crba,
        CRBA_LOWER => Algo::CrbaLower,
        _ => Algo::RneaDerivatives,
    };
    let nv = model.nv();
    let per = algo.per_state(nv);
    let count = out.len() / per.max(1);
    let mut s = 0;
    while s < count {
        let m = (count - s).min(W);
        prefetch_rows(io, model, io.first + s + super::CHUNK, W);
        if io.native && (W == 4 || W == 8) && m == W {
            let k = io.first + s;
            // SAFETY: with `native`, the CPU has AVX (AVX2 for 4 lanes, AVX-512F for 8).
            unsafe { transpose_in(io.qs, k, &mut p.q) };
            for (xs, lanes) in [(io.vs, &mut p.v), (io.xs, &mut p.x)] {
                if !xs.is_empty() {
                    // SAFETY: as above.
                    unsafe { transpose_in(xs, k, lanes) };
                }
            }
        } else {
            for l in 0..W {
                p.gather(l, io.first + s + l.min(m - 1), io.qs, io.vs, io.xs);
            }
        }
        match algo {
            Algo::Rnea => rnea(model, p),
            Algo::Aba => aba(model, p, None, None)?,
            Algo::Crba | Algo::CrbaLower => crba(model, p),
            Algo::RneaDerivatives => rnea_derivatives(model, p),
        }
        let o = &mut out[s * per..(s + m) * per];
        match algo {
            Algo::Rnea | Algo::Aba => transpose_out(&p.out, m, o, per, io.native),
            Algo::CrbaLower => transpose_out(&p.M, m, o, per, io.native),
            Algo::RneaDerivatives => {
                if let Some(d) = &p.deriv {
                    transpose_out(&d.dq, m, o, per, io.native);
                    let o2 = &mut out2[s * per..(s + m) * per];
                    transpose_out(&d.dv, m, o2, per, io.native);
                }
            }
            Algo::Crba => symmetric_out(&p.M, &p.mirror, m, o, io.native),
        }
        s += W;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::lanes_from;

    #[test]
    fn rigid_lanes_reads_two_four_or_eight_and_names_anything_else() {
        assert_eq!(lanes_from(None), Ok(None));
        assert_eq!(lanes_from(Some("")), Ok(None));
        assert_eq!(lanes_from(Some("2")), Ok(Some(2)));
        assert_eq!(lanes_from(Some(" 4 ")), Ok(Some(4)));
        assert_eq!(lanes_from(Some("8")), Ok(Some(8)));
        assert_eq!(lanes_from(Some("16")), Err("16".to_string()));
        assert_eq!(lanes_from(Some("avx2")), Err("avx2".to_string()));
    }
}
