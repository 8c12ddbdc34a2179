#!/usr/bin/env python3
"""Read every VTU under a directory with meshio and compare it with its
NAME.expected.json sidecar, when there is one.

Why: the VTU writer is hand-written, so an independent reader is the only
real test that ParaView and friends will see the numbers we meant. The
sidecar carries the same numbers in a second encoding (JSON), so a mismatch
points at a formatting bug rather than a numerical one.

Usage: python3 scripts/check_vtu.py DIR
Prints one line per file; exits 1 on any failure or if no VTU is found.
Works with meshio 5.3.5 and numpy 2.
"""

import json
import sys
from pathlib import Path

import numpy as np

try:
    import meshio
except ImportError:
    print("check_vtu: meshio is not installed (pip install meshio==5.3.5)", file=sys.stderr)
    sys.exit(2)

REL_TOL = 1e-12


def compare(label, got, want):
    """None if `got` matches `want` to REL_TOL relative to max(1, max |want|),
    otherwise a one-line description of the mismatch."""
    got = np.asarray(got, dtype=np.float64).ravel()
    want = np.asarray(want, dtype=np.float64).ravel()
    if got.shape != want.shape:
        return f"{label}: {got.size} values, expected {want.size}"
    if not np.all(np.isfinite(got)):
        return f"{label}: non-finite value at index {int(np.argmin(np.isfinite(got)))}"
    if want.size == 0:
        return None
    diff = float(np.max(np.abs(got - want)))
    scale = max(1.0, float(np.max(np.abs(want))))
    if diff > REL_TOL * scale:
        k = int(np.argmax(np.abs(got - want)))
        return f"{label}: max |diff| {diff:.3e} > {REL_TOL:.0e}·{scale:.3e} (index {k}: {got[k]!r} vs {want[k]!r})"
    return None


def check(path):
    """Returns (ok, message) for one VTU file."""
    try:
        mesh = meshio.read(path, file_format="vtu")
    # meshio reports some failures with sys.exit(1) rather than an exception;
    # either way it is this file's failure, not the end of the run.
    except (Exception, SystemExit) as e:
        return False, f"meshio cannot read it: {type(e).__name__}: {e}"

    n_points = len(mesh.points)
    n_cells = sum(len(block.data) for block in mesh.cells)
    summary = f"{n_points} points, {n_cells} cells, point data {sorted(mesh.point_data)}"

    for name, values in mesh.point_data.items():
        values = np.asarray(values)
        if values.shape[0] != n_points:
            return False, f"point data {name!r} has {values.shape[0]} rows for {n_points} points"
        if not np.all(np.isfinite(values)):
            return False, f"point data {name!r} holds non-finite values"

    expected_path = path.with_name(path.name[: -len(".vtu")] + ".expected.json")
    if not expected_path.exists():
        return True, summary + " (read only: no .expected.json)"
    try:
        expected = json.loads(expected_path.read_text())
    except (OSError, ValueError) as e:
        return False, f"cannot read {expected_path.name}: {e}"

    problems = []
    if "points" in expected:
        p = compare("points", mesh.points, expected["points"])
        if p:
            problems.append(p)
    for name, want in expected.get("point_data", {}).items():
        if name not in mesh.point_data:
            problems.append(f"point data {name!r} missing")
            continue
        p = compare(f"point data {name!r}", mesh.point_data[name], want)
        if p:
            problems.append(p)
    if problems:
        return False, "; ".join(problems)
    n_arrays = len(expected.get("point_data", {}))
    return True, summary + f" (matches {expected_path.name}: points + {n_arrays} arrays)"


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-3], file=sys.stderr)
        return 2
    root = Path(argv[1])
    if not root.is_dir():
        print(f"check_vtu: {root} is not a directory", file=sys.stderr)
        return 1
    files = sorted(root.rglob("*.vtu"))
    if not files:
        print(f"check_vtu: FAIL: no .vtu file under {root}")
        return 1
    failures = 0
    for path in files:
        ok, message = check(path)
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {path}: {message}")
    print(f"check_vtu: {len(files) - failures}/{len(files)} files ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
