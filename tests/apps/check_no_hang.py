#!/usr/bin/python3
"""Bad input that used to hang or abort xpl ends within seconds with a clear message (issue 15,
item 6).

Usage: check_no_hang.py CASE XPL BAR_DECK OUT_DIR, CASE one of
  velocity    an initial velocity of -1e12 m/s: the stable increment collapses to 0 at once;
              exit 3 with "stable increment collapsed" (it used to spin at t = 0)
  interval    *OUTPUT, FIELD, TIME INTERVAL=1e-20 and *OUTPUT, HISTORY, NUMBER INTERVAL=10^9:
              completed, one frame and row per increment at most, with a .msg note each
  files       /dev/zero, a directory, *INCLUDE, INPUT=. and INPUT=/dev/zero, a 2 GB line
              (a sparse file: refused after its first MiB, the memory stays small), a 3 GiB
              file, a 2 MiB line: exit 1, one line-numbered error each
  cycles      a deck including itself twice, three times, and through a second file: one
              error naming the chain, at once
  control     control characters (an ANSI escape) in deck text are echoed escaped, in
              messages, and the *HEADING and a step name in JOB.msg, JOB.sta and JOB.h5
Each xpl call has a 10 s limit (it finishes in well under a second).
"""

import pathlib
import re
import resource
import subprocess
import sys

import h5py

LIMIT = 10


def fail(message):
    sys.exit(f"FAIL: {message}")


def xpl_run(xpl, *args):
    try:
        return subprocess.run([xpl, *map(str, args)], capture_output=True, text=True,
                              errors="replace", timeout=LIMIT)
    except subprocess.TimeoutExpired:
        fail(f"xpl {' '.join(map(str, args))} did not end within {LIMIT} s")


def replaced(text, old, new):
    if text.count(old) != 1:
        fail(f"the bar example changed: expected {old!r} once")
    return text.replace(old, new)


def velocity(xpl, bar, out):
    deck = out / "fast.inp"
    deck.write_text(re.sub(r"\nMOVING, 1, -10\S*\n", "\nMOVING, 1, -1e12\n", bar.read_text()))
    if "MOVING, 1, -1e12" not in deck.read_text():
        fail("the bar example changed: no MOVING velocity line")
    r = xpl_run(xpl, "run", deck, "-o", out / "fast", "--threads", "1", "--quiet")
    if r.returncode != 3 or "stable increment collapsed to" not in r.stderr \
            or "wave transit time" not in r.stderr:
        fail(f"-1e12 m/s: exit {r.returncode}\n{r.stderr}")
    with h5py.File(out / "fast" / "fast.h5", "r") as f:
        if f.attrs["status"] != "failed" or "collapsed" not in f.attrs["error"]:
            fail(f"-1e12 m/s: status {f.attrs['status']!r}, error {f.attrs['error']!r}")


def interval(xpl, bar, out):
    text = replaced(bar.read_text(), "*OUTPUT, FIELD, TIME INTERVAL=1e-05",
                    "*OUTPUT, FIELD, TIME INTERVAL=1e-20")
    text = replaced(text, "*OUTPUT, HISTORY, TIME INTERVAL=2e-07",
                    "*OUTPUT, HISTORY, NUMBER INTERVAL=1000000000")
    deck = out / "tiny.inp"
    deck.write_text(text)
    r = xpl_run(xpl, "run", deck, "-o", out / "tiny", "--threads", "1", "--quiet")
    if r.returncode != 0:
        fail(f"tiny intervals: exit {r.returncode}\n{r.stderr}")
    msg = (out / "tiny" / "tiny.msg").read_text()
    for kind, value in (("FIELD", "1e-20"), ("HISTORY", "1e-13")):
        if not re.search(rf"\*OUTPUT, {kind} at \S+: the output interval {value} s is shorter "
                         r"than the stable increment \S+ s; output is written once per increment",
                         msg):
            fail(f"no note on the {kind} interval {value} s:\n{msg}")
    with h5py.File(out / "tiny" / "tiny.h5", "r") as f:
        increments = int(f["frames"][sorted(f["frames"])[-1]].attrs["increment"])
        frames = len(f["frames"])
        rows = f["history/step_1/time"].shape[0]
    # Frame 0 plus at most one frame (and one row) per increment.
    if not (frames == increments + 1 and rows == increments + 1):
        fail(f"{frames} frames and {rows} rows for {increments} increments")


def files(xpl, out):
    decks = out / "decks"
    decks.mkdir()
    (decks / "includes.inp").write_text("*HEADING\nx\n*INCLUDE, INPUT=.\n"
                                        "*INCLUDE, INPUT=/dev/zero\n")
    with open(decks / "line2gb.inp", "wb") as f:  # sparse: no disk space, no newline
        f.truncate(2_000_000_000)
    with open(decks / "size3gib.inp", "wb") as f:
        f.truncate(3 << 30)
    (decks / "long.inp").write_text("*HEADING\nx\n*NODE\n" + "1," * (1 << 20) + "\n")
    cases = [
        (pathlib.Path("/dev/zero"), ["/dev/zero: the deck is a device; expected a regular file"]),
        (decks, [f"{decks}: the deck is a directory; expected a regular file"]),
        (decks / "includes.inp", ["includes.inp:3: *INCLUDE: included file '" +
                                  str(decks) + "/' is a directory",
                                  "includes.inp:4: *INCLUDE: included file '/dev/zero' is a "
                                  "device"]),
        (decks / "line2gb.inp", ["line2gb.inp:1: line longer than 1048576 characters; "
                                 "expected deck lines of at most 1 MiB"]),
        (decks / "size3gib.inp", ["size3gib.inp: the deck is 3221225472 bytes, more than the "
                                  "limit of 2147483647 bytes (2 GiB)"]),
        (decks / "long.inp", ["long.inp:4: line longer than 1048576 characters"]),
    ]
    for deck, expected in cases:
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        r = xpl_run(xpl, "check", deck, "-o", out / "files")
        peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        if r.returncode != 1:
            fail(f"{deck}: exit {r.returncode}, expected 1\n{r.stderr}")
        for line in expected:
            if line not in r.stderr:
                fail(f"{deck}: stderr lacks {line!r}:\n{r.stderr}")
        # ru_maxrss is the largest child so far: only meaningful if it grew here.
        if deck.name == "line2gb.inp" and peak_kb > max(before, 200_000):
            fail(f"the 2 GB line took {peak_kb / 1024:.0f} MB of memory")
    if (out / "files").exists() and any((out / "files").iterdir()):
        fail("a refused deck wrote files")


