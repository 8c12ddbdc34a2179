#!/usr/bin/env bash
# Regenerate every result of the companion and build the book.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

# Idempotent: installs only missing tools (mdbook, the book's preprocessor, meshio).
echo "==> bash scripts/install-tools.sh"
bash scripts/install-tools.sh

# Every chapter program (examples/), each regenerating its chapter's folder
# book/src/generated/<chapter>/ as one set of files.
echo "==> cargo run --release --bin reproduce"
cargo run --release --bin reproduce

# rustdoc, then the book, with the API pages copied into it.
bash scripts/build-book.sh
