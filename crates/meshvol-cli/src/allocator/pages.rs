//! Large arrays as whole pages, and freed pages reused by moving them.
//!
//! A check's large arrays live a stage or two each, and each stage asks for other
//! sizes. Mapping every array afresh costs a page fault and a zeroed page for each
//! 4 KiB, every time; on a virtual machine whose host takes back freed memory (free
//! page reporting) the first touch of such a page costs about ten times as much again.
//! An arena that keeps freed space reuses it only where the next array fits, and grows
//! to about twice what a check holds.
//!
//! This pool keeps the *pages* of freed arrays, mapped and resident, and makes the next
//! large array out of them: the smallest free region large enough is used in place (its
//! front; the rest stays free); failing that, free regions, largest first, are moved
//! into a fresh mapping of the size asked with `mremap`, which moves page-table
//! entries, not bytes. So a run touches fresh pages only beyond the most it has held at
//! once, whatever the order and sizes of its arrays. Reused pages hold old bytes:
//! `alloc_zeroed` clears them (a `memset` at memory speed, against a fault for each
//! fresh page).
//!
//! `mremap` moves a range of one mapping only, and moved pieces stay mappings of their
//! own: so every free region lies inside one mapping, and an array made of pieces is
//! remembered with its pieces' lengths, and freed as those pieces.

use std::ptr::null_mut;
use std::sync::Mutex;

/// The page size (4 KiB on the platforms meshvol builds for; only a multiple of it
/// matters, since `mmap` and `mremap` round to pages themselves).
pub const PAGE: usize = 4096;

/// Free regions kept at most; the smallest are unmapped beyond it. (The pool's tables
/// are fixed arrays: the pool must not allocate, being inside the allocator.)
const REGIONS: usize = 256;

/// Free regions smaller than this are unmapped rather than kept.
const SMALLEST_KEPT: usize = 16 * PAGE;

/// Pieces an array is made of at most, the fresh part included.
const PIECES: usize = 16;

/// Arrays made of pieces alive at once at most; beyond it, arrays are mapped fresh.
const ASSEMBLED: usize = 64;

/// An array made of pieces: where it starts, and its pieces' lengths in order.
#[derive(Clone, Copy)]
struct Assembled {
    at: usize,
    pieces: usize,
    lengths: [usize; PIECES],
}

const NONE: Assembled = Assembled { at: 0, pieces: 0, lengths: [0; PIECES] };

struct Pool {
    /// Free regions `(address, length)`, lengths multiples of [`PAGE`], each inside one
    /// mapping.
    free: [(usize, usize); REGIONS],
    count: usize,
    /// The live arrays made of pieces.
    assembled: [Assembled; ASSEMBLED],
    assembled_count: usize,
}

static POOL: Mutex<Pool> = Mutex::new(Pool::new());

/// `size` rounded up to whole pages.
fn pages(size: usize) -> usize {
    size.div_ceil(PAGE) * PAGE
}

/// Gives the free regions kept until now back to the system.
pub fn trim() {
    lock().trim();
}

/// `size` bytes (> 0) on fresh or reused pages, cleared if `zeroed`; null if the system
/// has no memory for it.
pub fn alloc(size: usize, zeroed: bool) -> *mut u8 {
    let (at, reused) = lock().take(pages(size));
    if zeroed && reused > 0 {
        // SAFETY: [at, at + reused) is mapped, writable and now the caller's; past it
        // the pages are fresh, so zero already. Cleared outside the lock.
        unsafe { std::ptr::write_bytes(at as *mut u8, 0, reused.min(size)) };
    }
    at as *mut u8
}

/// Frees `size` bytes at `at`, a region [`alloc`] or [`resize`] gave.
pub fn free(at: *mut u8, size: usize) {
    lock().give_back(at as usize, pages(size));
}

/// The region at `at` of `old` bytes resized to `new` (both large), its contents kept
/// up to the smaller; null if the system has no memory for it (the old region then
/// still stands).
pub fn resize(at: *mut u8, old: usize, new: usize) -> *mut u8 {
    if let Some(moved) = lock().resize_in_place(at as usize, pages(old), pages(new)) {
        return moved as *mut u8;
    }
    // Made of pieces, which cannot move as one (or the system refused): a copy.
    let copy = alloc(new, false);
    if !copy.is_null() {
        // SAFETY: both regions are mapped, owned and disjoint; the first `old.min(new)`
        // bytes are the caller's contents.
        unsafe { std::ptr::copy_nonoverlapping(at, copy, old.min(new)) };
        free(at, old);
    }
    copy
}

