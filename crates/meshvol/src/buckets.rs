//! Items grouped by a small integer key: a counting sort.
//!
//! Corners by vertex (for edges and fans), faces by smallest vertex (for duplicates),
//! corners by hash slice (for welding) and items by the top bits of their Morton code
//! (for spatial order) are all "group by an integer below a known bound". A counting
//! sort does that in two linear passes (count, then place) without a comparison, in
//! parallel and with the same result at any thread count, and leaves each group tiny,
//! so sorting within groups is cheap. At a million triangles this replaced comparison
//! sorts of three million 128-bit keys: 0.28 s → about 0.08 s single-threaded for the
//! edge table.

use rayon::prelude::*;
use std::ops::Range;

/// Asks the processor to start loading the cache lines of `value` (a hint: no effect on
/// results, never a fault). Loops that read scattered items in an order known ahead
/// (the corners of a welding slice) prefetch a few items ahead, so that the memory
/// latencies overlap instead of adding up.
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let first = (value as *const T).cast::<i8>();
        let last = first.wrapping_add(std::mem::size_of::<T>().saturating_sub(1));
        // SAFETY: a prefetch reads nothing the program sees and cannot fault; SSE is
        // part of every x86_64 target.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(first);
            _mm_prefetch::<_MM_HINT_T0>(last);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// Items grouped by key: group k is `items[start[k]..start[k + 1]]`, in the order the
/// items were produced.
pub(crate) struct Buckets<T> {
    pub start: Vec<usize>,
    pub items: Vec<T>,
}

impl<T: Copy + Default + Send + Sync> Buckets<T> {
    /// Groups the `(key, item)` pairs that `pairs(inputs)` yields by key (every key
    /// below `keys`). The inputs `0..inputs` are split into ranges counted and placed
    /// in parallel; `pairs` must yield the same pairs each time it is given a range.
    /// The result does not depend on the split.
    pub fn new<I: Iterator<Item = (u32, T)>>(
        keys: usize,
        inputs: usize,
        pairs: impl Fn(Range<usize>) -> I + Sync,
    ) -> Self {
        let parts = rayon::current_num_threads().clamp(1, 16).min(inputs.max(1));
        let part = |j: usize| j * inputs / parts..(j + 1) * inputs / parts;
        let mut cursors: Vec<Vec<usize>> = (0..parts)
            .into_par_iter()
            .map(|j| {
                let mut count = vec![0usize; keys];
                pairs(part(j)).for_each(|(k, _)| count[k as usize] += 1);
                count
            })
            .collect();
        // Key-major: key k's items from part 0, then part 1, ...
        let start = par_starts(keys, |k| cursors.iter().map(|count| count[k]).sum::<usize>());
        let mut next: Vec<usize> = start[..keys].par_iter().copied().collect();
        for cursor in &mut cursors {
            cursor.par_iter_mut().zip(next.par_iter_mut()).for_each(|(cursor, next)| {
                let count = *cursor;
                (*cursor, *next) = (*next, *next + count);
            });
        }
        let mut items = filled(start[keys], T::default());
        let out = SharedItems::new(&mut items);
        cursors.into_par_iter().enumerate().for_each(|(j, mut cursor)| {
            for (k, item) in pairs(part(j)) {
                let at = &mut cursor[k as usize];
                // SAFETY: part j's cursor for key k runs over the positions counted for
                // (k, j), which no other (key, part) shares, and all lie below `total`.
                unsafe { out.write(*at, item) };
                *at += 1;
            }
        });
        Buckets { start, items }
    }

