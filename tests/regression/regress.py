#!/usr/bin/python3
"""Regression suite: every example deck against stored reference results (issue 16, item 5).

Usage:
  regress.py check XPL WORK NAME...   run the decks NAME (examples/**/NAME.inp) into WORK and
                                      compare each with references/NAME.h5 by `xpl compare`
                                      and with references/NAME.summary.txt; exit 1 if any
                                      differs
  regress.py bless XPL WORK [NAME...] run the decks (default: all of decks.txt) and rewrite
                                      their references; then review `git diff` of the
                                      summaries and commit the references with the change
                                      that moved them
  regress.py decks                    check that decks.txt lists every examples/**/*.inp once
                                      (`!NAME` lists one that is left out, with its reason)
                                      and that each deck that runs has a reference

A reference is a reduced copy of the run's JOB.h5, a few kB: the mesh ids and connectivity
(for the mesh check), the history of every step at REFERENCE_ROWS times (xpl compare
evaluates the new run on the reference's times, so fewer rows compare as well), and U and S
of the last frame; floats rounded to MANTISSA_BITS bits so that gzip packs them. Beside it,
NAME.summary.txt says in a few lines of text how the run ended (status, increments, end time,
the energy scale and the final ALLKE, ALLIE, ALLAE, ALLPD, ALLWK, ETOTAL, from
JOB.summary.json), so that a blessed change is reviewable in `git diff`; check compares the
run with it too, number by number at the same tolerances (an energy's FTOL is of its largest
|value| in the last step's history of NAME.h5, as xpl compare takes it; of the energy scale,
the watchdog's, for an energy the history does not hold), the status and units exactly.

Every run must also be a balanced completion (issue 33, SPEC R3): status "completed" in
JOB.summary.json and the energy watchdog's largest drift (energy_balance.relative_error,
checked at every increment from the first) finite and within the default limit.

Tolerances (passed to xpl compare):
  RTOL = 1e-6 relative and FTOL = 1e-6 of each dataset's largest |value|. On the machine that
  blessed them the results are bitwise equal. Another CPU (or compiler) changes the rounding
  of single operations (FMA contraction, vector width of reductions) by ~1e-16; in these short,
  stable explicit runs that grows roughly with the increment count, to an estimated ~1e-12
  after 10^4 increments (an estimate, not yet measured on a second CPU), so 1e-6 leaves about
  six orders of margin; a deck with a bifurcation (tube_crush buckles) may amplify round-off
  more and is the first to loosen, with a measurement, if another machine disagrees. A real change of the physics moves results by far more: a 0.1 % change of
  an initial velocity changes ALLKE by 2e-3 and U by ~1e-3, a different contact penalty the
  contact force history by percent. FTOL covers values near zero (stresses of 1e-3 Pa in a
  field of 1e8 Pa, displacements of fixed nodes), where a relative tolerance means nothing.
  The rounding of the stored references (2^-27 ≈ 7.5e-9 relative) is far below RTOL.
"""

import difflib
import json
import math
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]
REFERENCES = HERE / "references"
DECKS = HERE / "decks.txt"
RTOL = "1e-6"
FTOL = "1e-6"
REFERENCE_ROWS = 40   # history rows kept per step
MANTISSA_BITS = 26    # of float64's 52: relative rounding 2^-27 ≈ 7.5e-9
FIELDS = ("U", "S")   # of the last frame
# Decks that start from another deck's result: (deck, the deck whose .h5 it imports).
IMPORTS = {"import_target": "import_source"}
# Options a deck is run with (none needs any: blocks_deep, 30 % overlap pushed apart by the
# plain penalty, needed --energy-limit 30 while its drift showed as +27 %; it is 4.4 %).
EXTRA_ARGS = {}
ENERGY_LIMIT = 0.10  # xpl's default --energy-limit, as a fraction (no deck runs with another)
SUMMARY_ENERGIES = ("ALLKE", "ALLIE", "ALLAE", "ALLPD", "ALLWK", "ETOTAL")  # final values


def listed_names():
    return [line.split("#")[0].strip() for line in DECKS.read_text().splitlines()
            if line.split("#")[0].strip()]


def deck_names():
    """The decks that run; a line `!NAME  # reason` lists an example that is left out."""
    return [n for n in listed_names() if not n.startswith("!")]