impl Pool {
    const fn new() -> Pool {
        Pool { free: [(0, 0); REGIONS], count: 0, assembled: [NONE; ASSEMBLED], assembled_count: 0 }
    }

    /// `len` bytes (whole pages): where (0 if the system has none), and how many bytes
    /// at the front are reused pages, holding old contents (the rest are fresh, zero).
    fn take(&mut self, len: usize) -> (usize, usize) {
        // A free region large enough: its front, in place.
        if let Some(k) = self.best_fit(len) {
            let (at, free) = self.free[k];
            if free - len >= SMALLEST_KEPT {
                self.free[k] = (at + len, free - len);
            } else {
                self.remove(k);
                if free > len {
                    unmap(at + len, free - len);
                }
            }
            return (at, len);
        }
        let Some(at) = map(len) else { return (0, 0) };
        if self.count == 0 || self.assembled_count == ASSEMBLED {
            return (at, 0);
        }
        // Free regions, largest first, moved over the front of the fresh pages.
        let mut array = Assembled { at, ..NONE };
        let mut filled = 0;
        while self.count > 0 && filled < len && array.pieces < PIECES - 1 {
            let k = self.largest();
            let (from, free) = self.free[k];
            let moved = free.min(len - filled);
            if !move_pages(from, moved, at + filled) {
                break; // the region stays free; the rest of the array is fresh
            }
            if moved == free {
                self.remove(k);
            } else {
                self.free[k] = (from + moved, free - moved);
            }
            array.lengths[array.pieces] = moved;
            array.pieces += 1;
            filled += moved;
        }
        if filled < len {
            array.lengths[array.pieces] = len - filled;
            array.pieces += 1;
        }
        if array.pieces > 1 {
            self.assembled[self.assembled_count] = array;
            self.assembled_count += 1;
        }
        (at, filled)
    }

    /// Takes back the `len` bytes at `at` that [`Pool::take`] gave (or what a resize
    /// left of them): as its pieces, if it was made of them.
    fn give_back(&mut self, at: usize, len: usize) {
        match self.assembled_at(at) {
            Some(k) => {
                let array = self.assembled[k];
                self.assembled_count -= 1;
                self.assembled[k] = self.assembled[self.assembled_count];
                let mut start = array.at;
                for &piece in &array.lengths[..array.pieces] {
                    self.release(start, piece);
                    start += piece;
                }
            }
            None => self.release(at, len),
        }
    }

    /// The region at `at` resized from `old` to `new` bytes (whole pages) in place or
    /// moved by its page tables: its new place; `None` if it is made of pieces (which
    /// cannot move as one) or the system refuses.
    fn resize_in_place(&mut self, at: usize, old: usize, new: usize) -> Option<usize> {
        if self.assembled_at(at).is_some() {
            return None;
        }
        if new <= old {
            if new < old {
                self.release(at + new, old - new);
            }
            return Some(at);
        }
        grow(at, old, new)
    }

    fn trim(&mut self) {
        while self.count > 0 {
            let (at, len) = self.remove(self.count - 1);
            unmap(at, len);
        }
    }

    /// The smallest free region of at least `len` bytes.
    fn best_fit(&self, len: usize) -> Option<usize> {
        (0..self.count).filter(|&k| self.free[k].1 >= len).min_by_key(|&k| self.free[k].1)
    }

    /// The largest free region (the pool is not empty).
    fn largest(&self) -> usize {
        (0..self.count).max_by_key(|&k| self.free[k].1).unwrap_or(0)
    }

    /// The array made of pieces that starts at `at`, if it is one.
    fn assembled_at(&self, at: usize) -> Option<usize> {
        (0..self.assembled_count).find(|&k| self.assembled[k].at == at)
    }

    /// Removes free region `k` and returns it.
    fn remove(&mut self, k: usize) -> (usize, usize) {
        let region = self.free[k];
        self.count -= 1;
        self.free[k] = self.free[self.count];
        region
    }

