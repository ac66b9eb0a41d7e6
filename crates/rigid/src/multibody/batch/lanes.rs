//! `W` states side by side: every scalar of the algorithms becomes a `W`-wide vector [`L`], one
//! lane per state, and the spatial types of one state become their lane versions ([`V3`],
//! [`M3`], [`T6`]). Each operation is a loop over the lanes that the compiler turns into one
//! vector instruction when the kernel is compiled for a vector unit of `W` doubles
//! ([`super::simd`]: AVX-512 8, AVX2 4, SSE2 2); there are no shuffles, because a lane never
//! talks to another. Constants of the model (placements, inertias, axes) stay `f64` and are
//! broadcast by the product `L * f64`.
//!
//! The operations are those of the single-state code, one for one, without fused multiply-add
//! (Rust never contracts `a * b + c`), so a lane computes what a single call would when the two
//! take the same steps in the same order.

use crate::spatial::{Mat3, Transform, Twist, Vec3, Wrench};
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// `W` doubles, one per state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub(crate) struct L<const W: usize>(pub(crate) [f64; W]);

impl<const W: usize> L<W> {
    /// Every lane `x`.
    #[inline(always)]
    pub(crate) fn splat(x: f64) -> Self {
        Self([x; W])
    }

    /// Every lane 0.
    #[inline(always)]
    pub(crate) fn zero() -> Self {
        Self([0.0; W])
    }

    /// `f` of each lane (for the few steps that are not arithmetic: `sqrt`, a division).
    #[inline(always)]
    pub(crate) fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut r = self.0;
        for x in &mut r {
            *x = f(*x);
        }
        Self(r)
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt, $tra:ident, $fa:ident) => {
        impl<const W: usize> $tr for L<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                let mut r = self.0;
                for i in 0..W {
                    r[i] = self.0[i] $op o.0[i];
                }
                Self(r)
            }
        }
        impl<const W: usize> $tr<f64> for L<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: f64) -> Self {
                let mut r = self.0;
                for x in &mut r {
                    let y = *x;
                    *x = y $op o;
                }
                Self(r)
            }
        }
        impl<const W: usize> $tra for L<W> {
            #[inline(always)]
            fn $fa(&mut self, o: Self) {
                *self = *self $op o;
            }
        }
        impl<const W: usize> $tra<f64> for L<W> {
            #[inline(always)]
            fn $fa(&mut self, o: f64) {
                *self = *self $op o;
            }
        }
    };
}
lane_op!(Add, add, +, AddAssign, add_assign);
lane_op!(Sub, sub, -, SubAssign, sub_assign);
lane_op!(Mul, mul, *, MulAssign, mul_assign);

use std::ops::MulAssign;

impl<const W: usize> Neg for L<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|x| -x)
    }
}

/// Marks the body of a loop over lane vectors that LLVM must not vectorize a second time.
///
/// LLVM's loop vectorizer runs before its SLP vectorizer, so it sees each lane operation as `W`
/// scalar ones and may vectorize *across iterations*: four of a column's dot products at once,
/// their operands gathered lane by lane (`vmovsd`, `vmovhpd`, `vinsertf128`). In the lane CRBA's
/// columns on TALOS that took 180 instructions per four entries where the loop it replaced takes
/// 17 per entry. The loop vectorizer cannot widen an assembly block, so an empty one keeps it off
/// the loop; the block emits nothing and touches no memory, register or flag.
#[inline(always)]
pub(crate) fn one_iteration_at_a_time() {
    #[cfg(all(any(target_arch = "x86_64", target_arch = "aarch64"), not(miri)))]
    // SAFETY: the block is empty; `nomem` and `preserves_flags` say it touches nothing.
    unsafe {
        std::arch::asm!("", options(nomem, nostack, preserves_flags));
    }
}

