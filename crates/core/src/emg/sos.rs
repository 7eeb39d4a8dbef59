//! Second-order sections: a filter as a cascade of biquads ([`Sos`]), and the pairing of a
//! digital filter's zeros and poles into them as `scipy.signal.zpk2sos(z, p, k)` does by default
//! for a digital filter (SciPy 1.17, pairing `'nearest'`): the pole nearest the unit circle goes
//! last, with the zero nearest to it; the gain goes to the first section. Matching SciPy's pairing
//! and order makes the sections themselves comparable with `scipy.signal.butter(...,
//! output='sos')`, not only the filter they make.

use nalgebra::Complex;

/// Zeros, poles and gain of a transfer function (analog in s or digital in z).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Zpk {
    /// Zeros.
    pub(crate) z: Vec<Complex<f64>>,
    /// Poles.
    pub(crate) p: Vec<Complex<f64>>,
    /// Gain.
    pub(crate) k: f64,
}

/// One second-order section, `H(z) = (b0 + b1 z⁻¹ + b2 z⁻²)/(a0 + a1 z⁻¹ + a2 z⁻²)`, a0 = 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Numerator b0, b1, b2.
    pub b: [f64; 3],
    /// Denominator a0 (= 1), a1, a2.
    pub a: [f64; 3],
}

/// A filter as a cascade of second-order sections, applied first to last (SciPy's `sos` array,
/// one row a section).
#[derive(Debug, Clone, PartialEq)]
pub struct Sos {
    sections: Vec<Section>,
}

impl Sos {
    /// The sections, first applied first.
    pub fn sections(&self) -> &[Section] {
        &self.sections
    }
}

/// `x` is exactly real (NumPy's `isreal`).
fn is_real(x: &Complex<f64>) -> bool {
    x.im == 0.0
}

/// Index of the root nearest the unit circle (the first of equals), `argmin |1 - |p||`.
fn worst(roots: &[Complex<f64>]) -> Option<usize> {
    let distance = |p: &Complex<f64>| (1.0 - p.norm()).abs();
    (0..roots.len()).min_by(|&i, &j| distance(&roots[i]).total_cmp(&distance(&roots[j])))
}

/// Which roots a nearest-root search may return.
#[derive(Clone, Copy)]
enum Which {
    Real,
    Complex,
    Any,
}

/// Index of the root of `from` of kind `which` nearest `to` (SciPy's
/// `_nearest_real_complex_idx`); `None` when there is none of that kind.
fn nearest(from: &[Complex<f64>], to: Complex<f64>, which: Which) -> Option<usize> {
    let mut order: Vec<usize> = (0..from.len()).collect();
    order.sort_by(|&i, &j| (from[i] - to).norm().total_cmp(&(from[j] - to).norm()));
    order.into_iter().find(|&i| match which {
        Which::Real => is_real(&from[i]),
        Which::Complex => !is_real(&from[i]),
        Which::Any => true,
    })
}

/// Removes and returns the root of `from` of kind `which` nearest `to`, or 0 when there is none
/// (which a Butterworth filter never meets).
fn take_nearest(from: &mut Vec<Complex<f64>>, to: Complex<f64>, which: Which) -> Complex<f64> {
    match nearest(from, to, which) {
        Some(i) => from.remove(i),
        None => Complex::new(0.0, 0.0),
    }
}

/// The coefficients of `Π (1 - r x)` in powers of x, right-aligned in three slots (NumPy's
/// `poly`, real part; the roots come as conjugate pairs or real).
fn poly3(roots: &[Complex<f64>]) -> [f64; 3] {
    let mut c = vec![Complex::new(1.0, 0.0)];
    for r in roots {
        let mut next = vec![Complex::new(0.0, 0.0); c.len() + 1];
        for (i, ci) in c.iter().enumerate() {
            next[i] += ci;
            next[i + 1] += ci * -r;
        }
        c = next;
    }
    let mut out = [0.0; 3];
    let offset = 3usize.saturating_sub(c.len());
    for (slot, ci) in out.iter_mut().skip(offset).zip(&c) {
        *slot = ci.re;
    }
    out
}

/// The section of the given zeros and poles, gain 1 (SciPy's `_single_zpksos`).
fn section(z: &[Complex<f64>], p: &[Complex<f64>]) -> Section {
    Section {
        b: poly3(z),
        a: poly3(p),
    }
}

