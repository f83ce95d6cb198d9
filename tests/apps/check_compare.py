#!/usr/bin/python3
"""`xpl compare` (issue 16, item 2): what passes, what differs, what cannot be compared.

Usage: check_compare.py XPL MAKE_BAR WORK_DIR

A small bar deck (examples/make_bar.py, 20 x 2 x 2 elements, 30 us) is run several ways:
  identical      the same run twice                          -> exit 0 with rtol 0
  threads        1 and 2 threads                             -> exit 0 with rtol 0 (bitwise)
  perturbed      initial velocity 10.01 instead of 10 m/s    -> exit 1, names the datasets
  increments     fixed increments 1.3e-7 and 0.7e-7 s        -> the history compares on REF's
                 times (different row counts) and the energies agree within 2 %
  other mesh (21 elements long), a failed run, an interrupted, an unfinished ("running",
  as after SIGKILL) and a truncated file, an XDMF file, a missing file -> exit 2, message
  empty tables equal when both are empty; a table only one file has rows in differs.
"""

import json
import pathlib
import shutil
import subprocess
import sys

import h5py

PERIOD = "3e-05"


def fail(message):
    sys.exit(f"check_compare.py: FAILED: {message}")


def make_deck(make_bar, path, nx=20, velocity=-10.0, fixed=None):
    subprocess.run([sys.executable, make_bar, "--nx", str(nx), "--ny", "2", "--nz", "2",
                    "--period", PERIOD, "--velocity", str(velocity), "--out", str(path)],
                   check=True, capture_output=True)
    if fixed:
        text = path.read_text()
        old = f"*DYNAMIC, EXPLICIT\n, {PERIOD}\n"
        if text.count(old) != 1:
            fail(f"test bug: make_bar.py output lacks {old!r}")
        path.write_text(text.replace(
            old, f"*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n{fixed}, {PERIOD}\n"))
    return path


def run(xpl, deck, out, threads=1, expected=0):
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out), "--threads", str(threads),
                             "--quiet"], capture_output=True, text=True, timeout=120)
    if result.returncode != expected:
        fail(f"{deck.name}: exit {result.returncode}, expected {expected}: {result.stderr}")
    return out / f"{deck.stem}.h5"


def compare(xpl, ref, new, *options):
    result = subprocess.run([xpl, "compare", str(ref), str(new), *options], capture_output=True,
                            text=True, timeout=60)
    return result.returncode, result.stdout, result.stderr


