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

/// Asks for the `LINES` cache lines from `at`, a 64-byte aligned address
/// (a hint: any address may be given, none is read; no-op off x86_64).
#[inline(always)]
pub fn prefetch_lines<const LINES: usize>(at: *const u8) {
    #[cfg(target_arch = "x86_64")]
    for l in 0..LINES {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: `_mm_prefetch` only needs SSE, part of the x86_64
        // baseline; a prefetch is a hint that never faults, whatever the
        // address (`wrapping_add` computes it without assuming anything),
        // and does not change memory.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(at.wrapping_add(64 * l) as *const i8) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = at;
}