/// `n` lane values (of [`L`] or types made of them) in one buffer that starts on a 64-byte
/// cache line: a workspace of the kernels. In a `Vec` a buffer starts where the allocator puts
/// it, 16-byte aligned, and with 8 lanes every lane vector (64 bytes) then straddles two cache
/// lines, so each load and store of a number touches two: which buffers did depended on the
/// order and sizes of the allocations before them, and the kernels' speed moved by 10 % with
/// changes that touched no kernel (BENCHMARKS.md, "Lane buffers on cache lines"). Dereferences
/// to a slice.
pub(crate) struct Aligned<T: Copy> {
    /// The storage, `n size_of::<T>()` bytes rounded up to whole lines.
    lines: Vec<Line>,
    n: usize,
    _values: std::marker::PhantomData<T>,
}

/// A cache line of storage for [`Aligned`], copied as bytes that may be uninitialized (a lane
/// type's padding, if one had any), never read as numbers.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Line([std::mem::MaybeUninit<u64>; 8]);

impl<T: Copy> Aligned<T> {
    /// `n` copies of `x`.
    pub(crate) fn new(x: T, n: usize) -> Self {
        const {
            assert!(
                std::mem::align_of::<T>() <= 64,
                "a lane type aligned to at most a line"
            );
        }
        let bytes = n
            .checked_mul(std::mem::size_of::<T>())
            .expect("a lane buffer of fewer than usize::MAX bytes");
        let mut lines = vec![Line([std::mem::MaybeUninit::uninit(); 8]); bytes.div_ceil(64)];
        let at = lines.as_mut_ptr().cast::<T>();
        for k in 0..n {
            // SAFETY: `lines` holds `bytes = n size_of::<T>()` bytes or more, from a 64-byte
            // boundary, and `T` is aligned to at most 64 bytes (asserted above), so element `k`
            // is in bounds and aligned; a raw write, before any reference to a `T` exists.
            unsafe { at.add(k).write(x) };
        }
        Self {
            lines,
            n,
            _values: std::marker::PhantomData,
        }
    }
}

impl<T: Copy> std::ops::Deref for Aligned<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        // SAFETY: the first `n` elements were written by `new` (and since only through this
        // slice or the mutable one, as values of `T`), in bounds and aligned as shown there.
        unsafe { std::slice::from_raw_parts(self.lines.as_ptr().cast::<T>(), self.n) }
    }
}

impl<T: Copy> std::ops::DerefMut for Aligned<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        // SAFETY: as for `deref`, with `&mut self` borrowing the storage uniquely.
        unsafe { std::slice::from_raw_parts_mut(self.lines.as_mut_ptr().cast::<T>(), self.n) }
    }
}

impl<'a, T: Copy> IntoIterator for &'a Aligned<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<'a, T: Copy> IntoIterator for &'a mut Aligned<T> {
    type Item = &'a mut T;
    type IntoIter = std::slice::IterMut<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter_mut()
    }
}

impl<T: Copy> Clone for Aligned<T> {
    fn clone(&self) -> Self {
        Self {
            lines: self.lines.clone(),
            n: self.n,
            _values: std::marker::PhantomData,
        }
    }
}

impl<T: Copy + std::fmt::Debug> std::fmt::Debug for Aligned<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// A 3-vector per lane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3<const W: usize>(pub(crate) [L<W>; 3]);

impl<const W: usize> V3<W> {
    #[inline(always)]
    pub(crate) fn zero() -> Self {
        Self([L::zero(); 3])
    }

    /// The constant `x` in every lane.
    #[inline(always)]
    pub(crate) fn splat(x: &Vec3) -> Self {
        Self([L::splat(x.x), L::splat(x.y), L::splat(x.z)])
    }

    /// `a × b`.
    #[inline(always)]
    pub(crate) fn cross(&self, b: &Self) -> Self {
        let (a, b) = (&self.0, &b.0);
        Self([
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ])
    }

    /// `a · b`.
    #[inline(always)]
    pub(crate) fn dot(&self, b: &Self) -> L<W> {
        self.0[0] * b.0[0] + self.0[1] * b.0[1] + self.0[2] * b.0[2]
    }

    /// `a x` for a lane scalar `x`.
    #[inline(always)]
    pub(crate) fn scale(&self, x: L<W>) -> Self {
        Self([self.0[0] * x, self.0[1] * x, self.0[2] * x])
    }

