#!/usr/bin/python3
"""Generated decks (tests/fuzz/generate_decks.py: two small hex blocks, a shell plate, a rigid
wall, plasticity, ties, mass scaling, contact inclusions and exclusions, one or two steps) on one
rank and on N, compared bitwise by scripts/dev/mpi_examples.py: the general case behind the
few decks of the other MPI tests. Decks of a few elements split over the ranks leave a rank
without an element of some kind (no shell, no plasticity), which the example decks never do.

Usage: mpi_generated.py XPL OUT_DIR [--first SEED] [--count K] [--ranks 2]
Exit 1 when a deck differs or ends differently on N ranks.
"""

import argparse
import pathlib
import random
import shutil
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tests" / "fuzz"))
from generate_decks import generated_deck  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("out")
    parser.add_argument("--first", type=int, default=1000, help="seed of the first deck")
    parser.add_argument("--count", type=int, default=24)
    parser.add_argument("--ranks", default="2")
    args = parser.parse_args()
    decks = pathlib.Path(args.out) / "decks"
    shutil.rmtree(decks, ignore_errors=True)
    decks.mkdir(parents=True)
    for seed in range(args.first, args.first + args.count):
        (decks / f"generated_{seed}.inp").write_text(generated_deck(random.Random(seed))[0])
    return subprocess.run([sys.executable, str(REPO / "scripts" / "dev" / "mpi_examples.py"),
                           args.xpl, str(pathlib.Path(args.out) / "runs"), "--ranks", args.ranks,
                           "--decks", str(decks)]).returncode


if __name__ == "__main__":
    sys.exit(main())
