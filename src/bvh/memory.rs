//! Memory for a hierarchy's arrays: fallible allocation and advice to the kernel on pages (huge
//! pages for arrays written once into fresh memory, pre-faulting pages another thread will write).

use crate::error::Error;

/// An empty vector with room for `n`, or `Err(ModelOutOfMemory)`. A large one is offered huge
/// pages (see [`advise_huge_pages`]): a load writes every byte of its arrays once, into fresh
/// memory. (The build's own arrays are not offered them: see its `with_room` in `build.rs`.)
pub(crate) fn with_room<T>(n: usize) -> Result<Vec<T>, Error> {
    let mut v: Vec<T> = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| Error::ModelOutOfMemory)?;
    advise_huge_pages(v.as_mut_ptr().cast(), n * std::mem::size_of::<T>());
    Ok(v)
}

#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
unsafe extern "C" {
    /// libc's `int madvise(void *addr, size_t length, int advice)`.
    fn madvise(
        addr: *mut std::ffi::c_void,
        length: usize,
        advice: std::ffi::c_int,
    ) -> std::ffi::c_int;
}

/// Asks Linux to back the whole 2 MiB pages of `len` bytes at `start`, freshly allocated and not
/// yet touched, with huge pages (`madvise(MADV_HUGEPAGE)`; transparent huge pages on request are
/// the default setting). A load writes every byte of the model once: with 4 KiB pages most of its
/// time goes to the kernel's page faults (measured: 184 MB copied into fresh memory in 125-190 ms,
/// 35 ms with huge pages). Advice only: contents and ownership do not change, and where it is
/// refused (huge pages off) or not built (other systems, Miri) nothing changes but the speed.
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
pub(crate) fn advise_huge_pages(start: *mut u8, len: usize) {
    const HUGE: usize = 1 << 21;
    // MADV_HUGEPAGE on these targets (asm-generic/mman-common.h).
    const MADV_HUGEPAGE: std::ffi::c_int = 14;
    if len < 2 * HUGE {
        return;
    }
    let first = (start as usize).next_multiple_of(HUGE);
    let end = (start as usize + len) & !(HUGE - 1);
    if end > first {
        // SAFETY: [first, end) lies inside the allocation of `len` bytes at `start`, which the
        // caller owns; the advice changes neither its contents nor its mapping's validity. A
        // failure (huge pages disabled) is ignored: it only means no speed-up.
        unsafe { madvise(first as *mut std::ffi::c_void, end - first, MADV_HUGEPAGE) };
    }
}

#[cfg(not(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
)))]
pub(crate) fn advise_huge_pages(_start: *mut u8, _len: usize) {}

/// Asks Linux to map in, writable, the 4 KiB pages wholly inside the `len` bytes at `start` (part
/// of an allocation), as the first write to each would (`madvise(MADV_POPULATE_WRITE)`, Linux 5.14
/// on), without reading or writing any byte: the contents do not change, and another thread may
/// be using the memory meanwhile. Whether the call succeeded: false if refused (an older kernel)
/// or not built (other systems, Miri).
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
pub(crate) fn populate_pages(start: *mut u8, len: usize) -> bool {
    const PAGE: usize = 1 << 12;
    // MADV_POPULATE_WRITE (asm-generic/mman-common.h).
    const MADV_POPULATE_WRITE: std::ffi::c_int = 23;
    let first = (start as usize).next_multiple_of(PAGE);
    let end = (start as usize + len) & !(PAGE - 1);
    if end <= first {
        return true;
    }
    // SAFETY: [first, end) lies inside the allocation of `len` bytes at `start`; populating maps
    // in its pages with the contents they already have (zeros for pages never touched) and
    // accesses no byte of them as far as the program can tell.
    unsafe {
        madvise(
            first as *mut std::ffi::c_void,
            end - first,
            MADV_POPULATE_WRITE,
        ) == 0
    }
}

#[cfg(not(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
)))]
pub(crate) fn populate_pages(_start: *mut u8, _len: usize) -> bool {
    false
}
