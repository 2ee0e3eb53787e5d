"""Every public result of the book's scenarios, as fingerprints, for proving that a change of the code leaves
them as they were.

    python tests/regression/public_results.py record [--build _build] [--out tests/regression/public_results.json.gz]
    python tests/regression/public_results.py compare [--build _build]

Two sources are fingerprinted:

* the whole runs of ``benchmarks/public_runs.py`` (each CLIK method, ``clik2``, every controller of chapter 6 on
  the plant with the 5 kg payload, the PD + gravity loop): every array the result holds, its internal signals
  and the numbers of its ``summary()``;
* every executed chapter of the built book (``<build>/jupyter_execute``): every number the chapter glues into
  its text and the data of every figure it draws (each numeric array of each trace and frame).

An array's fingerprint is the SHA-256 of its bytes (equal means bit-identical), its shape, the sums of its
entries and of their magnitudes, and at most ``SAMPLES`` of its entries evenly spread over it. ``compare``
accepts an array that is bit-identical, or whose sums and samples agree within ``RTOL`` relative to the array's
largest magnitude (an operation whose order changed; a chapter's entries within ``BOOK_RTOL`` or ``BOOK_ATOL``,
for LAPACK's last bits differ between CPUs); it prints one line per difference and exits 1 when there
is any. Timings (``elapsed``, and glued numbers in ms or ns of the machine's clock) are not results
and are left out by name (``VARYING``).
"""
from __future__ import annotations

import argparse
import base64
import gzip
import hashlib
import importlib.util
import json
import math
import pathlib
import re
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEFAULT_OUT = ROOT / "tests" / "regression" / "public_results.json.gz"
SAMPLES = 64
RTOL = 1e-15
#: the executed chapters also compute with LAPACK (SVDs, eigenvalues, solves through numpy and scipy), whose last
#: bits depend on the kernels OpenBLAS picks for the machine's CPU: on an AMD EPYC with AVX2 (no AVX-512) four
#: of 72,784 book entries moved from the record made elsewhere: an SVD's smallest singular value at a singular
#: configuration (round-off of zero, 2.5e-17 -> 5.0e-17), a figure's 2.3e-10 error (7e-17 apart), an alignment
#: read from eigenvectors (3.6e-13 relative) and a sampled loop's eigenvalues (4.7e-14). A book entry agrees
#: within BOOK_RTOL of its largest magnitude, or BOOK_ATOL apart; a run (numba, the same on every CPU here)
#: within RTOL
BOOK_RTOL = 1e-12
BOOK_ATOL = 1e-15
#: names (regular expressions on the full key) whose values are the machine's timings, not results
VARYING = re.compile(r"(run_time|elapsed|_ms$|_ms_|_ns$|speed|timing|per_move|wall|cpu_|_cost|cost_|seconds|ratio_numba|"
                     r"startup|import_time|compile)", re.I)


# ---------------------------------------------------------------------------------------------- fingerprints
def fingerprint(value) -> dict:
    a = np.ascontiguousarray(np.asarray(value, dtype=float))
    flat = a.ravel()
    finite = flat[np.isfinite(flat)]
    idx = np.unique(np.linspace(0, flat.size - 1, min(SAMPLES, flat.size)).round().astype(int)) if flat.size else []
    return {
        "sha": hashlib.sha256(a.tobytes()).hexdigest()[:24],
        "shape": list(a.shape),
        "sum": float(finite.sum()) if finite.size else 0.0,
        "abs": float(np.abs(finite).sum()) if finite.size else 0.0,
        "max": float(np.abs(finite).max()) if finite.size else 0.0,
        "nonfinite": int(flat.size - finite.size),
        "samples": [None if not math.isfinite(float(flat[i])) else float(flat[i]) for i in idx],
    }


def _numeric(v) -> bool:
    try:
        a = np.asarray(v)
    except Exception:  # noqa: BLE001 - ragged lists and the like are not numeric arrays
        return False
    return a.dtype.kind in "fiu" and a.dtype != bool


