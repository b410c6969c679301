#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A tool's bash completion from its --help (CLI11's layout), for the build
(cmake/ToolDocs.cmake): its flags after '-', the choices of a flag that lists them
(`TEXT:{a,b}`), nothing after a flag taking a number, file names elsewhere.

Usage: scripts/bash_completion.py TOOL OUT
"""
import os
import re
import subprocess
import sys

NUMBER = re.compile(r"^(INT|UINT|FLOAT|NUMBER)\b")


def options(help_text):
    """(names, kind, choices) per option: kind 'flag', 'number', 'choice' or 'file'. A line
    is `  NAMES [TYPE] [Excludes: ...]  description`, the columns two blanks or more apart."""
    out = []
    for line in help_text.splitlines():
        if not line.startswith("  -"):
            continue
        columns = re.split(r"\s{2,}", line.strip())
        words = columns[0].split()
        names = [n for n in words[0].split(",") if n.startswith("-")]
        kind_text = words[1] if len(words) > 1 and not words[1].endswith(":") else ""
        meaning = columns[1] if len(columns) > 1 else ""
        listed = re.search(r"\(((?:[\w-]+, )+[\w-]+)\)", meaning)
        if not kind_text:
            kind, choices = "flag", []
        elif re.search(r":\{([^}]*)\}", kind_text):
            kind, choices = "choice", re.search(r":\{([^}]*)\}", kind_text).group(1).split(",")
        elif kind_text.startswith("TEXT:UNIT") and listed:  # --units: the units its help lists
            kind, choices = "choice", listed.group(1).split(", ")
        elif NUMBER.match(kind_text):
            kind, choices = "number", []
        else:
            kind, choices = "file", []
        out.append((names, kind, choices))
    return out


def script(tool, opts):
    fn = "_libsection_" + re.sub(r"\W", "_", tool)
    cases = []
    for names, kind, choices in opts:
        pattern = "|".join(names)
        if kind == "choice":
            cases.append(f'    {pattern}) COMPREPLY=($(compgen -W "{" ".join(choices)}" -- "$cur")); return ;;')
        elif kind == "number":
            cases.append(f"    {pattern}) return ;;")
        elif kind == "file":
            cases.append(f'    {pattern}) COMPREPLY=($(compgen -f -- "$cur")); compopt -o filenames 2>/dev/null; return ;;')
    words = " ".join(n for names, _, _ in opts for n in names)
    return "\n".join([
        f"# bash completion of {tool} (libsection), made from `{tool} --help` by scripts/bash_completion.py",
        f"{fn}() {{",
        '  local cur="${COMP_WORDS[COMP_CWORD]}" prev="${COMP_WORDS[COMP_CWORD-1]}"',
        '  case "$prev" in',
        *cases,
        "  esac",
        '  if [[ "$cur" == -* ]]; then',
        f'    COMPREPLY=($(compgen -W "{words}" -- "$cur"))',
        "  else",
        '    COMPREPLY=($(compgen -f -- "$cur")); compopt -o filenames 2>/dev/null',
        "  fi",
        "}",
        f"complete -F {fn} {tool}",
        "",
    ])


def main(tool_path, out):
    tool = os.path.basename(tool_path)
    text = subprocess.run([tool_path, "--help"], capture_output=True, text=True, check=True).stdout
    opts = options(text[text.find("\nOptions:"):])
    if not opts:
        sys.exit(f"bash_completion: {tool} --help lists no options")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out + ".tmp", "w") as f:
        f.write(script(tool, opts))
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main(*sys.argv[1:3])