def cycles(xpl, out):
    decks = out / "decks"
    decks.mkdir()
    body = "*HEADING\nx\n"
    (decks / "twice.inp").write_text(body + "*INCLUDE, INPUT=twice.inp\n" * 2)
    (decks / "thrice.inp").write_text(body + "*INCLUDE, INPUT=thrice.inp\n"
                                      "*INCLUDE, INPUT=./thrice.inp\n*INCLUDE, INPUT=thrice.inp\n")
    (decks / "a.inp").write_text(body + "*INCLUDE, INPUT=b.inp\n")
    (decks / "b.inp").write_text("*INCLUDE, INPUT=a.inp\n*INCLUDE, INPUT=a.inp\n")
    for name, chain in (("twice", f"{decks / 'twice.inp'} includes {decks / 'twice.inp'}"),
                        ("thrice", f"{decks / 'thrice.inp'} includes {decks / 'thrice.inp'}"),
                        ("a", f"{decks / 'a.inp'} includes {decks / 'b.inp'}, which includes "
                              f"{decks / 'a.inp'}")):
        r = xpl_run(xpl, "check", decks / f"{name}.inp", "-o", out / name)
        cycle_lines = [l for l in r.stderr.splitlines() if "cycle of includes" in l]
        if r.returncode != 1 or len(cycle_lines) != 1 or chain not in cycle_lines[0]:
            fail(f"{name}: exit {r.returncode}, expected one cycle error naming {chain!r}:\n"
                 f"{r.stderr}")


def control(xpl, bar_deck, out):
    deck = out / "escape.inp"
    deck.write_bytes(b"*HEADING\nx\n*\x1b[31mBOGUS\x07, A=\x1b[0m\n")
    r = xpl_run(xpl, "check", deck, "-o", out / "escape")
    if r.returncode != 1 or "\x1b" in r.stderr or "\x07" in r.stderr:
        fail(f"raw control characters echoed: {r.stderr!r}")
    if "*\\x1b[31MBOGUS\\x07" not in r.stderr:
        fail(f"the keyword is not echoed escaped: {r.stderr!r}")

    # *HEADING text is echoed in JOB.msg and kept in JOB.h5: escaped there too.
    bar = bar_deck.read_bytes()
    title = b"Steel bar 100 x 10 x 10 mm"
    if bar.count(title) != 1:
        fail("the bar example changed: no heading line starting with the title")
    deck = out / "heading.inp"
    step = b"*STEP, NAME=IMPACT"
    if bar.count(step) != 1:
        fail("the bar example changed: no *STEP, NAME=IMPACT")
    deck.write_bytes(bar.replace(title, b"\x1b[31mred\x07 bar\x7f " + title)
                     .replace(step, b"*STEP, NAME=IMP\x1bACT"))
    r = xpl_run(xpl, "check", deck, "-o", out / "heading")
    if r.returncode != 0:
        fail(f"the deck with a coloured heading: exit {r.returncode}\n{r.stderr}")
    msg = (out / "heading" / "heading.msg").read_bytes()
    sta = (out / "heading" / "heading.sta").read_bytes()
    for name, text in (("heading.msg", msg), ("heading.sta", sta)):
        if any(c in text for c in (b"\x1b", b"\x07", b"\x7f")):
            fail(f"raw control characters of *HEADING or the step name in {name}")
    if b"heading: \\x1b[31mred\\x07 bar\\x7f Steel bar" not in msg:
        fail(f"the heading is not echoed escaped in heading.msg:\n{msg.decode(errors='replace')}")
    if b"IMP\\x1bACT" not in msg or b"IMP\\x1bACT" not in sta:
        fail("the step name is not echoed escaped in heading.msg and heading.sta")
    with h5py.File(out / "heading" / "heading.h5", "r") as f:
        stored = f.attrs["heading"]
        stored = stored.decode() if isinstance(stored, bytes) else str(stored)
    if not stored.startswith("\\x1b[31mred\\x07 bar\\x7f Steel bar"):
        fail(f"heading attribute of heading.h5 not escaped: {stored!r}")


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case, xpl, bar, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3]), \
        pathlib.Path(sys.argv[4])
    import shutil
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    if case == "velocity":
        velocity(xpl, bar, out)
    elif case == "interval":
        interval(xpl, bar, out)
    elif case == "files":
        files(xpl, out)
    elif case == "cycles":
        cycles(xpl, out)
    elif case == "control":
        control(xpl, bar, out)
    else:
        sys.exit(__doc__)
    print(f"ok: {case}")


if __name__ == "__main__":
    main()
