//! The library is not the book's build system: nothing under `src/` reads
//! the source tree at compile time (`include_str!`, `CARGO_MANIFEST_DIR`)
//! or picks the global allocator of the programs that link it. The book's
//! machinery lives in `book/companion`, and the allocator of the command
//! line is declared by its `main.rs`.

use std::path::{Path, PathBuf};

/// Marks that tie a file to the source tree or to every program linking it.
const FORBIDDEN: [&str; 3] = ["include_str!", "CARGO_MANIFEST_DIR", "#[global_allocator]"];

/// Files allowed to hold a mark, with why.
const EXEMPT: &[(&str, &str, &str)] = &[(
    "src/main.rs",
    "#[global_allocator]",
    "the binary chooses its own allocator",
)];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_library_holds_no_machinery_of_the_book() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    assert!(files.len() > 20, "only {} files under src/", files.len());
    let mut offenders = Vec::new();
    for path in files {
        let rel = path
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(&path).unwrap();
        for mark in FORBIDDEN {
            let exempt = EXEMPT.iter().any(|(f, m, _)| *f == rel && *m == mark);
            for (k, line) in text.lines().enumerate() {
                if line.contains(mark) && !exempt {
                    offenders.push(format!("{rel}:{}: {}", k + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "the book's machinery belongs in book/companion, a global allocator in a binary:\n{}",
        offenders.join("\n")
    );
}

/// The command line is the one program of this package that declares an
/// allocator (the exemption above is used, not stale), and the library
/// declares no module of the book.
#[test]
fn the_binary_declares_the_allocator_and_the_library_no_book_module() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let main = std::fs::read_to_string(root.join("src/main.rs")).unwrap();
    assert!(main.contains("#[global_allocator]"));
    let lib = std::fs::read_to_string(root.join("src/lib.rs")).unwrap();
    for module in ["book", "allocator"] {
        assert!(
            !lib.lines().any(|l| l
                .trim_start()
                .trim_start_matches("pub ")
                .starts_with(&format!("mod {module}"))),
            "src/lib.rs declares `{module}`"
        );
    }
}
