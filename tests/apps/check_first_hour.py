#!/usr/bin/python3
"""The first hour of a new user (issue 34, item 4; SPEC I6).

Usage: check_first_hour.py CASE XPL REPO OUT_DIR, CASE one of
  defaults  a deck without output requests (the bar example with its *OUTPUT lines removed)
            warns on the terminal and in JOB.msg, and still writes frame 0 and the last frame
            of each step (U, V, S; PEEQ only on a plastic model) and the energies 200 times a
            step, with JOB.xdmf; a two-step deck gets a frame at the end of each step; the
            deck with its output requests writes what it asks for and no warning
  progress  a ~3 s run under a pseudo-terminal shows the progress line: step, time, percent,
            increment, dt, elapsed m:ss, increments per second and ETA m:ss (checked by a
            regular expression; the last ETA 0:00 or 0:01); JOB.sta has a WALL TIME column,
            non-decreasing, whose last value is within 1 s of the summary's elapsed time, and
            its other columns keep their meaning (the status line parsers of other tests)
  units     the bar in mm, t, s with '** xpl: UNITS=MM-T-S': JOB.h5 labels S MPa, U mm, ALLKE
            mJ, time s, coordinates mm, and says MM-T-S at its root; JOB.msg and
            JOB.summary.json say so; its U, S and ALLKE are the SI run's times 1e3, 1e-6, 1e3
            (rtol 1e-9: the same numbers in other units). Without the statement the same deck
            is never labelled m or Pa: dimension labels ([stress]) and a warning naming
            MM-T-S. The SI deck without a statement is labelled SI, said to be assumed. A
            misspelt statement (unknown system, unknown setting, two systems) is a deck error
            (exit 1) at its line; a stated system the material data do not fit (the SI deck
            stating MM-T-S) keeps its labels with a warning naming SI
"""

import json
import os
import pathlib
import pty
import re
import select
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"check_first_hour.py: FAILED: {message}")
    return condition


def run(xpl, deck, out, *extra, code=0):
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out), "--threads", "1", *extra],
                            capture_output=True, text=True, timeout=120)
    check(result.returncode == code,
          f"xpl run {deck.name}: exit {result.returncode}, expected {code}: {result.stderr}")
    return result


def without_output(text):
    """The deck text with every output request (from *OUTPUT to the next step keyword) left
    out."""
    lines, keep = [], True
    for line in text.splitlines():
        upper = line.upper()
        if upper.startswith("*OUTPUT"):
            keep = False
        elif upper.startswith("*END STEP"):
            keep = True
        if keep:
            lines.append(line)
    return "\n".join(lines) + "\n"


WARNING = "the deck has no output requests"