    /// Takes back `[at, at + len)`, inside one mapping: kept for reuse, unless small.
    fn release(&mut self, at: usize, len: usize) {
        if len < SMALLEST_KEPT {
            unmap(at, len);
            return;
        }
        if self.count == REGIONS {
            // Full: the smallest region goes (this one, if it is the smallest).
            let k = (0..self.count).min_by_key(|&k| self.free[k].1).unwrap_or(0);
            if self.free[k].1 >= len {
                unmap(at, len);
                return;
            }
            let (a, l) = self.remove(k);
            unmap(a, l);
        }
        self.free[self.count] = (at, len);
        self.count += 1;
    }
}

fn lock() -> std::sync::MutexGuard<'static, Pool> {
    // A panic while the lock is held leaves the pool consistent (every change to it is
    // one assignment after the system call), so a poisoned lock is still good.
    POOL.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Fresh mappings from this long up to [`HUGE_PAGES_BELOW`] are backed by huge pages
/// where the system has them for the asking (transparent huge pages in `madvise` mode,
/// the common default): one fault for each 2 MiB instead of 512. Measured on a 2-core
/// VM, alternated runs: a checked `volume` of the 1M-triangle STL spheres 0.90–0.93 of
/// the time, the 85,184 boxes 0.90–0.99, the 5M sphere and the 1M OBJ unchanged, the
/// same peak memory.
const HUGE_PAGES_FROM: usize = 4 << 20;

/// Longer mappings keep small pages: with huge pages for every length, `grid --moments`
/// at 256³ (arrays of 134 MB and more) took 3.79 s against 3.56 s (7 alternated runs),
/// the kernel finding and zeroing whole 2 MiB pages at the first touch (as `Mesh.cells`
/// did in Python: docs/cells.md); below 64 MiB, 3.60 against 3.53 s.
const HUGE_PAGES_BELOW: usize = 64 << 20;

/// `len` bytes of fresh, zero pages.
fn map(len: usize) -> Option<usize> {
    // SAFETY: a new private anonymous mapping, at an address the kernel picks.
    let at = unsafe {
        libc::mmap(
            null_mut(),
            len,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        )
    };
    if at == libc::MAP_FAILED {
        return None;
    }
    if (HUGE_PAGES_FROM..HUGE_PAGES_BELOW).contains(&len) {
        // SAFETY: advice on the mapping just made; a refusal (no huge pages here) only
        // leaves it on small pages.
        unsafe { libc::madvise(at, len, libc::MADV_HUGEPAGE) };
    }
    Some(at as usize)
}

fn unmap(at: usize, len: usize) {
    // SAFETY: [at, at + len) is whole pages that nothing else refers to.
    unsafe { libc::munmap(at as *mut libc::c_void, len) };
}

/// Moves the pages of `[from, from + len)`, inside one mapping, to `to`, replacing the
/// fresh pages there; false if the system refuses (nothing then changes).
fn move_pages(from: usize, len: usize, to: usize) -> bool {
    // SAFETY: the source is a free region inside one mapping that nothing refers to; the
    // target is inside the mapping this allocation made, which nobody else uses yet.
    let moved = unsafe {
        libc::mremap(
            from as *mut libc::c_void,
            len,
            len,
            libc::MREMAP_MAYMOVE | libc::MREMAP_FIXED,
            to as *mut libc::c_void,
        )
    };
    moved != libc::MAP_FAILED
}

