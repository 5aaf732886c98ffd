//! One formula, one value or several at once. The BRDF lobes (and the colour difference)
//! are written once, generic over [`Real`]: `f64` evaluates one view/light pair (the
//! renderer), [`Lanes`] evaluates a texel's eight direction pairs together (the
//! comparison), element by element, in straight-line code the compiler turns into vector
//! instructions. Each lane computes exactly what `f64` would: the same operations in the
//! same order, so the two agree bit for bit (tested in `material.rs`).

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A number type for branch-free formulas: arithmetic, comparisons to masks, and selects.
pub(crate) trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    type Mask: Copy
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
    fn splat(value: f64) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    fn min(self, other: Self) -> Self;
    fn max(self, other: Self) -> Self;
    fn lt(self, other: Self) -> Self::Mask;
    fn gt(self, other: Self) -> Self::Mask;
    fn ge(self, other: Self) -> Self::Mask;
    fn eq(self, other: Self) -> Self::Mask;
    /// `yes` where the mask is set, `no` elsewhere.
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self;
    /// Applies a scalar function to each value (for the rare terms, like the sheen lobe's
    /// powers, that have no branch-free form here).
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
    /// Applies `f` to the IEEE 754 bits of each value (integer steps of exp and cube root).
    fn map_bits(self, f: impl Fn(u64) -> u64) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(value: f64) -> Self {
        value
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn ge(self, other: Self) -> bool {
        self >= other
    }
    #[inline(always)]
    fn eq(self, other: Self) -> bool {
        self == other
    }
    #[inline(always)]
    fn select(mask: bool, yes: Self, no: Self) -> Self {
        if mask {
            yes
        } else {
            no
        }
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        f(self)
    }
    #[inline(always)]
    fn map_bits(self, f: impl Fn(u64) -> u64) -> Self {
        f64::from_bits(f(self.to_bits()))
    }
}

/// N values evaluated together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lanes<const N: usize>(pub [f64; N]);

/// Per-lane truth values of a comparison, all ones or all zeros per lane as vector compare
/// instructions produce them (a `bool` per lane kept the optimiser from vectorising
/// selects).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Mask<const N: usize>([u64; N]);

impl<const N: usize> Mask<N> {
    #[inline(always)]
    pub(crate) fn from_bools(truth: [bool; N]) -> Self {
        Mask(each(|i| if truth[i] { u64::MAX } else { 0 }))
    }
}

/// `[f(0), …, f(N − 1)]` as a plain loop: `array::map` and `array::from_fn` go through
/// helpers the optimiser does not always inline, which would leave a call per operation.
#[inline(always)]
fn each<T: Copy + Default, const N: usize>(f: impl Fn(usize) -> T) -> [T; N] {
    let mut out = [T::default(); N];
    for (i, slot) in out.iter_mut().enumerate() {
        *slot = f(i);
    }
    out
}

/// `[f(0), f(1), f(2)]`, written out, for the colour channels (see [`each`]).
#[inline(always)]
pub(crate) fn channels<T>(f: impl Fn(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

impl<const N: usize> Lanes<N> {
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Lanes(each(|i| f(self.0[i], other.0[i])))
    }

    #[inline(always)]
    fn compare(self, other: Self, f: impl Fn(f64, f64) -> bool) -> Mask<N> {
        Mask(each(|i| {
            if f(self.0[i], other.0[i]) {
                u64::MAX
            } else {
                0
            }
        }))
    }
}

macro_rules! lane_operator {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const N: usize> $trait for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: Self) -> Self {
                self.zip(other, |a, b| a $op b)
            }
        }
        impl<const N: usize> $trait<f64> for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: f64) -> Self {
                self.map(|a| a $op other)
            }
        }
    };
}

lane_operator!(Add, add, +);
lane_operator!(Sub, sub, -);
lane_operator!(Mul, mul, *);
lane_operator!(Div, div, /);

impl<const N: usize> Neg for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

macro_rules! mask_operator {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const N: usize> $trait for Mask<N> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: Self) -> Self {
                Mask(each(|i| self.0[i] $op other.0[i]))
            }
        }
    };
}

mask_operator!(BitAnd, bitand, &);
mask_operator!(BitOr, bitor, |);

impl<const N: usize> Not for Mask<N> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Mask(each(|i| !self.0[i]))
    }
}

impl<const N: usize> Real for Lanes<N> {
    type Mask = Mask<N>;
    #[inline(always)]
    fn splat(value: f64) -> Self {
        Lanes([value; N])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f64::abs)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        self.zip(other, f64::min)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        self.zip(other, f64::max)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> Mask<N> {
        self.compare(other, |a, b| a < b)
    }
    #[inline(always)]
    fn gt(self, other: Self) -> Mask<N> {
        self.compare(other, |a, b| a > b)
    }
    #[inline(always)]
    fn ge(self, other: Self) -> Mask<N> {
        self.compare(other, |a, b| a >= b)
    }
    #[inline(always)]
    fn eq(self, other: Self) -> Mask<N> {
        self.compare(other, |a, b| a == b)
    }
    #[inline(always)]
    fn select(mask: Mask<N>, yes: Self, no: Self) -> Self {
        Lanes(each(|i| {
            let m = mask.0[i];
            f64::from_bits((yes.0[i].to_bits() & m) | (no.0[i].to_bits() & !m))
        }))
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Lanes(each(|i| f(self.0[i])))
    }
    #[inline(always)]
    fn map_bits(self, f: impl Fn(u64) -> u64) -> Self {
        self.map(|a| f64::from_bits(f(a.to_bits())))
    }
}
