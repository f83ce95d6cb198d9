#!/usr/bin/env python3
"""Bar on bar through contact over mesh refinement (issue 16, item 6): the contact-duration
error of the default penalty.

The deck is examples/contact's bar_bar (two steel bars 100 x 10 x 10 mm, nu = 0, bar A at
10 m/s onto bar B at rest, ALL EXTERIOR general contact, default penalty) with N x 4 x 4
C3D8R per bar, and history output at every increment. For each N it prints the contact
duration against 2L/c0 two ways: the window where the total normal force exceeds 1e-3 of
its peak (as tests/apps/check_contact.py measures it: it includes the spring's slow rise and
decay tails, and is quantised to the increment), and the width of the pulse at half its
plateau (crossings interpolated between increments), the interface stress (median of the
force above half its peak) against rho c0 v / 2, the bar velocities after contact, the
largest |ETOTAL drift| and ALLPW at the end, both / ALLKE(0), and the increment count.

Usage: bar_family.py XPL [--n 10 40 160] [--work DIR] [--scale-penalty S]
Needs h5py and numpy.
"""
import argparse, math, pathlib, subprocess, sys, tempfile

import h5py
import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "examples" / "contact"))
import make_contact_decks as decks  # noqa: E402


def write_deck(n, path, penalty):
    decks.BAR_ELEMENTS = (n, 4, 4)
    original = decks.output_requests

    def dense_history(deck, period, frames, history_nodes, history_rows=400):
        original(deck, period, frames, history_nodes, history_rows=40000)

    decks.output_requests = dense_history
    try:
        deck, _ = decks.bar_bar("general")
    finally:
        decks.output_requests = original
    text = deck.text()
    if penalty != 1.0:
        text = text.replace("*CONTACT INCLUSIONS, ALL EXTERIOR",
                            "*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                            f"*CONTACT CONTROLS ASSIGNMENT, TYPE=SCALE PENALTY\n, , {penalty:g}")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def half_width(t, force, level):
    """Time between the first up- and the last down-crossing of `level`, interpolated."""
    above = np.where(force > level)[0]
    i, j = above[0], above[-1]
    up = t[i - 1] + (level - force[i - 1]) / (force[i] - force[i - 1]) * (t[i] - t[i - 1])
    down = t[j] + (force[j] - level) / (force[j] - force[j + 1]) * (t[j + 1] - t[j])
    return down - up


def measure(xpl, n, work, penalty):
    d = work / f"bar_{n}"
    write_deck(n, d / "bar.inp", penalty)
    r = subprocess.run([str(pathlib.Path(xpl).resolve()), "run", "bar.inp", "--threads", "1", "--quiet"], cwd=d,
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        return {"n": n, "failed": r.stderr.strip()[-160:]}
    c0 = math.sqrt(decks.YOUNGS_MODULUS / decks.DENSITY)
    with h5py.File(d / "bar.h5", "r") as f:
        h = f["history/step_1"]
        t = h["time"][:]
        force = h["contact/ALL_EXTERIOR/CFN"][:]
        e = h["energy"]
        et, ke0, pw = e["ETOTAL"][:], e["ALLKE"][0], e["ALLPW"][:]
        frame = f["frames"][sorted(f["frames"].keys())[-1]]
        x0 = f["mesh/coordinates"][:, 0]
        v = frame["V"][:, 0]
    on = t[force > 1e-3 * force.max()]
    duration = on[-1] - on[0]
    exact = 2 * decks.BAR_LENGTH / c0
    plateau = np.median(force[force > 0.5 * force.max()])
    stress = plateau / decks.BAR_SIDE**2
    return {"n": n, "duration": duration / exact - 1,
            "half_width": half_width(t, force, 0.5 * plateau) / exact - 1,
            "stress": stress / (decks.DENSITY * c0 * decks.BAR_SPEED / 2) - 1,
            "v_a": v[x0 < decks.BAR_LENGTH + 0.5 * decks.BAR_GAP].mean(),
            "v_b": v[x0 > decks.BAR_LENGTH + 0.5 * decks.BAR_GAP].mean(),
            "drift": np.abs(et - et[0]).max() / ke0, "pw_end": pw[-1] / ke0}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("xpl")
    p.add_argument("--n", type=int, nargs="+", default=[10, 40, 160])
    p.add_argument("--work", type=pathlib.Path)
    p.add_argument("--scale-penalty", type=float, default=1.0)
    a = p.parse_args()
    work = a.work or pathlib.Path(tempfile.mkdtemp(prefix="bar_family_"))
    print("| elements per bar | duration error (1e-3 window) | half-plateau width error | "
          "stress error | v_A after | v_B after | max drift / KE0 | ALLPW end / KE0 |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in a.n:
        r = measure(a.xpl, n, work, a.scale_penalty)
        if "failed" in r:
            print(f"| {n} | failed: {r['failed']} | | | | | | |")
            continue
        print(f"| {n} | {100 * r['duration']:+.2f} % | {100 * r['half_width']:+.2f} % | "
              f"{100 * r['stress']:+.2f} % | "
              f"{r['v_a']:.3f} | {r['v_b']:.3f} | {r['drift']:.2e} | {r['pw_end']:+.1e} |",
              flush=True)


if __name__ == "__main__":
    main()
