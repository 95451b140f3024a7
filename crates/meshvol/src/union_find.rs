//! Union–find: connected components under joins, with path halving. The smaller root
//! wins every join, so the components' roots do not depend on the order of joins.
//!
//! The one union–find of the crate: welding with a tolerance (clusters of close
//! points), the check's shells (faces joined across edges) and fans (corners joined
//! around a vertex), and [`crate::surface::connected_parts`] (faces joined at shared
//! positions).

pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }

    /// Back to `n` singletons, keeping the allocation.
    pub fn reset(&mut self, n: usize) {
        self.0.clear();
        self.0.extend(0..n as u32);
    }

    /// The root of `x`'s component: its smallest member.
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }

    /// Joins the components of `a` and `b`; whether they were apart.
    pub fn join(&mut self, a: u32, b: u32) -> bool {
        let (a, b) = (self.find(a), self.find(b));
        self.0[a.max(b) as usize] = a.min(b);
        a != b
    }
}