    /// `c × a` for a constant `c`.
    #[inline(always)]
    pub(crate) fn c_cross(c: &Vec3, a: &Self) -> Self {
        let a = &a.0;
        Self([
            a[2] * c.y - a[1] * c.z,
            a[0] * c.z - a[2] * c.x,
            a[1] * c.x - a[0] * c.y,
        ])
    }

    /// `C x` for a constant matrix `C`.
    #[inline(always)]
    pub(crate) fn c_mat(c: &Mat3, x: &Self) -> Self {
        let x = &x.0;
        Self([
            x[0] * c[(0, 0)] + x[1] * c[(0, 1)] + x[2] * c[(0, 2)],
            x[0] * c[(1, 0)] + x[1] * c[(1, 1)] + x[2] * c[(1, 2)],
            x[0] * c[(2, 0)] + x[1] * c[(2, 1)] + x[2] * c[(2, 2)],
        ])
    }

    /// `c x` for a constant `c` and a lane scalar `x`.
    #[inline(always)]
    pub(crate) fn c_scale(c: &Vec3, x: L<W>) -> Self {
        Self([x * c.x, x * c.y, x * c.z])
    }
}

impl<const W: usize> Add for V3<W> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}

impl<const W: usize> Sub for V3<W> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}

impl<const W: usize> AddAssign for V3<W> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const W: usize> SubAssign for V3<W> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<const W: usize> Neg for V3<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self([-self.0[0], -self.0[1], -self.0[2]])
    }
}

/// A symmetric 3x3 matrix per lane, its six entries stored `xx yy zz xy xz yz`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct S3<const W: usize>(pub(crate) [L<W>; 6]);

impl<const W: usize> S3<W> {
    /// Where entry `(r, c)` is kept.
    const AT: [[usize; 3]; 3] = [[0, 3, 4], [3, 1, 5], [4, 5, 2]];

    /// The upper triangle of the constant `m` in every lane (`m` symmetric).
    #[inline(always)]
    pub(crate) fn splat(m: &Mat3) -> Self {
        Self([(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)].map(|rc| L::splat(m[rc])))
    }

    /// Entry `(r, c)`.
    #[inline(always)]
    pub(crate) fn at(&self, r: usize, c: usize) -> L<W> {
        self.0[Self::AT[r][c]]
    }

    /// Entry `(r, c)`, `r ≤ c`, to set.
    #[inline(always)]
    pub(crate) fn at_mut(&mut self, r: usize, c: usize) -> &mut L<W> {
        &mut self.0[Self::AT[r][c]]
    }

    /// Column `c`.
    #[inline(always)]
    pub(crate) fn col(&self, c: usize) -> V3<W> {
        V3([self.at(0, c), self.at(1, c), self.at(2, c)])
    }

    /// `S x`, row by row as [`M3::mul_v`].
    #[inline(always)]
    pub(crate) fn mul_v(&self, x: &V3<W>) -> V3<W> {
        let (s, x) = (&self.0, &x.0);
        V3([
            s[0] * x[0] + s[3] * x[1] + s[4] * x[2],
            s[3] * x[0] + s[1] * x[1] + s[5] * x[2],
            s[4] * x[0] + s[5] * x[1] + s[2] * x[2],
        ])
    }
}

impl<const W: usize> AddAssign<&S3<W>> for S3<W> {
    #[inline(always)]
    fn add_assign(&mut self, y: &Self) {
        for (a, b) in self.0.iter_mut().zip(&y.0) {
            *a += *b;
        }
    }
}

/// A 3x3 matrix per lane, `m[r][c]` (row `r`, column `c`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct M3<const W: usize>(pub(crate) [[L<W>; 3]; 3]);

impl<const W: usize> M3<W> {
    /// The constant `m` in every lane.
    #[inline(always)]
    pub(crate) fn splat(m: &Mat3) -> Self {
        let mut r = [[L::zero(); 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = L::splat(m[(i, j)]);
            }
        }
        Self(r)
    }

    /// The matrix with these columns.
    #[inline(always)]
    pub(crate) fn from_columns(c: &[V3<W>; 3]) -> Self {
        let mut m = [[L::zero(); 3]; 3];
        for (j, col) in c.iter().enumerate() {
            for (i, row) in m.iter_mut().enumerate() {
                row[j] = col.0[i];
            }
        }
        Self(m)
    }