def excluded_names():
    return [n[1:] for n in listed_names() if n.startswith("!")]


def deck_path(name):
    found = sorted(REPO.glob(f"examples/**/{name}.inp"))
    if len(found) != 1:
        sys.exit(f"regress.py: {len(found)} decks named {name}.inp under examples/")
    return found[0]


def run(xpl, name, work):
    out = work / name
    shutil.rmtree(out, ignore_errors=True)
    extra = list(EXTRA_ARGS.get(name, []))
    if name in IMPORTS:
        source = work / IMPORTS[name] / f"{IMPORTS[name]}.h5"
        if not source.exists():
            run(xpl, IMPORTS[name], work)
        extra += ["--import", str(source)]
    result = subprocess.run([xpl, "run", str(deck_path(name)), "-o", str(out), "--threads", "1",
                             "--quiet", *extra], capture_output=True, text=True, timeout=900)
    if result.returncode != 0:
        sys.exit(f"regress.py: {name}: xpl run exited {result.returncode}:\n{result.stderr}")
    check_completed(name, out / f"{name}.summary.json")
    return out / f"{name}.h5"


def check_completed(name, summary_path):
    """"Completed" means balanced (SPEC R3, issue 33): the status is completed and the energy
    watchdog's largest drift (checked at every increment from the first) is finite and within
    the limit the deck ran with."""
    summary = json.loads(summary_path.read_text())
    balance = summary["energy_balance"]
    drift = balance["relative_error"]
    problems = []
    if summary["status"] != "completed":
        problems.append(f"status {summary['status']!r} ({summary['exit_reason']})")
    if drift is None or not math.isfinite(drift) or not 0.0 <= drift <= ENERGY_LIMIT:
        problems.append(f"energy balance drift {drift} of the scale {balance['energy_scale']} J "
                        f"(the limit is {ENERGY_LIMIT})")
    if balance["energy_scale"] is None or not balance["energy_scale"] > 0.0:
        problems.append(f"energy scale {balance['energy_scale']}: the balance was not measured")
    if problems:
        sys.exit(f"regress.py: {name}: the run is not a balanced completion: "
                 + "; ".join(problems))


def summary_path(name):
    return REFERENCES / f"{name}.summary.txt"


def summary_text(name, summary_json):
    """The text summary of a run (references/NAME.summary.txt): one `key value [unit]` a line;
    10 significant digits, far below RTOL, so the text alone can be compared."""
    summary = json.loads(summary_json.read_text())
    units = summary["units"]
    rows = [("status", summary["status"], ""),
            ("increments", str(summary["increments"]), ""),
            ("end_time", f"{summary['simulated_time']:.9e}", units["time"]),
            ("energy_scale", f"{summary['energy_balance']['energy_scale']:.9e}",
             units["energy"])]
    rows += [(key, f"{summary['energies'][key]:.9e}", units["energy"])
             for key in SUMMARY_ENERGIES]
    lines = [f"# {name}: how the run ends (regress.py bless writes it; check compares the run",
             f"# with it at rtol {RTOL}, ftol {FTOL}: the tolerances of the comparison with "
             f"{name}.h5)"]
    lines += [f"{key:<13} {value} {unit}".rstrip() for key, value, unit in rows]
    return "\n".join(lines) + "\n"


def parse_summary(text):
    rows = {}
    for line in text.splitlines():
        if line.strip() and not line.startswith("#"):
            key, value, *unit = line.split()
            rows[key] = (value, " ".join(unit))
    return rows


def energy_scales(ref):
    """The largest |value| of each SUMMARY_ENERGIES dataset of the last step's history in the
    reference ref (what xpl compare's FTOL is a fraction of); energies it does not hold are
    left out."""
    with h5py.File(ref, "r") as f:
        steps = sorted(f.get("history", {}), key=lambda s: int(s.rsplit("_", 1)[-1]))
        energy = f["history"][steps[-1]].get("energy", {}) if steps else {}
        return {key: float(np.nanmax(np.abs(energy[key][:]), initial=0.0))
                for key in SUMMARY_ENERGIES if key in energy}


