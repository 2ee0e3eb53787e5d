"""Offline grading of the submitted assignments.

``python -m scara.course grade --key KEY --submissions DIR --out OUT`` marks every notebook under ``DIR``
(``DIR/*.ipynb`` or ``DIR/<anything>/*.ipynb``) against the teacher's key written by ``assign``:

1. the student is the one the notebook's metadata names (``assign`` writes it), else the one its file or folder
   is named after;
2. the notebook runs, in a fresh kernel, inside a sandbox (:func:`sandbox_command`): bubblewrap, as an
   unprivileged user in a user namespace of its own, with no capability, no network, its own process tree, an empty environment, a private ``/tmp``, the
   system, the Python environment and the package (without its answers) read-only, and one writable folder
   holding a copy of that notebook only. The key and the other submissions do not exist in there. Limits: a
   time per cell (``--timeout``, 60 s), a wall time for the whole run, memory (``--memory``, 2048 MB of address
   space), file size (64 MB);
3. nbclient (:mod:`scara.course._runner`) runs every cell, errors allowed, then reads the answer variables the
   assignment names; each is compared with the key within its tolerance;
4. ``OUT/marks.csv`` (one row per submission), ``OUT/feedback/<id>.md`` (which answer, expected and given, by
   how much) and ``OUT/gradescope/<id>/results.json`` (Gradescope's format) are written.

A submission that loops, fills its memory, kills its kernel, floods its output or reaches for what is not its
own gets a mark line that says so and zero for the answers it could not give; the others are graded as if it
were not there (each runs in its own sandbox, with its own copy of the compiled-code cache).
"""
from __future__ import annotations

import csv
import json
import math
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from scara.course.exercises import Answer
from scara.errors import ScaraError

__all__ = ["grade", "sandbox_command", "SandboxMissing", "Submission", "STATUS_TEXT", "NOBODY"]

#: the user and group id a submission runs as, in its own user namespace
NOBODY = 65534
#: the largest submission read (bytes): a notebook is text, a few hundred kB at most
MAX_NOTEBOOK = 20_000_000
#: the largest file a submission may write (bytes)
MAX_FILE = 64 * 2**20
#: the largest result file read back (bytes)
MAX_RESULT = 1_000_000
#: what the kernel needs besides the cells' own time: its start, the package's import
STARTUP = 45.0
#: the wall time of a whole notebook, in cell time limits (cells past theirs are interrupted; this bounds the rest)
WALL_CELLS = 4

STATUS_TEXT = {
    "ok": "ran to the end",
    "timeout": "timed out after {timeout:g} s",
    "timeout-marked": "a cell timed out after {timeout:g} s (interrupted; the answers set by then are marked)",
    "dead": "kernel died",
    "memory": "ran out of memory (limit {memory} MB)",
    "unreadable": "not a readable notebook",
    "no-answers": "its answers could not be read (the last cell did not run to the end)",
    "unknown-student": "no student of the key has this id",
    "duplicate": "a second submission for the same student (graded: {first})",
    "sandbox": "the sandbox could not run it",
}


class SandboxMissing(ScaraError):
    """No sandbox (bubblewrap) is available to run submissions in."""


@dataclass
class Submission:
    path: Path
    student: str | None
    status: str = "ok"
    answers: dict = field(default_factory=dict)
    error: str | None = None
    seconds: float = 0.0
    detail: str = ""


def _mounts() -> list[str]:
    """bubblewrap's arguments that make the system, the Python environment and the package visible read-only."""
    import scara  # noqa: PLC0415

    args = ["--ro-bind", "/usr", "/usr"]
    for name in ("bin", "lib", "lib64", "lib32", "sbin"):
        p = Path("/") / name
        if p.is_symlink():
            args += ["--symlink", os.readlink(p), str(p)]
        elif p.is_dir():
            args += ["--ro-bind", str(p), str(p)]
    for name in ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "alternatives", "localtime", "nsswitch.conf",
                 "passwd", "group", "hosts", "ssl", "ca-certificates", "fonts", "mime.types"):
        p = Path("/etc") / name
        if p.exists():
            args += ["--ro-bind", str(p), str(p)]
    seen = set()
    for prefix in (sys.prefix, sys.base_prefix, sys.exec_prefix):
        real = str(Path(prefix).resolve())
        if real not in seen and not real.startswith("/usr/") and real != "/usr":
            seen.add(real)
            args += ["--ro-bind", real, real]
            if prefix != real:
                args += ["--symlink", real, prefix]
    package = Path(scara.__file__).resolve().parent
    args += ["--ro-bind", str(package), str(package)]
    answers = package / "course" / "answers"
    if answers.exists():  # the key's computations are not for the submissions
        args += ["--tmpfs", str(answers)]
    return args