    /// Column `c`.
    #[inline(always)]
    pub(crate) fn col(&self, c: usize) -> V3<W> {
        V3([self.0[0][c], self.0[1][c], self.0[2][c]])
    }

    /// `M x`.
    #[inline(always)]
    pub(crate) fn mul_v(&self, x: &V3<W>) -> V3<W> {
        let m = &self.0;
        let x = &x.0;
        V3([
            m[0][0] * x[0] + m[0][1] * x[1] + m[0][2] * x[2],
            m[1][0] * x[0] + m[1][1] * x[1] + m[1][2] * x[2],
            m[2][0] * x[0] + m[2][1] * x[1] + m[2][2] * x[2],
        ])
    }

    /// `Mᵀ x`.
    #[inline(always)]
    pub(crate) fn tr_mul_v(&self, x: &V3<W>) -> V3<W> {
        let m = &self.0;
        let x = &x.0;
        V3([
            m[0][0] * x[0] + m[1][0] * x[1] + m[2][0] * x[2],
            m[0][1] * x[0] + m[1][1] * x[1] + m[2][1] * x[2],
            m[0][2] * x[0] + m[1][2] * x[1] + m[2][2] * x[2],
        ])
    }

    /// `M c` for a constant `c`.
    #[inline(always)]
    pub(crate) fn mul_c(&self, c: &Vec3) -> V3<W> {
        let m = &self.0;
        V3([
            m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
            m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
            m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z,
        ])
    }

    /// `A B`.
    #[inline(always)]
    pub(crate) fn mul(&self, b: &Self) -> Self {
        let (a, b) = (&self.0, &b.0);
        let mut r = [[L::zero(); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
            }
        }
        Self(r)
    }

    /// `A Bᵀ`.
    #[inline(always)]
    pub(crate) fn mul_tr(&self, b: &Self) -> Self {
        let (a, b) = (&self.0, &b.0);
        let mut r = [[L::zero(); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = a[i][0] * b[j][0] + a[i][1] * b[j][1] + a[i][2] * b[j][2];
            }
        }
        Self(r)
    }

    /// `A Bᵀ` known to be symmetric (`R S Rᵀ`): the lower triangle computed, the upper copied.
    #[inline(always)]
    pub(crate) fn mul_tr_sym(&self, b: &Self) -> Self {
        let (a, b) = (&self.0, &b.0);
        let mut r = [[L::zero(); 3]; 3];
        for i in 0..3 {
            for j in 0..=i {
                r[i][j] = a[i][0] * b[j][0] + a[i][1] * b[j][1] + a[i][2] * b[j][2];
                r[j][i] = r[i][j];
            }
        }
        Self(r)
    }

    /// `A C` for a constant `C`.
    #[inline(always)]
    pub(crate) fn mul_cm(&self, c: &Mat3) -> Self {
        let a = &self.0;
        let mut r = [[L::zero(); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = a[i][0] * c[(0, j)] + a[i][1] * c[(1, j)] + a[i][2] * c[(2, j)];
            }
        }
        Self(r)
    }

    /// `C B` for a constant `C`.
    #[inline(always)]
    pub(crate) fn c_mul(c: &Mat3, b: &Self) -> Self {
        let b = &b.0;
        let mut r = [[L::zero(); 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = b[0][j] * c[(i, 0)] + b[1][j] * c[(i, 1)] + b[2][j] * c[(i, 2)];
            }
        }
        Self(r)
    }
}

/// A twist `(ω, v)` or a wrench `(m, f)` per lane, angular first.
#[derive(Clone, Copy, Debug)]
pub(crate) struct T6<const W: usize> {
    /// Angular part: `ω` of a twist, the moment `m` of a wrench.
    pub(crate) w: V3<W>,
    /// Linear part: `v` of a twist, the force `f` of a wrench.
    pub(crate) v: V3<W>,
}

impl<const W: usize> T6<W> {
    #[inline(always)]
    pub(crate) fn zero() -> Self {
        Self {
            w: V3::zero(),
            v: V3::zero(),
        }
    }