def summary_differences(ref_text, new_text, scales):
    """What differs between two summary texts: a number by more than RTOL of itself plus FTOL
    of its scale (scales[key] for an energy, else the energy scale of the text for an energy,
    else the number itself); status and units exactly."""
    ref, new = parse_summary(ref_text), parse_summary(new_text)
    problems = [f"{key} only in the {'reference' if key in ref else 'run'}"
                for key in sorted(set(ref) ^ set(new))]
    energy_scale = abs(float(ref["energy_scale"][0])) if "energy_scale" in ref else 0.0
    for key in [k for k in ref if k in new]:
        (ref_value, ref_unit), (new_value, new_unit) = ref[key], new[key]
        if ref_unit != new_unit:
            problems.append(f"{key}: unit {new_unit!r}, the reference has {ref_unit!r}")
        if key == "status":
            if ref_value != new_value:
                problems.append(f"status {new_value}, the reference has {ref_value}")
            continue
        a, b = float(ref_value), float(new_value)
        if key in SUMMARY_ENERGIES:
            scale = scales.get(key, energy_scale)
        else:
            scale = abs(a)
        floor = float(FTOL) * scale
        if not abs(b - a) <= float(RTOL) * abs(a) + floor:
            problems.append(f"{key} {new_value}, the reference has {ref_value}")
    return problems


def rounded(data):
    """float64 data with the low mantissa bits cleared (round to nearest), ints unchanged."""
    data = np.asarray(data)
    if data.dtype != np.float64:
        return data
    bits = data.copy().view(np.uint64)
    drop = np.uint64(52 - MANTISSA_BITS)
    half = np.uint64(1) << (drop - np.uint64(1))
    finite = np.isfinite(data)
    bits[finite] = ((bits[finite] + half) >> drop) << drop
    return bits.view(np.float64)


def copy_dataset(dst, path, data, attrs=(), exact=False):
    data = np.asarray(data) if exact else rounded(data)
    if data.size * data.itemsize < 1024:  # small: contiguous, no filter overhead
        dst.create_dataset(path, data=data)
    else:  # one chunk (the newest format indexes it without a B-tree), gzip after shuffle
        dst.create_dataset(path, data=data, chunks=data.shape, compression="gzip",
                           compression_opts=9, shuffle=True)
    for key, value in attrs:
        dst[path].attrs[key] = value


def reduce(src_path, dst_path):
    """Writes the reference of a run: mesh ids, history at REFERENCE_ROWS times, U/S last frame."""
    tmp = dst_path.with_suffix(".tmp")
    with h5py.File(src_path, "r") as src, h5py.File(tmp, "w", libver="latest") as dst:
        for key in ("status", "job", "xpl_version", "heading", "error"):
            dst.attrs[key] = src.attrs[key]
        mesh = src["mesh"]
        for name in ("node_ids", "element_ids"):
            copy_dataset(dst, f"mesh/{name}", mesh[name][:])
        for element_type in ("C3D8R", "S4R"):
            if element_type in mesh:
                for name in ("element_ids", "connectivity"):
                    copy_dataset(dst, f"mesh/{element_type}/{name}",
                                 mesh[element_type][name][:])
        for step_name, step in src.get("history", {}).items():
            rows = len(step["time"])
            keep = np.unique(np.linspace(0, rows - 1, min(rows, REFERENCE_ROWS)).round()
                             .astype(int))

            def visit(name, obj, step_name=step_name, keep=keep):
                if isinstance(obj, h5py.Dataset):  # times exact: NEW is interpolated on them
                    copy_dataset(dst, f"history/{step_name}/{name}", obj[:][keep],
                                 obj.attrs.items(), exact=name == "time")

            step.visititems(visit)
        frames = sorted(src.get("frames", {}))
        if frames:
            last = src["frames"][frames[-1]]
            group = dst.create_group(f"frames/{frames[-1]}")
            for key, value in last.attrs.items():
                group.attrs[key] = value
            for name in FIELDS:
                if name in last:
                    copy_dataset(dst, f"frames/{frames[-1]}/{name}", last[name][:])
    tmp.replace(dst_path)


def reference_fields(ref):
    """The FIELDS the reference's last frame holds (a deck that asks only for U has no S):
    xpl compare refuses a field REF does not have, so that a typo cannot pass as '0 differ'."""
    with h5py.File(ref, "r") as f:
        frames = sorted(f.get("frames", {}))
        held = set(f["frames"][frames[-1]]) if frames else set()
    return [name for name in FIELDS if name in held]


