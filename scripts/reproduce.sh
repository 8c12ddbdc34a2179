#!/usr/bin/env bash
# Regenerate every result of the companion and build the book.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

if ! command -v mdbook >/dev/null 2>&1 || ! command -v mdbook-katex >/dev/null 2>&1; then
    echo "==> book tools missing: bash scripts/install-tools.sh"
    bash scripts/install-tools.sh
fi

echo "==> cargo run --release --bin iga-contact -- reproduce"
cargo run --release --bin iga-contact -- reproduce

# The Lamé verification of the elasticity chapter and the kernel
# benchmark are not contact studies; their examples regenerate their
# chapters' tables and figures.
echo "==> cargo run --release --example lame"
cargo run --release --example lame

# The kernel-factorisation comparison of "Starting and correcting BFGS".
echo "==> cargo run --release --example kernel_factorisation"
cargo run --release --example kernel_factorisation

echo "==> mdbook build book"
mdbook build book

echo "==> the book is at $(pwd)/book/book/index.html"