def sandbox_command(workdir: Path, command: list[str], env: dict) -> list[str]:
    """The command that runs ``command`` in bubblewrap with ``workdir`` as its only writable folder (mounted at
    the same path), ``env`` as its whole environment; raises :class:`SandboxMissing` when bubblewrap is not
    installed."""
    bwrap = shutil.which("bwrap")
    if bwrap is None:
        raise SandboxMissing("grading runs each submission in bubblewrap, which is not installed "
                             "(Debian/Ubuntu: apt-get install bubblewrap)")
    # its own user namespace, as an unprivileged uid with no capability (as root too), and every other namespace
    args = [bwrap, "--unshare-all", "--uid", str(NOBODY), "--gid", str(NOBODY), "--cap-drop", "ALL",
            "--die-with-parent", "--new-session", "--proc", "/proc", "--dev", "/dev",
            "--tmpfs", "/tmp", "--tmpfs", "/var", "--tmpfs", "/run", "--dir", "/etc"]
    args += _mounts()
    args += ["--bind", str(workdir), str(workdir), "--chdir", str(workdir), "--clearenv"]
    for key, value in env.items():
        args += ["--setenv", key, value]
    return args + ["--", *command]


def _limits(memory_mb: int, cpu_seconds: int):
    def apply():
        os.setsid()
        resource.setrlimit(resource.RLIMIT_AS, (memory_mb * 2**20, memory_mb * 2**20))
        resource.setrlimit(resource.RLIMIT_FSIZE, (MAX_FILE, MAX_FILE))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 5))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def warm_cache(folder: Path, labels=()) -> Path | None:
    """A numba cache of the package's compiled kernels in ``folder`` (None without numba), so that each
    submission starts from compiled code rather than compiling it again: each gets a copy of its own.

    The kernels are compiled into the package's own cache (numba's ``CACHE_DIR`` in this process, kept per version
    of the kernels' sources, which the book and the chapters fill too) when it can be written, so that a second
    grading compiles nothing; ``folder`` is then a copy of it (numba checks each entry against its source, and
    the submissions see the package at the same path). Elsewhere they are compiled into ``folder`` itself."""
    try:
        import numba  # noqa: PLC0415
    except ImportError:
        return None
    own = Path(numba.config.CACHE_DIR) if numba.config.CACHE_DIR else None
    try:
        if own is not None:
            own.mkdir(parents=True, exist_ok=True)
        shared = own is not None and os.access(own, os.W_OK)
    except OSError:
        shared = False
    target = own if shared else folder
    folder.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(target))
    subprocess.run([sys.executable, "-m", "scara.course.warm", *labels], env=env, check=True,
                   stdout=subprocess.DEVNULL, timeout=1800)
    if shared:
        # numba writes each file as NAME.tmp.UID, then renames it: a half-written one is left out
        shutil.copytree(own, folder, dirs_exist_ok=True, ignore=shutil.ignore_patterns("*.tmp.*"))
    return folder


