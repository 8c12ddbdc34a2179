//! The global allocator of every program built on the crate (feature
//! `allocator`, on by default; turn it off with `default-features = false`
//! to keep your own).
//!
//! Two reasons. Speed: assembly still allocates per element (the element
//! matrix, its DOF lists) and the triplet and column buffers grow from
//! every thread. The per-point vectors that made glibc's malloc twice as
//! slow are gone (`space::ElementValues`), and mimalloc still pays:
//! assembling the CSC stiffness of Hertz p = 2 took 0.29 s with the
//! system allocator against 0.20 s with mimalloc at 256², and 1.61 s
//! against 0.76 s at 512² (medians of five runs of
//! `examples/assembly_bench.rs -- assembly 5 256 512` on a shared
//! two-core machine; before the buffers: 0.50 s and 0.27 s, 1.94 s and
//! 1.01 s). Safety: a failed allocation
//! ends the process with one `error:` line and exit code 1 instead of
//! Rust's abort.

use std::alloc::{GlobalAlloc, Layout};
use std::io::Write;

/// The allocator the guard forwards to.
static INNER: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The allocator, except that a failed allocation ends the process
/// with one `error:` line and exit code 1 instead of Rust's abort (SIGABRT,
/// "memory allocation of … bytes failed"). The resource estimate refuses
/// runs that would not fit before they start; this is the last line of
/// defence when the estimate is exceeded (another process took the memory,
/// a `ulimit -v` tighter than the budget).
struct Guarded;

// SAFETY: every call is forwarded to the inner allocator unchanged; only
// a null result is intercepted, and then the process ends.
unsafe impl GlobalAlloc for Guarded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = INNER.alloc(layout);
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = INNER.alloc_zeroed(layout);
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = INNER.realloc(ptr, layout, new_size);
        if p.is_null() {
            out_of_memory(new_size);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        INNER.dealloc(ptr, layout)
    }
}

/// Reports a failed allocation and exits, allocating nothing: the message
/// is formatted into a stack buffer and written with `write(2)`.
fn out_of_memory(size: usize) -> ! {
    let mut buf = [0u8; 320];
    let mut cur = std::io::Cursor::new(&mut buf[..]);
    let _ = writeln!(
        cur,
        "error: out of memory: allocating {size} bytes failed; the run needs more memory than is \
         available (lower --max-memory to have such runs refused before they start)"
    );
    let n = cur.position() as usize;
    // SAFETY: writes n initialised bytes of `buf` to stderr, then exits
    // without running destructors or allocating.
    unsafe {
        libc::write(2, buf.as_ptr().cast(), n);
        libc::_exit(1)
    }
}

#[global_allocator]
static ALLOCATOR: Guarded = Guarded;
