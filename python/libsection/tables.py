# SPDX-License-Identifier: GPL-3.0-or-later
"""Reading the pipe stream (docs/FORMAT.md) without the compiled module: each table as a
pandas DataFrame or as rows of dicts, and numbers formatted as the tools write them."""
import math

__all__ = ["read_tables", "table", "format_number", "to_csv"]


def _text(source):
    if hasattr(source, "read"):
        text = source.read()
        return text.decode() if isinstance(text, bytes) else text
    if isinstance(source, str) and ("\n" in source or source.startswith("# libsection-stream")):
        return source
    with open(source, encoding="utf-8") as f:
        return f.read()


def _tables(text):
    """name -> (header, rows): each table's rows gathered over the stream's parts."""
    out, name, header = {}, None, None
    for number, line in enumerate(text.splitlines(), 1):
        line = line.strip()
        if not line:
            continue
        if line.startswith("#"):
            name, header = (line[len("# table "):].strip(), None) if line.startswith("# table ") else (None, None)
            continue
        if name is None:
            raise ValueError(f"line {number}: a data line outside a table")
        if header is None:
            header = line.split(",")
            known = out.setdefault(name, (header, []))[0]
            if known != header:
                raise ValueError(f"line {number}: table '{name}' has another header than before")
            continue
        cells = line.split(",")
        if len(cells) != len(header):
            raise ValueError(f"line {number}: {len(cells)} values for the {len(header)} columns of '{name}'")
        out[name][1].append([float(c) for c in cells])
    return out


def read_tables(source):
    """Every table of a stream as a pandas DataFrame: dict name -> DataFrame (float64
    columns, the rows of all parts in order). `source`: a path, an open file, or the text."""
    import pandas as pd

    return {name: pd.DataFrame(rows, columns=header, dtype="float64")
            for name, (header, rows) in _tables(_text(source)).items()}


def table(path, name):
    """One table of a stream as a list of dicts, column name -> float (what
    scripts/stream_tables.py gives the validation scripts)."""
    header, rows = _tables(_text(path)).get(name, ([], []))
    return [dict(zip(header, row)) for row in rows]


def format_number(x):
    """A number as the tools write it: the shortest digits that read back to the same double
    (Python's repr), laid out fixed or scientific, whichever is shorter (fixed on a tie),
    as C++'s std::to_chars does: 3.0 -> '3', 1e-05 -> '1e-05', 1e15 -> '1e+15'."""
    x = float(x)
    if math.isnan(x):
        return "-nan" if math.copysign(1, x) < 0 else "nan"
    if math.isinf(x):
        return "-inf" if x < 0 else "inf"
    sign = "-" if math.copysign(1, x) < 0 else ""
    mantissa, _, exponent = repr(abs(x)).partition("e")
    whole, _, fraction = mantissa.partition(".")
    digits = (whole + fraction).lstrip("0")
    if not digits:
        return sign + "0"
    # abs(x) = 0.DIGITS x 10^point: the leading zeros dropped move the point left.
    point = len(whole) + int(exponent or 0) - (len(whole + fraction) - len(digits))
    digits = digits.rstrip("0")
    if point >= len(digits):
        fixed = str(int(abs(x)))  # an integer: its exact digits, as std::to_chars prints them
    elif point > 0:
        fixed = digits[:point] + "." + digits[point:]
    else:
        fixed = "0." + "0" * (-point) + digits
    e = point - 1
    scientific = digits[0] + ("." + digits[1:] if len(digits) > 1 else "") + ("e-" if e < 0 else "e+") + f"{abs(e):02d}"
    return sign + (fixed if len(fixed) <= len(scientific) else scientific)


def to_csv(columns):
    """A table (dict column -> sequence, or a DataFrame) as the CSV the tools write (camber
    --params): the header, then a line per row, numbers by format_number."""
    names = list(columns.keys())
    values = [list(columns[n]) for n in names]
    lines = [",".join(names)]
    for row in zip(*values):
        lines.append(",".join(format_number(v) for v in row))
    return "\n".join(lines) + "\n"
