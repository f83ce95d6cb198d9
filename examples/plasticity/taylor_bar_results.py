#!/usr/bin/python3
"""The measured quantities of a Taylor bar run (examples/plasticity/taylor_bar.inp or a deck
of make_taylor_bar.py) from its JOB.h5.

Usage: taylor_bar_results.py JOB.h5   (prints them; tests and benchmarks import measure())

- final length: the largest current z of the far end (nodes with reference z = L0);
- impact-face radius: the largest current distance from the axis of the nodes on the wall
  (reference z = 0), i.e. of the foot's rim;
- lowest z of any node (a node below the wall would have rolled over through it);
- the energies at the end: ALLIE, ALLPD, ALLAE (hourglass), ALLKE; the largest
  |ETOTAL - ETOTAL(0)| over the run, and the initial kinetic energy ALLKE(0).
Needs h5py and numpy (Debian's /usr/bin/python3 has them).
"""

import sys

import h5py
import numpy as np


def measure(path):
    with h5py.File(path, "r") as f:
        reference = f["mesh/coordinates"][()]
        frames = sorted(f["frames"])
        last = f["frames"][frames[-1]]
        current = reference + last["U"][()]
        z0 = reference[:, 2]
        length0 = z0.max()
        top = np.isclose(z0, length0, rtol=0.0, atol=1e-9 * length0)
        wall = np.isclose(z0, 0.0, rtol=0.0, atol=1e-9 * length0)
        radius = np.hypot(current[wall, 0], current[wall, 1]).max()
        energy = f["history/step_1/energy"]
        etotal = energy["ETOTAL"][()]
        result = {
            "time": float(last.attrs["time"]),
            "length": float(current[top, 2].max()),
            "radius": float(radius),
            "lowest_z": float(current[:, 2].min()),
            "peeq_max": float(last["PEEQ"][()].max()) if "PEEQ" in last else float("nan"),
            "ALLKE0": float(energy["ALLKE"][0]),
            "ALLKE": float(energy["ALLKE"][-1]),
            "ALLIE": float(energy["ALLIE"][-1]),
            "ALLPD": float(energy["ALLPD"][-1]),
            "ALLAE": float(energy["ALLAE"][-1]),
            "ALLSE": float(energy["ALLSE"][-1]),
            "ALLVD": float(energy["ALLVD"][-1]),
            "drift": float(np.abs(etotal - etotal[0]).max()),
            "elements": int(f["mesh/element_ids"].shape[0]),
        }
    return result


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    r = measure(sys.argv[1])
    print(f"t = {r['time'] * 1e6:.2f} us, {r['elements']} elements")
    print(f"final length {r['length'] * 1e3:.4f} mm (Wilkins-Guinan 21.45), "
          f"impact-face radius {r['radius'] * 1e3:.4f} mm (7.15)")
    print(f"lowest z {r['lowest_z'] * 1e3:.4g} mm, largest PEEQ {r['peeq_max']:.4g}")
    print(f"ALLKE(0) {r['ALLKE0']:.5g} J; at the end ALLKE {r['ALLKE']:.4g}, ALLIE "
          f"{r['ALLIE']:.5g} (ALLPD {r['ALLPD']:.5g}, ALLSE {r['ALLSE']:.4g}, ALLAE "
          f"{r['ALLAE']:.4g} = {100 * r['ALLAE'] / r['ALLIE']:.2f} % of ALLIE), ALLVD "
          f"{r['ALLVD']:.4g}; ETOTAL drift {100 * r['drift'] / r['ALLKE0']:.3f} % of ALLKE(0)")


if __name__ == "__main__":
    main()
