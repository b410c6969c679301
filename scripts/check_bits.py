# SPDX-License-Identifier: GPL-3.0-or-later
"""The params table's check bits (section/checks.h) for the validation scripts: which
check each bit is and which columns it flags."""
import os
import re

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def check_bits():
    """bit -> (check name, the columns it flags; None = every column), from checks.h."""
    text = open(os.path.join(ROOT, "libsection", "include", "section", "checks.h")).read()
    value = {m[0]: 1 << int(m[1]) for m in re.findall(r"(\w+) = (?:1u|CheckBits\(1\)) << (\d+),", text)}
    bits = {}
    # An entry may be wrapped over lines, its columns split into adjacent string literals.
    for check, name, literals in re.findall(r'\{Check::(\w+),\s*"(\w+)",\s*((?:"[^"]*"\s*)+)\}', text):
        columns = "".join(re.findall(r'"([^"]*)"', literals))
        cols = None if columns.startswith("every") else set(columns.split())
        bits[value[check]] = (name, cols)
    return bits


def flagged_by(flags, column, bits):
    """The names of the set bits of `flags` that flag `column`."""
    flags = int(flags)
    return [name for b, (name, cols) in sorted(bits.items()) if flags & b and (cols is None or column in cols)]
