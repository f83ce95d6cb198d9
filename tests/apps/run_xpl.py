#!/usr/bin/python3
"""Runs xpl as a ctest fixture step and keeps what it printed.

Usage: run_xpl.py OUT_DIR EXPECTED_EXIT_CODE -- XPL ARGS...

Removes OUT_DIR first (so a later check can never read the files of an earlier run), creates
it, runs `XPL ARGS...` and writes its stdout and stderr to OUT_DIR/stdout.txt and
OUT_DIR/stderr.txt. Exits non-zero, echoing both streams, if the exit code is not
EXPECTED_EXIT_CODE. ARGS normally contain `-o OUT_DIR`.
"""

import pathlib
import shutil
import subprocess
import sys


def main():
    if len(sys.argv) < 5 or sys.argv[3] != "--":
        sys.exit(__doc__)
    out_dir = pathlib.Path(sys.argv[1])
    expected = int(sys.argv[2])
    command = sys.argv[4:]
    shutil.rmtree(out_dir, ignore_errors=True)
    out_dir.mkdir(parents=True)
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    (out_dir / "stdout.txt").write_text(result.stdout)
    (out_dir / "stderr.txt").write_text(result.stderr)
    if result.returncode != expected:
        sys.stdout.write(result.stdout)
        sys.stderr.write(result.stderr)
        sys.exit(f"run_xpl.py: FAILED: {' '.join(command)} exited with {result.returncode}, "
                 f"expected {expected}")
    print(f"run_xpl.py: {' '.join(command)}: exit code {result.returncode} as expected")


if __name__ == "__main__":
    main()