    /// The constant twist `t` in every lane.
    #[inline(always)]
    pub(crate) fn splat(t: &Twist) -> Self {
        Self {
            w: V3::splat(&t.w),
            v: V3::splat(&t.v),
        }
    }

    /// The constant wrench `f` in every lane (moment in `w`, force in `v`).
    #[inline(always)]
    pub(crate) fn splat_wrench(f: &Wrench) -> Self {
        Self {
            w: V3::splat(&f.m),
            v: V3::splat(&f.f),
        }
    }

    /// Lane `l` as a twist (a wrench's moment and force are its `w` and `v`).
    #[inline(always)]
    pub(crate) fn lane(&self, l: usize) -> Twist {
        let (w, v) = (&self.w.0, &self.v.0);
        Twist::new(
            Vec3::new(w[0].0[l], w[1].0[l], w[2].0[l]),
            Vec3::new(v[0].0[l], v[1].0[l], v[2].0[l]),
        )
    }

    /// Component `c` (angular first).
    #[inline(always)]
    pub(crate) fn get(&self, c: usize) -> L<W> {
        if c < 3 {
            self.w.0[c]
        } else {
            self.v.0[c - 3]
        }
    }

    /// Component `c` (angular first), to write.
    #[inline(always)]
    pub(crate) fn get_mut(&mut self, c: usize) -> &mut L<W> {
        if c < 3 {
            &mut self.w.0[c]
        } else {
            &mut self.v.0[c - 3]
        }
    }

    /// `a · b` of a twist and a wrench (power).
    #[inline(always)]
    pub(crate) fn dot(&self, b: &Self) -> L<W> {
        self.w.dot(&b.w) + self.v.dot(&b.v)
    }

    /// `a x` for a lane scalar `x`.
    #[inline(always)]
    pub(crate) fn scale(&self, x: L<W>) -> Self {
        Self {
            w: self.w.scale(x),
            v: self.v.scale(x),
        }
    }

    /// `V × T = [ad_V] T` of two twists: `(ω × ω', v × ω' + ω × v')`.
    #[inline(always)]
    pub(crate) fn cross(&self, t: &Self) -> Self {
        Self {
            w: self.w.cross(&t.w),
            v: self.v.cross(&t.w) + self.w.cross(&t.v),
        }
    }

    /// `V × (x e_c)`, [`T6::cross`] with a twist that has one component `x` (`c`, angular
    /// first), written out: `(ω × w, v × w)` for an angular `w = x e_c`, `(0, ω × u)` for a
    /// linear `u = x e_(c−3)` (4 products instead of 18; the same numbers, up to the sign of
    /// zeros).
    #[inline(always)]
    pub(crate) fn cross_axis(&self, c: usize, x: L<W>) -> Self {
        // a × (x e_k)
        #[inline(always)]
        fn cross_e<const W: usize>(a: &V3<W>, k: usize, x: L<W>) -> V3<W> {
            let (a, z) = (&a.0, L::zero());
            V3(match k {
                0 => [z, a[2] * x, -(a[1] * x)],
                1 => [-(a[2] * x), z, a[0] * x],
                _ => [a[1] * x, -(a[0] * x), z],
            })
        }
        if c < 3 {
            Self {
                w: cross_e(&self.w, c, x),
                v: cross_e(&self.v, c, x),
            }
        } else {
            Self {
                w: V3::zero(),
                v: cross_e(&self.w, c - 3, x),
            }
        }
    }

    /// `V ×* F = -[ad_V]ᵀ F` of a twist and a wrench: `(ω × m + v × f, ω × f)`.
    #[inline(always)]
    pub(crate) fn cross_star(&self, f: &Self) -> Self {
        Self {
            w: self.w.cross(&f.w) + self.v.cross(&f.v),
            v: self.w.cross(&f.v),
        }
    }
}

impl<const W: usize> Add for T6<W> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self {
            w: self.w + o.w,
            v: self.v + o.v,
        }
    }
}

impl<const W: usize> AddAssign for T6<W> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const W: usize> Sub for T6<W> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self {
            w: self.w - o.w,
            v: self.v - o.v,
        }
    }
}

