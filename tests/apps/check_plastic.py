#!/usr/bin/python3
"""`xpl check` and `xpl run` of decks with *PLASTIC / *RATE DEPENDENT (issue 14, deck part).

Usage: check_plastic.py XPL OUT_DIR

Writes its own decks (two bricks: STEEL with a hardening table and Cowper-Symonds rate
dependence, TI6AL4V with Johnson-Cook hardening and rate dependence) and checks:
- `xpl check` of the good deck exits 0 and its .msg lists each plastic material's initial
  yield stress and hardening form, the Johnson-Cook thermal-term note and the warning that
  the element kernels do not run plasticity yet;
- `xpl run` of the same deck exits 1 with that refusal and writes nothing (no silent elastic
  run) -- until the C3D8R return mapping lands;
- `xpl check` of a deck with several bad *PLASTIC / *RATE DEPENDENT values exits 1 with every
  message, each at its line, and writes nothing.
"""

import pathlib
import shutil
import subprocess
import sys

MODEL = """*HEADING
two plastic bricks
*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 2, 0, 0
6, 2, 1, 0
7, 0, 0, 1
8, 1, 0, 1
9, 1, 1, 1
10, 0, 1, 1
11, 2, 0, 1
12, 2, 1, 1
*ELEMENT, TYPE=C3D8R, ELSET=LEFT
1, 1, 2, 3, 4, 7, 8, 9, 10
*ELEMENT, TYPE=C3D8R, ELSET=RIGHT
2, 2, 5, 6, 3, 8, 11, 12, 9
*MATERIAL, NAME=STEEL
*DENSITY
7800.
*ELASTIC
2.1e11, 0.3
*PLASTIC
{steel_table}*RATE DEPENDENT, TYPE=POWER LAW
{steel_rate}
*MATERIAL, NAME=TI6AL4V
*DENSITY
4430.
*ELASTIC
1.1e11, 0.34
*PLASTIC, HARDENING=JOHNSON COOK
{ti_jc}
*RATE DEPENDENT, TYPE=JOHNSON COOK
0.014, 1.0
*SOLID SECTION, ELSET=LEFT, MATERIAL=STEEL
*SOLID SECTION, ELSET=RIGHT, MATERIAL=TI6AL4V
*STEP
*DYNAMIC, EXPLICIT
, 1e-4
*END STEP
"""

GOOD = MODEL.format(steel_table="4.0e8, 0.0\n4.5e8, 0.1\n5.0e8, 0.5\n", steel_rate="40.4, 5",
                    ti_jc="1.098e9, 1.092e9, 0.93, 1.1, 1878., 293.")
BAD = MODEL.format(steel_table="4.0e8, 0.01\n-4.5e8, 0.1\n5.0e8, 0.05\n", steel_rate="0, 5",
                   ti_jc="1.098e9, -1.092e9, 0.93, 1.1, 1878., 293.")


def check(condition, message):
    if not condition:
        sys.exit(f"check_plastic.py: FAILED: {message}")


def line_of(deck, needle):
    """1-based number of the first line of `deck` that starts with `needle`."""
    for number, line in enumerate(deck.splitlines(), start=1):
        if line.startswith(needle):
            return number
    sys.exit(f"check_plastic.py: {needle!r} not in the deck")


def xpl(binary, *args):
    result = subprocess.run([binary, *args], capture_output=True, text=True, timeout=60)
    return result.returncode, result.stdout, result.stderr


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    binary, out = sys.argv[1], pathlib.Path(sys.argv[2])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)

    # 1. Data check of the good deck: exit 0, the yield stresses in the .msg.
    good = out / "plastic_good.inp"
    good.write_text(GOOD)
    check_dir = out / "check"
    code, stdout, stderr = xpl(binary, "check", str(good), "-o", str(check_dir), "--quiet")
    check(code == 0, f"xpl check of the good deck exited {code}:\n{stdout}{stderr}")
    msg = (check_dir / "plastic_good.msg").read_text()
    plastic = line_of(GOOD, "*PLASTIC")  # STEEL's *PLASTIC: the first
    ti_plastic = line_of(GOOD, "*PLASTIC, HARDENING=JOHNSON COOK")
    for expected in [
        "STEEL: initial yield stress 4.0000E+08",
        "hardening tabular isotropic: 3 points to PEEQ 0.5 (yield 5.0000E+08), constant beyond",
        "rate dependence power law (Cowper-Symonds) 1 + (rate/D)^(1/n): D 40.4 1/s, n 5",
        "TI6AL4V: initial yield stress 1.0980E+09",
        "hardening Johnson-Cook A + B*PEEQ^n: A 1.0980E+09, B 1.0920E+09, n 0.93",
        "rate dependence Johnson-Cook 1 + C ln(rate/rate0): C 0.014, rate0 1 1/s",
        f"***NOTE: {good}:{ti_plastic}: *PLASTIC: material TI6AL4V: the Johnson-Cook thermal "
        "term is taken as 1",
        f"***WARNING: {good}:{plastic}: *PLASTIC: plasticity (*PLASTIC) on C3D8R elements "
        "(material STEEL) is not implemented yet",
        f"***WARNING: {good}:{ti_plastic}: *PLASTIC: plasticity (*PLASTIC) on C3D8R elements "
        "(material TI6AL4V) is not implemented yet",
    ]:
        check(expected in msg, f".msg lacks {expected!r}:\n{msg}")

    # 2. A run of the same deck is refused (the elements would run it elastic), nothing written.
    run_dir = out / "run"
    code, stdout, stderr = xpl(binary, "run", str(good), "-o", str(run_dir), "--quiet")
    check(code == 1, f"xpl run of the plastic deck exited {code}, expected 1:\n{stderr}")
    check(f"{good}:{plastic}: *PLASTIC: plasticity (*PLASTIC) on C3D8R elements (material "
          "STEEL) is not implemented yet" in stderr, f"stderr:\n{stderr}")
    check("2 error(s)" in stderr, f"expected 2 errors (one per material):\n{stderr}")
    check(not (run_dir / "plastic_good.h5").exists(), "a refused run wrote results")

    # 3. Several bad values: all reported at their lines, exit 1, nothing written.
    bad = out / "plastic_bad.inp"
    bad.write_text(BAD)
    bad_dir = out / "bad"
    code, stdout, stderr = xpl(binary, "check", str(bad), "-o", str(bad_dir))
    check(code == 1, f"xpl check of the bad deck exited {code}, expected 1:\n{stderr}")
    for needle, text in [
        ("4.0e8, 0.01", "*PLASTIC: the first plastic strain is 0.01, not 0"),
        ("-4.5e8, 0.1", "*PLASTIC: yield stress -4.5e+08 is not positive"),
        ("5.0e8, 0.05", "*PLASTIC: plastic strain 0.05 does not increase (previous 0.1)"),
        ("0, 5", "*RATE DEPENDENT: D = 0 is not positive"),
        ("1.098e9, -1.092e9", "*PLASTIC: B = -1.092e+09 is negative"),
    ]:
        expected = f"{bad}:{line_of(BAD, needle)}: {text}"
        check(expected in stderr, f"stderr lacks {expected!r}:\n{stderr}")
    check("5 error(s)" in stderr, f"expected exactly 5 errors:\n{stderr}")
    check(not (bad_dir / "plastic_bad.h5").exists(), "a deck with errors wrote results")
    print("check_plastic.py: check lists the yield stresses, run refused, 5 bad values reported")


if __name__ == "__main__":
    main()
