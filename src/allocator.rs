//! The global allocator of every program built on the crate (feature
//! `allocator`, on by default; turn it off with `default-features = false`
//! to keep your own).
//!
//! Two reasons. Speed: assembly allocates small vectors per quadrature
//! point from every thread, and with glibc's malloc it took twice as long
//! as with mimalloc (Hertz p = 2: 0.59 s against 0.30 s at 256², 0.044 s
//! against 0.023 s at 64²), which made assembly cost more than the
//! Cholesky factorisation on small meshes. Safety: a failed allocation
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
