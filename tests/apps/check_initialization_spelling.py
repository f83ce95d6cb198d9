#!/usr/bin/python3
"""*CONTACT INITIALIZATION DATA / ASSIGNMENT run the same code as *CONTACT CLEARANCE /
ASSIGNMENT (SPEC C14, issue 35 item 2): one implementation, two spellings, bitwise the same
results.

Usage: check_initialization_spelling.py XPL DECK REFERENCE_H5 WORK_DIR

Rewrites DECK (written with *CONTACT CLEARANCE) in today's spelling:
  *CONTACT CLEARANCE, NAME=n, CLEARANCE=v, ...  ->  *CONTACT INITIALIZATION DATA, NAME=n,
                                                   INITIAL CLEARANCE=v, ...
  (ADJUST=, SEARCH ABOVE=, SEARCH BELOW= and the manual's continuation line unchanged)
  *CONTACT CLEARANCE ASSIGNMENT                 ->  *CONTACT INITIALIZATION ASSIGNMENT
  surf1, surf2, n, MASTER                       ->  surf1, surf2, n, SECOND SURFACE SFC
  surf1, surf2, n, SLAVE                        ->  surf1, surf2, n, FIRST SURFACE SFC
runs it, and compares its results with REFERENCE_H5 (the run of DECK as written) with
`xpl compare` at tolerance 0: mesh, overclosure tables, every history series, last frame.
It also checks that the rewritten deck really uses the new keywords and that the .msg files
say the same thing (the clearance lines name "contact initialization" instead of "contact
clearance").
"""

import pathlib
import re
import shutil
import subprocess
import sys


def rewrite(text):
    out = []
    in_assignment = False
    count = {"data": 0, "assignment": 0}
    for line in text.splitlines():
        if line.startswith("*"):
            in_assignment = False
            if re.match(r"^\*CONTACT CLEARANCE ASSIGNMENT\s*$", line, re.I):
                line = "*CONTACT INITIALIZATION ASSIGNMENT"
                in_assignment = True
                count["assignment"] += 1
            elif re.match(r"^\*CONTACT CLEARANCE\s*,", line, re.I):
                line = re.sub(r"^\*CONTACT CLEARANCE", "*CONTACT INITIALIZATION DATA", line,
                              flags=re.I)
                line = re.sub(r"(,\s*)CLEARANCE\s*=", r"\1INITIAL CLEARANCE=", line, flags=re.I)
                count["data"] += 1
        elif in_assignment and not line.startswith("**"):
            fields = [f.strip() for f in line.split(",")]
            if len(fields) == 4:
                fields[3] = {"MASTER": "SECOND SURFACE SFC",
                             "SLAVE": "FIRST SURFACE SFC"}.get(fields[3].upper(), fields[3])
            line = ", ".join(fields)
        elif re.match(r"^\s*CLEARANCE\s*=", line, re.I):
            line = re.sub(r"CLEARANCE\s*=", "INITIAL CLEARANCE=", line, count=1, flags=re.I)
        out.append(line)
    return "\n".join(out) + "\n", count


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    xpl, deck, reference = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work = pathlib.Path(sys.argv[4])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    text, count = rewrite(deck.read_text())
    if count["data"] == 0 or count["assignment"] == 0:
        sys.exit(f"FAIL: {deck} has no *CONTACT CLEARANCE / ASSIGNMENT to rewrite ({count})")
    if re.search(r"^\*CONTACT CLEARANCE", text, re.I | re.M):
        sys.exit("FAIL: the rewritten deck still has *CONTACT CLEARANCE")
    new_deck = work / deck.name
    new_deck.write_text(text)
    # Files the deck includes (none today) would sit beside it.
    for other in deck.parent.iterdir():
        if other.is_file() and other.suffix != ".inp":
            shutil.copy(other, work / other.name)
    run = subprocess.run([xpl, "run", str(new_deck), "-o", str(work)], capture_output=True,
                         text=True)
    if run.returncode != 0:
        sys.exit(f"FAIL: xpl run exited {run.returncode}\n{run.stdout}\n{run.stderr}")
    new_h5 = work / (deck.stem + ".h5")
    compare = subprocess.run([xpl, "compare", str(reference), str(new_h5)], capture_output=True,
                             text=True)
    print(compare.stdout.strip().splitlines()[-1] if compare.stdout.strip() else "")
    if compare.returncode != 0:
        sys.exit(f"FAIL: the two spellings differ\n{compare.stdout}\n{compare.stderr}")
    # The .msg files: the same lines, up to the name of the keyword family and the timings.
    def normalized(path):
        lines = []
        for line in path.read_text().splitlines():
            line = line.replace("contact initialization ", "contact clearance ")
            line = re.sub(r"[0-9.]+(e[-+]?\d+)? s\b", "T s", line)
            if re.search(r"wall|elapsed|seconds|threads|xpl version|date|host", line, re.I):
                continue
            if deck.stem in line and (".inp" in line or "job" in line.lower()):
                continue
            lines.append(line)
        return lines
    ref_msg = normalized(reference.with_suffix(".msg"))
    new_msg = normalized(new_h5.with_suffix(".msg"))
    ref_clear = [l for l in ref_msg if "contact clearance" in l]
    new_clear = [l for l in new_msg if "contact clearance" in l]
    if ref_clear != new_clear:
        for a, b in zip(ref_clear, new_clear):
            if a != b:
                print("ref:", a)
                print("new:", b)
                break
        sys.exit(f"FAIL: the clearance lines of the .msg differ ({len(ref_clear)} vs "
                 f"{len(new_clear)} lines)")
    print(f"PASS {deck.stem}: {count['data']} definition(s) and {count['assignment']} "
          f"assignment block(s) in the new spelling give bitwise the same results; "
          f"{len(ref_clear)} clearance lines of the .msg agree")


if __name__ == "__main__":
    main()
