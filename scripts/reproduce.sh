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

echo "==> mdbook build book"
mdbook build book

echo "==> the book is at $(pwd)/book/book/index.html"
