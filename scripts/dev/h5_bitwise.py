#!/usr/bin/python3
"""Compare every dataset and attribute of every .h5 below two folders bitwise.

Usage: h5_bitwise.py A_DIR B_DIR   (exit 1 on any difference; xpl_version and the run summary
/summary, whose wall times, memory, threads and build differ from run to run, are not compared)
"""
import glob
import os
import sys

import h5py
import numpy as np


def objects(f):
    names = []
    f.visit(names.append)
    return [n for n in names if n != "summary" and not n.startswith("summary/")]


def main(a_root, b_root):
    differences = 0
    datasets = 0
    files = sorted(glob.glob(os.path.join(a_root, "**/*.h5"), recursive=True))
    for a_path in files:
        rel = os.path.relpath(a_path, a_root)
        b_path = os.path.join(b_root, rel)
        if not os.path.exists(b_path):
            print("missing:", rel)
            differences += 1
            continue
        with h5py.File(a_path, "r") as fa, h5py.File(b_path, "r") as fb:
            names_a, names_b = objects(fa), objects(fb)
            if names_a != names_b:
                print(rel, "objects differ:", sorted(set(names_a) ^ set(names_b)) or "order")
                differences += 1
            for name in ["/"] + [n for n in names_a if n in fb]:
                oa, ob = fa[name], fb[name]
                for key in sorted(set(oa.attrs) | set(ob.attrs)):
                    if key == "xpl_version":
                        continue
                    va, vb = oa.attrs.get(key), ob.attrs.get(key)
                    if not np.array_equal(np.asarray(va), np.asarray(vb)):
                        print(rel, name, "attribute", key, "differs:", va, vb)
                        differences += 1
                if isinstance(oa, h5py.Dataset):
                    datasets += 1
                    da, db = oa[()], ob[()]
                    if (da.dtype != db.dtype or np.shape(da) != np.shape(db)
                            or np.asarray(da).tobytes() != np.asarray(db).tobytes()):
                        print(rel, name, "differs")
                        differences += 1
    print(f"{len(files)} files, {datasets} datasets compared, {differences} differences")
    return 1 if differences else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
