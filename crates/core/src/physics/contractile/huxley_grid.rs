//! The full Huxley (1957) model, eq. (9), by the method of characteristics (docs/model.md §7).
//!
//! Cells of width Δξ ride with the actin: every cell moves by the same shift, so the grid is an
//! offset plus a run of bond fractions. Over a step each cell's bond fraction is advanced
//! exactly for rates frozen at the cell's mid-step position:
//! `n ← n∞ + (n - n∞) exp(-(f + g) Δt)`, `n∞ = r f / (f + g)`.
//! Empty cells enter on the inflow side and cells leave once their bonds are negligible. The
//! storage is allocated once; a full grid drops its outermost cell.
//!
//! Written by hand: no crate offers a moving-grid characteristic solver for this equation.

use crate::physics::contractile::crossbridge::Rates;
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};
use std::collections::VecDeque;

/// Bond fraction below which an outer cell is dropped.
pub(crate) const NEGLIGIBLE_BONDS: f64 = 1e-13;
/// The grid always covers [-COVER_MARGIN, 1 + COVER_MARGIN] (the attachment range and a margin).
pub(crate) const COVER_MARGIN: f64 = 0.05;

/// Exact relaxation of one cell's bond fraction over `dt` with rates frozen at position `xi`:
/// `n∞ + (n - n∞) exp(-(f + g) dt)`, `n∞ = r f / (f + g)`.
fn relax(rates: &Rates, r: f64, n: f64, xi: f64, dt: f64) -> f64 {
    let f = rates.attach(xi);
    let total = f + rates.detach(xi);
    if total > 0.0 {
        let n_inf = r * f / total;
        n_inf + (n - n_inf) * (-total * dt).exp()
    } else {
        n
    }
}

/// The parts of the cell [c - w/2, c + w/2] in ξ < 0, [0, 1] and ξ > 1 where the rates are
/// smooth: (fraction of the cell, centroid) each; a cell inside one region is one part.
fn split_cell(c: f64, w: f64) -> [(f64, f64); 3] {
    let (a, b) = (c - 0.5 * w, c + 0.5 * w);
    if (a >= 0.0 && b <= 1.0) || b <= 0.0 || a >= 1.0 {
        return [(1.0, c), (0.0, 0.0), (0.0, 0.0)];
    }
    let part = |lo: f64, hi: f64| {
        let (lo, hi) = (lo.max(a), hi.min(b));
        if hi > lo {
            ((hi - lo) / w, 0.5 * (lo + hi))
        } else {
            (0.0, 0.0)
        }
    };
    [
        part(f64::NEG_INFINITY, 0.0),
        part(0.0, 1.0),
        part(1.0, f64::INFINITY),
    ]
}

/// Bond distribution n(ξ) on a moving uniform grid of cells.
#[derive(Debug, Clone)]
pub struct CrossBridgeGrid {
    dxi: f64,
    /// Centre of the first cell, in ξ.
    first_centre: f64,
    n: VecDeque<f64>,
    capacity: usize,
}

impl CrossBridgeGrid {
    /// An empty distribution (no bonds) with `cells_per_unit` cells per unit ξ and room for
    /// `max_extent` units of ξ.
    pub fn new(cells_per_unit: usize, max_extent: f64) -> Self {
        let dxi = 1.0 / cells_per_unit as f64;
        let capacity = (max_extent / dxi).ceil() as usize + 8;
        let mut grid = Self {
            dxi,
            first_centre: 0.5 * dxi,
            n: VecDeque::with_capacity(capacity),
            capacity,
        };
        grid.reset();
        grid
    }

    /// Back to no bonds, cells aligned with ξ = 0 and ξ = 1.
    pub(crate) fn reset(&mut self) {
        self.n.clear();
        let margin_cells = (COVER_MARGIN / self.dxi).ceil() as usize;
        self.first_centre = (0.5 - margin_cells as f64) * self.dxi;
        let cells = (1.0 / self.dxi).round() as usize + 2 * margin_cells;
        self.n.extend(std::iter::repeat_n(0.0, cells));
    }

    /// Sets every cell to `n(ξ_centre)`.
    pub fn fill(&mut self, n: impl Fn(f64) -> f64) {
        let (c0, dxi) = (self.first_centre, self.dxi);
        for (i, v) in self.n.iter_mut().enumerate() {
            *v = n(c0 + i as f64 * dxi);
        }
    }

    /// Moments `Q_k = ∫ ξ^k n dξ`, k = 0, 1, 2, exact for n constant on each cell.
    pub fn moments(&self) -> [f64; 3] {
        let (c0, dxi) = (self.first_centre, self.dxi);
        let w2 = dxi * dxi / 12.0;
        let mut q = [0.0; 3];
        for (i, &v) in self.n.iter().enumerate() {
            let c = c0 + i as f64 * dxi;
            q[0] += v;
            q[1] += v * c;
            q[2] += v * (c * c + w2);
        }
        [q[0] * dxi, q[1] * dxi, q[2] * dxi]
    }

    /// The rate integrals `φ_k = ∫ ξ^k (f + g) n dξ`, k = 0, 1, 2 (cell-centre rates).
    pub(crate) fn closure(&self, rates: &Rates) -> [f64; 3] {
        let (c0, dxi) = (self.first_centre, self.dxi);
        let mut phi = [0.0; 3];
        for (i, &v) in self.n.iter().enumerate() {
            if v == 0.0 {
                continue;
            }
            let c = c0 + i as f64 * dxi;
            let rate: f64 = split_cell(c, dxi)
                .iter()
                .filter(|(w, _)| *w > 0.0)
                .map(|(w, x)| w * (rates.attach(*x) + rates.detach(*x)))
                .sum();
            let k = rate * v;
            phi[0] += k;
            phi[1] += k * c;
            phi[2] += k * c * c;
        }
        [phi[0] * dxi, phi[1] * dxi, phi[2] * dxi]
    }

