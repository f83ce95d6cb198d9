#!/usr/bin/env python3
"""Mutation fuzzer for the deck reader: mutates seed decks and runs `xpl check` on each.

Every mutated deck must end as a deck error (exit 1) or a clean data check (exit 0): a
signal, a sanitizer report, a run past the time limit, or any other exit code (an internal
error on bad input, exit 4, included) is a finding. Findings are written to the keep
directory as `finding-NNNN.inp` with the mutation and the output beside them, so that each
can be turned into a regression deck (tests/fuzz/regressions/).

The mutations are deck-aware (lines, keyword parameters, numbers, ids) plus raw byte damage,
driven by one seed so that a run is reproducible:

    fuzz_decks.py --xpl build/sanitize/apps/xpl --count 3000 --seed 1
    fuzz_decks.py --xpl build/release/apps/xpl --replay tests/fuzz/regressions

Exit code: 0 when no finding, 1 otherwise, 2 on a usage error.
"""

import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DEFAULT_SEEDS = [REPO / "examples", REPO / "tests" / "data" / "decks"]
ACCEPTED_EXIT = {0, 1}
SANITIZER_MARKS = ("AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer",
                   "runtime error:")

EXTREME_NUMBERS = ["0", "-0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf",
                   "2147483647", "2147483648", "-2147483649", "9223372036854775808",
                   "99999999999999999999999", "1e999", "0x10", "1,", "", "abc", "1.5.5",
                   "1e", "+", "-", "."]
EXTREME_PARAMETERS = ["", "=", "==", "ALL", "-1", "0", "1e-20", "1e20", "NAN", "YES",
                      "NO", "X" * 300, "\"", "'"]
RAW_BYTES = [b"\x00", b"\x1b[31m", b"\x07", b"\xff\xfe", b"\r", b"\t", b"**", b"*",
             b",,,,", b"\n*\n", b"\xc3\x28", b"\x7f"]
NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def seed_decks(paths):
    decks = []
    for p in paths:
        p = Path(p)
        decks.extend(sorted(p.rglob("*.inp")) if p.is_dir() else [p])
    return [d for d in decks if d.stat().st_size < 2_000_000]


def keyword_lines(decks):
    """Every keyword line of the seeds (the vocabulary of the insert mutation)."""
    vocabulary = set()
    for deck in decks:
        for line in deck.read_bytes().splitlines():
            if line.startswith(b"*") and not line.startswith(b"**"):
                vocabulary.add(line)
    return sorted(vocabulary)


def mutate_numbers(line, rng):
    matches = list(NUMBER.finditer(line))
    if not matches:
        return line
    m = rng.choice(matches)
    return line[:m.start()] + rng.choice(EXTREME_NUMBERS) + line[m.end():]


def mutate_parameter(line, rng):
    parts = line.split(",")
    if len(parts) < 2:
        return line + "," + rng.choice(["NAME", "ELSET", "TYPE", "INPUT"]) + "=" + \
            rng.choice(EXTREME_PARAMETERS)
    i = rng.randrange(1, len(parts))
    key = parts[i].split("=")[0]
    choice = rng.random()
    if choice < 0.4:
        parts[i] = key + "=" + rng.choice(EXTREME_PARAMETERS)
    elif choice < 0.6:
        parts[i] = key
    elif choice < 0.8:
        del parts[i]
    else:
        parts.append(parts[i])
    return ",".join(parts)


def mutate(text, rng, vocabulary, other_seeds):
    """One mutation of a deck (bytes in, bytes out) and its description."""
    lines = text.split(b"\n")
    kind = rng.randrange(11)
    i = rng.randrange(len(lines)) if lines else 0
    if kind == 0 and len(lines) > 1:
        del lines[i]
        return b"\n".join(lines), f"delete line {i + 1}"
    if kind == 1:
        lines.insert(i, lines[i])
        return b"\n".join(lines), f"duplicate line {i + 1}"
    if kind == 2 and len(lines) > 1:
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines), f"swap lines {i + 1} and {j + 1}"
    if kind in (3, 4):
        line = lines[i].decode("latin-1")
        lines[i] = mutate_numbers(line, rng).encode("latin-1")
        return b"\n".join(lines), f"number on line {i + 1}"
    if kind == 5:
        starts = [k for k, l in enumerate(lines) if l.startswith(b"*") and not l.startswith(b"**")]
        if starts:
            i = rng.choice(starts)
            lines[i] = mutate_parameter(lines[i].decode("latin-1"), rng).encode("latin-1")
            return b"\n".join(lines), f"parameter on line {i + 1}"
    if kind == 6 and vocabulary:
        lines.insert(i, rng.choice(vocabulary))
        return b"\n".join(lines), f"insert keyword at line {i + 1}"
    if kind == 7:
        cut = rng.randrange(len(text) + 1)
        return text[:cut], f"truncate at byte {cut}"
    if kind == 8:
        pos = rng.randrange(len(text) + 1)
        return text[:pos] + rng.choice(RAW_BYTES) + text[pos:], f"bytes at {pos}"
    if kind == 9 and other_seeds:
        other = rng.choice(other_seeds).read_bytes().split(b"\n")
        a = rng.randrange(len(other))
        chunk = other[a:a + rng.randrange(1, 40)]
        lines[i:i] = chunk
        return b"\n".join(lines), f"splice {len(chunk)} lines at {i + 1}"
    if kind == 10:
        # Repeat a data block: duplicate ids, sets and definitions.
        j = min(len(lines), i + rng.randrange(1, 30))
        lines[j:j] = lines[i:j]
        return b"\n".join(lines), f"repeat lines {i + 1}-{j}"
    return text + b"\n" + rng.choice(RAW_BYTES), "append bytes"


