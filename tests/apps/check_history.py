#!/usr/bin/python3
"""`xpl history` (issue 16, item 3): the history of a result file as CSV.

Usage: check_history.py XPL RESULTS_DIR JOB

Runs `XPL history DIR/JOB.h5` (stdout), `--csv FILE` and `--step 1`, parses each with
Python's csv module and checks: the header is `time`, then one column per energy (ALLKE) and
per variable and node (RF1@N1000) of every /history dataset; every cell equals the .h5 value
bitwise (the CSV carries 17 significant digits). `--step 2` of a one-step job (saying there is
no step 2 and that the result has one step), a missing file and an unknown option exit 2.
"""

import csv
import io
import pathlib
import subprocess
import sys

import h5py


def fail(message):
    sys.exit(f"check_history.py: FAILED: {message}")


def expected_columns(h5_path):
    """{column name: values} from the .h5 file, the way the CSV names them."""
    columns = {}
    with h5py.File(h5_path, "r") as f:
        step = f["history/step_1"]
        columns["time"] = step["time"][:]

        def visit(name, obj):
            if not isinstance(obj, h5py.Dataset) or name == "time":
                return
            parts = name.split("/")
            data = obj[:]
            if "node_ids" in obj.attrs:
                for c, node in enumerate(obj.attrs["node_ids"]):
                    columns.setdefault(f"{parts[-1]}@N{node}", data[:, c] if data.ndim > 1
                                       else data)
            elif parts[0] == "energy":
                columns[parts[-1]] = data
            else:
                columns[f"{parts[-1]}@{parts[-2]}"] = data

        step.visititems(visit)
    return columns


def check_table(text, columns, what):
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    if header[0] != "time" or sorted(header) != sorted(columns):
        fail(f"{what}: header {header[:6]}... has {sorted(set(header) ^ set(columns))} extra or "
             f"missing")
    if len(body) != len(columns["time"]):
        fail(f"{what}: {len(body)} rows, the .h5 has {len(columns['time'])}")
    for k, name in enumerate(header):
        for r, row in enumerate(body):
            if float(row[k]) != float(columns[name][r]):
                fail(f"{what}: {name} row {r}: CSV {row[k]}, .h5 {columns[name][r]!r}")
    return len(header), len(body)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, directory, job = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
    h5_path = directory / f"{job}.h5"
    columns = expected_columns(h5_path)
    out = subprocess.run([xpl, "history", str(h5_path)], capture_output=True, text=True,
                         timeout=60)
    if out.returncode != 0:
        fail(f"exit {out.returncode}: {out.stderr}")
    width, rows = check_table(out.stdout, columns, "stdout")
    csv_path = directory / "history.csv"
    csv_path.unlink(missing_ok=True)
    result = subprocess.run([xpl, "history", str(h5_path), "--step", "1", "--csv", str(csv_path)],
                            capture_output=True, text=True, timeout=60)
    if result.returncode != 0 or result.stdout:
        fail(f"--csv: exit {result.returncode}, stdout {result.stdout[:80]!r}: {result.stderr}")
    check_table(csv_path.read_text(), columns, "--csv")
    # A step the result does not have is named as such, with the steps it has (issue 34).
    for words, needle in ((["--step", "2"], "no step 2: the result has one step (1)"),
                          (["--bogus"], "unknown option")):
        result = subprocess.run([xpl, "history", str(h5_path), *words], capture_output=True,
                                text=True, timeout=60)
        if result.returncode != 2 or needle not in result.stderr:
            fail(f"{words}: exit {result.returncode}, {result.stderr!r}")
    result = subprocess.run([xpl, "history", str(directory / "missing.h5")], capture_output=True,
                            text=True, timeout=60)
    if result.returncode != 2 or "does not exist" not in result.stderr:
        fail(f"missing file: exit {result.returncode}, {result.stderr!r}")
    print(f"check_history.py: {width} columns x {rows} rows equal to {h5_path} bitwise")


if __name__ == "__main__":
    main()
