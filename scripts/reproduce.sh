#!/usr/bin/env bash
# Regenerate every result of the companion and build the book.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

# Idempotent: installs only missing tools (mdbook, the book's preprocessor, meshio).
echo "==> bash scripts/install-tools.sh"
bash scripts/install-tools.sh

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

# The formulation chapters' figures: basis functions, the disk's control net,
# the contact sketch.
echo "==> cargo run --release --example formulation"
cargo run --release --example formulation

# rustdoc, then the book, with the API pages copied into it.
bash scripts/build-book.sh