def case_defaults(xpl, repo, out):
    bar = (repo / "examples/bar_impact/bar_impact.inp").read_text()
    check("*OUTPUT" in bar, "the bar example has output requests")
    decks = out / "decks"
    decks.mkdir()
    plain = decks / "plain.inp"
    plain.write_text(without_output(bar))
    # Plastic, two steps: PEEQ in the frames, one frame at the end of each step.
    plastic = decks / "plastic.inp"
    text = without_output(bar).replace("*ELASTIC\n2e+11, 0\n",
                                       "*ELASTIC\n2e+11, 0\n*PLASTIC\n2e8, 0\n")
    check("*PLASTIC" in text, "could not make the bar plastic")
    step = text[text.index("*STEP"):]
    plastic.write_text(text + step.replace("NAME=IMPACT", "NAME=REBOUND"))

    result = run(xpl, plain, out / "plain")
    check(f"warning: {WARNING}" in result.stderr, f"no warning on the terminal: {result.stderr}")
    msg = (out / "plain" / "plain.msg").read_text()
    check(f"***WARNING: {WARNING}" in msg, "no warning in plain.msg")
    check((out / "plain" / "plain.xdmf").exists(), "no plain.xdmf")
    with h5py.File(out / "plain" / "plain.h5", "r") as f:
        frames = sorted(f["frames"])
        check(frames == ["000000", "000001"], f"frames {frames}")
        last = f["frames"][frames[-1]]
        check(sorted(last) == ["HGSTATE", "MISES", "S", "U", "V"], f"last frame {sorted(last)}")
        check(last.attrs["time"] == 1e-4, f"last frame at t = {last.attrs['time']}")
        check(np.abs(last["U"][()]).max() > 0.0, "the last frame's U is zero")
        energy = f["history/step_1/energy"]
        rows = energy["ALLKE"].shape[0]
        check(199 <= rows <= 202, f"{rows} history rows (200 intervals)")
        check("ETOTAL" in energy and "ALLIE" in energy, f"energies {sorted(energy)}")

    result = run(xpl, plastic, out / "plastic")
    check(f"warning: {WARNING}" in result.stderr, "no warning for the plastic deck")
    with h5py.File(out / "plastic" / "plastic.h5", "r") as f:
        frames = sorted(f["frames"])
        check(frames == ["000000", "000001", "000002"], f"two steps: frames {frames}")
        steps = [int(f["frames"][n].attrs["step"]) for n in frames]
        check(steps == [1, 1, 2], f"frame steps {steps}")
        check("PEEQ" in f["frames"][frames[-1]], "no PEEQ in the plastic model's last frame")
        check(float(np.max(f["frames"][frames[-1]]["PEEQ"][()])) > 0.0, "PEEQ is zero")
        check("step_1" in f["history"] and "step_2" in f["history"], "history of both steps")
        check("ALLPD" in f["history/step_2/energy"], "no ALLPD in the plastic history")

    result = run(xpl, repo / "examples/bar_impact/bar_impact.inp", out / "asked")
    check(WARNING not in result.stderr, "a deck with output requests is warned of")
    check(WARNING not in (out / "asked" / "bar_impact.msg").read_text(), "warning in the .msg")
    with h5py.File(out / "asked" / "bar_impact.h5", "r") as f:
        check(len(f["frames"]) == 11, f"bar_impact: {len(f['frames'])} frames, asked for 11")
        check("A" in f["frames/000010"], "bar_impact's own request (A) is not written")
    print("defaults: warned on the terminal and in JOB.msg; frame 0 and the last frame of each "
          "step (PEEQ where plastic), energies 200 times a step; a deck with requests unchanged")


PROGRESS = re.compile(
    r"step 1/1  t = \d\.\d{4}e[-+]\d\d of \d\.\d{4}e[-+]\d\d s \(\s*\d+\.\d%\)  increment \d+  "
    r"dt \d\.\d{3}e[-+]\d\d s  elapsed \d+:\d\d  [\d.e+]+ inc/s  ETA (\d+):(\d\d)")