/// A pose `(R, p)` per lane: the child frame's axes `R` and origin `p` in the parent frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct X<const W: usize> {
    pub(crate) r: M3<W>,
    pub(crate) p: V3<W>,
}

impl<const W: usize> X<W> {
    /// The identity pose in every lane.
    pub(crate) fn identity() -> Self {
        Self {
            r: M3::splat(&Mat3::identity()),
            p: V3::zero(),
        }
    }

    /// `*self = *x`, row by row: a copy of the whole pose (12 lane vectors, 384 bytes with 4
    /// lanes) would be a call to `memcpy` in the kernels' loops.
    #[inline(always)]
    pub(crate) fn set(&mut self, x: &Self) {
        for r in 0..3 {
            self.r.0[r] = x.r.0[r];
        }
        self.p = x.p;
    }

    /// Lane `l` as a [`Transform`].
    pub(crate) fn lane(&self, l: usize) -> Transform {
        let r = &self.r.0;
        Transform::new(
            Mat3::from_fn(|i, j| r[i][j].0[l]),
            Vec3::new(self.p.0[0].0[l], self.p.0[1].0[l], self.p.0[2].0[l]),
        )
    }

    /// `[Ad_{X⁻¹}] T`: a twist of the parent frame in the child frame,
    /// `(Rᵀ ω, Rᵀ (v − p × ω))` ([`Transform::inv_act_twist`](crate::spatial::Transform::inv_act_twist)).
    #[inline(always)]
    pub(crate) fn inv_act(&self, t: &T6<W>) -> T6<W> {
        T6 {
            w: self.r.tr_mul_v(&t.w),
            v: self.r.tr_mul_v(&(t.v - self.p.cross(&t.w))),
        }
    }

    /// `[Ad_X]⁻ᵀ F`: a wrench of the child frame in the parent frame, `(R m + p × R f, R f)`
    /// ([`Transform::act_wrench`](crate::spatial::Transform::act_wrench)).
    #[inline(always)]
    pub(crate) fn act_wrench(&self, f: &T6<W>) -> T6<W> {
        let rf = self.r.mul_v(&f.v);
        T6 {
            w: self.r.mul_v(&f.w) + self.p.cross(&rf),
            v: rf,
        }
    }

    /// `A B`: the pose of frame `b` in `a`'s parent from `a` and `b` in `a`.
    #[inline(always)]
    pub(crate) fn compose(&self, b: &Self) -> Self {
        Self {
            r: self.r.mul(&b.r),
            p: self.r.mul_v(&b.p) + self.p,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Aligned, L, T6};

    /// Every buffer starts on a cache line, for any length and lane type, holds `n` copies of
    /// its value, writes through, and clones into a buffer of its own, also on a line.
    #[test]
    fn aligned_buffers_start_on_a_cache_line() {
        fn check<T: Copy + PartialEq + std::fmt::Debug>(x: T, y: T) {
            for n in 0..20 {
                let mut b = Aligned::new(x, n);
                assert_eq!(b.as_ptr() as usize % 64, 0, "n {n}");
                assert_eq!(b.len(), n);
                assert!(b.iter().all(|v| *v == x));
                if n > 0 {
                    b[n - 1] = y;
                }
                let c = b.clone();
                assert_eq!(c.as_ptr() as usize % 64, 0, "clone, n {n}");
                assert!(n == 0 || c.as_ptr() != b.as_ptr());
                assert_eq!(&c[..], &b[..]);
                assert!(n == 0 || c[n - 1] == y);
            }
        }
        check(L([1.0; 2]), L([2.0; 2]));
        check(L([1.0; 4]), L([2.0; 4]));
        check(L([1.0; 8]), L([2.0; 8]));
        check([L([3.0; 8]); 2], [L([4.0; 8]); 2]);
        let mut t = T6::<4>::zero();
        *t.get_mut(5) = L([7.0; 4]);
        for n in 0..20 {
            let v = Aligned::new(t, n);
            assert_eq!(v.as_ptr() as usize % 64, 0, "T6, n {n}");
            assert!(v
                .iter()
                .all(|e| e.get(5) == L([7.0; 4]) && e.get(0) == L([0.0; 4])));
        }
    }
}
