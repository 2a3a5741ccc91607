#!/usr/bin/env python3
"""Holds the C++ of the libraries and programs to functions of at most
MAX_FUNCTION_LINES lines (from the first line of the signature to the
closing brace), so that none grows back into a page-long block.

A function here is a definition at namespace scope, the project's layout
(clang-format, namespaces not indented): a line in column 0 that begins a
signature (a name, then '(' on this line) and reaches '{' before any ';',
its body ending at the next line that begins with '}' in column 0. Member
functions defined inside a class body are not counted (they are short by
the project's habit); lambdas count within the function that holds them.

Usage: check_function_length.py ROOT_DIR [SUBDIR ...]   (default subdirs:
the libraries' and programs' sources). Prints each violation; exits 1 if
there is one, 2 on bad usage.
"""
import pathlib
import re
import sys

MAX_FUNCTION_LINES = 200
DEFAULT_DIRS = ("libsol", "compute", "viewer", "xr", "python", "common", "bench")
SKIP = re.compile(r"^(namespace|struct|class|enum|union|extern|template|using|static_assert|typedef|#|//|/\*|\}|\{)")
START = re.compile(r"^[A-Za-z_~].*\(")


def functions(lines):
    """(first line, line count, text of the first line) of each definition."""
    out = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if START.match(line) and not SKIP.match(line) and not line.rstrip().endswith(";"):
            j = i
            while j < len(lines) and not lines[j].rstrip().endswith("{") and not lines[j].rstrip().endswith(";"):
                j += 1
            if j < len(lines) and lines[j].rstrip().endswith("{"):
                k = j + 1
                while k < len(lines) and not lines[k].startswith("}"):
                    k += 1
                out.append((i + 1, k - i + 1, line.strip()))
                i = k
        i += 1
    return out


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1])
    dirs = argv[2:] or DEFAULT_DIRS
    bad = 0
    for d in dirs:
        if not (root / d).is_dir():
            print(f"{root / d}: not a directory", file=sys.stderr)
            return 2
        for path in sorted((root / d).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h") or not path.is_file():
                continue
            lines = path.read_text(encoding="utf-8", errors="replace").split("\n")
            for first, count, text in functions(lines):
                if count > MAX_FUNCTION_LINES:
                    print(f"{path.relative_to(root)}:{first}: {count} lines (at most {MAX_FUNCTION_LINES}): {text[:80]}")
                    bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
