//! The book's chapters as doc-tests: every Rust code block of every chapter
//! is compiled and run by `cargo test`, so the book cannot drift from the code.

// ANCHOR: chapters
macro_rules! chapters {
    ($($name:ident => $file:literal),* $(,)?) => {
        $(
            #[cfg(doctest)]
            #[doc = include_str!(concat!("../../src/", $file))]
            pub mod $name {}
        )*
    };
}

chapters! {
    introduction => "introduction.md",
    notation => "notation.md",
    claims => "claims.md",
    nurbs => "nurbs.md",
    elasticity => "elasticity.md",
    gap => "gap.md",
    nitsche => "nitsche.md",
    penalty => "penalty.md",
    bfgs => "bfgs.md",
    correction => "correction.md",
    taylor => "taylor.md",
    hertz => "hertz.md",
    two_cylinders => "two_cylinders.md",
    pin_ring => "pin_ring.md",
    iga_vs_fem => "iga_vs_fem.md",
    error_vs_time => "error_vs_time.md",
    solvers => "solvers.md",
    stability => "stability.md",
    incompressibility => "incompressibility.md",
    penalty_study => "penalty_study.md",
    scenes => "scenes.md",
    reliability => "reliability.md",
    limitations => "limitations.md",
}
// ANCHOR_END: chapters
