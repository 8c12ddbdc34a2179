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

# The Lamé verification of the elasticity chapter is not a contact study;
# its example regenerates that chapter's table and figure.
echo "==> cargo run --release --example lame"
cargo run --release --example lame

echo "==> mdbook build book"
mdbook build book

echo "==> the book is at $(pwd)/book/book/index.html"