    /// [`Buckets::new`] for many keys (about as many as items: corners by vertex, faces
    /// by smallest vertex), when the items come in increasing order (face or corner
    /// numbers): the same groups in the same order. One counter a key, shared by all
    /// threads (atomics, so no key × thread table: 16 threads made it 320 MB at five
    /// million triangles, with a serial prefix sum over it), a prefix sum in parallel
    /// blocks, items placed through the shared counters in whatever order threads
    /// reach them, then each group sorted back into increasing order.
    pub fn new_increasing<I: Iterator<Item = (u32, T)>>(
        keys: usize,
        inputs: usize,
        pairs: impl Fn(Range<usize>) -> I + Sync,
    ) -> Self
    where
        T: Ord,
    {
        use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
        const PART: usize = 1 << 14;
        let parts = inputs.div_ceil(PART);
        let part = |j: usize| j * PART..((j + 1) * PART).min(inputs);
        let counter = || (0..keys).into_par_iter().map(|_| AtomicUsize::new(0)).collect();
        let count: Vec<AtomicUsize> = counter();
        (0..parts).into_par_iter().for_each(|j| {
            pairs(part(j)).for_each(|(k, _)| {
                count[k as usize].fetch_add(1, Relaxed);
            })
        });
        let start = par_starts(keys, |k| count[k].load(Relaxed));
        let total = start[keys];
        drop(count);
        let cursor: Vec<AtomicUsize> =
            start[..keys].par_iter().map(|&s| AtomicUsize::new(s)).collect();
        let mut items = filled(total, T::default());
        let out = SharedItems::new(&mut items);
        (0..parts).into_par_iter().for_each(|j| {
            for (k, item) in pairs(part(j)) {
                let at = cursor[k as usize].fetch_add(1, Relaxed);
                // SAFETY: each fetch_add hands out a distinct position of key k's group,
                // which was counted, so below `total`.
                unsafe { out.write(at, item) };
            }
        });
        drop(cursor);
        let mut buckets = Buckets { start, items };
        buckets.for_each_mut(|group| {
            if group.len() > 1 {
                group.sort_unstable();
            }
        });
        buckets
    }

    pub fn get(&self, key: usize) -> &[T] {
        &self.items[self.start[key]..self.start[key + 1]]
    }

    /// Runs `f` on every group, in parallel.
    pub fn for_each_mut(&mut self, f: impl Fn(&mut [T]) + Sync) {
        let start = &self.start;
        let range = |k: usize| start[k]..start[k + 1];
        for_each_range_mut(&mut self.items, start.len() - 1, &range, &|_, group| f(group));
    }
}

/// Where each group starts when groups of these sizes are laid end to end: `sizes.len()
/// + 1` running totals from 0 (group k is `starts[k]..starts[k + 1]`).
pub(crate) fn starts<T: Copy + Default + std::ops::Add<Output = T>>(
    sizes: impl ExactSizeIterator<Item = T>,
) -> Vec<T> {
    let mut starts = Vec::with_capacity(sizes.len() + 1);
    let mut total = T::default();
    starts.push(total);
    for size in sizes {
        total = total + size;
        starts.push(total);
    }
    starts
}

/// [`starts`] of the sizes `size(0..n)`, summed in parallel blocks (the same totals at
/// any thread count: integers) and written by the workers that summed them.
///
/// Serial prefix sums over every face, corner or vertex, and the serial fill of their
/// fresh arrays, were most of what did not scale in a check (16 threads: a check of
/// 5M triangles was 8× faster than on one thread, its parallel parts 11×).
pub(crate) fn par_starts<T>(n: usize, size: impl Fn(usize) -> T + Sync) -> Vec<T>
where
    T: Copy + Default + std::ops::Add<Output = T> + Send + Sync,
{
    // Blocks of 4k to 64k items, at least four a thread where there are enough items:
    // a block is one task (sizes can cost a pass over other arrays), and integer sums
    // are the same whatever the blocks.
    let len = n.div_ceil(4 * rayon::current_num_threads()).clamp(1 << 12, 1 << 16);
    let block = |b: usize| b * len..((b + 1) * len).min(n);
    let block_sums: Vec<T> = (0..n.div_ceil(len))
        .into_par_iter()
        .map(|b| block(b).fold(T::default(), |total, k| total + size(k)))
        .collect();
    let block_start = starts(block_sums.into_iter());
    let mut start = filled(n + 1, T::default());
    start[n] = block_start[block_start.len() - 1];
    start[..n].par_chunks_mut(len).enumerate().for_each(|(b, out)| {
        let mut total = block_start[b];
        for (o, k) in out.iter_mut().zip(block(b)) {
            *o = total;
            total = total + size(k);
        }
    });
    start
}

