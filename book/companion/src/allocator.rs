//! The global allocator of every chapter program: each example links this
//! crate, so this declaration is theirs (feature `allocator`, which the root
//! package's default feature `allocator` turns on; the `iga-contact` binary
//! declares its own, the library none).
//!
//! Speed: the command line's whole run of Hertz p = 2 on 256² is about
//! 1.2× faster with mimalloc than with the system allocator, though
//! assembly alone now gains little (the figures are in the doc comment of
//! `allocator` in `src/main.rs`). The chapters time the library as the
//! command line runs it, so they run on the allocator the command line
//! uses.
//!
//! Unlike the binary's, this one is not guarded against a failed
//! allocation: a chapter program is run by the book's maintainers, for whom
//! Rust's abort names the failure well enough, and the fault-injection
//! programs probe the binary, not themselves.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
