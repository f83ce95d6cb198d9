#!/usr/bin/env python3
"""Self-test of scripts/check_sizes.py: function sizes found by brace matching on the C++
constructs of this code base (constructor initialiser lists with braces, lambdas, braces in
strings and comments, classes, enums, brace initialisers), and the allow-list rules."""

import pathlib
import subprocess
import sys
import tempfile

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "check_sizes.py"
sys.path.insert(0, str(SCRIPT.parent))
import check_sizes  # noqa: E402

SOURCE = """#include <vector>
// a comment with a brace {
namespace xpl {
namespace {
constexpr int table[] = {1, 2, 3};
enum class Kind { A, B };
int small(int a) { return a; }
}  // namespace
/* block { comment */
template <typename T = int>
struct Box : Base {
  Box(int a, int b)
      : m_a{a},
        m_b(b) {
    const char* s = "}";
    auto f = [&](int x) {
      return x;
    };
  }
  int get() const { return '{'; }
};
const auto named = [](int x) {
  return x + 1;
};
}  // namespace xpl
"""


def check(condition, what):
    if not condition:
        print(f"FAIL: {what}")
        sys.exit(1)


def main():
    found = {name: (start, size) for name, start, size in check_sizes.functions_of(SOURCE)}
    check(found.get("small") == (7, 1), f"small: {found.get('small')}")
    check(found.get("Box") == (12, 8), f"constructor with a brace initialiser: {found.get('Box')}")
    check(found.get("get") == (20, 1), f"member function: {found.get('get')}")
    check(found.get("named") == (22, 3), f"lambda bound to a name: {found.get('named')}")
    check("f" not in found, "a lambda inside a function counts towards that function")
    check(set(found) == {"small", "Box", "get", "named"}, f"only functions: {sorted(found)}")

    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "solver").mkdir()
        body = "\n".join(f"  x += {k};" for k in range(130))
        (root / "solver" / "big.cpp").write_text(f"void big(int& x) {{\n{body}\n}}\n")
        allow = root / "allow.txt"

        def run(allow_text):
            allow.write_text(allow_text)
            return subprocess.run([sys.executable, str(SCRIPT), str(root), "--allow", str(allow)],
                                  capture_output=True, text=True).returncode

        check(run("") == 1, "an unlisted offender fails")
        check(run("function solver/big.cpp:big 132 -- someone\n") == 0, "a listed one passes")
        check(run("function solver/big.cpp:big 131 -- someone\n") == 1, "a grown one fails")
        check(run("function solver/big.cpp:big\n") == 2, "a bad allow-list line is an error")
    print("check_sizes self-test passed")


if __name__ == "__main__":
    main()