def expect_unusable(xpl, ref, new, words, what):
    code, out, err = compare(xpl, ref, new)
    if code != 2 or not all(w in err for w in words):
        fail(f"{what}: exit {code}, stderr {err!r}; expected exit 2 and {words}")
    code, out, _ = compare(xpl, ref, new, "--json")
    report = json.loads(out)
    if code != 2 or report["passed"] or not all(w in report["unusable"] for w in words):
        fail(f"{what} --json: exit {code}, {report}")
    print(f"{what}: exit 2: {err.strip()}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, make_bar, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    bar = make_deck(make_bar, work / "bar.inp")
    ref = run(xpl, bar, work / "ref")
    again = run(xpl, bar, work / "again")
    two = run(xpl, bar, work / "two", threads=2)

    # Identical runs, and 1 against 2 threads, pass with no tolerance at all.
    for new, what in ((again, "identical"), (two, "1 vs 2 threads")):
        code, out, err = compare(xpl, ref, new, "--rtol", "0", "--atol", "0")
        if code != 0 or "PASSED" not in out:
            fail(f"{what}: exit {code}\n{out}{err}")
        print(f"{what}: exit 0, {out.splitlines()[-1]}")

    # A perturbed initial velocity differs; the report names the datasets.
    slow = run(xpl, make_deck(make_bar, work / "perturbed.inp", velocity=-10.01), work / "perturbed")
    code, out, _ = compare(xpl, ref, slow, "--rtol", "1e-6", "--atol", "1e-9")
    if code != 1 or "FAIL /history/step_1/energy/ALLKE" not in out or "FAIL /frames/" not in out:
        fail(f"perturbed: exit {code}\n{out}")
    code, out, _ = compare(xpl, ref, slow, "--rtol", "1e-6", "--atol", "1e-9", "--json")
    report = json.loads(out)
    failed = {d["name"]: d for d in report["datasets"] if not d["passed"]}
    ke = failed.get("/history/step_1/energy/ALLKE")
    if code != 1 or report["passed"] or ke is None or ke["worst"]["difference"] <= 0:
        fail(f"perturbed --json: exit {code}, failed {sorted(failed)}")
    # ALLKE scales with v²: (10.01/10)² - 1 = 2e-3 at t = 0, where the worst must be no larger.
    if not 0 < ke["worst"]["difference"] / ke["worst"]["reference"] < 3e-3:
        fail(f"perturbed: worst ALLKE difference {ke['worst']}")
    print(f"perturbed: exit 1, {len(failed)} datasets differ, ALLKE worst {ke['worst']}")

    # Runs with different increment counts: history compared on REF's times.
    coarse = run(xpl, make_deck(make_bar, work / "coarse.inp", fixed="1.3e-07"), work / "coarse")
    fine = run(xpl, make_deck(make_bar, work / "fine.inp", fixed="0.7e-07"), work / "fine")
    with h5py.File(coarse) as a, h5py.File(fine) as b:
        rows = len(a["history/step_1/time"])
        # The rows fall on the first increment after each 2e-7 s interval: other times.
        t_a, t_b = a["history/step_1/time"][:], b["history/step_1/time"][:]
        if len(t_a) == len(t_b) and (t_a == t_b).all():
            fail("test bug: the two increments give the same history times")
        increments = (a["frames"][sorted(a["frames"])[-1]].attrs["increment"],
                      b["frames"][sorted(b["frames"])[-1]].attrs["increment"])
    # 2 %: the energies of two stable central-difference runs differ by O(dt²) and by the
    # linear interpolation between history rows 2e-7 s apart; a 0.2 % velocity change is ~0.4 %.
    code, out, _ = compare(xpl, coarse, fine, "--history", "--rtol", "0.02", "--atol", "0.02",
                           "--json")
    report = json.loads(out)
    energies = [d for d in report["datasets"] if "/energy/" in d["name"]]
    if code not in (0, 1) or not energies or not all(d["passed"] for d in energies):
        fail(f"increments: exit {code}, energies {energies}")
    if any(d["compared"] != rows for d in energies) or any("/frames" in d["name"]
                                                            for d in report["datasets"]):
        fail(f"increments: not compared on REF's {rows} rows only: {report['datasets']}")
    print(f"different increment counts {increments}: energies pass on REF's {rows} times")

    # --fields / --frames all: only U, in every frame.
    code, out, _ = compare(xpl, ref, again, "--fields", "U", "--frames", "all", "--json")
    names = [d["name"] for d in json.loads(out)["datasets"]]
    with h5py.File(ref) as f:
        frames = len(f["frames"])
    if code != 0 or len(names) != frames or not all(n.endswith("/U") for n in names):
        fail(f"--fields U --frames all: exit {code}, {names}")

    # Empty tables are equal when both are empty; rows in one only differ.
    tables = []
    for name, rows in (("empty_a", 0), ("empty_b", 0), ("one_row", 1)):
        path = work / f"{name}.h5"
        shutil.copy(ref, path)
        with h5py.File(path, "a") as f:
            f.create_dataset("overclosure/step_1/adjusted/node", data=[7] * rows, dtype="i8",
                             shape=(rows,))
        tables.append(path)
    code, out, _ = compare(xpl, tables[0], tables[1])
    if code != 0 or "pass /overclosure/step_1/adjusted/node: empty in both" not in out:
        fail(f"empty tables: exit {code}\n{out}")
    code, out, _ = compare(xpl, tables[0], tables[2])
    if code != 1 or "FAIL /overclosure/step_1/adjusted/node: shape" not in out:
        fail(f"table with a row: exit {code}\n{out}")
    print("tables: empty = empty passes, 0 rows against 1 differs")

    # Unusable inputs: exit 2 and a message naming the file and the cause.
    other = run(xpl, make_deck(make_bar, work / "other.inp", nx=21), work / "other")
    expect_unusable(xpl, ref, other, [str(other), "another mesh"], "other mesh")
    unstable = run(xpl, make_deck(make_bar, work / "unstable.inp", fixed="1.5e-06"),
                   work / "unstable", expected=3)
    expect_unusable(xpl, ref, unstable, [str(unstable), "the run failed", "NaN/instability"],
                    "failed run")
    for status, words in (("interrupted", ["truncated", "interrupted"]),
                          ("running", ["did not finish", "running"])):
        path = work / f"{status}.h5"
        shutil.copy(ref, path)
        with h5py.File(path, "a") as f:
            f.attrs["status"] = status
        expect_unusable(xpl, ref, path, [str(path)] + words, f"status {status}")
    cut = work / "cut.h5"
    data = ref.read_bytes()
    cut.write_bytes(data[: len(data) // 2])
    expect_unusable(xpl, ref, cut, [str(cut), "truncated or damaged"], "truncated file")
    xdmf = ref.with_suffix(".xdmf")
    expect_unusable(xpl, xdmf, ref, [str(xdmf), "not an HDF5 file"], "XDMF file")
    missing = work / "missing.h5"
    expect_unusable(xpl, ref, missing, [str(missing), "does not exist"], "missing file")

    # Usage errors are exit 2 too.
    for words in (["compare", str(ref)], ["compare", str(ref), str(ref), "--rtol", "x"],
                  ["compare", str(ref), str(ref), "--frames", "first"]):
        result = subprocess.run([xpl, *words], capture_output=True, text=True, timeout=60)
        if result.returncode != 2 or "xpl compare:" not in result.stderr:
            fail(f"{words}: exit {result.returncode}, {result.stderr!r}")
    print("check_compare.py: all cases as expected")


if __name__ == "__main__":
    main()
