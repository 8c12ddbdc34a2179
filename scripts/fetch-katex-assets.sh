#!/usr/bin/env bash
# (Re)create book/src/katex/ from the npm package `katex`.
#
# The assets are committed, so building or reading the book never needs this
# script; run it only to change the KaTeX version. The version must match the
# npm package katex that the book's preprocessor renders with (pinned in
# book/tools/package.json and package-lock.json), otherwise the HTML and the CSS
# may disagree; scripts/install-tools.sh refuses a mismatch. To upgrade:
#   (cd book/tools && npm install --save-exact katex@X.Y.Z) && scripts/fetch-katex-assets.sh X.Y.Z
#
# Only the woff2 fonts are kept (about 0.3 MB instead of 1.2 MB); every current
# browser reads woff2, and the stylesheet is rewritten to reference only those.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

KATEX_VERSION="${1:-$(node -e 'console.log(require("./book/tools/package-lock.json").packages["node_modules/katex"].version)')}"
DEST="book/src/katex"

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

echo "==> npm pack katex@$KATEX_VERSION"
(cd "$tmp" && npm pack --silent "katex@$KATEX_VERSION" >/dev/null && tar xzf "katex-$KATEX_VERSION.tgz")

rm -rf "$DEST"
mkdir -p "$DEST/fonts"
cp "$tmp"/package/dist/fonts/*.woff2 "$DEST/fonts/"
cp "$tmp/package/LICENSE" "$DEST/LICENSE"
# Drop the woff and ttf fallbacks from every @font-face rule.
sed -E 's/,url\(fonts\/[A-Za-z0-9_-]+\.woff\) format\("woff"\)//g; s/,url\(fonts\/[A-Za-z0-9_-]+\.ttf\) format\("truetype"\)//g' \
    "$tmp/package/dist/katex.min.css" > "$DEST/katex.min.css"
echo "$KATEX_VERSION" > "$DEST/VERSION"

if grep -qE '\.(woff|ttf)\)' "$DEST/katex.min.css"; then
    echo "error: katex.min.css still references woff/ttf fonts" >&2
    exit 1
fi
for f in $(grep -oE 'fonts/[A-Za-z0-9_-]+\.woff2' "$DEST/katex.min.css" | sort -u); do
    [ -f "$DEST/$f" ] || { echo "error: $DEST/$f referenced but missing" >&2; exit 1; }
done
echo "==> wrote $DEST ($(du -sh "$DEST" | cut -f1))"
