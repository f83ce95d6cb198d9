#!/usr/bin/env python3
"""Size limits of the source folders (issue 36): no file over 450 lines, no function over 120.

    check_sizes.py SOURCE_DIR [--allow FILE] [--list]

Scans the C++ sources (.cpp, .hpp) of solver/, elements/, contact/ and io/ under SOURCE_DIR.
A file's size is its line count; a function's size is the lines from the first line of its
signature to its closing brace. Function bodies are found by brace matching after comments,
string and character literals and preprocessor lines are blanked out: a brace block at
namespace or class scope whose header (the text since the previous ';', '{' or '}' at that
scope) has a parenthesis is a function (or a lambda bound to a name); class, struct, union,
namespace and extern blocks are scopes searched in turn; enum bodies and brace initialisers
are skipped. Lambdas and local classes inside a function count towards that function.

The allow-list names the offenders that are being shrunk, one a line:

    file      PATH           LINES  -- who shrinks it
    function  PATH:NAME      LINES  -- who shrinks it

An offender fails the check unless it is listed, and a listed one fails if it has grown past
the listed LINES, so the limits cannot grow back while the renovation finishes. A listed
offender that is now within the limit is reported as stale (drop its line) but does not fail.
Exit status 0 when every offender is allowed, 1 otherwise, 2 on bad usage or allow-list.
--list prints every offender with its size, in allow-list form.
"""

import argparse
import pathlib
import re
import sys

FILE_LIMIT = 450
FUNCTION_LIMIT = 120
FOLDERS = ("solver", "elements", "contact", "io")
SUFFIXES = (".cpp", ".hpp")


