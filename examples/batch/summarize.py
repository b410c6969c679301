# SPDX-License-Identifier: GPL-3.0-or-later
"""One table of every blade: the params.csv of each scan (camber --params) stacked, with the
scan's name first.

    python3 summarize.py OUT.csv SCAN... -- PARAMS.csv...   (the same number of each, in order)
"""
import csv
import sys


def main(argv):
    out, rest = argv[0], argv[1:]
    cut = rest.index("--")
    scans, files = rest[:cut], rest[cut + 1:]
    if len(scans) != len(files):
        sys.exit("summarize: give as many scan names as params files")
    header, rows = None, []
    for scan, path in zip(scans, files):
        with open(path, newline="") as f:
            table = list(csv.reader(f))
        if not table:
            sys.exit(f"summarize: {path}: empty (did camber fail?)")
        if header is None:
            header = table[0]
        elif table[0] != header:
            sys.exit(f"summarize: {path}: other columns than {files[0]}")
        rows += [[scan] + row for row in table[1:]]
    with open(out, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["scan"] + header)
        w.writerows(rows)


if __name__ == "__main__":
    main(sys.argv[1:])
