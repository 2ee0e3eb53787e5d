"""``python -m scara.course``: the teacher's commands.

    python -m scara.course edition student              # build the student edition of the book
    python -m scara.course assign --roster roster.csv --secret-file S --out DIR
    python -m scara.course grade --key DIR/key.json --submissions SUBS --out MARKS
    python -m scara.course exercises                    # list the exercises and which can be set

A mistake in the input (a roster without ids, a short secret, an unknown exercise, no sandbox) ends with one
line that says what is wrong and exit status 2, never a traceback.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from scara.errors import ScaraError


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m scara.course", description="The course as a teacher runs it.")
    sub = p.add_subparsers(dest="command", required=True)

    e = sub.add_parser("edition", help="write and build an edition of the book")
    e.add_argument("which", choices=["student"], help="the student edition: no solution, no key, anywhere")
    e.add_argument("--source", type=Path, default=Path("_build/student-source"), help="where its sources go")
    e.add_argument("--output", type=Path, default=Path("_build/student"), help="where it is built (OUTPUT/_build/html)")
    e.add_argument("--no-build", action="store_true", help="write the sources only")
    e.add_argument("--execute", action="store_true", help="execute the chapters again (default: keep the outputs of "
                                                           "the book's build, from its cache _build/.jupyter_cache)")

    a = sub.add_parser("assign", help="write each student's assignment and the key")
    a.add_argument("--roster", type=Path, required=True, help="CSV with a column 'id' (and optionally 'name')")
    a.add_argument("--secret-file", type=Path, required=True, help="the course secret (at least 16 bytes)")
    a.add_argument("--out", type=Path, required=True, help="folder for the assignments and key.json")
    a.add_argument("--exercises", default="", help="comma-separated labels (default: every one that can be set)")
    a.add_argument("--title", default="Robot manipulators: your assignment")

    g = sub.add_parser("grade", help="run and mark the submitted notebooks, offline, each in a sandbox")
    g.add_argument("--key", type=Path, required=True, help="key.json written by assign")
    g.add_argument("--submissions", type=Path, required=True, help="folder of the submitted notebooks")
    g.add_argument("--out", type=Path, required=True, help="folder for marks.csv, feedback/ and gradescope/")
    g.add_argument("--timeout", type=float, default=60.0, help="seconds per cell (default 60)")
    g.add_argument("--memory", type=int, default=2048, help="MB of memory per submission (default 2048)")
    g.add_argument("--jobs", type=int, default=2, help="submissions graded at once (default 2)")

    sub.add_parser("exercises", help="list the book's exercises")
    return p


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    try:
        if args.command == "edition":
            from scara.course.edition import build_student, executed_notebooks, write_student_source  # noqa: PLC0415

            write_student_source(args.source, executed=None if args.execute else executed_notebooks())
            print(f"student edition's sources: {args.source}")
            if args.no_build:
                return 0
            status = build_student(args.source, args.output)
            print(f"student edition: {args.output / '_build' / 'html' / 'index.html'}" if status == 0 else
                  f"the student edition's build failed (status {status})")
            return status
        if args.command == "assign":
            from scara.course.assign import assign, read_secret  # noqa: PLC0415

            t0 = time.monotonic()
            labels = [s.strip() for s in args.exercises.split(",") if s.strip()]
            key = assign(args.roster, read_secret(args.secret_file), args.out, labels or None, args.title)
            print(f"{len(key['students'])} assignments of {len(key['exercises'])} exercises in "
                  f"{time.monotonic() - t0:.1f} s; the key: {args.out / 'key.json'} (keep it to yourself)")
            return 0
        if args.command == "grade":
            from scara.course.grade import grade  # noqa: PLC0415

            t0 = time.monotonic()
            rows = grade(args.key, args.submissions, args.out, args.timeout, args.memory, args.jobs)
            print(f"{len(rows)} submissions graded in {time.monotonic() - t0:.1f} s: {args.out / 'marks.csv'}")
            return 0
        if args.command == "exercises":
            from scara.course.assign import assignable  # noqa: PLC0415
            from scara.course.exercises import catalog  # noqa: PLC0415

            for ex in catalog().values():
                kind = "numeric, can be set" if assignable(ex) else ("numeric" if ex.numeric else "argument")
                print(f"{ex.number:>5}  {ex.label:<32} {kind}")
            return 0
    except (ScaraError, KeyError, OSError) as exc:
        message = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
        print(f"python -m scara.course {args.command}: {message}", file=sys.stderr)
        return 2
    return 1


if __name__ == "__main__":
    sys.exit(main())
