#!/usr/bin/python3
"""Input that cannot be meant, run end to end (issue 33, items 3 and 5).

Usage: check_input_sanity.py CASE XPL OUT_DIR, CASE one of
  contact_repeat  a *CONTACT INCLUSIONS pair given again in a later step (default OP=MOD) runs
                  to completion with a note at its line (it stopped with exit 4: "HDF5: cannot
                  create dataset ... name already exists"); the same pair twice in one step is
                  a deck error at the second line (exit 1, nothing written)
  tie_none        a *TIE whose slave nodes all lie beyond the position tolerance warns in the
                  .msg (of a data check) that it ties no node, with the node count, the
                  tolerance and the nearest distance
  tie_far         ADJUST=YES with a position tolerance larger than an element warns (data
                  check) that it moves the slave nodes by more than their master face, with
                  the largest move; a move of a tenth of an element is not warned of
The model: two blocks of 2 x 1 x 1 C3D8R elements of 10 mm, one above the other with a gap.
"""

import pathlib
import re
import shutil
import subprocess
import sys

H = 0.01


def fail(message):
    sys.exit(f"FAIL: {message}")


def block(first_node, first_element, z0, elset):
    lines = ["*NODE"]
    def nid(i, j, k):
        return first_node + i + 3 * (j + 2 * k)
    for k in range(2):
        for j in range(2):
            for i in range(3):
                lines.append(f"{nid(i, j, k)}, {i * H}, {j * H}, {z0 + k * H}")
    lines.append(f"*ELEMENT, TYPE=C3D8R, ELSET={elset}")
    for i in range(2):
        corners = [nid(i, 0, 0), nid(i + 1, 0, 0), nid(i + 1, 1, 0), nid(i, 1, 0),
                   nid(i, 0, 1), nid(i + 1, 0, 1), nid(i + 1, 1, 1), nid(i, 1, 1)]
        lines.append(f"{first_element + i}, " + ", ".join(map(str, corners)))
    return lines


