#!/usr/bin/python3
"""How a run ends when it is not left alone (issue 15, items 1, 3 and 7).

Usage: check_job_end.py CASE XPL REPO OUT_DIR, CASE one of
  lock      a second run of the job in the same directory is refused at once (exit 5, the
            first run's pid named) and the first run's results stay whole
  stale     a JOB.lck left by a dead process is taken over, with a note in the .msg
  sigterm   SIGTERM mid-run: exit 143, status "interrupted" with time_reached, frames readable
  diskfull  a 1 MB tmpfs fills up: exit 4 (no signal), status "failed" with the cause, the
            frames written readable, no stray .tmp; skipped (exit 77) where mounting fails
The deck is a 10^3 block of benchmarks/make_block.py (~3 s) with field and history output.
"""

import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

import h5py

from summary_check import check_summary

SCHEMA = pathlib.Path(__file__).resolve().parents[2] / "apps" / "summary.schema.json"

SKIP = 77


def fail(message):
    sys.exit(f"FAIL: {message}")


def write_deck(repo, out):
    deck = out / "deck" / "block.inp"
    deck.parent.mkdir(parents=True)
    subprocess.run([sys.executable, str(repo / "benchmarks" / "make_block.py"), "-n", "10",
                    "--increments", "40000", "--out", str(deck)], check=True,
                   capture_output=True)
    text = deck.read_text().replace(
        "** No output requests: the benchmark times the element loop.",
        "*OUTPUT, FIELD, TIME INTERVAL=0.0005\n*NODE OUTPUT\nU, V\n"
        "*OUTPUT, HISTORY, TIME INTERVAL=0.0001\n*ENERGY OUTPUT")
    deck.write_text(text)
    return deck