def run_check(xpl, deck_path, out_dir, timeout):
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE",
               ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:exitcode=86",
               UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87")
    start = time.monotonic()
    try:
        p = subprocess.run([str(xpl), "check", str(deck_path), "-o", str(out_dir)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                           timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as e:
        return "hang", None, (e.stderr or b"")[-4000:], time.monotonic() - start
    elapsed = time.monotonic() - start
    err = p.stderr[-8000:]
    text = err.decode("utf-8", "replace")
    if any(mark in text for mark in SANITIZER_MARKS):
        return "sanitizer", p.returncode, err, elapsed
    if p.returncode < 0:
        return "signal", p.returncode, err, elapsed
    if p.returncode not in ACCEPTED_EXIT:
        return f"exit {p.returncode}", p.returncode, err, elapsed
    return "ok", p.returncode, err, elapsed


def prepare_workspace(seed, work_root, index):
    """A private copy of the seed's directory (for its *INCLUDE files) and an output dir."""
    work = work_root / f"w{index}"
    if work.exists():
        shutil.rmtree(work)
    shutil.copytree(seed.parent, work / "deck", ignore=shutil.ignore_patterns("*.h5", "*.xdmf"))
    (work / "out").mkdir()
    return work / "deck" / seed.name, work / "out"


def fuzz_one(args, index, seeds, vocabulary, work_root):
    rng = random.Random(args.seed * 1_000_003 + index)
    seed = rng.choice(seeds)
    text = seed.read_bytes()
    steps = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        text, what = mutate(text, rng, vocabulary, seeds)
        steps.append(what)
    deck_path, out_dir = prepare_workspace(seed, work_root, index)
    deck_path.write_bytes(text)
    outcome, rc, err, elapsed = run_check(args.xpl, deck_path, out_dir, args.timeout)
    shutil.rmtree(deck_path.parent.parent, ignore_errors=True)
    return index, seed, steps, text, outcome, rc, err, elapsed


def keep_finding(keep, number, seed, steps, text, outcome, err):
    keep.mkdir(parents=True, exist_ok=True)
    base = keep / f"finding-{number:04d}"
    base.with_suffix(".inp").write_bytes(text)
    base.with_suffix(".txt").write_text(
        f"seed deck: {seed}\nmutations: {'; '.join(steps)}\noutcome: {outcome}\n\n" +
        err.decode("utf-8", "replace"))


def replay(args):
    decks = sorted(Path(args.replay).glob("*.inp"))
    findings = 0
    with tempfile.TemporaryDirectory() as tmp:
        for k, deck in enumerate(decks):
            out = Path(tmp) / f"o{k}"
            out.mkdir()
            outcome, rc, err, _ = run_check(args.xpl, deck, out, args.timeout)
            if outcome != "ok":
                findings += 1
                print(f"{deck.name}: {outcome}\n{err.decode('utf-8', 'replace')[-2000:]}")
    print(f"replayed {len(decks)} regression decks: {findings} findings")
    return 1 if findings else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--xpl", required=True, type=Path, help="the xpl program")
    parser.add_argument("--seeds", nargs="*", type=Path, default=DEFAULT_SEEDS,
                        help="seed decks or directories (default: examples, tests/data/decks)")
    parser.add_argument("--count", type=int, default=3000, help="mutated decks to run")
    parser.add_argument("--seed", type=int, default=1, help="random seed")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds per deck")
    parser.add_argument("--jobs", type=int, default=2, help="decks checked at once")
    parser.add_argument("--keep", type=Path, default=Path("fuzz-findings"),
                        help="directory for findings")
    parser.add_argument("--replay", type=Path, help="run the decks of a directory instead")
    args = parser.parse_args()
    if not args.xpl.exists():
        print(f"fuzz_decks: {args.xpl} does not exist", file=sys.stderr)
        return 2
    if args.replay:
        return replay(args)

    seeds = seed_decks(args.seeds)
    if not seeds:
        print("fuzz_decks: no seed decks", file=sys.stderr)
        return 2
    vocabulary = keyword_lines(seeds)
    outcomes = {}
    exit_codes = {}
    findings = 0
    slowest = 0.0
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="xpl-fuzz-") as tmp:
        work_root = Path(tmp)
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = [pool.submit(fuzz_one, args, i, seeds, vocabulary, work_root)
                       for i in range(args.count)]
            for future in concurrent.futures.as_completed(futures):
                index, seed, steps, text, outcome, rc, err, elapsed = future.result()
                outcomes[outcome] = outcomes.get(outcome, 0) + 1
                exit_codes[rc] = exit_codes.get(rc, 0) + 1
                slowest = max(slowest, elapsed)
                if outcome != "ok":
                    findings += 1
                    keep_finding(args.keep, index, seed, steps, text, outcome, err)
                    print(f"finding {index}: {outcome} from {seed.name} ({'; '.join(steps)})")
    wall = time.monotonic() - start
    codes = ", ".join(f"{k}: {v}" for k, v in sorted(exit_codes.items(), key=lambda kv: str(kv[0])))
    print(f"fuzz_decks: {args.count} mutated decks from {len(seeds)} seeds (seed {args.seed}) "
          f"in {wall:.0f} s, slowest {slowest:.1f} s; exit codes {{{codes}}}; "
          f"findings: {findings} "
          f"({', '.join(f'{k} {v}' for k, v in sorted(outcomes.items()) if k != 'ok') or 'none'})")
    if findings:
        print(f"fuzz_decks: findings kept in {args.keep}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
