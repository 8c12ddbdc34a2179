#!/usr/bin/env bash
# Build the book with its API pages:
#   1. rustdoc of the workspace's default members, the library iga_contact and
#      the book's crate companion (cargo doc --no-deps --release), into target/doc;
#   2. mdbook build book: the preprocessor (book/tools/) renders the maths and
#      resolves the chapters' api: links against target/doc, failing on an
#      unknown name;
#   3. target/doc copied into the book's output as api/, where those links point.
# The generated tables and figures must exist already (scripts/reproduce.sh).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

doc_dir="${CARGO_TARGET_DIR:-target}/doc"
out="book/book"

echo "==> cargo doc --no-deps --release"
cargo doc --no-deps --release

echo "==> mdbook build book"
IGA_BOOK_API_DOC_DIR="$(cd "$doc_dir" && pwd)" mdbook build book

echo "==> copy $doc_dir to $out/api"
rm -rf "$out/api"
mkdir -p "$out/api"
# The lock file is cargo's, not part of the documentation.
cp -R "$doc_dir"/. "$out/api/"
rm -f "$out/api/.lock"
# cargo doc makes no top-level index for one crate; rustdoc's help and settings
# pages link to one.
cat > "$out/api/index.html" <<'HTML'
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>iga_contact API</title>
<meta http-equiv="refresh" content="0; url=iga_contact/index.html"></head>
<body><p><a href="iga_contact/index.html">The iga_contact API documentation</a></p></body></html>
HTML
echo "==> the book is at $(pwd)/$out/index.html, its API pages at $out/api/iga_contact/index.html"