def check_summary(name, work):
    """Compares the run's summary with references/NAME.summary.txt; prints what differs (and
    the text diff a bless would make). Writes the run's text as WORK/NAME/NAME.summary.txt."""
    new_text = summary_text(name, work / name / f"{name}.summary.json")
    (work / name / f"{name}.summary.txt").write_text(new_text)
    if not summary_path(name).exists():
        print(f"regress.py: {name}: no summary {summary_path(name)}; bless it "
              f"(docs/dev/testing.md)")
        return False
    ref_text = summary_path(name).read_text()
    problems = summary_differences(ref_text, new_text,
                                   energy_scales(REFERENCES / f"{name}.h5"))
    if problems:
        print(f"regress.py: {name}: the run differs from {summary_path(name)}: "
              + "; ".join(problems))
        print("".join(difflib.unified_diff(ref_text.splitlines(True), new_text.splitlines(True),
                                           f"{summary_path(name)} (reference)",
                                           f"{work / name / name}.summary.txt (run)")))
    return not problems


def check(xpl, work, names):
    failed = []
    for name in names:
        new = run(xpl, name, work)
        ref = REFERENCES / f"{name}.h5"
        if not ref.exists():
            print(f"regress.py: {name}: no reference {ref}; bless it (docs/dev/testing.md)")
            failed.append(name)
            continue
        summary_ok = check_summary(name, work)
        fields = reference_fields(ref)
        result = subprocess.run([xpl, "compare", str(ref), str(new), "--history"] +
                                (["--fields", ",".join(fields)] if fields else []) +
                                ["--rtol", RTOL, "--ftol", FTOL],
                                capture_output=True, text=True, timeout=120)
        if result.returncode != 0:
            print(result.stdout + result.stderr)
            failed.append(name)
        elif not summary_ok:
            failed.append(name)
        else:
            print(f"regress.py: {name}: {result.stdout.strip().splitlines()[-1]}")
    if failed:
        print(f"regress.py: {len(failed)} deck(s) differ from their reference: "
              f"{' '.join(failed)}.\nIf the change is intended, bless them:\n"
              f"  /usr/bin/python3 tests/regression/regress.py bless {xpl} {work} "
              f"{' '.join(failed)}")
        return 1
    return 0


def bless(xpl, work, names):
    REFERENCES.mkdir(exist_ok=True)
    for name in names:
        new = run(xpl, name, work)
        reduce(new, REFERENCES / f"{name}.h5")
        summary_path(name).write_text(summary_text(name, new.with_suffix(".summary.json")))
        size = (REFERENCES / f"{name}.h5").stat().st_size
        print(f"regress.py: blessed {name} ({size / 1024:.0f} kB)")
    return 0


def decks():
    names = deck_names() + excluded_names()
    on_disk = sorted(p.stem for p in REPO.glob("examples/**/*.inp"))
    problems = []
    if sorted(names) != on_disk:
        problems.append(f"decks.txt and examples/ differ: {sorted(set(names) ^ set(on_disk))}")
    if len(set(names)) != len(names):
        problems.append("decks.txt lists a deck twice")
    problems += [f"no reference for {n}" for n in deck_names()
                 if not (REFERENCES / f"{n}.h5").exists()]
    problems += [f"no summary for {n}" for n in deck_names() if not summary_path(n).exists()]
    total = sum(p.stat().st_size for p in REFERENCES.glob("*.h5"))
    for problem in problems:
        print(f"regress.py: {problem}")
    print(f"regress.py: {len(names)} decks, references {total / 1024:.0f} kB in all")
    return 1 if problems else 0


def main():
    args = sys.argv[1:]
    if args[:1] == ["decks"] and len(args) == 1:
        return decks()
    if len(args) < 3 and not (args[:1] == ["bless"] and len(args) == 3):
        sys.exit(__doc__)
    command, xpl, work = args[0], args[1], pathlib.Path(args[2])
    names = args[3:] or deck_names()
    work.mkdir(parents=True, exist_ok=True)
    if command == "check":
        return check(xpl, work, names)
    if command == "bless":
        return bless(xpl, work, names)
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
