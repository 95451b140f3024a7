//! The open cells of one base column, ready to refine: for each touching body the faces
//! whose boxes meet the cell (its list) and the area field of the faces wholly above it
//! ([`super::refine`]). One pass over the column's faces: a face goes to the lists of
//! the open cells its box meets, found by bisection over the column's open layers, and
//! its projected area to one bucket, that of the highest open cell it lies wholly above;
//! a suffix sum over the buckets, from the top down, gives every cell its field. So a
//! column costs its faces (each clipped to the fine squares once) and its open cells.

use super::bounds::{face_box, Bodies, Cell};
use super::refine::{add_area, meets, OpenCell, Part, FINE, MARGIN};
use crate::Surface;

impl<S: Surface + ?Sized> Bodies<'_, S> {
    /// The open cells of base column `c`, bottom up, with their parts.
    pub(super) fn open_cells(&self, c: usize) -> Vec<OpenCell> {
        let [_, ny, nz] = self.grid.counts;
        let (i, j) = (c / ny, c % ny);
        let mut cells: Vec<OpenCell> = (0..nz)
            .filter_map(|k| match self.cell(c * nz + k) {
                Cell::Open { lower, upper } => Some(OpenCell {
                    column: c,
                    at: [i as f64, j as f64, k as f64],
                    level: 0,
                    parts: Vec::new(),
                    lower,
                    upper,
                }),
                Cell::Exact(_) => None,
            })
            .collect();
        if cells.is_empty() {
            return cells;
        }
        let touch = self.column_touches(c);
        let squares = FINE * FINE;
        let origin = [i as f64, j as f64, 0.0];
        for (b, body) in self.bodies.iter().enumerate() {
            // The open cells this body touches, bottom up.
            let mine: Vec<usize> =
                (0..cells.len()).filter(|&n| touch[b * nz + cells[n].at[2] as usize]).collect();
            if mine.is_empty() {
                continue;
            }
            let mut lists = vec![Vec::new(); mine.len()];
            let mut buckets = vec![0.0; mine.len() * squares];
            for &f in self.bins[b].column(c) {
                let (lo, hi) = face_box(body, f as usize, |p| self.units.map(p));
                // Cells 0..below lie wholly below the face; from `below` up, the face may
                // meet them until their bottom passes its top.
                let below = mine.partition_point(|&n| cells[n].at[2] + 1.0 + MARGIN < lo[2]);
                for (n, list) in lists.iter_mut().enumerate().skip(below) {
                    let at = cells[mine[n]].at;
                    if at[2] - MARGIN > hi[2] {
                        break;
                    }
                    if meets(lo, hi, at, 1.0) {
                        list.push(f);
                    }
                }
                if below > 0 {
                    let bucket = &mut buckets[(below - 1) * squares..below * squares];
                    body.fan(f as usize, |p, q, r| {
                        add_area([p, q, r].map(|v| self.units.map(v)), origin, FINE, bucket);
                    });
                }
            }
            // Field of cell n: the faces wholly above it, those of buckets n and up.
            for n in (0..mine.len().saturating_sub(1)).rev() {
                let (low, high) = buckets.split_at_mut((n + 1) * squares);
                for (a, b) in low[n * squares..].iter_mut().zip(&high[..squares]) {
                    *a += b;
                }
            }
            for ((n, faces), above) in lists.into_iter().enumerate().zip(buckets.chunks(squares)) {
                let part = Part { body: b, faces, above: above.to_vec() };
                cells[mine[n]].parts.push(part);
            }
        }
        cells
    }
}
