#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks the rooms of the tree (docs/ARCHITECTURE.md):

- no C++ source file over MAX_FILE lines, no function over MAX_FUNCTION lines;
- what each room may include: the stages (libsection/include/section/*.h, src/*.cpp)
  nothing of io/, pipe/ or extras/; io/ nothing of pipe/ or extras/; pipe/ nothing of
  extras/; the library's headers nothing of src/;
- the stages touch no files and no text streams (fopen, fstream, std::cout ...);
- CGAL, FLANN, CHOLMOD and OpenMesh only in libsection/src/detail/.

Usage: scripts/check_layout.py [ROOT]   (exit 1 and one line per finding when any)
"""
import os
import re
import sys

MAX_FILE = 600
MAX_FUNCTION = 80
SOURCE_DIRS = ["libsection", "tools", "bench", "tests", "examples", "fuzz", "python"]

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
LIB = "libsection/"


def sources():
    for top in SOURCE_DIRS:
        for dirpath, _, names in os.walk(os.path.join(ROOT, top)):
            for name in sorted(names):
                if name.endswith((".cpp", ".h")):
                    yield os.path.relpath(os.path.join(dirpath, name), ROOT)


def strip(text):
    """The code without comments, strings and character literals (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 digit separators
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(code):
    """(name, first line, last line) of every function body at namespace or class level."""
    found, stack = [], []  # stack: (kind, name, line of the signature)
    last_end = 0  # where the text before the next brace begins
    line_of = lambda pos: code.count("\n", 0, pos) + 1
    for m in re.finditer(r"[{};]", code):
        ch, pos = m.group(), m.start()
        if ch == ";":
            if not any(k == "function" for k, _, _ in stack):
                last_end = pos + 1
            continue
        if ch == "}":
            if stack:
                kind, name, start = stack.pop()
                if kind == "function" and not any(k == "function" for k, _, _ in stack):
                    found.append((name, start, line_of(pos)))
            if not any(k == "function" for k, _, _ in stack):
                last_end = pos + 1
            continue
        head = code[last_end:pos]
        if any(k == "function" for k, _, _ in stack):
            stack.append(("block", "", 0))
            continue
        flat = " ".join(head.split())
        if re.search(r"\b(namespace|class|struct|union|enum)\b[^()]*$", flat) or re.search(r"\bextern \"\"$", flat):
            stack.append(("scope", "", 0))
        elif re.search(r"\)\s*(const|noexcept|override|final|mutable|->[^{]*|:[^{]*|\s)*$", flat) and "=" not in flat.split("(")[0]:
            name = re.findall(r"([~\w:]+)\s*\(", flat)
            sig = len(head) - len(head.lstrip())
            stack.append(("function", name[0] if name else "?", line_of(last_end + sig)))
        else:
            stack.append(("block", "", 0))
        last_end = pos + 1
    return found


ROOMS = [  # (room, prefixes of what it may not include)
    ("stage", ("section/io/", "section/pipe/", "section/extras/")),
    ("io", ("section/pipe/", "section/extras/")),
    ("pipe", ("section/extras/",)),
]
THIRD_PARTY = re.compile(r"#include\s*[<\"](CGAL/|flann/|cholmod|suitesparse/|OpenMesh/)")
FILE_IO = re.compile(r"\b(fopen|fstream|ifstream|ofstream|std::cout|std::cerr|std::cin|stdout|stderr|popen)\b")


def room(path):
    if not path.startswith(LIB):
        return None
    rest = path[len(LIB):]
    for prefix, name in (("include/section/io/", "io"), ("src/io/", "io"), ("include/section/pipe/", "pipe"),
                         ("src/pipe/", "pipe"), ("include/section/extras/", "extras"), ("src/extras/", "extras"),
                         ("src/detail/", "detail")):
        if rest.startswith(prefix):
            return name
    if rest.startswith("include/section/") or (rest.startswith("src/") and rest.count("/") == 1):
        return "stage"
    return None


def main():
    problems = []
    for path in sources():
        text = open(os.path.join(ROOT, path), encoding="utf-8", errors="replace").read()
        lines = text.count("\n")
        if lines > MAX_FILE:
            problems.append(f"{path}: {lines} lines (at most {MAX_FILE})")
        code = strip(text)
        for name, first, last in functions(code):
            if last - first + 1 > MAX_FUNCTION:
                problems.append(f"{path}:{first}: function {name} has {last - first + 1} lines (at most {MAX_FUNCTION})")
        r = room(path)
        includes = re.findall(r'#include\s*[<"]([^>"]+)[>"]', text)
        for name, banned in ROOMS:
            if r == name:
                for inc in includes:
                    if inc.startswith(banned):
                        problems.append(f"{path}: the {name} room includes {inc}")
        if path.startswith(LIB + "include/") and any(i.startswith("detail/") for i in includes):
            problems.append(f"{path}: a public header includes the library's internals")
        if path.startswith(LIB) and r != "detail" and THIRD_PARTY.search(text):
            problems.append(f"{path}: CGAL, FLANN, CHOLMOD or OpenMesh outside libsection/src/detail/")
        if r == "stage" and FILE_IO.search(code):
            problems.append(f"{path}: a stage touches files or standard streams ({FILE_IO.search(code).group()})")
    for p in problems:
        print(p)
    print(f"check_layout: {len(problems)} finding(s)" if problems else "check_layout: ok")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
