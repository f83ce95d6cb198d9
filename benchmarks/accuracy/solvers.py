"""Running xpl and CalculiX on one deck and reading what each writes (issue 16, item 1).

Both runners return a dict with the wall time measured around the child process (the same
clock for both solvers, start-up included), the CPU time of the child (user + sys from
wait4, which the load of other jobs on a shared machine does not inflate the way it inflates
wall time), the increment count and the solver's own output, read into numpy arrays:

  xpl:      JOB.summary.json (increments, its own elapsed time, energy balance) and the
            history of JOB.h5 (h5py)
  CalculiX: the .dat file of *NODE PRINT / *EL PRINT / *CONTACT PRINT blocks, one block
            per print request and increment; the increment count from the .sta file
"""
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import time

import numpy as np


def _run(cmd, cwd, env, log):
    """Run cmd; return (exit code, wall s, cpu s of the child: user + sys)."""
    start = time.perf_counter()
    with open(log, "w") as out:
        process = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    return process.returncode, wall, usage.ru_utime + usage.ru_stime


def run_xpl(xpl, deck, threads, work):
    """Run `xpl run DECK -o WORK --threads N --quiet`."""
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    job = pathlib.Path(deck).stem
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    command = [str(xpl), "run", str(pathlib.Path(deck).resolve()), "-o", str(work.resolve()),
               "--threads", str(threads), "--quiet"]
    code, wall, cpu = _run(command, work, env, work / f"{job}.stdout")
    summary_path = work / f"{job}.summary.json"
    summary = json.loads(summary_path.read_text()) if summary_path.exists() else {}
    if code != 0 or summary.get("status") != "completed":
        raise RuntimeError(f"xpl failed on {deck} (exit {code}, status "
                           f"{summary.get('status')}: {summary.get('exit_reason')}); see {work}")
    return {"solver": "xpl", "threads": threads, "wall": wall, "cpu": cpu,
            "increments": summary["increments"], "summary": summary,
            "h5": work / f"{job}.h5"}


def xpl_history(h5_path, step=1):
    """{'time': t, 'energy/ALLKE': ..., 'node/NSET/RF1': (nt x n), 'contact/PAIR/CFN': ...}."""
    import h5py
    out = {}
    with h5py.File(h5_path, "r") as f:
        group = f[f"history/step_{step}"]

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
        group.visititems(visit)
    return out


def xpl_last_frame(h5_path, field):
    """(node ids or element ids, values) of `field` in the last frame."""
    import h5py
    with h5py.File(h5_path, "r") as f:
        names = sorted(f["frames"].keys())
        data = f[f"frames/{names[-1]}/{field}"][()]
        ids = f["mesh/node_ids"][()] if data.shape[0] == f["mesh/node_ids"].shape[0] \
            else f["mesh/element_ids"][()]
    return ids, data


def find_ccx():
    return shutil.which("ccx") or shutil.which("ccx_2.20")


def ccx_version(ccx):
    text = subprocess.run([ccx, "-v"], capture_output=True, text=True).stdout
    match = re.search(r"Version\s+(\S+)", text)
    return match.group(1) if match else "unknown"


def run_ccx(ccx, deck, threads, work):
    """Run `ccx -i JOB` in WORK with OMP_NUM_THREADS=threads (a copy of the deck there)."""
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    job = pathlib.Path(deck).stem
    if pathlib.Path(deck).resolve() != (work / f"{job}.inp").resolve():
        shutil.copy(deck, work / f"{job}.inp")
    env = dict(os.environ)
    for key in ("CCX_NPROC_STIFFNESS", "CCX_NPROC_RESULTS", "NUMBER_OF_PROCESSORS"):
        env.pop(key, None)
    env["OMP_NUM_THREADS"] = str(threads)
    code, wall, cpu = _run([ccx, "-i", job], work, env, work / f"{job}.stdout")
    text = (work / f"{job}.stdout").read_text(errors="replace")
    if code != 0 or "*ERROR" in text:
        lines = [line for line in text.splitlines() if "ERROR" in line]
        raise RuntimeError(f"CalculiX failed on {deck} (exit {code}): {lines[:3]}; see {work}")
    dat = parse_dat(work / f"{job}.dat")
    match = re.search(r"SELECTED time increment:\s*(\S+)", text)
    return {"solver": "calculix", "threads": threads, "wall": wall, "cpu": cpu,
            "increments": ccx_increments(dat), "dat": dat,
            "dt": float(match.group(1)) if match else math.nan}


def ccx_increments(dat):
    """CalculiX's explicit runs write no increment lines to .sta or .cvg: the decks print
    to .dat at every increment (FREQUENCY=1), so the increments are the distinct print
    times (the step's last increment is printed once)."""
    times = set()
    for key, value in dat.items():
        if len(key) == 2:
            times.update(value[0].tolist())
    return len(times)


_FORTRAN_EXPONENT = re.compile(r"(\d)([+-]\d{3})$")


def number(text):
    """A .dat number; Fortran drops the E of three-digit exponents (-8.999678-100)."""
    try:
        return float(text)
    except ValueError:
        return float(_FORTRAN_EXPONENT.sub(r"\1E\2", text))


_HEADER = re.compile(r"^\s*(.+?) for set (\S+) and time\s+(\S+)\s*$")
_CSTR = re.compile(r"^\s*contact stress \(slave node,press,tang1,tang2\) for all contact "
                   r"elements and time\s*(\S+)")


def parse_dat(dat_path):
    """The .dat print blocks as {(what, set): (times, values)}.

    what is the block's title ('total force (fx,fy,fz)', 'velocities (vx,vy,vz)', 'total
    internal energy', ...); values is (n_times x rows x columns) without the node or element
    number column for per-node blocks (the ids are in {(what, set, 'ids'): ids}).
    *CONTACT PRINT CSTR gives {('contact stress', 'all'): (times, [{slave node: pressure}])}
    (CF totals print as zero in CalculiX 2.20's explicit runs).
    """
    blocks = {}
    cstress = ([], [])
    lines = pathlib.Path(dat_path).read_text(errors="replace").splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        match = _HEADER.match(line)
        if match:
            what, nset, t = match.group(1).strip(), match.group(2), float(match.group(3))
            rows = []
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            while i < len(lines) and lines[i].strip() and not _HEADER.match(lines[i]):
                rows.append([number(v) for v in lines[i].split()])
                i += 1
            key = (what, nset)
            times, values = blocks.setdefault(key, ([], []))
            if rows and len(rows[0]) > 1 and len(rows) >= 1 and rows[0][0] == int(rows[0][0]) \
                    and not what.startswith("total"):
                blocks[(what, nset, "ids")] = [int(r[0]) for r in rows]
                rows = [r[1:] for r in rows]
            times.append(t)
            values.append(rows)
            continue
        cstr = _CSTR.match(line)
        if cstr:
            pressures = {}
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            while i < len(lines) and len(lines[i].split()) == 4:
                fields = lines[i].split()
                pressures[int(fields[0])] = number(fields[1])
                i += 1
            cstress[0].append(float(cstr.group(1)))
            cstress[1].append(pressures)
            continue
        i += 1
    out = {}
    if cstress[0]:
        out[("contact stress", "all")] = (np.array(cstress[0]), cstress[1])
    for key, value in blocks.items():
        if len(key) == 3:
            out[key] = value
            continue
        times, values = value
        out[key] = (np.array(times), np.array(values, dtype=float))
    return out
