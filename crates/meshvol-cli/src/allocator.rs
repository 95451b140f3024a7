//! The allocator, mimalloc, and how it holds the large short-lived arrays of a check
//! (a check of a million triangles allocates and frees about 0.8 GB of them, stage by
//! stage).
//!
//! Two ways, each best somewhere. **Reuse** (mimalloc's arenas, freed memory kept): no
//! page is faulted in twice, but a freed array's space is not always the shape the next
//! stage asks for, so the arenas grow to about twice what a check holds at once.
//! **From the system** (each large array mapped, and unmapped when freed): the process
//! holds what the check holds, and every array's pages are faulted in fresh. Measured on
//! this project's 2-core machine (`meshvol volume`, binary STL spheres, alternated runs):
//!
//! | triangles | reuse | from the system |
//! |---|---|---|
//! | 1M (8 runs) | 0.423 s, 230 MB | 0.528 s, 115 MB |
//! | 5M (4 runs) | 2.79–3.28 s, 1001–1011 MB | 2.28–2.43 s, 515 MB |
//!
//! So a run reuses until it reads an input of [`LARGE_INPUT`] bytes or more (about 2M
//! triangles of binary STL), and from then on takes large arrays from the system: small
//! inputs go fastest, and large ones fit (a 100M-triangle check in 10.2 GB). A server
//! keeps mimalloc's default, giving freed memory back after a delay, since it runs for
//! long; its uploads are held to the memory guard's estimate.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// mimalloc's `mi_option_purge_delay` and `mi_option_disallow_arena_alloc` (mimalloc.h of
/// the v3 sources libmimalloc-sys builds; it names no constants for them).
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;
const MI_OPTION_DISALLOW_ARENA_ALLOC: libmimalloc_sys::mi_option_t = 26;

/// The input size from which large arrays come from the system.
const LARGE_INPUT: u64 = 100_000_000;

/// Sets the allocator up for a run: freed memory kept for reuse, unless the run is a
/// server.
pub fn configure(server: bool) {
    if !server {
        keep_freed_memory();
    }
}

/// Called with each input's size before it is read.
pub fn reading(bytes: u64) {
    if bytes >= LARGE_INPUT {
        from_the_system();
    }
}

/// Large arrays from the system from now on, not from mimalloc's arenas.
fn from_the_system() {
    // SAFETY: sets one option value, which mimalloc reads on each allocation.
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_DISALLOW_ARENA_ALLOC, 1) };
}

/// Keeps freed memory for reuse instead of giving it back to the kernel after a delay.
/// A run is one short process: memory given back is only faulted in again, zeroed, by
/// the next stage. Measured on a 5M-triangle check (`/usr/bin/time`, same file): 14,013
/// to 16,903 page faults with the default delay, 3,764 to 3,797 with none, peak memory
/// 0.92–0.99 GB against 1.00–1.02 GB.
fn keep_freed_memory() {
    // SAFETY: sets one option value, which mimalloc reads when it purges.
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
}
