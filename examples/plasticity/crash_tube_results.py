#!/usr/bin/python3
"""The measured quantities of a crash tube run (examples/plasticity/crash_tube.inp or a deck
of make_crash_tube.py) from its JOB.h5.

Usage: crash_tube_results.py JOB.h5   (prints them; tests and benchmarks import measure())

- crush: -U3 of the driven end (TOP_REF) over the history; crush force: -RF3 of TOP_REF;
- mean crush force over the middle of the stroke (crush between MEAN_WINDOW of the final
  crush, make_crash_tube.py), the mean of the history rows there (evenly spaced in time, and
  the crush speed is constant after the ramp, so this is the mean over the crush distance);
  compared with Abramowicz-Jones 13.06 sigma0 t^(5/3) C^(1/3);
- the peak force and the energies at the end; the energy balance: the largest |ETOTAL| over
  the run against the external work ALLWK at the end;
- folds: in the last frame, along the middle line of each wall, the outward deviation of the
  current position from the wall's plane; a lobe is a local outward maximum above t (one
  wall thickness). The lobes per wall are reported (progressive folding stacks them along
  the crushed part, from the trigger downwards).
Needs h5py and numpy (Debian's /usr/bin/python3 has them).
"""

import pathlib
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import make_crash_tube as tube  # noqa: E402


def lobes(reference, current):
    """Outward lobes per wall (4 numbers) along the wall middle lines of the last frame."""
    half = tube.SIDE / 2.0
    counts = []
    for axis, sign in ((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)):
        other = 1 - axis
        line = (np.isclose(reference[:, axis], sign * half, atol=0.02 * tube.SIDE)
                & np.isclose(reference[:, other], 0.0, atol=1e-9))
        order = np.argsort(reference[line, 2])
        w = sign * current[line, axis][order] - half
        peaks = [k for k in range(1, len(w) - 1)
                 if w[k] > tube.THICKNESS and w[k] >= w[k - 1] and w[k] > w[k + 1]]
        counts.append(len(peaks))
    return counts


def measure(path):
    with h5py.File(path, "r") as f:
        history = f["history/step_1"]
        crush = -history["node/TOP_REF/U3"][()].ravel()
        force = -history["node/TOP_REF/RF3"][()].ravel()
        energy = history["energy"]
        etotal = energy["ETOTAL"][()]
        low, high = (w * crush[-1] for w in tube.MEAN_WINDOW)
        window = (crush >= low) & (crush <= high)
        reference = f["mesh/coordinates"][()]
        frames = sorted(f["frames"])
        last = f["frames"][frames[-1]]
        current = reference + last["U"][()]
        shells = f["mesh/element_ids"].shape[0]
        result = {
            "elements": int(shells),
            "time": float(last.attrs["time"]),
            "crush": float(crush[-1]),
            "window": (float(low), float(high)),
            "mean_force": float(force[window].mean()),
            "peak_force": float(force.max()),
            "reference_force": tube.mean_crush_force(),
            "ALLWK": float(energy["ALLWK"][-1]),
            "ALLIE": float(energy["ALLIE"][-1]),
            "ALLPD": float(energy["ALLPD"][-1]),
            "ALLAE": float(energy["ALLAE"][-1]),
            "ALLSE": float(energy["ALLSE"][-1]),
            "ALLKE": float(energy["ALLKE"][-1]),
            "ALLPW": float(energy["ALLPW"][-1]) if "ALLPW" in energy else 0.0,
            "ALLPW_min": float(energy["ALLPW"][()].min()) if "ALLPW" in energy else 0.0,
            "balance": float(np.abs(etotal).max()),
            "lobes": lobes(reference, current),
            "peeq_max": float(last["PEEQ"][()].max()),
        }
    return result


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    r = measure(sys.argv[1])
    ratio = r["mean_force"] / r["reference_force"]
    print(f"{r['elements']} S4R, t = {r['time'] * 1e3:.3f} ms, crush {r['crush'] * 1e3:.2f} mm")
    print(f"mean crush force over {r['window'][0] * 1e3:.1f}-{r['window'][1] * 1e3:.1f} mm: "
          f"{r['mean_force'] / 1e3:.2f} kN = {ratio:.3f} x Abramowicz-Jones "
          f"{r['reference_force'] / 1e3:.2f} kN; peak {r['peak_force'] / 1e3:.2f} kN")
    print(f"ALLWK {r['ALLWK']:.5g} J, ALLIE {r['ALLIE']:.5g} (ALLPD {r['ALLPD']:.5g}, ALLSE "
          f"{r['ALLSE']:.4g}, ALLAE {r['ALLAE']:.4g}), ALLKE {r['ALLKE']:.4g}, ALLPW "
          f"{r['ALLPW']:.4g} (lowest {r['ALLPW_min']:.4g}); largest |ETOTAL| {r['balance']:.4g} J = "
          f"{100 * r['balance'] / r['ALLWK']:.3f} % of ALLWK")
    print(f"outward lobes per wall (+x, -x, +y, -y): {r['lobes']}; largest PEEQ "
          f"{r['peeq_max']:.3g}")


if __name__ == "__main__":
    main()
