//! How the short-lived commands take memory from the allocator (glibc on Linux; elsewhere as
//! usual): process-wide settings, made by the application before the work starts, never by the
//! library.

/// Keeps the memory the process frees for its later allocations (glibc only; elsewhere
/// nothing): no block is mapped on its own and the heap is not trimmed. An `anisomesh dtgrid`
/// step allocates and frees band-sized buffers (the new band, its distances, the system matrix); mapped afresh
/// each time, every page of them is faulted in and cleared by the kernel again (about a sixth
/// of a step's processor time on 257³). With this, a later step reuses the pages of the earlier
/// ones. The results do not change.
pub(super) fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets allocator parameters; it is called before the large buffers of a
    // run exist and takes effect for later allocations.
    unsafe {
        libc::mallopt(libc::M_MMAP_MAX, 0);
        libc::mallopt(libc::M_TRIM_THRESHOLD, libc::c_int::MAX);
    }
}

/// `anisomesh fit`: lets this short-lived process reuse the memory it frees and take its memory in large pages:
/// large blocks come from one heap instead of fresh `mmap` pages, the heap is not trimmed back,
/// and it is grown once by [`HEAP_RESERVE`] bytes that are marked for transparent huge pages
/// (where the system offers them on request), so the memory the fit touches is mapped a 2 MiB
/// page per fault instead of a 4 KiB page per fault (each fault is zeroed memory and a trip to
/// the kernel: the 201² case took about 3,500 faults, about 1,000 with the large pages).
/// Nothing is returned to the system before the command ends. Best effort: where a call fails,
/// memory is simply taken as usual; on systems other than Linux with glibc, it does nothing.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
pub(super) fn reserve_heap_in_large_pages() {
    const HUGE: usize = 2 << 20;
    // SAFETY: mallopt only sets allocator parameters, malloc/free pair a block, sbrk(0) only
    // reads the end of the heap, and madvise only advises on pages of the heap (which it does
    // not change); all before the threads start.
    unsafe {
        libc::mallopt(libc::M_ARENA_MAX, 1);
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 30);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 1 << 30);
        libc::mallopt(libc::M_TOP_PAD, HEAP_RESERVE as libc::c_int);
        // A block larger than what is left of the heap makes it grow by the reserve at once.
        // (`black_box`: the allocation is wanted for its effect on the heap alone.)
        let before = libc::sbrk(0) as usize;
        let block = std::hint::black_box(libc::malloc(4 * HUGE));
        libc::free(block);
        let end = libc::sbrk(0) as usize;
        if block.is_null() || before == usize::MAX || end == usize::MAX || end < before {
            return;
        }
        // The grown part, where the next allocations go (the block merged back into it).
        let start = before.next_multiple_of(HUGE);
        let stop = end / HUGE * HUGE;
        if stop > start {
            libc::madvise(
                start as *mut libc::c_void,
                stop - start,
                libc::MADV_HUGEPAGE,
            );
        }
    }
}

/// Outside Linux with glibc, memory is taken as usual.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub(super) fn reserve_heap_in_large_pages() {}

/// The heap `anisomesh fit` reserves at its start (64 MiB; the 201² case uses about 20 MiB;
/// beyond it the heap grows as usual).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const HEAP_RESERVE: usize = 64 << 20;
