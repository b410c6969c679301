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
        if check not in value:
            raise ValueError(f"checks.h: no bit read for check {check} (its enum line `{check} = 1u << N,` wrapped?)")
        bits[value[check]] = (name, cols)
    return bits


def flagged_by(flags, column, bits):
    """The names of the set bits of `flags` that flag `column`."""
    flags = int(flags)
    return [name for b, (name, cols) in sorted(bits.items()) if flags & b and (cols is None or column in cols)]


def score_row(label, kind, row, truth, targets, bits, quiet=False):
    """Prints each value of a params `row` off its target against `truth` (targets: column
    -> ("abs" or "rel", tolerance); a sharp-te's TE radius skipped) and the checks flagging
    it (SILENT: none); returns how many were off with no flag. quiet: prints nothing and
    returns how many were off."""
    silent = off = 0
    for col, (kind_of, tol) in targets.items():
        if kind == "sharp-te" and col == "te_radius":
            continue
        m, tv = float(row[col]), float(truth[col])
        err = m / tv - 1 if kind_of == "rel" and tv > 0 else m - tv
        if abs(err) > tol:
            off += 1
            if quiet:
                continue
            names = flagged_by(row["flags"], col, bits)
            silent += not names
            print(f"{label}: {col} {err:+.4f} {'flagged ' + ','.join(names) if names else 'SILENT'}")
    return off if quiet else silent


if __name__ == "__main__":
    # What the validation scripts read of checks.h, read whole: every check of the enum a
    # bit, every bit a named entry, as many as check_count (a line clang-format wrapped
    # once hid le_choice from the scripts).
    import sys
    text = open(os.path.join(ROOT, "libsection", "include", "section", "checks.h")).read()
    count = int(re.search(r"check_count = (\d+);", text)[1])
    try:
        bits = check_bits()
    except ValueError as e:
        sys.exit(f"check_bits: {e}")
    if sorted(bits) != [1 << k for k in range(count)]:
        missing = [k for k in range(count) if (1 << k) not in bits]
        sys.exit(f"check_bits: checks.h's bits {missing} are not read (of check_count {count})")
    print(f"check_bits: {count} checks read")