def deck(gap, model_lines, steps):
    lines = ["*HEADING", "two blocks"]
    lines += block(1, 1, 0.0, "LOWER") + block(101, 11, H + gap, "UPPER")
    lines += ["*SURFACE, NAME=LOWER_TOP", "LOWER, S2", "*SURFACE, NAME=UPPER_BOTTOM", "UPPER, S1",
              "*MATERIAL, NAME=STEEL", "*DENSITY", "7800.", "*ELASTIC", "2.1e11, 0.3",
              "*SOLID SECTION, ELSET=LOWER, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=UPPER, MATERIAL=STEEL",
              "*NSET, NSET=MOVING, ELSET=UPPER", "*INITIAL CONDITIONS, TYPE=VELOCITY",
              "MOVING, 3, -1."]
    lines += model_lines
    for n, step in enumerate(steps, start=1):
        lines += [f"*STEP, NAME=S{n}", "*DYNAMIC, EXPLICIT", ", 2e-5"] + step
        lines += ["*OUTPUT, HISTORY, NUMBER INTERVAL=5", "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(lines) + "\n"


def run(xpl, text, out, name, expected, command="run"):
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.inp"
    path.write_text(text)
    results = out / name
    p = subprocess.run([xpl, command, str(path), "-o", str(results), "--quiet"],
                       capture_output=True, text=True, timeout=120)
    if p.returncode != expected:
        fail(f"{name}: exit {p.returncode}, expected {expected}\n{p.stdout}\n{p.stderr}")
    return p, results


def case_contact_repeat(xpl, out):
    include = ["*CONTACT", "*CONTACT INCLUSIONS", "LOWER_TOP, UPPER_BOTTOM"]
    text = deck(0.001, [], [include, include])
    _, results = run(xpl, text, out, "repeat", 0)
    msg = (results / "repeat.msg").read_text()
    lines = text.splitlines()
    first = lines.index("LOWER_TOP, UPPER_BOTTOM") + 1
    line = lines.index("LOWER_TOP, UPPER_BOTTOM", first) + 1
    note = (f"repeat.inp:{line}: *CONTACT INCLUSIONS: the pair LOWER_TOP, UPPER_BOTTOM is in "
            f"effect since {out / 'repeat.inp'}:{first}")
    if note not in msg or "given again, it changes nothing" not in msg:
        fail(f"no note at line {line} in the .msg")
    twice = deck(0.001, [], [include + ["UPPER_BOTTOM, LOWER_TOP"]])
    p, results = run(xpl, twice, out, "twice", 1)
    line = twice.splitlines().index("UPPER_BOTTOM, LOWER_TOP") + 1
    if f"twice.inp:{line}: *CONTACT INCLUSIONS: the pair UPPER_BOTTOM, LOWER_TOP is given " \
            f"twice in step S1 (first at {out / 'twice.inp'}:" not in p.stderr:
        fail(f"the pair given twice in one step: {p.stderr}")
    if results.exists() and any(results.iterdir()):
        fail(f"a deck error wrote files: {sorted(results.iterdir())}")
    print("a pair repeated in a later step runs (with a note); twice in one step is refused")


def case_tie_none(xpl, out):
    tie = ["*TIE, NAME=GLUE, POSITION TOLERANCE=0.001", "UPPER_BOTTOM, LOWER_TOP"]
    _, results = run(xpl, deck(0.005, tie, [[]]), out, "tie_none", 0, "check")
    msg = (results / "tie_none.msg").read_text()
    m = re.search(r"\*\*\*WARNING: tie GLUE ties no node: none of the (\d+) slave node\(s\) of "
                  r"UPPER_BOTTOM lies within the position tolerance ([\d.e+-]+) m of LOWER_TOP "
                  r"\(the nearest is ([\d.e+-]+) m away\); the tie has no effect", msg)
    if not m:
        fail(f"no warning with the numbers in the .msg:\n{msg}")
    nodes, tolerance, nearest = int(m.group(1)), float(m.group(2)), float(m.group(3))
    if nodes != 6 or tolerance != 0.001 or abs(nearest - 0.005) > 1e-12:
        fail(f"numbers: {nodes} nodes, tolerance {tolerance}, nearest {nearest}")
    print(m.group(0))


def case_tie_far(xpl, out):
    tie = ["*TIE, NAME=GLUE, POSITION TOLERANCE=0.05, ADJUST=YES", "UPPER_BOTTOM, LOWER_TOP"]
    _, results = run(xpl, deck(0.02, tie, [[]]), out, "tie_far", 0, "check")
    msg = (results / "tie_far.msg").read_text()
    m = re.search(r"\*\*\*WARNING: tie GLUE: ADJUST=YES moves (\d+) slave node\(s\) by more than "
                  r"the size of the master face they are tied to \(node (\d+) by ([\d.e+-]+) m, "
                  r"its face's diagonal ([\d.e+-]+) m; position tolerance ([\d.e+-]+) m\)", msg)
    if not m:
        fail(f"no warning with the numbers in the .msg:\n{msg}")
    moved, move, diagonal = int(m.group(1)), float(m.group(3)), float(m.group(4))
    # The .msg prints 4 significant digits.
    if moved != 6 or abs(move - 0.02) > 1e-12 or abs(diagonal - H * 2 ** 0.5) > 5e-6:
        fail(f"numbers: {moved} moved, by {move}, diagonal {diagonal}")
    near = ["*TIE, NAME=GLUE, POSITION TOLERANCE=0.05, ADJUST=YES", "UPPER_BOTTOM, LOWER_TOP"]
    _, results = run(xpl, deck(0.001, near, [[]]), out, "tie_near", 0, "check")
    if "***WARNING: tie GLUE" in (results / "tie_near.msg").read_text():
        fail("a move of 1 mm (a tenth of an element) was warned of")
    print(m.group(0))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    case, xpl, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    {"contact_repeat": case_contact_repeat, "tie_none": case_tie_none,
     "tie_far": case_tie_far}[case](xpl, out)


if __name__ == "__main__":
    main()
