"""Run one submitted notebook and write what it answered: the part of the grading that runs inside the sandbox.

``python -m scara.course._runner NOTEBOOK RESULT TIMEOUT NAMES`` executes ``NOTEBOOK`` with nbclient in a fresh
kernel (every cell, errors allowed, ``TIMEOUT`` seconds per cell), then one more cell of its own that prints the
values of the answer variables ``NAMES`` (comma-separated), and writes ``RESULT`` (JSON): the status (``ok``,
``timeout``, ``dead``, ``memory``, ``unreadable``), the answers read, and the first error a cell of the student's
raised. This process sees only the submission's copy: it never holds the key.

Before the student's cells, a cell of its own (:data:`CAP`) caps what the kernel sends of the notebook's printed
output at :data:`OUTPUT_CAP` characters per stream: past it, the stream is the null device, so a cell that
prints a million lines runs in under a second rather than sending them all to this process (which would keep
them), and the collecting cell writes to the kernel's own stream, past the cap.
"""
from __future__ import annotations

import json
import sys

#: the line the collecting cell prints, before the answers as JSON
MARKER = "SCARA-ANSWERS "
#: the most characters of a student's error message kept for the feedback
ERROR_CHARS = 300
#: the most characters of each output stream (stdout, stderr) of a notebook that the kernel sends
OUTPUT_CAP = 1_000_000

#: the first cell run: stdout and stderr capped at OUTPUT_CAP characters each; the kernel's own stdout kept aside
#: for the collecting cell
CAP = '''\
def __scara_cap(limit):
    import os, sys

    null = open(os.devnull, "w")

    class Capped:
        """A stream that passes on its first ``limit`` characters; past them it hands its place in ``sys`` to
        the null device, whose writes cost nothing."""

        def __init__(self, name):
            self._name, self._stream, self._left = name, getattr(sys, name), limit

        def write(self, text):
            n = len(text)
            if self._left > 0:
                self._left -= n
                self._stream.write(text if self._left >= 0 else text[:n + self._left])
            if self._left <= 0 and getattr(sys, self._name) is self:
                self._stream.flush()
                setattr(sys, self._name, null)
            return n

        def __getattr__(self, name):
            return getattr(self._stream, name)

    raw = sys.stdout
    sys.stdout, sys.stderr = Capped("stdout"), Capped("stderr")
    return raw
__scara_stdout = __scara_cap(%d)
del __scara_cap
''' % OUTPUT_CAP

COLLECT = '''\
def __scara_collect(names):
    import json, math, numbers
    out = {}
    for name in names:
        value = globals().get(name, None)
        if isinstance(value, numbers.Real) and not isinstance(value, bool):
            number = float(value)
            out[name] = number if math.isfinite(number) else repr(number)
        else:
            out[name] = None if value is None else repr(value)[:80]
    if hasattr(__scara_stdout, "set_parent"):  # the kernel's stream, told which cell it now writes for
        __scara_stdout.set_parent(get_ipython().get_parent())
    __scara_stdout.write("\\n%s" + json.dumps(out) + "\\n")
    __scara_stdout.flush()
__scara_collect(%r)
'''


def _first_error(nb) -> str | None:
    for k, cell in enumerate(nb.cells, 1):
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                text = f"cell {k}: {output.get('ename', 'Error')}: {output.get('evalue', '')}"
                return text[:ERROR_CHARS]
    return None


def _collected(cell) -> dict | None:
    """The answers the collecting cell printed (its last marker line), or None."""
    found = None
    for output in cell.get("outputs", []):
        if output.get("output_type") == "stream":
            for line in str(output.get("text", "")).splitlines():
                if line.startswith(MARKER):
                    found = line[len(MARKER):]
    if found is None:
        return None
    try:
        data = json.loads(found)
    except ValueError:
        return None
    return data if isinstance(data, dict) else None


def run(path: str, result: str, timeout: float, names: list[str]) -> dict:
    import nbformat  # noqa: PLC0415
    from nbclient import NotebookClient  # noqa: PLC0415
    from nbclient.exceptions import CellTimeoutError, DeadKernelError  # noqa: PLC0415

    out = {"status": "ok", "answers": {}, "error": None}
    try:
        nb = nbformat.read(path, as_version=4)
        nb.cells = [c for c in nb.cells if c.cell_type in ("code", "markdown", "raw")]
        for c in nb.cells:
            if c.cell_type == "code":
                c.outputs = []
    except Exception as exc:  # noqa: BLE001 - any unreadable file is the submission's fault, reported
        out.update(status="unreadable", error=f"{type(exc).__name__}: {str(exc)[:ERROR_CHARS]}")
        return out
    nb.cells.insert(0, nbformat.v4.new_code_cell(CAP))
    nb.cells.append(nbformat.v4.new_code_cell(COLLECT % (MARKER, names)))
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    # a cell past its time is interrupted and the notebook goes on, so that the answers set before it count
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", allow_errors=True, startup_timeout=120,
                            record_timing=False, store_widget_state=False, interrupt_on_timeout=True)
    try:
        client.execute()
    except CellTimeoutError:
        out["status"] = "timeout"
    except DeadKernelError:
        out["status"] = "dead"
    except Exception as exc:  # noqa: BLE001 - e.g. the kernel could not start: reported, not raised
        out.update(status="dead", error=f"{type(exc).__name__}: {str(exc)[:ERROR_CHARS]}")
    nb.cells.pop(0)  # the cap's cell: the student's cells are numbered from 1 in the feedback
    interrupted = any(o.get("output_type") == "error" and o.get("ename") == "KeyboardInterrupt"
                      for c in nb.cells[:-1] for o in c.get("outputs", []))
    if out["status"] in ("ok", "timeout"):
        answers = _collected(nb.cells[-1])
        if answers is not None:
            out["answers"] = {n: answers.get(n) for n in names}
        if interrupted:
            out["status"] = "timeout"
        elif answers is None and out["status"] == "ok":
            out["status"] = "no-answers"
    out["error"] = out["error"] or _first_error(nb)
    out["memory_error"] = any(o.get("output_type") == "error" and o.get("ename") == "MemoryError"
                              for c in nb.cells for o in c.get("outputs", []))
    return out


def main(argv: list[str]) -> int:
    path, result, timeout, names = argv[1], argv[2], float(argv[3]), [n for n in argv[4].split(",") if n]
    try:
        out = run(path, result, timeout, names)
    except MemoryError:
        out = {"status": "memory", "answers": {}, "error": "MemoryError"}
    with open(result, "w", encoding="utf-8") as fh:
        json.dump(out, fh)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
