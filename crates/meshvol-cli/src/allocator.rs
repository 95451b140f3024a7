//! The allocator: mimalloc for small allocations, and whole pages, reused, for the large
//! short-lived arrays of a check (a check of a million triangles allocates and frees
//! about 0.8 GB of them, stage by stage).
//!
//! Arrays of [`LARGE`] bytes (256 KiB) or more are pages of their own ([`pages`]): freed, their
//! pages are kept, resident, and the next large array is made of them, in place or
//! moved by their page tables; fresh pages are touched only beyond the most the run
//! has held at once. Neither way used before did both: mimalloc's arenas reuse freed
//! space only where the next array fits, and grow to about twice what a check holds;
//! mapping each array from the system holds no more than the check does, but faults in
//! and zeroes every array's pages afresh, which on this project's virtual machine was a
//! quarter of a 5M-triangle check's time (`perf`: `clear_page_erms` 23%, 1.8% with the
//! pages reused). Measured there (`meshvol volume`, binary STL spheres and an OBJ,
//! 5 alternated runs, CPU seconds with both cores busy with other builds):
//!
//! | input | before: arenas below 100 MB of input, the system above | pages reused |
//! |---|---|---|
//! | 1M STL | 0.729 s, 234 MB | 0.684 s, 141 MB |
//! | 1M OBJ | 0.636 s, 237 MB | 0.648 s, 217 MB |
//! | 5M STL | 4.987 s, 511 MB | 3.925 s, 521 MB |
//!
//! A server, too, reuses the pages of its large arrays from request to request, holding
//! the most its requests have held at once, as mimalloc's arenas did (8 checks of a 1M
//! STL uploaded one after another, twice: 6.05 s and 253–255 MB against 6.21–6.23 s and
//! 258–263 MB); its small allocations keep mimalloc's default, which gives freed memory
//! back after a delay.

// Linux's: the pool moves pages with `mremap`. Elsewhere mimalloc takes every size.
#[cfg(target_os = "linux")]
mod pages;

#[cfg(target_os = "linux")]
use std::alloc::{GlobalAlloc, Layout};

/// Allocations of at least this many bytes are whole pages of their own. (A reader's
/// per-block arrays are a few hundred KiB: from pages, a 1M-triangle OBJ's `volume`
/// peaked at 167 MB against 209 MB with 1 MiB here, mimalloc's arenas holding them in
/// huge pages; 1M STL 122 MB against 141 MB; CPU time the same within the noise, 5 runs
/// each. 64 KiB gave 155 and 119 MB.)
#[cfg(target_os = "linux")]
const LARGE: usize = 256 << 10;

/// mimalloc's `mi_option_purge_delay` (mimalloc.h of the v3 sources libmimalloc-sys
/// builds; it names no constant for it).
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

/// mimalloc below [`LARGE`], [`pages`] from it.
#[cfg(target_os = "linux")]
struct Allocator;

#[cfg(target_os = "linux")]
#[global_allocator]
static ALLOCATOR: Allocator = Allocator;

#[cfg(not(target_os = "linux"))]
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Whether `layout` is served by [`pages`]: large, and aligned to no more than a page.
#[cfg(target_os = "linux")]
fn paged(layout: Layout) -> bool {
    layout.size() >= LARGE && layout.align() <= pages::PAGE
}

// SAFETY: each block is freed by the allocator that made it, told apart by its layout
// (which the caller passes unchanged); `realloc` moves a block across the threshold by
// a copy.
#[cfg(target_os = "linux")]
unsafe impl GlobalAlloc for Allocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if paged(layout) {
            pages::alloc(layout.size(), false)
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { mimalloc::MiMalloc.alloc(layout) }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if paged(layout) {
            pages::alloc(layout.size(), true)
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { mimalloc::MiMalloc.alloc_zeroed(layout) }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if paged(layout) {
            pages::free(ptr, layout.size());
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { mimalloc::MiMalloc.dealloc(ptr, layout) }
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: `realloc`'s contract: `new_size` with this alignment is a valid layout.
        let new = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
        match (paged(layout), paged(new)) {
            (true, true) => pages::resize(ptr, layout.size(), new_size),
            // SAFETY: the caller's contract, passed on.
            (false, false) => unsafe { mimalloc::MiMalloc.realloc(ptr, layout, new_size) },
            _ => {
                // SAFETY: a block for the new layout, the old contents copied up to the
                // smaller size, then the old block freed by its own allocator.
                unsafe {
                    let moved = self.alloc(new);
                    if !moved.is_null() {
                        std::ptr::copy_nonoverlapping(ptr, moved, layout.size().min(new_size));
                        self.dealloc(ptr, layout);
                    }
                    moved
                }
            }
        }
    }
}

/// Sets the allocator up for a run: mimalloc's freed memory kept for reuse, unless the
/// run is a server.
pub fn configure(server: bool) {
    if !server {
        keep_freed_memory();
    }
}

/// Gives the large arrays' freed pages back to the system: called when a run's check
/// has ended, since what follows (measuring) reads the surface again, a mapped file's
/// pages among it, and needs few large arrays. (Kept, a 5M-triangle `volume` peaked at
/// 800 MB in its measuring stage, against 548 MB given back.)
pub fn trim() {
    #[cfg(target_os = "linux")]
    pages::trim();
}

/// Keeps mimalloc's freed memory for reuse instead of giving it back to the kernel after
/// a delay. A run is one short process: memory given back is only faulted in again,
/// zeroed, by the next stage. Measured on a 5M-triangle check when mimalloc held the
/// large arrays too (`/usr/bin/time`, same file): 14,013 to 16,903 page faults with the default delay, 3,764 to 3,797 with none,
/// peak memory 0.92–0.99 GB against 1.00–1.02 GB.
fn keep_freed_memory() {
    // SAFETY: sets one option value, which mimalloc reads when it purges.
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
}