/// `[at, at + len)`, inside one mapping, grown to `new` bytes where it lies or moved
/// (its pages, not copied) to where it can grow; `None` if the system refuses, and the
/// region then stands as it was.
fn grow(at: usize, len: usize, new: usize) -> Option<usize> {
    // SAFETY: the region is whole pages of one mapping that nothing else refers to; the
    // kernel returns its new place, or fails and leaves it.
    let moved = unsafe { libc::mremap(at as *mut libc::c_void, len, new, libc::MREMAP_MAYMOVE) };
    (moved != libc::MAP_FAILED).then_some(moved as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MB: usize = 1 << 20;

    fn bytes<'a>(at: usize, len: usize) -> &'a mut [u8] {
        // SAFETY: the tests read and write only regions their pool handed out.
        unsafe { std::slice::from_raw_parts_mut(at as *mut u8, len) }
    }

    fn free_bytes(pool: &Pool) -> usize {
        pool.free[..pool.count].iter().map(|r| r.1).sum()
    }

    #[test]
    fn a_freed_region_is_reused_in_place_from_its_front() {
        let mut pool = Pool::new();
        let (at, reused) = pool.take(4 * MB);
        assert_eq!(reused, 0, "nothing to reuse yet: fresh pages");
        assert!(bytes(at, 4 * MB).iter().all(|&b| b == 0));
        bytes(at, 4 * MB).fill(7);
        pool.give_back(at, 4 * MB);
        let (again, reused) = pool.take(MB);
        assert_eq!((again, reused), (at, MB));
        assert!(bytes(again, MB).iter().all(|&b| b == 7), "the same pages, not fresh ones");
        assert_eq!(free_bytes(&pool), 3 * MB);
        pool.give_back(again, MB);
        pool.trim();
        assert_eq!(pool.count, 0);
    }

    #[test]
    fn a_larger_array_is_made_of_the_free_regions_moved_largest_first() {
        let mut pool = Pool::new();
        let regions: Vec<(usize, u8)> = [(2 * MB, 2u8), (3 * MB, 3), (4 * MB, 4)]
            .map(|(len, mark)| {
                let (at, _) = pool.take(len);
                bytes(at, len).fill(mark);
                (at, mark)
            })
            .into_iter()
            .collect();
        for (&(at, _), len) in regions.iter().zip([2 * MB, 3 * MB, 4 * MB]) {
            pool.give_back(at, len);
        }
        // 8 MB from 9 MB free in three regions: 4, then 3, then 1 of the 2.
        let (at, reused) = pool.take(8 * MB);
        assert_eq!(reused, 8 * MB);
        let array = bytes(at, 8 * MB);
        assert!(array[..4 * MB].iter().all(|&b| b == 4));
        assert!(array[4 * MB..7 * MB].iter().all(|&b| b == 3));
        assert!(array[7 * MB..].iter().all(|&b| b == 2));
        assert_eq!(free_bytes(&pool), MB);
        // Freed as its pieces, each movable again: 10 MB is the 9 reused and 1 fresh.
        pool.give_back(at, 8 * MB);
        assert_eq!((pool.count, pool.assembled_count), (4, 0));
        let (at, reused) = pool.take(10 * MB);
        assert_eq!(reused, 9 * MB);
        assert_eq!(pool.count, 0);
        assert!(bytes(at + 9 * MB, MB).iter().all(|&b| b == 0), "the fresh part is zero");
        assert!(bytes(at, 9 * MB).iter().all(|&b| (2..=4).contains(&b)));
        pool.give_back(at, 10 * MB);
        assert_eq!(free_bytes(&pool), 10 * MB);
        pool.trim();
    }

    #[test]
    fn resizing_keeps_the_contents() {
        let mut pool = Pool::new();
        let (at, _) = pool.take(2 * MB);
        for (i, b) in bytes(at, 2 * MB).iter_mut().enumerate() {
            *b = (i % 251) as u8;
        }
        // Grown by its page tables (in place or moved), then shrunk in place.
        let grown = pool.resize_in_place(at, 2 * MB, 6 * MB).expect("one mapping grows");
        let shrunk = pool.resize_in_place(grown, 6 * MB, MB).expect("shrinks in place");
        assert_eq!(shrunk, grown);
        assert_eq!(free_bytes(&pool), 5 * MB, "the cut tail is free for reuse");
        assert!(bytes(shrunk, MB).iter().enumerate().all(|(i, &b)| b == (i % 251) as u8));
        // An array made of pieces is not resized in place (the caller copies it).
        let (other, _) = pool.take(2 * MB);
        pool.give_back(other, 2 * MB);
        let (pieces, _) = pool.take(9 * MB);
        assert_eq!(pool.assembled_count, 1);
        assert_eq!(pool.resize_in_place(pieces, 9 * MB, 12 * MB), None);
        pool.give_back(pieces, 9 * MB);
        pool.give_back(shrunk, MB);
        pool.trim();
    }

    #[test]
    fn zeroed_arrays_are_zero_on_reused_pages() {
        // Through the process's allocator: arrays over the threshold, filled, freed, and
        // asked for again zeroed (on the pages just freed, unless another test's thread
        // took them first: then on others, which must be zero all the same).
        for round in 0..4 {
            let mut a = vec![0u8; 3 * MB + round * 12345];
            a.fill(0xa5);
            let len = a.len();
            drop(a);
            let b = vec![0u8; len - 4096];
            assert!(b.iter().all(|&x| x == 0), "round {round}");
            let c: Vec<u64> = vec![0; len / 8 + 1000];
            assert!(c.iter().all(|&x| x == 0), "round {round}");
        }
    }
}
