#!/usr/bin/python3
"""Results do not depend on the number of OpenMP threads, bit for bit.

Usage: check_threads.py JOB DIR_1 DIR_2

DIR_1 and DIR_2 hold JOB.h5 from `xpl run --threads 1` and `--threads 2` of the same deck
(see run_xpl.py). The solver assembles forces race-free in element colours, so every frame's
U and every history series (ETOTAL in particular) must be identical, not merely close.
"""

import pathlib
import sys

import h5py
import numpy as np


def check(condition, message):
    if not condition:
        sys.exit(f"check_threads.py: FAILED: {message}")


def threads_used(directory):
    """The thread count printed in the run's summary line."""
    text = (directory / "stdout.txt").read_text()
    for line in text.splitlines():
        if line.startswith("xpl: element cycles per second:"):
            return int(line.rsplit(",", 1)[1].split()[0])
    check(False, f"no summary line in {directory / 'stdout.txt'}")
    return 0


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    job, one, two = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    check(threads_used(one) == 1, f"{one} was not run with 1 thread")
    check(threads_used(two) == 2, f"{two} was not run with 2 threads")
    with h5py.File(one / f"{job}.h5", "r") as a, h5py.File(two / f"{job}.h5", "r") as b:
        for f in (a, b):
            check(f.attrs["status"] == "completed", f"{f.filename}: status {f.attrs['status']!r}")
        frames_a, frames_b = sorted(a["frames"]), sorted(b["frames"])
        check(frames_a == frames_b, f"frames differ: {frames_a} vs {frames_b}")
        last = frames_a[-1]
        check(a["frames"][last].attrs["increment"] == b["frames"][last].attrs["increment"],
              "last frames are at different increments")
        u_a, u_b = a["frames"][last]["U"][()], b["frames"][last]["U"][()]
        check(np.any(u_a != 0.0), "last frame has no displacement")
        check(np.array_equal(u_a, u_b),
              f"U of frame {last} differs between 1 and 2 threads by up to "
              f"{np.abs(u_a - u_b).max():.3e}")
        for name in frames_a:
            for field in a["frames"][name]:
                check(np.array_equal(a["frames"][name][field][()], b["frames"][name][field][()]),
                      f"frame {name} {field} differs between 1 and 2 threads")
        e_a = a["history/step_1/energy/ETOTAL"][()]
        e_b = b["history/step_1/energy/ETOTAL"][()]
        check(e_a.shape == e_b.shape, f"ETOTAL shapes {e_a.shape} vs {e_b.shape}")
        check(np.array_equal(e_a, e_b),
              f"history ETOTAL differs between 1 and 2 threads by up to {np.abs(e_a - e_b).max():.3e}")
        check(np.array_equal(a["history/step_1/time"][()], b["history/step_1/time"][()]),
              "history time differs")

        def compare(name, obj):
            if isinstance(obj, h5py.Dataset):
                check(np.array_equal(obj[()], b["history"][name][()]),
                      f"history {name} differs between 1 and 2 threads")

        a["history"].visititems(compare)
    print(f"check_threads.py: {job}: {len(frames_a)} frames and all history identical "
          f"with 1 and 2 threads")


if __name__ == "__main__":
    main()
