#!/usr/bin/env bash
# Idempotent installer for the tools the book and the checks need.
# Installs only what is missing or at the wrong version:
#   mdbook        (pinned) — builds the book
#   mdbook-katex  (pinned) — pre-renders $...$ / $$...$$ maths to HTML at build time
#   meshio        (pinned, Python) — used to check the VTU files the examples write
# Needs: cargo, python3 + pip. Reaches only crates.io and PyPI.
set -euo pipefail

MDBOOK_VERSION="0.5.4"
MDBOOK_KATEX_VERSION="0.10.0"
MESHIO_VERSION="5.3.5"

export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

say() { echo "[install-tools] $*"; }

# cargo_tool BIN CRATE VERSION: install CRATE@VERSION unless `BIN --version` already reports it.
cargo_tool() {
    local bin="$1" crate="$2" version="$3" have=""
    if command -v "$bin" >/dev/null 2>&1; then
        have="$("$bin" --version 2>/dev/null || true)"
    fi
    if [[ "$have" == *"$version"* ]]; then
        say "$crate $version already installed ($have)"
    else
        say "installing $crate $version (found: ${have:-none})"
        cargo install "$crate" --locked --version "$version"
    fi
}

cargo_tool mdbook mdbook "$MDBOOK_VERSION"
cargo_tool mdbook-katex mdbook-katex "$MDBOOK_KATEX_VERSION"

PY="${PYTHON:-python3}"
if have_meshio="$("$PY" -c 'import meshio, numpy; print(meshio.__version__)' 2>/dev/null)" \
        && [[ "$have_meshio" == "$MESHIO_VERSION" ]]; then
    say "meshio $MESHIO_VERSION already installed"
else
    say "installing meshio $MESHIO_VERSION and numpy (found: ${have_meshio:-none})"
    # Debian's system Python may be "externally managed" (PEP 668); allow installing anyway.
    pip_flags=(--quiet --disable-pip-version-check)
    if "$PY" -m pip install --help 2>/dev/null | grep -q -- --break-system-packages; then
        pip_flags+=(--break-system-packages)
    fi
    PIP_ROOT_USER_ACTION=ignore "$PY" -m pip install "${pip_flags[@]}" "meshio==$MESHIO_VERSION" numpy
fi

say "mdbook:       $(mdbook --version)"
say "mdbook-katex: $(mdbook-katex --version 2>/dev/null || echo "$MDBOOK_KATEX_VERSION")"
say "meshio:       $("$PY" -c 'import meshio; print(meshio.__version__)')"
