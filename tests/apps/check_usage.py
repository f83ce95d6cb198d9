#!/usr/bin/python3
"""Command-line usage of xpl: --help, --version, each command's --help and usage errors (exit
code 2).

`xpl run|check|compare|history --help` (and -h, and --help after other words) print that
command's usage on stdout and exit 0 (issue 34, SPEC I6); an unknown command is named as such,
with the usage, and exits 2, with or without a deck after it.

Usage: check_usage.py XPL DECK WORK_DIR

DECK is a valid deck (the bar example): the usage errors must be caught before it is read,
and nothing may be written. WORK_DIR is emptied and used as the working directory.
"""

import os
import pathlib
import shutil
import subprocess
import sys

VERSION = "0.1.0"
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"check_usage.py: FAILED: {message}")
    return condition


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, deck, work = sys.argv[1], str(pathlib.Path(sys.argv[2]).resolve()), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    def run(*args, env=None):
        return subprocess.run([xpl, *args], cwd=work, capture_output=True, text=True, timeout=60,
                              env=env)

    result = run("--version")
    check(result.returncode == 0, f"--version: exit code {result.returncode}")
    check(result.stdout == f"xpl {VERSION}\n", f"--version printed {result.stdout!r}")

    result = run("--help")
    check(result.returncode == 0, f"--help: exit code {result.returncode}")
    for word in ("xpl run DECK.inp", "xpl check DECK.inp", "--threads", "-o DIR"):
        check(word in result.stdout, f"--help does not mention '{word}':\n{result.stdout}")

    command_help = {
        ("run", "--help"): "usage: xpl run DECK.inp",
        ("run", "-h"): "usage: xpl run DECK.inp",
        ("run", deck, "-o", "out_help", "--help"): "usage: xpl run DECK.inp",
        ("check", "--help"): "usage: xpl check DECK.inp",
        ("compare", "--help"): "usage: xpl compare REF.h5 NEW.h5",
        ("compare", "a.h5", "-h"): "usage: xpl compare REF.h5 NEW.h5",
        ("history", "--help"): "usage: xpl history JOB.h5",
    }
    for args, first in command_help.items():
        result = run(*args)
        check(result.returncode == 0, f"{' '.join(args)}: exit code {result.returncode}, expected 0"
              f"\nstderr:\n{result.stderr}")
        check(result.stdout.startswith(first),
              f"{' '.join(args)}: stdout does not start with {first!r}:\n{result.stdout}")
        check(result.stderr == "", f"{' '.join(args)}: wrote on stderr: {result.stderr!r}")
    for option in ("--energy-limit", "--import", "--threads"):
        check(option in run("run", "--help").stdout, f"run --help does not explain {option}")
    for option in ("--rtol", "--history", "--frames", "--json"):
        check(option in run("compare", "--help").stdout, f"compare --help does not explain {option}")
    check("--step" in run("history", "--help").stdout, "history --help does not explain --step")

    for args in (["frobnicate", deck], ["frobnicate"], ["--frobnicate"]):
        result = run(*args)
        check(result.returncode == 2 and f"unknown command '{args[0]}'" in result.stderr
              and "usage: xpl run" in result.stderr,
              f"{' '.join(args)}: exit {result.returncode}, expected 2 with \"unknown command "
              f"'{args[0]}'\" and the usage; stderr:\n{result.stderr}")

    usage_errors = {
        "no arguments": [],
        "unknown command": ["frobnicate", deck],
        "threads 0": ["run", deck, "--threads", "0", "-o", "out_threads0"],
        "threads not a number": ["run", deck, "--threads", "two", "-o", "out_threads_two"],
        "run without deck": ["run"],
        "unknown option": ["run", deck, "--bogus", "-o", "out_bogus"],
    }
    for what, args in usage_errors.items():
        result = run(*args)
        check(result.returncode == 2,
              f"{what} ({' '.join(args)}): exit code {result.returncode}, expected 2\n"
              f"stderr:\n{result.stderr}")
        check(result.stderr.strip() != "", f"{what}: nothing on stderr")
        check(result.stdout == "", f"{what}: printed on stdout: {result.stdout!r}")
    # A misspelt XPL_CONTACT_SLEEP is a usage error, not the default (contact/slot_sleep.hpp).
    for value in ("of", "ON", "0"):
        env = dict(os.environ, XPL_CONTACT_SLEEP=value)
        result = run("run", deck, "-o", "out_sleep", env=env)
        check(result.returncode == 2 and f"XPL_CONTACT_SLEEP={value}: unknown value" in result.stderr
              and "expected on, off, count or check" in result.stderr,
              f"XPL_CONTACT_SLEEP={value!r}: exit {result.returncode}, expected 2 with "
              f"\"unknown value\"; stderr:\n{result.stderr}")
    written = sorted(p.name for p in work.rglob("*"))
    check(not written, f"usage errors wrote files: {written}")

    if failures:
        sys.exit(f"check_usage.py: {len(failures)} check(s) failed")
    print(f"check_usage.py: --version, --help, {len(command_help)} command helps and "
          f"{len(usage_errors)} usage errors OK")


if __name__ == "__main__":
    main()
