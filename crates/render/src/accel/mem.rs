//! Allocation of the large traversal arrays.
//!
//! Traversal of a big BVH touches nodes and triangles at random, so most of
//! its time goes to cache and TLB misses; under virtualisation a TLB miss is a
//! two-level page walk. Backing the arrays with 2 MiB transparent huge pages
//! (as Embree does) removes most of those walks.

/// An empty `Vec` with room for `n` elements whose pages the kernel is asked
/// to back with transparent huge pages (Linux; elsewhere a plain `Vec`).
/// Fill it without growing past `n`, or the advice is lost with the buffer.
pub fn huge_vec<T>(n: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(n);
    #[cfg(target_os = "linux")]
    advise_huge(v.as_ptr() as usize, n * std::mem::size_of::<T>());
    v
}

#[cfg(target_os = "linux")]
fn advise_huge(addr: usize, bytes: usize) {
    const PAGE: usize = 4096;
    const MADV_HUGEPAGE: i32 = 14;
    extern "C" {
        fn madvise(addr: *mut std::ffi::c_void, len: usize, advice: i32) -> i32;
    }
    if bytes < (4 << 20) {
        return;
    }
    // Only whole pages inside the allocation.
    let start = (addr + PAGE - 1) & !(PAGE - 1);
    let end = (addr + bytes) & !(PAGE - 1);
    if end > start {
        // SAFETY: `[start, end)` is page aligned and lies inside a live
        // allocation we own (not yet initialised or shared). MADV_HUGEPAGE
        // is advisory only: it changes neither the contents nor the validity
        // of the mapping, and failure (e.g. THP disabled) is harmless, so the
        // return value is ignored.
        unsafe {
            madvise(start as *mut std::ffi::c_void, end - start, MADV_HUGEPAGE);
        }
    }
}

/// Asks for the cache lines of `items` ahead of their use (a hint; no-op
/// off x86_64).
#[inline(always)]
pub fn prefetch<T>(items: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let start = items.as_ptr() as usize & !63;
        let end = items.as_ptr() as usize + std::mem::size_of_val(items);
        let mut p = start;
        while p < end {
            // SAFETY: `_mm_prefetch` only needs SSE, part of the x86_64
            // baseline; a prefetch is a hint that never faults, whatever the
            // address, and does not change memory.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p as *const i8) };
            p += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = items;
}
