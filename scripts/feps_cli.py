#!/usr/bin/env python3
"""Ordinary mistakes as one line and an exit status, never a traceback (the scripts' standard).

    from feps_cli import Error, guard
    def main(argv=None):
        ...
        raise Error(f"no model C results in {folder}")          # 'prog: no model C ...', exit 1
    if __name__ == "__main__":
        sys.exit(guard(main))

Error(message, status) is printed by guard() as `prog: message` on stderr and becomes the exit
status: 1 (default) for something that ran or was looked for and failed, 2 for a bad argument
(as argparse exits): a value out of range, a file or folder named that is missing. An OSError
(a file that cannot be written, a folder that cannot be made) becomes one line and status 1.
The argparse types below refuse NaN and infinities, which float() accepts.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Error(Exception):
    """An expected error: `message` for the user, `status` to exit with (1, or 2 for bad arguments)."""

    def __init__(self, message, status=1):
        super().__init__(message)
        self.status = status


def prog():
    """The script's name, for messages: 'postprocess_model_c' for scripts/postprocess_model_c.py."""
    return os.path.splitext(os.path.basename(sys.argv[0]))[0] or "feps-script"


def guard(main, *args):
    """Call main(*args); an Error or OSError becomes `prog: message` on stderr and its exit status."""
    try:
        return main(*args)
    except Error as exc:
        print(f"{prog()}: {exc}", file=sys.stderr)
        return exc.status
    except OSError as exc:
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"{prog()}: {where}{exc.strerror or exc}", file=sys.stderr)
        return 1


def finite(text):
    """argparse type: a finite number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def positive(text):
    """argparse type: a finite number > 0."""
    value = finite(text)
    if not value > 0.0:
        raise argparse.ArgumentTypeError(f"{text!r} is not positive")
    return value


def positive_int(text):
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not at least 1")
    return value


def feps_executable(profile="debug"):
    """Build feps with fpm's `profile` (debug or release) and return the executable's path;
    exit with fpm's message if it does not build."""
    built = subprocess.run(["fpm", "build", "--profile", profile], cwd=ROOT, capture_output=True, text=True)
    out = subprocess.run(["fpm", "run", "--profile", profile, "--runner", "echo"], cwd=ROOT,
                         capture_output=True, text=True)
    lines = [line for line in out.stdout.strip().splitlines() if line.strip()]
    if built.returncode != 0 or out.returncode != 0 or not lines:
        sys.exit(f"{prog()}: cannot build feps ({profile}):\n" + built.stderr + out.stderr)
    return os.path.join(ROOT, lines[-1].strip())


def feps_option(path, profile="release"):
    """The feps executable a script runs: `path` (a --feps option) made absolute, so that it still
    resolves after the script changes folder, or fpm's `profile` build when `path` is empty;
    Error (status 2) when `path` names no executable file."""
    if not path:
        return feps_executable(profile)
    feps = os.path.abspath(path)
    if not (os.path.isfile(feps) and os.access(feps, os.X_OK)):
        raise Error(f"--feps {path}: not an executable file", 2)
    return feps


def benchmarks_dir():
    """The folder of the thesis's tables: $FEPS_BENCHMARKS, default ../shared/benchmarks beside the
    repository; Error (status 2) naming the folder and the variable when it is not there."""
    folder = os.environ.get("FEPS_BENCHMARKS") or os.path.join(ROOT, "..", "shared", "benchmarks")
    if not os.path.isdir(folder):
        raise Error(f"no benchmarks folder {os.path.normpath(folder)} (the thesis's tables; set FEPS_BENCHMARKS "
                    "to the folder that holds them)", 2)
    return folder


def benchmark_file(name):
    """Path of one table in benchmarks_dir(); Error (status 2) when the folder or the file is missing."""
    path = os.path.join(benchmarks_dir(), name)
    if not os.path.isfile(path):
        raise Error(f"no {name} in the benchmarks folder {os.path.dirname(path)} (FEPS_BENCHMARKS)", 2)
    return path


def benchmark_rows(name):
    """The rows of one CSV table in benchmarks_dir() as dicts ('#' lines are comments)."""
    with open(benchmark_file(name)) as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))