def _put(out: dict, key: str, value):
    if VARYING.search(key):
        return
    if isinstance(value, (bool, np.bool_, str, type(None))):
        out[key] = {"exact": value if not isinstance(value, np.bool_) else bool(value)}
    elif _numeric(value):
        out[key] = fingerprint(value)


# --------------------------------------------------------------------------------------------- whole runs
def run_results() -> dict:
    spec = importlib.util.spec_from_file_location("public_runs", ROOT / "benchmarks" / "public_runs.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    out = {}
    for name, (fn, _timer) in mod.runs().items():
        result = fn()
        for attr, v in sorted(vars(result).items()):
            if isinstance(v, dict):
                for k, s in sorted(v.items()):
                    _put(out, f"run/{name}/{attr}/{k}", s)
            elif isinstance(v, np.ndarray):
                _put(out, f"run/{name}/{attr}", v)
        for k, v in sorted(result.summary().items()):
            _put(out, f"run/{name}/summary/{k}", v)
    return out


# ------------------------------------------------------------------------------------------ executed book
def _decode(obj):
    """plotly's JSON with its base64 arrays (``{dtype, bdata, shape}``) turned back into numpy arrays."""
    if isinstance(obj, dict):
        if "bdata" in obj and "dtype" in obj:
            a = np.frombuffer(base64.b64decode(obj["bdata"]), dtype=np.dtype(obj["dtype"]))
            if "shape" in obj:
                shape = [int(s) for s in str(obj["shape"]).split(",")] if isinstance(obj["shape"], str) else obj["shape"]
                a = a.reshape(shape)
            return a
        return {k: _decode(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_decode(v) for v in obj]
    return obj


def _figure_arrays(prefix: str, obj, out: dict):
    if isinstance(obj, np.ndarray):
        _put(out, prefix, obj)
    elif isinstance(obj, dict):
        for k, v in obj.items():
            if k in ("uid", "meta", "template"):
                continue
            _figure_arrays(f"{prefix}/{k}", v, out)
    elif isinstance(obj, list):
        if obj and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in obj):
            _put(out, prefix, np.asarray(obj, dtype=float))
        elif obj and all(isinstance(v, list) for v in obj) and _numeric(obj):
            _put(out, prefix, np.asarray(obj, dtype=float))
        else:
            for i, v in enumerate(obj):
                _figure_arrays(f"{prefix}[{i}]", v, out)
    elif isinstance(obj, (int, float)) and not isinstance(obj, bool):
        _put(out, prefix, float(obj))
    elif isinstance(obj, str) and prefix.endswith(("/text", "/title/text", "/name")):
        out[prefix] = {"exact": obj}


def _glued_number(text: str):
    try:
        return float(text)
    except ValueError:
        return None


def book_results(build: pathlib.Path) -> dict:
    out = {}
    executed = build / "jupyter_execute"
    notebooks = sorted(executed.rglob("*.ipynb"))
    if not notebooks:
        raise SystemExit(f"no executed chapters under {executed}: build the book first (jupyter-book build .)")
    for nb_path in notebooks:
        chapter = nb_path.stem
        nb = json.loads(nb_path.read_text())
        outputs = [o for cell in nb["cells"] for o in cell.get("outputs", [])]
        glued = nb_path.with_suffix(".glue.json")  # myst-nb keeps the values glued with display=False here
        if glued.exists():
            outputs += list(json.loads(glued.read_text()).values())
        figure = 0
        for output in outputs:
            data = output.get("data", {})
            name = output.get("metadata", {}).get("scrapbook", {}).get("name")
            plot = data.get("application/vnd.plotly.v1+json")
            if name is not None:
                key = f"book/{chapter}/glue/{name}"
                if plot is not None:
                    _figure_arrays(key, _decode(plot), out)
                    continue
                text = "".join(data.get("text/markdown", data.get("text/plain", "")))
                number = _glued_number(text)
                if number is not None:
                    _put(out, key, number)
                elif "text/html" not in data and not VARYING.search(key):
                    out[key] = {"exact": text}
            elif plot is not None:
                _figure_arrays(f"book/{chapter}/figure{figure}", _decode(plot), out)
                figure += 1
    return out


# ------------------------------------------------------------------------------------------------ compare
def agree(before: dict, after: dict, rtol: float = RTOL, atol: float = 0.0) -> str | None:
    """None when ``after`` equals ``before`` (bit-identical, or within ``rtol`` of the largest magnitude, or
    ``atol`` apart); else what differs."""
    if "exact" in before or "exact" in after:
        return None if before.get("exact") == after.get("exact") else f"{before.get('exact')!r} -> {after.get('exact')!r}"
    if before["sha"] == after["sha"]:
        return None
    if before["shape"] != after["shape"] or before["nonfinite"] != after["nonfinite"]:
        return f"shape {before['shape']} -> {after['shape']} (non-finite {before['nonfinite']} -> {after['nonfinite']})"
    scale = max(before["max"], after["max"], np.finfo(float).tiny)
    n = max(1, int(np.prod(before["shape"])))
    for what in ("sum", "abs"):
        if abs(before[what] - after[what]) > max(rtol * scale, atol) * n:
            return f"{what} {before[what]!r} -> {after[what]!r}"
    for i, (b, a) in enumerate(zip(before["samples"], after["samples"])):
        if (b is None) != (a is None) or (b is not None and abs(b - a) > max(rtol * scale, atol)):
            return f"sample {i}: {b!r} -> {a!r} (scale {scale:.3g})"
    return None


#: results whose name changed with the package's one vocabulary (the end of the recorded key -> its end now);
#: the values are compared as before
RENAMED = {
    "summary/max_abs_error": "summary/max_abs_error_components",
    "summary/rms_error": "summary/rms_error_components",
    "summary/steady_state_error": "summary/steady_state_error_components",
}


def current_name(key: str) -> str:
    """The name a recorded result has now (:data:`RENAMED`)."""
    for old, now in RENAMED.items():
        if key.endswith("/" + old):
            return key[: -len(old)] + now
    return key


def compare(recorded: dict, current: dict) -> list[str]:
    """What differs between the recorded results and the current ones, one line each (timings left out)."""
    problems = []
    for key, before in recorded.items():
        if VARYING.search(key):
            continue
        now_key = current_name(key)
        if now_key not in current:
            problems.append(f"{key}: missing now")
            continue
        book = key.startswith("book/")
        why = agree(before, current[now_key], BOOK_RTOL if book else RTOL, BOOK_ATOL if book else 0.0)
        if why:
            problems.append(f"{key}: {why}")
    return problems


def collect(build: pathlib.Path, runs: bool = True, book: bool = True) -> dict:
    out = {}
    if runs:
        out.update(run_results())
    if book:
        out.update(book_results(build))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("action", choices=("record", "compare"))
    ap.add_argument("--build", type=pathlib.Path, default=ROOT / "_build")
    ap.add_argument("--out", type=pathlib.Path, default=DEFAULT_OUT)
    ap.add_argument("--only", choices=("runs", "book"), help="fingerprint (and compare) only the whole runs or the book")
    args = ap.parse_args(argv)
    current = collect(args.build, runs=args.only != "book", book=args.only != "runs")
    if args.action == "record":
        with gzip.open(args.out, "wt") as fh:
            json.dump(current, fh, sort_keys=True)
        print(f"recorded {len(current)} results to {args.out}")
        return 0
    recorded = json.load(gzip.open(args.out, "rt"))
    if args.only:
        recorded = {k: v for k, v in recorded.items() if k.startswith("run/" if args.only == "runs" else "book/")}
    problems = compare(recorded, current)
    for p in problems:
        print(p)
    print(f"{len(recorded)} recorded results, {len(problems)} differ")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
