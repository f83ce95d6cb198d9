#!/usr/bin/python3
"""Result tools that cannot pass vacuously or be fooled (issue 33, item 8).

Usage: check_result_tools.py CASE XPL REPO OUT_DIR, CASE one of
  fields     `xpl compare --fields FOO,BAR` is an error (exit 2) naming the field and the
             fields there are, not "PASSED: 0 of 0 datasets differ"; --fields S still passes
  reordered  a file whose /mesh/element_ids was permuted (its fields left as they are) is
             refused by --import (exit 1) and by compare (exit 2), naming the row; an
             untouched copy is accepted by both
  escaped    control characters in a file's attributes (status, error) and dataset names
             reach the terminal escaped (\\x1b) from compare and history, never raw
  limits     --energy-limit takes any finite number > 0 (1e7 runs), 0 and inf are usage
             errors; --threads above 1024 is a usage error (exit 2) that writes nothing: no
             JOB.h5, no lock
  exitcodes  every exit code each command uses (apps/*.cpp, *.hpp) is in docs/user/cli.md: run
             and check in the exit-code table, compare in its table, history in its section
  meshfull   the disk fills while the mesh is written (a 256 kB tmpfs, a 30^3 block): exit
             4, JOB.h5 removed and the message says so, a summary with status failed;
             skipped (exit 77) where mounting fails
  framefull  the disk fills between frames (a 1 MB tmpfs): the message quotes the space the
             check wants (twice the last frame plus 64 KiB), which is more than is free
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys

import h5py

SKIP = 77


def fail(message):
    sys.exit(f"FAIL: {message}")


def run(command, expected=None, timeout=300):
    p = subprocess.run([str(c) for c in command], capture_output=True, timeout=timeout,
                       stdin=subprocess.DEVNULL)
    if expected is not None and p.returncode != expected:
        fail(f"{' '.join(map(str, command))}: exit {p.returncode}, expected {expected}\n"
             f"{p.stdout.decode(errors='replace')}\n{p.stderr.decode(errors='replace')}")
    return p


def block_deck(repo, out, n, extra_output=True, increments=60):
    deck = out / "deck" / f"block{n}.inp"
    deck.parent.mkdir(parents=True, exist_ok=True)
    run([sys.executable, repo / "benchmarks" / "make_block.py", "-n", n, "--increments",
         increments, "--out", deck], 0)
    if extra_output:
        text = deck.read_text().replace(
            "** No output requests: the benchmark times the element loop.",
            "*OUTPUT, FIELD, NUMBER INTERVAL=20\n*NODE OUTPUT\nU, V\n*ELEMENT OUTPUT\nS\n"
            "*OUTPUT, HISTORY, NUMBER INTERVAL=10\n*ENERGY OUTPUT")
        deck.write_text(text)
    return deck


def result(xpl, repo, out, n=3):
    deck = block_deck(repo, out, n)
    results = out / "results"
    run([xpl, "run", deck, "-o", results, "--quiet"], 0)
    return deck, results / f"{deck.stem}.h5"


def case_fields(xpl, repo, out):
    _, h5 = result(xpl, repo, out)
    p = run([xpl, "compare", h5, h5, "--fields", "FOO,BAR"], 2)
    err = p.stderr.decode()
    if "--fields FOO: no such field" not in err or "fields: HGSTATE, MISES, S, U, V" not in err:
        fail(f"the message does not name the unknown field and the fields there: {err!r}")
    if b"PASSED" in p.stdout:
        fail(f"a typo passed: {p.stdout!r}")
    p = run([xpl, "compare", h5, h5, "--fields", "S"], 0)
    if b"PASSED: 0 of 1 datasets differ" not in p.stdout:
        fail(f"--fields S: {p.stdout!r}")
    print(f"--fields FOO,BAR: exit 2: {err.strip()}")


def case_reordered(xpl, repo, out):
    deck, h5 = result(xpl, repo, out)
    intact = out / "intact.h5"
    shutil.copy(h5, intact)
    reordered = out / "reordered.h5"
    shutil.copy(h5, reordered)
    with h5py.File(reordered, "r+") as f:
        ids = f["/mesh/element_ids"][...]
        f["/mesh/element_ids"][...] = ids[::-1]  # the PEEQ and S rows stay where they were
    p = run([xpl, "run", deck, "-o", out / "imported", "--import", reordered, "--quiet"], 1)
    err = p.stderr.decode()
    if "/mesh/element_ids has element" not in err or "at row 0" not in err:
        fail(f"--import of a reordered file: {err!r}")
    p = run([xpl, "compare", h5, reordered], 2)
    if "/mesh/element_ids has element" not in p.stderr.decode():
        fail(f"compare of a reordered file: {p.stderr!r}")
    run([xpl, "run", deck, "-o", out / "imported_intact", "--import", intact, "--quiet"], 0)
    run([xpl, "compare", h5, intact], 0)
    print(f"reordered /mesh/element_ids refused: {err.strip().splitlines()[0]}")


def case_escaped(xpl, repo, out):
    _, h5 = result(xpl, repo, out)
    bad = out / "bad.h5"
    shutil.copy(h5, bad)
    with h5py.File(bad, "r+") as f:
        f.attrs["status"] = "failed"
        f.attrs["error"] = "boom \x1b[31mRED\x1b[0m \x07bell"
    p = run([xpl, "compare", h5, bad], 2)
    for stream in (p.stdout, p.stderr):
        if b"\x1b" in stream or b"\x07" in stream:
            fail(f"compare printed a raw control character: {stream!r}")
    if b"\\x1b[31mRED" not in p.stderr:
        fail(f"compare did not print the escaped error: {p.stderr!r}")
    with h5py.File(bad, "r+") as f:
        f.attrs["status"] = "run\x1b]0;title\x07ning"
        group = f["/history/step_1/energy"]
        group["ALL\x1bKE"] = group["ALLKE"][...]
    p = run([xpl, "history", bad], 0)
    for stream in (p.stdout, p.stderr):
        if b"\x1b" in stream or b"\x07" in stream:
            fail(f"history printed a raw control character: {stream!r}")
    if b"run\\x1b]0;title\\x07ning" not in p.stderr or b"ALL\\x1bKE" not in p.stdout:
        fail(f"history did not print the escaped status and column: {p.stderr!r}")
    print("compare and history escape control characters from the file")


def case_limits(xpl, repo, out):
    deck = block_deck(repo, out, 2, increments=20)
    run([xpl, "run", deck, "-o", out / "big_limit", "--energy-limit", "1e7", "--quiet"], 0)
    for bad in ("0", "-5", "inf", "nan", "1e400"):
        p = run([xpl, "run", deck, "-o", out / "bad_limit", "--energy-limit", bad], 2)
        if b"not a finite number > 0" not in p.stderr:
            fail(f"--energy-limit {bad}: {p.stderr!r}")
    for threads in ("1025", "40000", "65536", "99999999999"):
        target = out / f"threads_{threads}"
        p = run([xpl, "run", deck, "-o", target, "--threads", threads], 2)
        if b"is not a whole number from 1 to 1024" not in p.stderr:
            fail(f"--threads {threads}: {p.stderr!r}")
        if target.exists() and any(target.iterdir()):
            fail(f"--threads {threads} left files: {sorted(target.iterdir())}")
    run([xpl, "run", deck, "-o", out / "threads_3", "--threads", "3", "--quiet"], 0)
    print("--energy-limit 1e7 runs; 0, inf, nan refused; --threads above 1024 refused, no files")


def table_codes(readme, header):
    """The exit codes of the table of docs/user/cli.md that starts with `header` ("| 130 / 143 |"
    too)."""
    block = readme[readme.index(header):].split("\n\n")[0]
    codes = set()
    for cell in re.findall(r"^\| ([\d /]+) \|", block, re.M):
        codes |= {int(c) for c in cell.split("/") if c.strip()}
    return codes


def used_codes(*sources):
    codes = set()
    for source in sources:
        text = source.read_text()
        codes |= {int(c) for c in re.findall(r"constexpr int EXIT_\w+ = (\d+);", text)}
        codes |= {int(c) for c in re.findall(r"\breturn (\d+);", text)}
        codes |= {int(c) for c in re.findall(r"\? 0 : (\d+);", text)}
    return codes


def case_exitcodes(xpl, repo, out):
    apps = repo / "apps"
    readme = (repo / "docs" / "user" / "cli.md").read_text()
    # main() ends compare and history with EXIT_INTERNAL (4) on an exception that escapes them.
    internal = {4}
    commands = {
        "run/check": (used_codes(apps / "job.hpp", apps / "xpl.cpp") | {128 + 2, 128 + 15},
                      table_codes(readme, "| exit code | meaning |")),
        "compare": (used_codes(apps / "compare.cpp") | {0} | internal,
                    table_codes(readme, "| `xpl compare` exit code | meaning |")),
        "history": (used_codes(apps / "history.cpp") | internal,
                    {int(c) for c in re.findall(
                        r"(\d)(?:,| or| on| when)",
                        re.search(r"## History as CSV\n\n.*?(?:\n\n|\Z)", readme, re.S).group(0)
                        .split("Exit ", 1)[1])}),
    }
    for command, (used, listed) in commands.items():
        missing = sorted(used - listed)
        if missing:
            fail(f"xpl {command} uses exit codes {missing} that docs/user/cli.md does not list "
                 f"(used {sorted(used)}, listed {sorted(listed)})")
        print(f"xpl {command}: exit codes {sorted(used)} all in docs/user/cli.md")


def mount_tmpfs(mount, size):
    mount.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(mount)],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        print(f"SKIP: cannot mount a tmpfs: {mounted.stderr.strip()}")
        sys.exit(SKIP)


def case_meshfull(xpl, repo, out):
    deck = block_deck(repo, out, 30, extra_output=False, increments=5)
    mount = out / "tmpfs"
    mount_tmpfs(mount, "256k")
    try:
        results = mount / "results"
        p = run([xpl, "run", deck, "-o", results, "--threads", "1", "--quiet"], 4)
        err = p.stderr.decode()
        h5 = results / f"{deck.stem}.h5"
        if h5.exists():
            fail(f"{h5} is left after a failed mesh write: {err!r}")
        if "while writing the mesh" not in err or f"{h5} was removed" not in err:
            fail(f"the message does not say what happened: {err!r}")
        summary = (results / f"{deck.stem}.summary.json").read_text()
        if '"status": "failed"' not in summary or "was removed" not in summary:
            fail(f"summary: {summary}")
        stray = [p.name for p in results.iterdir() if p.suffix in (".tmp", ".lck")]
        if stray:
            fail(f"stray files: {stray}")
        print(f"disk full during the mesh: exit 4, {err.strip()}")
    finally:
        subprocess.run(["umount", str(mount)], check=False)


def case_framefull(xpl, repo, out):
    deck = block_deck(repo, out, 10, increments=4000)
    text = deck.read_text().replace("NUMBER INTERVAL=20", "NUMBER INTERVAL=5")
    deck.write_text(text)
    mount = out / "tmpfs"
    mount_tmpfs(mount, "1m")
    try:
        results = mount / "results"
        p = run([xpl, "run", deck, "-o", results, "--threads", "1", "--quiet"], 4)
        with h5py.File(results / f"{deck.stem}.h5", "r") as f:
            error = f.attrs["error"]
            error = error.decode() if isinstance(error, bytes) else error
        m = re.search(r"(\d+) bytes free for .*, less than the (\d+) bytes xpl keeps free before "
                      r"a frame \(twice the last frame's (\d+) bytes, and (\d+) bytes", error)
        if not m:
            fail(f"disk-full message: {error!r}")
        free, needed, frame, margin = map(int, m.groups())
        if needed != 2 * frame + margin or margin != 65536 or not free < needed:
            fail(f"the message quotes {needed} bytes, the check wants 2 x {frame} + {margin}; "
                 f"{free} free: {error!r}")
        print(f"disk full between frames: {error}")
    finally:
        subprocess.run(["umount", str(mount)], check=False)


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case, xpl, repo, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3]), \
        pathlib.Path(sys.argv[4])
    if os.path.ismount(out / "tmpfs"):
        subprocess.run(["umount", str(out / "tmpfs")], check=False)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    {"fields": case_fields, "reordered": case_reordered, "escaped": case_escaped,
     "limits": case_limits, "exitcodes": case_exitcodes, "meshfull": case_meshfull,
     "framefull": case_framefull}[case](xpl, repo, out)


if __name__ == "__main__":
    main()
