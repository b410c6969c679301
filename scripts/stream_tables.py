# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads one table of a libsection pipe stream (docs/FORMAT.md) for the validation
scripts: a list of dicts, column name -> float."""


def table(path, name):
    rows, header, inside = [], None, False
    for line in open(path):
        if line.startswith("#"):
            inside, header = line.strip() == "# table " + name, None
            continue
        if inside:
            if header is None:
                header = line.strip().split(",")
            else:
                rows.append(dict(zip(header, map(float, line.strip().split(",")))))
    return rows
