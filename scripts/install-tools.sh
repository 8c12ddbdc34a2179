#!/usr/bin/env bash
# Idempotent installer for the tools the book and the checks need; installs only
# what is missing or at the wrong version, all pinned:
#   mdbook 0.5.4     builds the book; only its `search` feature (no server, no
#                    file watcher: those are most of its compile time)
#   book/tools/      the book's preprocessor (Node.js): the npm package katex,
#                    pinned by book/tools/package-lock.json, installed by `npm ci`
#   meshio 5.3.5     (Python) checks the VTU files the examples write
# With --checks, also what .ci/run's browser check needs:
#   chromium         Debian's package (apt-get)
#   websocket-client 1.9.2 (Python) drives it over the DevTools protocol
# Needs: cargo, node >= 18 with npm, python3 with pip. Reaches only crates.io,
# npm, PyPI (and Debian's apt with --checks).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

MDBOOK_VERSION="0.5.4"
MDBOOK_FEATURES="search"
MESHIO_VERSION="5.3.5"
WEBSOCKET_CLIENT_VERSION="1.9.2"

checks=false
for arg in "$@"; do
    case "$arg" in
        --checks) checks=true ;;
        *) echo "usage: $0 [--checks]" >&2; exit 2 ;;
    esac
done

export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
say() { echo "[install-tools] $*"; }

# --- mdbook -------------------------------------------------------------------
have="$(mdbook --version 2>/dev/null || true)"
if [[ "$have" == "mdbook v$MDBOOK_VERSION" ]]; then
    say "mdbook $MDBOOK_VERSION already installed"
else
    say "installing mdbook $MDBOOK_VERSION, features: $MDBOOK_FEATURES (found: ${have:-none})"
    cargo install mdbook --locked --version "$MDBOOK_VERSION" \
        --no-default-features --features "$MDBOOK_FEATURES"
fi

# --- the book's preprocessor ----------------------------------------------------
if ! node_version="$(node --version 2>/dev/null)"; then
    echo "error: node (>= 18) is needed to build the book: apt-get install -y nodejs npm" >&2
    exit 1
fi
node_major="${node_version#v}"
node_major="${node_major%%.*}"
if (( node_major < 18 )); then
    echo "error: node $node_version is too old; the book's preprocessor needs node >= 18" >&2
    exit 1
fi
want_katex="$(node -e 'console.log(require("./book/tools/package-lock.json").packages["node_modules/katex"].version)')"
have_katex="$(node -e 'try { console.log(require("./book/tools/node_modules/katex/package.json").version) } catch { console.log("none") }')"
if [[ "$have_katex" == "$want_katex" ]]; then
    say "katex $want_katex already installed in book/tools/node_modules"
else
    say "installing katex $want_katex into book/tools/node_modules (found: $have_katex)"
    npm ci --prefix book/tools --no-audit --no-fund --loglevel=error
fi
css_katex="$(cat book/src/katex/VERSION)"
if [[ "$css_katex" != "$want_katex" ]]; then
    echo "error: book/src/katex is KaTeX $css_katex but book/tools pins katex $want_katex:" \
         "run scripts/fetch-katex-assets.sh $want_katex" >&2
    exit 1
fi

# --- Python packages --------------------------------------------------------------
PY="${PYTHON:-python3}"
pip_install() {
    # Debian's system Python may be "externally managed" (PEP 668); allow installing anyway.
    local flags=(--quiet --disable-pip-version-check)
    if "$PY" -m pip install --help 2>/dev/null | grep -q -- --break-system-packages; then
        flags+=(--break-system-packages)
    fi
    PIP_ROOT_USER_ACTION=ignore "$PY" -m pip install "${flags[@]}" "$@"
}
# py_package IMPORT_NAME VERSION PIP_SPEC...: install unless IMPORT_NAME reports VERSION.
py_package() {
    local module="$1" version="$2" have
    shift 2
    have="$("$PY" -c "import $module; print($module.__version__)" 2>/dev/null || echo none)"
    if [[ "$have" == "$version" ]]; then
        say "$module $version already installed"
    else
        say "installing $* (found: $module $have)"
        pip_install "$@"
    fi
}
py_package meshio "$MESHIO_VERSION" "meshio==$MESHIO_VERSION" numpy

# --- the browser check (.ci/run) ----------------------------------------------------
if $checks; then
    if command -v chromium >/dev/null 2>&1; then
        say "chromium already installed"
    else
        say "installing chromium (apt)"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq
        apt-get install -y -qq chromium >/dev/null
    fi
    py_package websocket "$WEBSOCKET_CLIENT_VERSION" "websocket-client==$WEBSOCKET_CLIENT_VERSION"
    say "chromium:     $(chromium --version 2>/dev/null | head -1)"
fi

say "mdbook:       $(mdbook --version)"
say "node:         $node_version, katex $want_katex"
say "meshio:       $("$PY" -c 'import meshio; print(meshio.__version__)')"
