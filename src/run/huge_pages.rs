//! The command line's memory allocator: the system's `malloc`, with Linux's
//! transparent huge pages asked for (`madvise(MADV_HUGEPAGE)`) on the
//! 2 MiB-aligned interior of every block of at least [`LARGE`] bytes.
//!
//! A run touches most of its memory once: the factor's values, the
//! trailing inverses, the pattern, the element blocks. `malloc` gives a
//! large block fresh pages from `mmap`, and the kernel faults them in
//! 4 KiB at a time: two-spheres' condensed run took about 57 000 minor
//! faults for 210 MiB, 0.12 s of system time beside 0.37 s of user time.
//! A huge page is one fault for 512 of those. Debian's kernels (and most
//! others) set `/sys/kernel/mm/transparent_hugepage/enabled` to
//! `madvise`, so a process gets huge pages only where it asks. Asked
//! (DESIGN.md, "Huge pages"), the same run takes about 23 000 faults, and
//! it is 8–10 % faster with the same peak memory and the same bits.
//!
//! Why by hand: glibc's own switch (`GLIBC_TUNABLES=glibc.malloc.hugetlb=1`)
//! is read from the environment when the process starts, so the program
//! cannot set it for itself; mimalloc (the `mimalloc` crate) faulted even
//! fewer pages but held 35–60 % more peak memory and was slower on Hertz.
//! Only blocks of at least [`LARGE`] bytes are advised: smaller ones share
//! pages with other blocks, and a huge page there would only add memory.
//! Where the kernel has huge pages off (`never`), or off Linux, the advice
//! does nothing.
//!
//! The library does not choose the allocator: `src/main.rs` installs
//! [`HugePageAdvice`] as the binary's `#[global_allocator]`.

use std::alloc::{GlobalAlloc, Layout, System};

/// A transparent huge page on x86-64 and (with 4 KiB base pages) AArch64.
pub const HUGE_PAGE: usize = 2 << 20;

/// Blocks from this size on are advised: at least one whole aligned huge
/// page lies inside any of them.
pub const LARGE: usize = 2 * HUGE_PAGE;

/// The system allocator, with huge pages asked for on large blocks.
pub struct HugePageAdvice;

/// The whole huge pages inside the block of `size` bytes at `address`:
/// `(start, length)` with `start` the first multiple of [`HUGE_PAGE`] at
/// or after `address` and `start + length` the last at or before
/// `address + size`; `None` for a block under [`LARGE`] bytes (or holding
/// no whole huge page).
pub fn huge_page_interior(address: usize, size: usize) -> Option<(usize, usize)> {
    if size < LARGE {
        return None;
    }
    let start = address.checked_next_multiple_of(HUGE_PAGE)?;
    let end = address.saturating_add(size) / HUGE_PAGE * HUGE_PAGE;
    (end > start).then(|| (start, end - start))
}

/// Asks the kernel for huge pages on the interior of the block at `p`
/// ([`huge_page_interior`]); a refusal (huge pages off, an old kernel)
/// only leaves the block on base pages.
fn advise(p: *mut u8, size: usize) {
    if p.is_null() {
        return;
    }
    #[cfg(target_os = "linux")]
    if let Some((start, length)) = huge_page_interior(p as usize, size) {
        // SAFETY: the range lies inside the block just allocated to us;
        // MADV_HUGEPAGE changes how its pages are backed, never its contents
        unsafe { libc::madvise(start as *mut libc::c_void, length, libc::MADV_HUGEPAGE) };
    }
    #[cfg(not(target_os = "linux"))]
    let _ = size;
}

// SAFETY: every block comes from `System` and goes back to it unchanged;
// `advise` neither moves nor frees memory.
unsafe impl GlobalAlloc for HugePageAdvice {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, passed on
        let p = unsafe { System.alloc(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, passed on
        let p = unsafe { System.alloc_zeroed(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, passed on
        unsafe { System.dealloc(p, layout) }
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's contract, passed on
        let q = unsafe { System.realloc(p, layout, new_size) };
        advise(q, new_size);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interior's ends are the huge-page multiples just inside the
    /// block, and a block with no whole huge page (or under `LARGE`) has
    /// none.
    #[test]
    fn the_interior_is_the_whole_huge_pages_inside() {
        let h = HUGE_PAGE;
        assert_eq!(huge_page_interior(h + 16, 4 * h), Some((2 * h, 3 * h)));
        assert_eq!(huge_page_interior(3 * h, 2 * h), Some((3 * h, 2 * h)));
        assert_eq!(huge_page_interior(h + 16, 2 * h), Some((2 * h, h)));
        assert_eq!(huge_page_interior(h + 16, 2 * h - 32), None);
        assert_eq!(huge_page_interior(0, LARGE - 1), None);
        assert_eq!(huge_page_interior(usize::MAX - h, LARGE), None);
    }
}