def read_pty(xpl, deck, out):
    """Runs xpl with stderr on a pseudo-terminal; returns (exit code, what stderr showed)."""
    master, slave = pty.openpty()
    process = subprocess.Popen([xpl, "run", str(deck), "-o", str(out), "--threads", "1"],
                               stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    chunks, deadline = [], time.monotonic() + 120
    while time.monotonic() < deadline:
        ready, _, _ = select.select([master], [], [], 0.5)
        if ready:
            try:
                data = os.read(master, 65536)
            except OSError:  # the other end closed: the process is done
                break
            if not data:
                break
            chunks.append(data)
        elif process.poll() is not None:
            break
    code = process.wait(timeout=60)
    os.close(master)
    return code, b"".join(chunks).decode(errors="replace")


def case_progress(xpl, repo, out):
    deck = out / "block.inp"
    subprocess.run([sys.executable, str(repo / "benchmarks" / "make_block.py"), "-n", "10",
                    "--increments", "40000", "--out", str(deck)], check=True,
                   capture_output=True)
    code, shown = read_pty(xpl, deck, out / "results")
    check(code == 0, f"exit {code}: {shown[-500:]}")
    lines = [part.strip() for part in re.split(r"[\r\n]", shown) if part.startswith("step ")
             or part.strip().startswith("step ")]
    progress = [m for m in (PROGRESS.fullmatch(line) for line in lines) if m]
    check(len(progress) >= 2, f"{len(progress)} progress lines match; shown:\n{shown[-1500:]}")
    if progress:
        minutes, seconds = (int(v) for v in progress[-1].groups())
        check(minutes == 0 and seconds <= 1, f"last ETA {minutes}:{seconds:02d}")
        print(f"progress: {progress[-1].group(0)}")
    sta = (out / "results" / "block.sta").read_text()
    check("WALL TIME" in sta, "JOB.sta has no WALL TIME column")
    rows = [line.split() for line in sta.splitlines()
            if re.match(r"^\s+\d+\s+\d+\s+[-\d.E+]+\s", line)]
    check(len(rows) >= 100 and all(len(r) == 10 for r in rows),
          f"{len(rows)} status lines, widths {sorted({len(r) for r in rows})}")
    # The columns that other tests read keep their places (check_penalty_increment.py).
    parsed = [re.match(r"^\s+\d+\s+(\d+)\s+([-\d.E+]+)\s+[-\d.E+]+\s+([-\d.E+]+)\s+(node \d+|\d+)\s",
                       line) for line in sta.splitlines() if re.match(r"^\s+\d+\s+\d+\s", line)]
    check(all(parsed), "a status line no longer parses as increment, time, dt, critical")
    wall = [float(r[-1]) for r in rows]
    check(all(b >= a for a, b in zip(wall, wall[1:])), "WALL TIME decreases")
    summary = json.loads((out / "results" / "block.summary.json").read_text())
    elapsed = summary["wall_time"]["elapsed"]
    check(abs(wall[-1] - elapsed) < 1.0, f"last WALL TIME {wall[-1]} s, elapsed {elapsed} s")
    check(wall[-1] > 2.0, f"the run took {wall[-1]} s: too short to show the progress line")
    print(f"progress: {len(progress)} lines matched; .sta WALL TIME up to {wall[-1]:.2f} s "
          f"(elapsed {elapsed:.2f} s)")


def millimetre_deck(text):
    """The SI bar deck in mm, t, s: coordinates x 1e3, density x 1e-12, E x 1e-6, velocity
    x 1e3; times unchanged."""
    out, in_nodes = [], False
    for line in text.splitlines():
        if line.startswith("*"):
            in_nodes = line.upper().startswith("*NODE") and not line.upper().startswith(
                "*NODE OUTPUT")
            out.append(line)
            continue
        if in_nodes and not line.startswith("**"):
            fields = [v.strip() for v in line.split(",")]
            out.append(", ".join([fields[0]] + [repr(float(v) * 1e3) for v in fields[1:]]))
            continue
        out.append(line)
    text = "\n".join(out) + "\n"
    for old, new in (("*DENSITY\n7850\n", "*DENSITY\n7.85e-09\n"),
                     ("*ELASTIC\n2e+11, 0\n", "*ELASTIC\n200000, 0\n"),
                     ("MOVING, 1, -10\n", "MOVING, 1, -10000\n")):
        check(old in text, f"the bar deck has no {old!r}")
        text = text.replace(old, new)
    return text


def case_units(xpl, repo, out):
    si_deck = repo / "examples/bar_impact/bar_impact.inp"
    decks = out / "decks"
    decks.mkdir()
    mm_text = millimetre_deck(si_deck.read_text())
    stated = decks / "bar_mm.inp"
    stated.write_text(mm_text.replace("*HEADING", "** xpl: UNITS=MM-T-S\n*HEADING", 1))
    unstated = decks / "bar_mm_unstated.inp"
    unstated.write_text(mm_text)

    run(xpl, si_deck, out / "si")
    result = run(xpl, stated, out / "mm")
    check("units: length mm, mass t, time s, force N, stress MPa, energy mJ" in result.stdout,
          f"the terminal does not state the units: {result.stdout}")
    with h5py.File(out / "si" / "bar_impact.h5", "r") as si, \
            h5py.File(out / "mm" / "bar_mm.h5", "r") as mm:
        check(si.attrs["unit_system"] == "SI (assumed)", f"SI deck: {si.attrs['unit_system']}")
        check("SI assumed" in si.attrs["units"], f"SI deck units: {si.attrs['units']}")
        check(si["frames/000010/S"].attrs["units"] == "Pa", "SI deck: S not in Pa")
        check(mm.attrs["unit_system"] == "MM-T-S", f"mm deck: {mm.attrs['unit_system']}")
        check("length mm, mass t, time s, force N, stress MPa, energy mJ" in mm.attrs["units"],
              f"mm deck units: {mm.attrs['units']}")
        labels = {"frames/000010/S": "MPa", "frames/000010/U": "mm", "frames/000010/V": "mm/s",
                  "frames/000010/A": "mm/s^2", "frames/000010/RF": "N", "frames/000010/MISES": "MPa",
                  "mesh/coordinates": "mm", "history/step_1/time": "s",
                  "history/step_1/energy/ALLKE": "mJ", "history/step_1/node/FIXED/RF1": "N",
                  "history/step_1/node/FREE_END/U1": "mm"}
        for path, unit in labels.items():
            check(mm[path].attrs["units"] == unit,
                  f"{path}: units {mm[path].attrs['units']!r}, expected {unit}")
        # The same physics in other units: the numbers differ by the unit factors only.
        for path, factor in (("frames/000010/U", 1e3), ("frames/000010/S", 1e-6),
                             ("history/step_1/energy/ALLKE", 1e3)):
            a, b = si[path][()] * factor, mm[path][()]
            scale = np.abs(a).max()
            check(np.allclose(b, a, rtol=1e-9, atol=1e-9 * scale),
                  f"{path}: mm run / SI run differ by {np.abs(b - a).max() / scale:.2e} of the "
                  f"largest value")
    msg = (out / "mm" / "bar_mm.msg").read_text()
    check("units stated at" in msg and "stress MPa" in msg, "bar_mm.msg does not state the units")
    summary = json.loads((out / "mm" / "bar_mm.summary.json").read_text())
    check(summary["units"]["system"] == "MM-T-S" and summary["units"]["stress"] == "MPa"
          and summary["units"]["energy"] == "mJ" and summary["units"]["stated"] is True,
          f"summary units {summary['units']}")

    result = run(xpl, unstated, out / "unstated")
    check("not SI" in result.stderr, f"no warning on the terminal: {result.stderr}")
    msg = (out / "unstated" / "bar_mm_unstated.msg").read_text()
    check("***WARNING: the deck does not state its units" in msg and "MM-T-S" in msg,
          "bar_mm_unstated.msg does not warn and name MM-T-S")
    with h5py.File(out / "unstated" / "bar_mm_unstated.h5", "r") as f:
        check(f.attrs["unit_system"] == "unstated", f"unstated: {f.attrs['unit_system']}")
        found = {path: f[path].attrs["units"] for path in ("frames/000010/S", "frames/000010/U",
                                                           "history/step_1/energy/ALLKE")}
        check(found == {"frames/000010/S": "[stress]", "frames/000010/U": "[length]",
                        "history/step_1/energy/ALLKE": "[energy]"}, f"unstated labels {found}")

    # A stated system the material data cannot be in keeps its labels, with a warning.
    wrong = decks / "bar_si_says_mm.inp"
    wrong.write_text("** xpl: UNITS=MM-T-S\n" + si_deck.read_text())
    run(xpl, wrong, out / "wrong")
    msg = (out / "wrong" / "bar_si_says_mm.msg").read_text()
    check("UNITS=MM-T-S, but the material data do not fit it" in msg and "they fit SI" in msg,
          "no warning that the SI data do not fit the stated MM-T-S")
    with h5py.File(out / "wrong" / "bar_si_says_mm.h5", "r") as f:
        check(f["frames/000010/S"].attrs["units"] == "MPa", "the stated system's labels are kept")

    bad = {"UNITS=FURLONG-FIRKIN-FORTNIGHT": "unknown unit system 'FURLONG-FIRKIN-FORTNIGHT'",
           "UNIT=SI": "unknown setting 'UNIT=SI'",
           "UNITS=SI\n** xpl: UNITS=MM-T-S": "UNITS=MM-T-S after UNITS=SI at "}
    for statement, needle in bad.items():
        deck = decks / "bad.inp"
        deck.write_text(f"*HEADING\nbad units\n** xpl: {statement}\n" +
                        si_deck.read_text().split("\n", 2)[2])
        result = run(xpl, deck, out / "bad", code=1)
        line = 3 if "after" not in needle else 4
        first = result.stderr.splitlines()[0] if result.stderr else ""
        check(f"bad.inp:{line}: ** xpl: {needle}" in first and "; expected" in first
              and "error(s)" in result.stderr, f"{statement!r}: {result.stderr}")
    print("units: MM-T-S labels (MPa, mm, mJ) in the .h5, .msg and summary; the numbers are the "
          "SI run's in those units; unstated non-SI data get dimension labels and a warning; "
          "bad statements are deck errors")


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case, xpl = sys.argv[1], sys.argv[2]
    repo, out = pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    {"defaults": case_defaults, "progress": case_progress, "units": case_units}[case](
        xpl, repo, out)
    if failures:
        sys.exit(f"check_first_hour.py: {case}: {len(failures)} check(s) failed")


if __name__ == "__main__":
    main()