/// `item(i)` for each `i < n` that `keep(i)`, in order: kept items counted in parallel
/// blocks and written in place by the workers. (A rayon `filter(..).collect()` appends
/// its workers' pieces on one thread: 80 MB of a 5M-triangle solid's faces, serially.)
pub(crate) fn par_compact<T: Copy + Default + Send + Sync>(
    n: usize,
    keep: impl Fn(usize) -> bool + Sync,
    item: impl Fn(usize) -> T + Sync,
) -> Vec<T> {
    const BLOCK: usize = 1 << 16;
    let blocks = n.div_ceil(BLOCK);
    let block = |b: usize| (b * BLOCK..((b + 1) * BLOCK).min(n)).filter(|&i| keep(i));
    // Each block counted by a task of its own: `par_starts` over the few blocks would
    // hand them all to one task (it splits its input in blocks of its own size), and
    // counting is a pass over every item (on 16 threads, the welded vertices' 15M
    // corners took 27 ms this way, as long as on 2).
    let counts: Vec<usize> = (0..blocks).into_par_iter().map(|b| block(b).count()).collect();
    let first = starts(counts.into_iter());
    let mut out = filled(first[blocks], T::default());
    for_each_range_mut(&mut out, blocks, &|b| first[b]..first[b + 1], &|b, out| {
        for (out, i) in out.iter_mut().zip(block(b)) {
            *out = item(i);
        }
    });
    out
}

/// `len` copies of `value`, written by all the workers, a part each: the first touch of
/// fresh memory (the system's faults and zeroing of its pages) is most of the cost of a
/// large array, and `vec![value; len]` writes it on one thread.
pub(crate) fn filled<T: Copy + Send + Sync>(len: usize, value: T) -> Vec<T> {
    let mut out = Vec::with_capacity(len);
    out.par_extend(rayon::iter::repeat_n(value, len));
    out
}

/// A buffer that threads write at disjoint positions (each position by one thread).
pub(crate) struct SharedItems<'a, T> {
    items: *mut T,
    len: usize,
    _borrow: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: used only to write disjoint positions, and to read positions no thread
// writes at the time (see the callers' SAFETY notes).
unsafe impl<T: Send> Sync for SharedItems<'_, T> {}

impl<'a, T> SharedItems<'a, T> {
    pub fn new(items: &'a mut [T]) -> Self {
        SharedItems { items: items.as_mut_ptr(), len: items.len(), _borrow: Default::default() }
    }

    /// # Safety
    /// No other thread writes or reads position `at` while this runs.
    pub unsafe fn write(&self, at: usize, item: T) {
        assert!(at < self.len);
        unsafe { self.items.add(at).write(item) }
    }

    /// # Safety
    /// No thread writes position `at` while this runs.
    pub unsafe fn read(&self, at: usize) -> T
    where
        T: Copy,
    {
        assert!(at < self.len);
        unsafe { self.items.add(at).read() }
    }
}

