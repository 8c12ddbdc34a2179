//! The global allocator of every chapter program: each example links this
//! crate, so this declaration is theirs (feature `allocator`, which the root
//! package's default feature `allocator` turns on; the `iga-contact` binary
//! declares its own, the library none).
//!
//! Speed: assembly still allocates per element (the element matrix, its
//! DOF lists) and the triplet and column buffers grow from every thread.
//! The per-point vectors that made glibc's malloc twice as slow are gone
//! (`space::ElementValues`), and mimalloc still pays: assembling the CSC
//! stiffness of Hertz p = 2 took 0.29 s with the system allocator against
//! 0.20 s with mimalloc at 256², and 1.61 s against 0.76 s at 512² (medians
//! of five runs of `examples/assembly_bench.rs -- assembly 5 256 512` on a
//! shared two-core machine; before the buffers: 0.50 s and 0.27 s, 1.94 s
//! and 1.01 s). The chapters time the library as the command line runs it,
//! so they run on the allocator the command line uses.
//!
//! Unlike the binary's, this one is not guarded against a failed
//! allocation: a chapter program is run by the book's maintainers, for whom
//! Rust's abort names the failure well enough, and the fault-injection
//! programs probe the binary, not themselves.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