/// Complex roots (one of each conjugate pair, the upper half, averaged with its partner) then
/// real roots, sorted as SciPy's `_cplxreal` sorts them: by real part, then by |imaginary part|
/// (a run of equal real parts within 100 ε by |imaginary part|); a root whose imaginary part is
/// within 100 ε of its modulus is real.
pub(crate) fn complex_then_real(roots: &[Complex<f64>]) -> Vec<Complex<f64>> {
    let tol = 100.0 * f64::EPSILON;
    let mut sorted = roots.to_vec();
    sorted.sort_by(|x, y| {
        x.re.total_cmp(&y.re)
            .then(x.im.abs().total_cmp(&y.im.abs()))
    });
    let real = |x: &Complex<f64>| x.im.abs() <= tol * x.norm();
    let reals: Vec<Complex<f64>> = sorted
        .iter()
        .filter(|x| real(x))
        .map(|x| Complex::new(x.re, 0.0))
        .collect();
    let mut upper: Vec<Complex<f64>> = sorted
        .iter()
        .filter(|x| !real(x) && x.im > 0.0)
        .copied()
        .collect();
    let mut lower: Vec<Complex<f64>> = sorted
        .iter()
        .filter(|x| !real(x) && x.im < 0.0)
        .copied()
        .collect();
    sort_runs_by_imaginary(&mut upper, tol);
    sort_runs_by_imaginary(&mut lower, tol);
    let mut out: Vec<Complex<f64>> = upper
        .iter()
        .zip(&lower)
        .map(|(u, l)| (u + l.conj()) / 2.0)
        .collect();
    out.extend(reals);
    out
}

/// Sorts each run of (nearly) equal real parts by |imaginary part|; the runs are those of the
/// upper half (`diff(re) <= tol |x|`), as SciPy takes them.
fn sort_runs_by_imaginary(roots: &mut [Complex<f64>], tol: f64) {
    let mut start = 0;
    while start < roots.len() {
        let mut stop = start + 1;
        while stop < roots.len()
            && roots[stop].re - roots[stop - 1].re <= tol * roots[stop - 1].norm()
        {
            stop += 1;
        }
        roots[start..stop].sort_by(|x, y| x.im.abs().total_cmp(&y.im.abs()));
        start = stop;
    }
}

/// Second-order sections of a digital filter (SciPy's `zpk2sos`, pairing `'nearest'`).
pub(crate) fn zpk_to_sos(zpk: &Zpk) -> Sos {
    let (mut z, mut p) = (zpk.z.clone(), zpk.p.clone());
    let zero = Complex::new(0.0, 0.0);
    let n = z.len().max(p.len());
    z.resize(n, zero);
    p.resize(n, zero);
    let count = n.div_ceil(2);
    if n % 2 == 1 {
        z.push(zero);
        p.push(zero);
    }
    let mut z = complex_then_real(&z);
    let mut p = complex_then_real(&p);
    let identity = Section {
        b: [1.0, 0.0, 0.0],
        a: [1.0, 0.0, 0.0],
    };
    let mut sections = vec![identity; count];
    for si in (0..count).rev() {
        let Some(i) = worst(&p) else { break };
        let p1 = p.remove(i);
        sections[si] = pair(p1, &mut p, &mut z);
    }
    if let Some(first) = sections.first_mut() {
        for b in first.b.iter_mut() {
            *b *= zpk.k;
        }
    }
    Sos { sections }
}

/// The section of pole `p1` (already taken from `p`), with its partner pole and the zeros
/// nearest it, taken from `p` and `z`.
fn pair(p1: Complex<f64>, p: &mut Vec<Complex<f64>>, z: &mut Vec<Complex<f64>>) -> Section {
    let zero = Complex::new(0.0, 0.0);
    let real_count = |v: &[Complex<f64>]| v.iter().filter(|x| is_real(x)).count();
    if is_real(&p1) && real_count(p) == 0 {
        // The last real pole: with the nearest real zero, as a first-order section.
        let z1 = take_nearest(z, p1, Which::Real);
        return section(&[z1, zero], &[p1, zero]);
    }
    if p.len() + 1 == z.len() && !is_real(&p1) && real_count(p) == 1 && real_count(z) == 1 {
        // One real pole and one real zero remain for each other: a complex zero pair here.
        let z1 = take_nearest(z, p1, Which::Complex);
        return section(&[z1, z1.conj()], &[p1, p1.conj()]);
    }
    let p2 = if is_real(&p1) {
        let real: Vec<usize> = (0..p.len()).filter(|&i| is_real(&p[i])).collect();
        let candidates: Vec<Complex<f64>> = real.iter().map(|&i| p[i]).collect();
        match worst(&candidates).and_then(|j| real.get(j)) {
            Some(&i) => p.remove(i),
            None => zero,
        }
    } else {
        p1.conj()
    };
    if z.is_empty() {
        return section(&[], &[p1, p2]);
    }
    let z1 = take_nearest(z, p1, Which::Any);
    if !is_real(&z1) {
        section(&[z1, z1.conj()], &[p1, p2])
    } else if !z.is_empty() {
        let z2 = take_nearest(z, p1, Which::Real);
        section(&[z1, z2], &[p1, p2])
    } else {
        section(&[z1], &[p1, p2])
    }
}