    /// Advances by `dt` seconds while every cell moves by `shift` (in ξ; `-∫u dt`, negative when
    /// shortening) at attachment factor `r`, each cell at its mid-step position. A cell that
    /// straddles a rate breakpoint (ξ = 0 or 1) is advanced part by part, each part with the
    /// rates at its own centroid, and keeps the length-weighted mean: the grid then responds
    /// smoothly to motion instead of switching a whole cell's bonds at once.
    pub fn advance(&mut self, rates: &Rates, r: f64, dt: f64, shift: f64) {
        let (c0, dxi) = (self.first_centre + 0.5 * shift, self.dxi);
        for (i, v) in self.n.iter_mut().enumerate() {
            let c = c0 + i as f64 * dxi;
            let parts = split_cell(c, dxi);
            *v = parts
                .iter()
                .filter(|(w, _)| *w > 0.0)
                .map(|(w, x)| w * relax(rates, r, *v, *x, dt))
                .sum();
        }
        self.first_centre += shift;
        self.maintain_cover();
    }

    /// Adds empty cells so that the grid covers the attachment range with its margin, and drops
    /// outer cells whose bonds are negligible.
    fn maintain_cover(&mut self) {
        let lo = -COVER_MARGIN;
        let hi = 1.0 + COVER_MARGIN;
        while self.first_centre - 0.5 * self.dxi > lo {
            self.make_room(true);
            self.n.push_front(0.0);
            self.first_centre -= self.dxi;
        }
        while self.last_centre() + 0.5 * self.dxi < hi {
            self.make_room(false);
            self.n.push_back(0.0);
        }
        while self.first_centre + 0.5 * self.dxi < lo
            && self.n.front().is_some_and(|v| v.abs() < NEGLIGIBLE_BONDS)
        {
            self.n.pop_front();
            self.first_centre += self.dxi;
        }
        while self.last_centre() - 0.5 * self.dxi > hi
            && self.n.back().is_some_and(|v| v.abs() < NEGLIGIBLE_BONDS)
        {
            self.n.pop_back();
        }
    }

    fn last_centre(&self) -> f64 {
        self.first_centre + (self.n.len() as f64 - 1.0) * self.dxi
    }

    /// Keeps the storage within its capacity: drops the cell at the far end from where one is
    /// about to be added (it is the oldest outflow cell).
    fn make_room(&mut self, adding_front: bool) {
        if self.n.len() + 1 >= self.capacity {
            if adding_front {
                self.n.pop_back();
            } else {
                self.n.pop_front();
                self.first_centre += self.dxi;
            }
        }
    }
}

/// The distribution: its first cell's centre and its cells (between one and the capacity); the
/// cell width and the capacity are the rebuilt grid's.
impl SavedState for CrossBridgeGrid {
    fn save_state(&self, out: &mut StateWriter) {
        out.f64(self.first_centre);
        out.usize(self.n.len());
        for &v in &self.n {
            out.f64(v);
        }
    }

    fn restore_state(&mut self, input: &mut StateReader) -> Result<(), StateError> {
        self.first_centre = input.f64("bond grid's first cell")?;
        self.n.clear();
        let cells = input.f64s_extend("bond grid cells", self.capacity, &mut self.n)?;
        // What a reset and every advance leave, to a cell: the attachment range and its margin
        // covered (a grid far from it would be extended cell by cell on the next sub-step).
        let slack = 2.0 * self.dxi;
        let (lo, hi) = (-COVER_MARGIN + slack, 1.0 + COVER_MARGIN - slack);
        let covers = cells > 0
            && self.first_centre.is_finite()
            && self.first_centre - 0.5 * self.dxi <= lo
            && self.last_centre() + 0.5 * self.dxi >= hi;
        if !covers {
            return Err(StateError::Invalid(format!(
                "bond grid: {cells} cells from {} do not cover the attachment range",
                self.first_centre
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::contractile::crossbridge_scale;
    use crate::physics::limb_params::MuscleParams;

    /// A grid after some motion comes back cell for cell; one moved off the attachment range,
    /// or with more cells than its room, is refused.
    #[test]
    fn a_saved_grid_comes_back_and_a_displaced_one_is_refused() {
        let scale = crossbridge_scale::calibrate_exact(&MuscleParams::default());
        let mut grid = CrossBridgeGrid::new(50, 4.0);
        for k in 0..40 {
            let shift = if k < 20 { -0.01 } else { 0.015 };
            grid.advance(&scale.rates, 0.8, 1e-3, shift);
        }
        let mut out = StateWriter::new();
        grid.save_state(&mut out);
        let mut back = CrossBridgeGrid::new(50, 4.0);
        back.restore_state(&mut StateReader::new(out.bytes()))
            .unwrap();
        assert_eq!(back.first_centre.to_bits(), grid.first_centre.to_bits());
        assert_eq!(back.n, grid.n);

        let mut moved = grid.clone();
        moved.first_centre += 0.5;
        let mut out = StateWriter::new();
        moved.save_state(&mut out);
        let e = back
            .restore_state(&mut StateReader::new(out.bytes()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("do not cover"), "{e}");

        let mut out = StateWriter::new();
        out.f64(grid.first_centre);
        out.usize(grid.capacity + 1);
        let e = back
            .restore_state(&mut StateReader::new(out.bytes()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("over its bound"), "{e}");
    }
}