def start(xpl, deck, results):
    return subprocess.Popen([xpl, "run", str(deck), "-o", str(results), "--threads", "1"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_frames(results, count, process, limit=60.0):
    """Waits until the running job's .sta shows progress and `count` frames may exist."""
    sta = results / "block.sta"
    t0 = time.monotonic()
    while time.monotonic() - t0 < limit:
        if process.poll() is not None:
            fail(f"the run ended before it could be disturbed: {process.communicate()}")
        if sta.exists() and sta.read_text().count("\n") > 12 + count:
            return
        time.sleep(0.05)
    fail("the run made no progress")


def read_frames(h5_path):
    """Status attributes and the number of frames, reading every U."""
    with h5py.File(h5_path, "r") as f:
        frames = f["frames"] if "frames" in f else {}
        for name in frames:
            frames[name]["U"][...]
        return dict(f.attrs), len(frames)


def case_lock(xpl, deck, out):
    results = out / "results"
    first = start(xpl, deck, results)
    wait_for_frames(results, 5, first)
    t0 = time.monotonic()
    second = subprocess.run([xpl, "run", str(deck), "-o", str(results), "--threads", "1"],
                            capture_output=True, text=True, timeout=60)
    seconds = time.monotonic() - t0
    if second.returncode != 5:
        fail(f"second run: exit {second.returncode}, expected 5: {second.stderr}")
    if seconds > 5.0:
        fail(f"second run took {seconds:.1f} s to refuse")
    if "already running" not in second.stderr or str(first.pid) not in second.stderr:
        fail(f"second run's message does not name process {first.pid}: {second.stderr!r}")
    if first.wait(timeout=120) != 0:
        fail(f"first run: exit {first.returncode}: {first.communicate()}")
    attrs, frames = read_frames(results / "block.h5")
    if attrs["status"] != "completed" or frames < 100:
        fail(f"first run's results: status {attrs['status']}, {frames} frames")
    if (results / "block.msg").read_text().count("MESSAGE FILE") != 1:
        fail("the second run wrote into the .msg")
    if (results / "block.lck").exists():
        fail("block.lck left behind")
    print(f"second run refused in {seconds:.2f} s; first run completed, {frames} frames")


def case_stale(xpl, deck, out):
    results = out / "results"
    results.mkdir()
    dead = subprocess.Popen(["true"])
    dead.wait()
    (results / "block.lck").write_text(f"{dead.pid}\n")
    run = subprocess.run([xpl, "run", str(deck), "-o", str(results), "--threads", "1",
                          "--quiet"], capture_output=True, text=True, timeout=120)
    if run.returncode != 0:
        fail(f"exit {run.returncode}: {run.stderr}")
    msg = (results / "block.msg").read_text()
    if f"process {dead.pid} (no longer running) was taken over" not in msg:
        fail("no note of the stale lock in the .msg")
    if (results / "block.lck").exists():
        fail("block.lck left behind")
    print(f"stale lock of process {dead.pid} taken over")


def case_sigterm(xpl, deck, out):
    results = out / "results"
    run = start(xpl, deck, results)
    wait_for_frames(results, 10, run)
    run.send_signal(signal.SIGTERM)
    _, stderr = run.communicate(timeout=60)
    if run.returncode != 128 + signal.SIGTERM:
        fail(f"exit {run.returncode}, expected 143: {stderr}")
    attrs, frames = read_frames(results / "block.h5")
    if attrs["status"] != "interrupted" or "SIGTERM" not in attrs["error"]:
        fail(f"status {attrs['status']!r}, error {attrs['error']!r}")
    reached = float(attrs["time_reached"])
    if not 0.0 < reached < 0.05 or frames < 2:
        fail(f"time_reached {reached}, {frames} frames")
    with h5py.File(results / "block.h5", "r") as f:
        last = max(f["frames"], key=lambda n: float(f["frames"][n].attrs["time"]))
        last_time = float(f["frames"][last].attrs["time"])
    if abs(last_time - reached) > 1e-12 * max(1.0, reached):
        fail(f"the last frame (t = {last_time}) is not at the time reached ({reached})")
    for log in ("block.sta", "block.msg"):
        text = (results / log).read_text()
        if "THE ANALYSIS HAS BEEN INTERRUPTED" not in text or "SIGTERM" not in text:
            fail(f"{log} does not say the run was interrupted")
    if (results / "block.lck").exists():
        fail("block.lck left behind")
    try:
        summary = check_summary(SCHEMA, results, "block", "interrupted")
    except AssertionError as e:
        fail(str(e))
    if "SIGTERM" not in summary["exit_reason"] or summary["simulated_time"] != reached:
        fail(f"summary: exit_reason {summary['exit_reason']!r}, time {summary['simulated_time']}")
    print(f"interrupted at t = {reached:.6g} s, {frames} frames readable, summary valid")


def case_diskfull(xpl, deck, out):
    mount = out / "tmpfs"
    mount.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(mount)],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        print(f"SKIP: cannot mount a tmpfs: {mounted.stderr.strip()}")
        sys.exit(SKIP)
    try:
        results = mount / "results"
        run = subprocess.run([xpl, "run", str(deck), "-o", str(results), "--threads", "1",
                              "--quiet"], capture_output=True, text=True, timeout=120)
        if run.returncode != 4:
            fail(f"exit {run.returncode}, expected 4 (a negative code is a signal): "
                 f"{run.stderr}")
        attrs, frames = read_frames(results / "block.h5")
        if attrs["status"] != "failed" or "disk full" not in attrs["error"]:
            fail(f"status {attrs['status']!r}, error {attrs['error']!r}")
        if frames < 1:
            fail("no frame readable")
        stray = [p.name for p in results.iterdir() if p.suffix in (".tmp", ".lck")]
        if stray:
            fail(f"stray files: {stray}")
        print(f"disk full: status failed, {frames} frames readable: {attrs['error']}")
    finally:
        subprocess.run(["umount", str(mount)], check=False)


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case, xpl, repo, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3]), \
        pathlib.Path(sys.argv[4])
    if case == "diskfull" and os.path.ismount(out / "tmpfs"):
        subprocess.run(["umount", str(out / "tmpfs")], check=False)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    deck = write_deck(repo, out)
    {"lock": case_lock, "stale": case_stale, "sigterm": case_sigterm,
     "diskfull": case_diskfull}[case](xpl, deck, out)


if __name__ == "__main__":
    main()