def blank_out(text):
    """Comments, literals and preprocessor lines replaced by spaces; newlines kept."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":
            # Preprocessor line, with its continuations.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        line_start = False
        if c == "\n":
            out.append(c)
            line_start = True
            i += 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not text[i - 1].isalnum()):
            open_paren = text.find("(", i + 2)
            delim = text[i + 2 : open_paren]
            end = text.find(")" + delim + '"', open_paren)
            end = n if end < 0 else end + len(delim) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
        elif c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()) and text[i - 1] not in "uUL8":
                # Digit separator (1'000'000).
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching_brace(text, open_at):
    depth = 0
    for k in range(open_at, len(text)):
        if text[k] == "{":
            depth += 1
        elif text[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(text) - 1


def strip_template(header):
    """The header without a leading template <...> (default arguments may hold '=')."""
    m = re.match(r"\s*template\s*<", header)
    if not m:
        return header
    depth, k = 1, m.end()
    while k < len(header) and depth:
        depth += {"<": 1, ">": -1}.get(header[k], 0)
        k += 1
    return strip_template(header[k:])


def function_name(header):
    h = " ".join(strip_template(header).split())
    lam = re.search(r"([A-Za-z_]\w*)\s*=\s*\[", h)
    if lam and "(" not in h[: lam.start()]:
        return lam.group(1)
    op = re.search(r"((?:\w+::)*operator\s*(?:\(\)|[^\s(]+))\s*\(", h)
    if op:
        return op.group(1).replace(" ", "")
    m = re.search(r"((?:~?\w+\s*::\s*)*~?\w+)\s*(?:<[^()]*>)?\s*\(", h)
    return m.group(1).replace(" ", "") if m else h[:40]


def classify(header):
    """'scope', 'function' or 'skip' for a brace block at namespace or class scope."""
    h = strip_template(header)
    first_paren = h.find("(")
    head = h if first_paren < 0 else h[:first_paren]
    if re.search(r"\benum\b", head):
        return "skip"
    if re.search(r"\b(namespace|class|struct|union)\b", head) or re.fullmatch(
        r"\s*extern\s*(\s+\w+)?\s*", h
    ):
        return "scope"
    if first_paren < 0:
        return "skip"
    if "operator" in head:
        return "function"
    eq = re.search(r"(?<![=!<>])=(?!=)", head)
    if eq:
        return "function" if h[eq.end() :].lstrip().startswith("[") else "skip"
    return "function"


CTOR_INIT = re.compile(r"\)\s*(noexcept\s*)?:(?!:)")


def scan(text, begin, end, line_of, found):
    """Functions in text[begin:end], a namespace or class body."""
    header_start = begin
    k = begin
    while k < end:
        c = text[k]
        if c == ";" or c == "}":
            header_start = k + 1
        elif c == "{":
            header = text[header_start:k]
            before = text[header_start:k].rstrip()
            if CTOR_INIT.search(header) and before and (before[-1].isalnum() or before[-1] in "_>"):
                # A member initialiser in a constructor's initialiser list: part of the header.
                k = matching_brace(text, k) + 1
                continue
            close = matching_brace(text, k)
            kind = classify(header)
            if kind == "scope":
                scan(text, k + 1, close, line_of, found)
            elif kind == "function":
                first = header_start + (len(header) - len(header.lstrip()))
                start_line, end_line = line_of(first), line_of(close)
                found.append((function_name(header), start_line, end_line - start_line + 1))
            header_start = close + 1
            k = close + 1
            continue
        k += 1


def functions_of(source):
    text = blank_out(source)
    newlines = [i for i, c in enumerate(text) if c == "\n"]

    def line_of(pos):
        lo, hi = 0, len(newlines)
        while lo < hi:
            mid = (lo + hi) // 2
            if newlines[mid] < pos:
                lo = mid + 1
            else:
                hi = mid
        return lo + 1

    found = []
    scan(text, 0, len(text), line_of, found)
    return found


def offenders(root):
    result = []  # (kind, key, lines, where)
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in SUFFIXES or not path.is_file():
                continue
            rel = path.relative_to(root).as_posix()
            source = path.read_text(encoding="utf-8", errors="replace")
            lines = source.count("\n") + (0 if source.endswith("\n") or not source else 1)
            if lines > FILE_LIMIT:
                result.append(("file", rel, lines, rel))
            for name, start, size in functions_of(source):
                if size > FUNCTION_LIMIT:
                    result.append(("function", f"{rel}:{name}", size, f"{rel}:{start}"))
    return result


def read_allow_list(path):
    allowed, errors = {}, []
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        line = raw.split("#", 1)[0].strip() if raw.lstrip().startswith("#") else raw.strip()
        if not line:
            continue
        m = re.fullmatch(r"(file|function)\s+(\S+)\s+(\d+)\s+--\s+(\S.*)", line)
        if not m:
            errors.append(
                f"{path}:{number}: allow-list line not understood; expected "
                "'file|function PATH[:NAME] LINES -- who shrinks it'"
            )
            continue
        allowed[(m.group(1), m.group(2))] = int(m.group(3))
    return allowed, errors


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source_dir", type=pathlib.Path)
    parser.add_argument("--allow", type=pathlib.Path, help="allow-list file")
    parser.add_argument("--list", action="store_true", help="print every offender and exit 0")
    args = parser.parse_args()

    found = offenders(args.source_dir)
    if args.list:
        for kind, key, lines, where in found:
            print(f"{kind:<9} {key:<60} {lines:>4} -- ({where})")
        return 0

    allowed, errors = ({}, []) if args.allow is None else read_allow_list(args.allow)
    if errors:
        print("\n".join(errors), file=sys.stderr)
        return 2

    failures, seen = [], set()
    for kind, key, lines, where in found:
        limit = FILE_LIMIT if kind == "file" else FUNCTION_LIMIT
        seen.add((kind, key))
        if (kind, key) not in allowed:
            failures.append(f"{where}: {kind} {key} has {lines} lines, over the limit of {limit}; "
                            "split it by responsibility (or list it in the allow-list with who "
                            "shrinks it)")
        elif lines > allowed[(kind, key)]:
            failures.append(f"{where}: {kind} {key} grew to {lines} lines, past the "
                            f"{allowed[(kind, key)]} it is allowed while it is being shrunk")
    for kind, key in sorted(set(allowed) - seen):
        print(f"note: {kind} {key} is within the limit now; drop its allow-list line")

    print(f"{len(found)} over the limits ({FILE_LIMIT} lines a file, {FUNCTION_LIMIT} a "
          f"function), {len(found) - len(failures)} of them allowed")
    for failure in failures:
        print(failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