def _run_one(sub: Submission, names: list[str], base: Path, timeout: float, memory_mb: int,
             cache: Path | None) -> Submission:
    """Run one submission in its sandbox and fill in its status and answers."""
    start = time.monotonic()
    work = Path(tempfile.mkdtemp(prefix="sub-", dir=base))
    try:
        raw = sub.path.read_bytes()[:MAX_NOTEBOOK + 1]
        if len(raw) > MAX_NOTEBOOK:
            sub.status, sub.error = "unreadable", f"the file is larger than {MAX_NOTEBOOK // 10**6} MB"
            return sub
        (work / "submission.ipynb").write_bytes(raw)
        env = {"HOME": str(work / "home"), "PATH": f"{Path(sys.executable).parent}:/usr/bin:/bin",
               "JUPYTER_RUNTIME_DIR": str(work / "runtime"), "MPLBACKEND": "Agg", "PYTHONDONTWRITEBYTECODE": "1",
               "JUPYTER_PLATFORM_DIRS": "1", "LANG": "C.UTF-8", "OPENBLAS_NUM_THREADS": "1",
               "NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        if cache is not None:
            shutil.copytree(cache, work / "numba-cache")
            env["NUMBA_CACHE_DIR"] = str(work / "numba-cache")
        command = [sys.executable, "-m", "scara.course._runner", str(work / "submission.ipynb"),
                   str(work / "result.json"), f"{timeout:g}", ",".join(names)]
        wall = WALL_CELLS * timeout + STARTUP
        proc = subprocess.Popen(sandbox_command(work, command, env), stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                preexec_fn=_limits(memory_mb, int(wall) + 10))
        try:
            _, err = proc.communicate(timeout=wall)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            sub.status = "timeout"
            return sub
        result = work / "result.json"
        if not result.is_file() or result.stat().st_size > MAX_RESULT:
            if proc.returncode in (-signal.SIGXCPU, -signal.SIGKILL) or proc.returncode == 128 + signal.SIGXCPU:
                sub.status = "timeout"
            elif b"MemoryError" in err[-4000:]:
                sub.status = "memory"
            else:
                sub.status, sub.error = "sandbox", err[-300:].decode(errors="replace").strip() or None
            return sub
        try:
            data = json.loads(result.read_text(encoding="utf-8"))
            status, answers, error = data["status"], data.get("answers", {}), data.get("error")
        except (ValueError, KeyError, TypeError):
            sub.status = "no-answers"
            return sub
        sub.status = status if status in STATUS_TEXT else "no-answers"
        sub.answers = answers if isinstance(answers, dict) else {}
        if sub.status == "timeout" and any(v is not None for v in sub.answers.values()):
            sub.status = "timeout-marked"
        sub.error = str(error)[:300] if error else None
        if data.get("memory_error") and sub.status in ("ok", "dead", "no-answers"):
            sub.status = "memory"  # a cell ran out of memory: said so, whatever it answered
        return sub
    finally:
        sub.seconds = time.monotonic() - start
        shutil.rmtree(work, ignore_errors=True)


def _student_of(path: Path, students: dict) -> str | None:
    try:
        raw = path.read_bytes()[:MAX_NOTEBOOK]
        meta = json.loads(raw).get("metadata", {}).get("scara", {})
        sid = str(meta.get("student", "")) if isinstance(meta, dict) else ""
    except (ValueError, OSError, AttributeError):
        sid = ""
    for candidate in (sid, path.stem, path.parent.name):
        if candidate in students:
            return candidate
    return None


def _answer_of(spec: dict) -> Answer:
    return Answer(name="a", text=spec["text"], unit=spec["unit"], tolerance=spec["tolerance"],
                  absolute=spec["absolute"], fmt=spec.get("fmt", ".4g"))


def _mark(sub: Submission, key: dict, timeout: float, memory_mb: int) -> dict:
    """The marks and the feedback lines of one graded submission."""
    specs = key["students"][sub.student]["answers"] if sub.student else {}
    status_line = STATUS_TEXT[sub.status].format(timeout=timeout, memory=memory_mb, first=sub.detail)
    lines, tests, score = [], [], 0
    for name, spec in specs.items():
        answer = _answer_of(spec)
        given = sub.answers.get(name)
        ok = answer.matches(spec["expected"], given)
        score += ok
        if given is None:
            what = "no answer"
        elif isinstance(given, str):
            what = f"given {given[:40]!r}, not a number"
        else:
            what = f"given {given:.6g}, off by {abs(given - spec['expected']):.3g} {spec['unit']}".rstrip()
        line = (f"{'right' if ok else 'wrong'}: Exercise {spec['number']}, {spec['text']} (`{name}`): expected "
                f"{spec['expected']:{spec.get('fmt', '.4g')}} {spec['unit']} ({answer.tolerance_text()}), {what}")
        lines.append(line)
        tests.append({"name": f"Exercise {spec['number']}: {spec['text']} ({name})", "score": int(ok),
                      "max_score": 1, "output": line, "visibility": "visible"})
    return {"score": score, "max": len(specs), "status": status_line, "lines": lines, "tests": tests}


def grade(key_path: Path, submissions: Path, out: Path, timeout: float = 60.0, memory_mb: int = 2048,
          jobs: int = 2, log=print) -> list[dict]:
    """Grade every submission under ``submissions`` against the key; write the marks, the feedback and the
    Gradescope results under ``out``; return the rows of ``marks.csv``."""
    if not (timeout > 0 and math.isfinite(timeout)):
        raise ScaraError(f"the time limit must be a positive number of seconds, got {timeout}")
    if memory_mb < 512:
        raise ScaraError(f"the memory limit must be at least 512 MB (a kernel needs that much), got {memory_mb}")
    if jobs < 1:
        raise ScaraError(f"jobs must be at least 1, got {jobs}")
    key = json.loads(Path(key_path).read_text(encoding="utf-8"))
    students = key["students"]
    submissions, out = Path(submissions), Path(out)
    if not submissions.is_dir():
        raise ScaraError(f"no folder of submissions at {submissions}")
    files = sorted(set(submissions.glob("*.ipynb")) | set(submissions.glob("*/*.ipynb")))
    files = [f for f in files if f.is_file() and not f.is_symlink() and ".ipynb_checkpoints" not in f.parts]
    subs, first = [], {}
    for f in files:
        sid = _student_of(f, students)
        sub = Submission(f, sid)
        if sid is None:
            sub.status = "unknown-student"
        elif sid in first:
            sub.status, sub.detail = "duplicate", first[sid].name
        else:
            first[sid] = f
        subs.append(sub)
    sandbox_missing = shutil.which("bwrap") is None
    if sandbox_missing and any(s.status == "ok" for s in subs):
        raise SandboxMissing("grading runs each submission in bubblewrap, which is not installed "
                             "(Debian/Ubuntu: apt-get install bubblewrap); nothing was graded")
    out.mkdir(parents=True, exist_ok=True)
    base = Path(tempfile.mkdtemp(prefix="scara-grading-"))
    os.chmod(base, 0o711)
    try:
        t0 = time.monotonic()
        cache = warm_cache(base / "numba-cache", key.get("exercises", ()))
        log(f"compiled the package's kernels for the submissions in {time.monotonic() - t0:.1f} s")
        todo = [s for s in subs if s.status == "ok"]
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            for sub in pool.map(lambda s: _run_one(s, names_of(key, s.student), base, timeout, memory_mb, cache),
                                todo):
                said = STATUS_TEXT[sub.status].format(timeout=timeout, memory=memory_mb, first=sub.detail)
                log(f"{sub.path.name}: {said.split(' (')[0]}, in {sub.seconds:.1f} s")
    finally:
        shutil.rmtree(base, ignore_errors=True)
    rows = []
    (out / "feedback").mkdir(exist_ok=True)
    for sub in subs:
        m = _mark(sub, key, timeout, memory_mb)
        who = sub.student or sub.path.stem
        rows.append({"student": who, "file": str(sub.path.relative_to(submissions)), "score": m["score"],
                     "max_score": m["max"], "status": m["status"], "first_error": sub.error or "",
                     "seconds": f"{sub.seconds:.1f}"})
        if sub.status in ("unknown-student", "duplicate"):
            continue
        text = [f"# Feedback for {who}", "", f"Run: {m['status']}.", ""]
        if sub.error:
            text += [f"First error in your notebook: {sub.error}", ""]
        text += [f"Score: {m['score']} / {m['max']}", ""] + [f"- {line}" for line in m["lines"]]
        (out / "feedback" / f"{who}.md").write_text("\n".join(text) + "\n", encoding="utf-8")
        gs = out / "gradescope" / who
        gs.mkdir(parents=True, exist_ok=True)
        (gs / "results.json").write_text(json.dumps({
            "score": m["score"], "max_score": m["max"], "output": f"Run: {m['status']}.", "tests": m["tests"],
            "visibility": "visible"}, indent=1), encoding="utf-8")
    with open(out / "marks.csv", "w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=["student", "file", "score", "max_score", "status", "first_error",
                                                "seconds"])
        writer.writeheader()
        writer.writerows(rows)
    return rows


def names_of(key: dict, student: str) -> list[str]:
    """The answer variables of one student's assignment."""
    return sorted(key["students"][student]["answers"])

