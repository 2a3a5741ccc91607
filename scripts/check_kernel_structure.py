#!/usr/bin/env python3
"""Holds the GLSL kernels (compute/shaders) to the shape docs/renderer.md
describes, so that a change cannot quietly grow them back into one file:

  - no shader file over MAX_FILE_LINES lines;
  - no function over MAX_FUNCTION_LINES lines (from its signature to its
    closing brace);
  - one march: within the march kernel (march.comp and march/*.glsl), a
    ray's positions are taken (sol_forward, sol_forward_zeta,
    sol_position_forward, quotient_forward, rk4_advance) by the march alone
    (march/march.glsl; march/plane_roots.glsl, which solves a ray's
    crossings of planes x = c, y = c for it; march/crowd.glsl, the march
    through a crowd's tree of bounds, which march() takes for a crowd), and
    march/march.glsl defines march() once.

Usage: check_kernel_structure.py [SHADER_DIR]   (default: compute/shaders
beside this script). Prints each violation; exits 1 if there is one, 2 on
bad usage.
"""
import pathlib
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 150
# The calls that advance a ray along its geodesic.
POSITION_CALLS = ("sol_forward", "sol_forward_zeta", "sol_position_forward", "quotient_forward", "rk4_advance")
MARCH_MODULE = "march/march.glsl"
MARCH_FILES = (MARCH_MODULE, "march/plane_roots.glsl", "march/crowd.glsl")

# A function definition at the top level: a return type, a name, '(' and
# (on this line or a later one) '{', never ';'.
SIGNATURE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s+([A-Za-z_][A-Za-z0-9_]*)\s*\(")
COMMENT = re.compile(r"//.*$")


def functions(lines):
    """(name, first line, line count) of each top-level function definition."""
    out = []
    i = 0
    while i < len(lines):
        m = SIGNATURE.match(lines[i])
        if m and m.group(1) not in ("return", "else", "layout", "struct", "const", "uniform", "buffer"):
            # Find the end of the signature: '{' opens a body, ';' ends a declaration.
            j = i
            text = COMMENT.sub("", lines[j])
            while "{" not in text and ";" not in text and j + 1 < len(lines):
                j += 1
                text = COMMENT.sub("", lines[j])
            if "{" in text:
                depth = 0
                k = i
                while k < len(lines):
                    code = COMMENT.sub("", lines[k])
                    depth += code.count("{") - code.count("}")
                    if depth == 0 and "}" in code:
                        break
                    k += 1
                out.append((m.group(2), i + 1, k - i + 1))
                i = k
        i += 1
    return out


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1]) if len(argv) == 2 else pathlib.Path(__file__).resolve().parent.parent / "compute" / "shaders"
    if not root.is_dir():
        print(f"check_kernel_structure: {root} is not a folder", file=sys.stderr)
        return 2
    files = sorted(p for p in root.rglob("*") if p.suffix in (".glsl", ".comp"))
    if not files:
        print(f"check_kernel_structure: no shaders under {root}", file=sys.stderr)
        return 2
    problems = []
    march_definitions = 0
    for path in files:
        name = path.relative_to(root).as_posix()
        lines = path.read_text(encoding="utf-8").split("\n")
        if len(lines) > MAX_FILE_LINES:
            problems.append(f"{name}: {len(lines)} lines (at most {MAX_FILE_LINES})")
        for function, first, count in functions(lines):
            if count > MAX_FUNCTION_LINES:
                problems.append(f"{name}:{first}: {function} is {count} lines (at most {MAX_FUNCTION_LINES})")
            if name == MARCH_MODULE and function == "march":
                march_definitions += 1
        in_kernel = name == "march.comp" or name.startswith("march/")
        if in_kernel and name not in MARCH_FILES:
            for number, line in enumerate(lines, 1):
                code = COMMENT.sub("", line)
                for call in POSITION_CALLS:
                    if re.search(r"\b" + call + r"\s*\(", code) and not SIGNATURE.match(code):
                        problems.append(f"{name}:{number}: calls {call}: rays advance in the march alone ({', '.join(MARCH_FILES)})")
    if march_definitions != 1:
        problems.append(f"{MARCH_MODULE}: defines march() {march_definitions} times (once)")
    for p in problems:
        print(p)
    print(f"check_kernel_structure: {len(files)} shader files, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