/// Runs `f(k, &mut items[range(k)])` for every k below `count`, in parallel, where the
/// ranges are consecutive and cover `items` (faces' corners, buckets' items).
pub(crate) fn for_each_range_mut<T: Send>(
    items: &mut [T],
    count: usize,
    range: &(impl Fn(usize) -> Range<usize> + Sync),
    f: &(impl Fn(usize, &mut [T]) + Sync),
) {
    fn split<T: Send>(
        items: &mut [T],
        keys: Range<usize>,
        range: &(impl Fn(usize) -> Range<usize> + Sync),
        f: &(impl Fn(usize, &mut [T]) + Sync),
    ) {
        let offset = if keys.is_empty() { 0 } else { range(keys.start).start };
        if items.len() < 1 << 15 || keys.len() < 2 {
            for k in keys {
                let r = range(k);
                f(k, &mut items[r.start - offset..r.end - offset]);
            }
        } else {
            let mid = keys.start + keys.len() / 2;
            let (left, right) = items.split_at_mut(range(mid).start - offset);
            rayon::join(
                || split(left, keys.start..mid, range, f),
                || split(right, mid..keys.end, range, f),
            );
        }
    }
    split(items, 0..count, range, f);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn increasing_items_group_as_the_counting_sort_does_at_any_thread_count() {
        // Keys scattered over many groups (more keys than a thread table would want),
        // items in increasing order: the same groups as `new`, in the same order.
        let n = 300_000usize;
        let keys = 120_000usize;
        let key = |i: usize| ((i as u64 * 2_654_435_761 % 1_000_003) % keys as u64) as u32;
        let pairs =
            |r: Range<usize>| r.flat_map(move |i| [(key(i), i as u32), (key(i / 3), i as u32)]);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| Buckets::new(keys, n, pairs));
        for threads in [1, 2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let b = pool.install(|| Buckets::new_increasing(keys, n, pairs));
            assert_eq!((&b.start, &b.items), (&one.start, &one.items), "{threads} threads");
        }
    }

    #[test]
    fn groups_by_key_keeping_order_and_sorts_groups() {
        let pairs = [(2u32, 'a'), (0, 'b'), (2, 'c'), (1, 'd'), (0, 'e')];
        let mut b = Buckets::new(4, pairs.len(), |r| pairs[r].iter().copied());
        assert_eq!(b.start, [0, 2, 3, 5, 5]);
        assert_eq!(b.items, ['b', 'e', 'd', 'a', 'c']);
        assert_eq!(b.get(3), [] as [char; 0]);
        b.for_each_mut(|g| g.reverse());
        assert_eq!(b.items, ['e', 'b', 'd', 'c', 'a']);
        // Any number of threads: the same groups, in input order.
        let in_pool = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| Buckets::new(97, 10_000, |r| r.map(|i| ((i * 31 % 97) as u32, i))))
        };
        let one = in_pool(1);
        for threads in [2, 3, 16] {
            let many = in_pool(threads);
            assert_eq!((&many.start, &many.items), (&one.start, &one.items));
        }
        assert!((0..97).all(|k| one.get(k).windows(2).all(|w| w[0] < w[1])));
        // Large enough to split across threads: each group sorted on its own.
        let n = 200_000u32;
        let mut big =
            Buckets::new(1000, n as usize, |r| r.map(|i| (i as u32 % 1000, n - i as u32)));
        big.for_each_mut(|g| g.sort_unstable());
        for k in 0..1000 {
            let g = big.get(k);
            assert_eq!(g.len(), 200);
            assert!(
                g.windows(2).all(|w| w[0] < w[1])
                    && g.iter().all(|&x| x % 1000 == (1000 - k as u32) % 1000)
            );
        }
    }

    #[test]
    fn parallel_starts_and_compaction_equal_the_serial_loops_at_any_thread_count() {
        // More than one block, the last one short; sizes and keeps scattered.
        let n = 3 * (1 << 16) + 12_345;
        let size = |i: usize| (i * 2_654_435_761) % 7;
        let keep = |i: usize| (i * 40_503) % 11 < 4;
        let mut serial_starts = vec![0usize];
        for i in 0..n {
            serial_starts.push(serial_starts[i] + size(i));
        }
        let serial_kept: Vec<(usize, u8)> =
            (0..n).filter(|&i| keep(i)).map(|i| (i, (i % 251) as u8)).collect();
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (starts, kept, fill) = pool.install(|| {
                (
                    par_starts(n, size),
                    par_compact(n, keep, |i| (i, (i % 251) as u8)),
                    filled(n, 7u16),
                )
            });
            assert_eq!(starts, serial_starts, "{threads} threads");
            assert_eq!(kept, serial_kept, "{threads} threads");
            assert!(fill.len() == n && fill.iter().all(|&x| x == 7));
        }
        assert_eq!(par_starts(0, size), [0]);
        assert!(par_compact(0, keep, |i| i).is_empty());
    }
}
