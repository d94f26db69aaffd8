#!/usr/bin/env python3
"""The feps executable fpm builds, for the scripts that run it.

    from feps_build import feps_executable
    feps = feps_executable("release")        # builds if needed; the path of app/feps
"""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def feps_executable(profile="debug"):
    """Build feps with fpm's `profile` (debug or release) and return the executable's path;
    exit with fpm's message if it does not build."""
    built = subprocess.run(["fpm", "build", "--profile", profile], cwd=ROOT, capture_output=True, text=True)
    out = subprocess.run(["fpm", "run", "--profile", profile, "--runner", "echo"], cwd=ROOT,
                         capture_output=True, text=True)
    lines = [line for line in out.stdout.strip().splitlines() if line.strip()]
    if built.returncode != 0 or out.returncode != 0 or not lines:
        sys.exit(f"{os.path.basename(sys.argv[0])}: cannot build feps ({profile}):\n"
                 + built.stderr + out.stderr)
    return os.path.join(ROOT, lines[-1].strip())
