#!/usr/bin/env python3
"""spallbar-compare: compare a candidate curve table with a reference, with tolerances.

    spallbar-compare REFERENCE CANDIDATE [--column NAME[:CAND_NAME]]... [--rtol R] [--atol A]
                     [--time-tol T] [--t-max T] [--report FILE] [--plot FILE.png] [--quiet]

REFERENCE and CANDIDATE are spallbar column outputs (.his, .gau, .sweep: `#` header lines,
the last one naming the columns) or plain tables `t value ...` (`#` or `!` comments, blanks
or commas between numbers, an optional first line naming the columns, Fortran `D`
exponents read; a UTF-8 byte-order mark is read as nothing): a digitised curve, a legacy
printout. The first column is the abscissa. A plain table without a header names its
columns by position: 1 (the abscissa), 2, 3, ...

Each compared column (default: every value column of the reference, which the candidate
must have; --column NAME compares the columns named only; a headerless two-column reference
against a named candidate needs --column NAME, which maps the reference's one value column
to the candidate's NAME; --column 2:reaction_bottom maps explicitly) is evaluated at the
reference's abscissae, the candidate interpolated linearly. A repeated abscissa is a jump,
compared from both sides: the first reference row there against the candidate's left limit,
the last against its right limit (a single reference row at a jump of the candidate against
the nearer side). A point passes when
    |c - r| <= atol + rtol |r|
(rtol default 1e-6, applied at each point; atol default 1e-12 of the column's largest |r|,
round-off around a zero of the curve: a 400 % error fails wherever |r| is above 2.5e-13 of
the column's largest); with --time-tol T it also passes when the candidate curve comes
within that band somewhere within +-T of the point's abscissa (a tube: timing differences
within T pass; for curves read off a figure), and the shift it needed is reported. A
reference point outside the candidate's abscissa range fails (unless the tube reaches it).
--t-max T compares the reference's points up to abscissa T only.

Both tables are read row by row and merged in abscissa order (the reference twice when atol
is the default), so memory stays bounded whatever their length; only --plot holds the
plotted columns.

Prints per column: points, max absolute and relative error, relative L1 and L2 norms
(sum |c - r| / sum |r|, sqrt(sum (c - r)^2 / sum r^2)), failures, the largest time shift
used, and the first failing abscissa. Exit 0: every point of every column passes; 1: some
fail (the columns are named); 2: bad input (one line on stderr, nothing written).

Only the Python standard library is needed; --plot needs matplotlib (the project venv).
"""
import argparse
import bisect
import itertools
import math
import os
import shutil
import sys
import tempfile

PROG = "spallbar-compare"
ATOL_OF_SCALE = 1e-12      # the default atol, a fraction of the column's largest |r|


class BadInput(Exception):
    """Bad input: one line on stderr, exit 2."""


def _number(word):
    try:
        return float(word)
    except ValueError:
        return float(word.replace("D", "E").replace("d", "e"))


def _is_number(word):
    try:
        _number(word)
        return True
    except ValueError:
        return False


def open_rewindable(path):
    """The text of path, open for reading from its start again (a pipe is spooled to a
    temporary file); a UTF-8 byte-order mark is read as nothing."""
    try:
        f = open(path, encoding="utf-8-sig", errors="replace")
    except OSError as e:
        raise BadInput(f"{path}: cannot read: {e.strerror}") from None
    if f.seekable():
        return f
    spool = tempfile.TemporaryFile("w+", encoding="utf-8")
    with f:
        shutil.copyfileobj(f, spool)
    spool.seek(0)
    return spool


class Table:
    """A spallbar column output or a plain table, read row by row from the start of f: the
    column names on construction, then rows() yields each row's numbers, checked as read."""

    def __init__(self, path, f):
        f.seek(0)
        self.path, self.line_no = path, 0
        self._lines = self._text(f)
        self.names, self._first = self._head()

    def _text(self, f):
        for line in f:
            self.line_no += 1
            text = line.strip()
            if text:
                yield text

    def _values(self, text):
        try:
            values = list(map(_number, text.replace(",", " ").split()))
        except ValueError:
            raise BadInput(f"{self.path}: line {self.line_no}: not a row of numbers: "
                           f"{text[:60]!r}") from None
        if not all(map(math.isfinite, values)):
            raise BadInput(f"{self.path}: line {self.line_no}: a value is not finite")
        return values

    def _head(self):
        names, last_comment = None, None
        for text in self._lines:
            if text[0] in "#!":
                last_comment = text[1:].strip()
                continue
            words = text.replace(",", " ").split()
            if names is None and not all(_is_number(w) for w in words):
                names = words        # a plain table's header line
                continue
            values = self._values(text)
            if names is None and last_comment:
                cand = last_comment.split()
                if len(cand) == len(values) and all(not _is_number(w) for w in cand):
                    names = cand     # a spallbar output: the last '#' line names the columns
            if len(values) < 2:
                raise BadInput(f"{self.path}: one column only; a table is 'abscissa value ...'")
            names = names or [str(j + 1) for j in range(len(values))]
            if len(names) != len(values):
                raise BadInput(f"{self.path}: {len(names)} column names for {len(values)} "
                               "columns")
            if len(set(names)) != len(names):
                raise BadInput(f"{self.path}: a column name is repeated")
            return names, values
        raise BadInput(f"{self.path}: no rows of numbers")

    def rows(self):
        """Every row's numbers, the first included; the abscissa must not decrease, but
        after a `#` line (a .prf's next profile time) where self.block counts up."""
        prev, comment, self.block = self._first, False, 1
        yield prev
        for text in self._lines:
            if text[0] in "#!":
                comment = True
                continue
            values = self._values(text)
            if len(values) != len(prev):
                raise BadInput(f"{self.path}: line {self.line_no}: {len(values)} numbers, the "
                               f"first row has {len(prev)}")
            if values[0] < prev[0]:
                if not comment:
                    raise BadInput(f"{self.path}: the abscissa ({self.names[0]}) decreases at "
                                   f"line {self.line_no}; the first column must be "
                                   "non-decreasing (but after a '#' line: the next block)")
                self.block += 1
            prev, comment = values, False
            yield values

    def blocks(self):
        """(block number, its rows) in order."""
        return itertools.groupby(self.rows(), key=lambda _: self.block)


def pairs_to_compare(ref_names, cand_names, asked):
    """[(reference column, candidate column)] by name; asked: the --column values."""
    if asked:
        out = []
        for a in asked:
            r, _, c = a.partition(":")
            c = c or r
            if r not in ref_names and len(ref_names) == 2 and ref_names[1] == "2":
                r = "2"              # a headerless curve: its one value column
            if r not in ref_names[1:]:
                raise BadInput(f"--column {a}: the reference has no column {r!r} "
                               f"(it has {' '.join(ref_names[1:])})")
            if c not in cand_names[1:]:
                raise BadInput(f"--column {a}: the candidate has no column {c!r} "
                               f"(it has {' '.join(cand_names[1:])})")
            out.append((r, c))
        return out
    common = [n for n in ref_names[1:] if n in cand_names[1:]]
    if not common:
        raise BadInput("the two tables share no column name; give --column REF_NAME:CAND_NAME "
                       f"(reference: {' '.join(ref_names[1:])}; candidate: "
                       f"{' '.join(cand_names[1:])})")
    missing = [n for n in ref_names[1:] if n not in cand_names[1:]]
    if missing:
        raise BadInput(f"the candidate lacks the reference's column{'s' * (len(missing) > 1)} "
                       f"{' '.join(missing)}; --column NAME compares the columns named only")
    return [(n, n) for n in common]


def reference_groups(rows, t_max):
    """(t, [rows at t]) in order, a repeated abscissa (a jump) one group; rows beyond t_max
    are read (checked) but not returned."""
    group = []
    for row in rows:
        if t_max is not None and row[0] > t_max:
            continue
        if group and row[0] != group[0][0]:
            yield group[0][0], group
            group = []
        group.append(row)
    if group:
        yield group[0][0], group


class Window:
    """The candidate's rows around the abscissa being compared, read as needed: those within
    the tube [t - T, t + T] and one on either side; earlier rows are dropped."""

    def __init__(self, rows, cols):
        self.rows, self.cols = rows, cols
        self.x, self.y = [], [[] for _ in cols]
        self.start, self.first, self.done = 0, None, False

    def _drop_before(self, lo):
        x = self.x
        while len(x) - self.start >= 2 and x[self.start + 1] < lo:
            self.start += 1
        if self.start > 1024 and 2 * self.start > len(x):
            del x[:self.start]
            for y in self.y:
                del y[:self.start]
            self.start = 0

    def advance(self, t, time_tol):
        """Read the candidate up to the first row beyond t + T, keeping one row before
        t - T; False when t is outside the candidate's abscissae."""
        lo, hi = t - time_tol, t + time_tol
        while not self.done and (len(self.x) == self.start or self.x[-1] <= hi):
            row = next(self.rows, None)
            if row is None:
                self.done = True
                break
            self.x.append(row[0])
            for y, j in zip(self.y, self.cols):
                y.append(row[j])
            if self.first is None:
                self.first = row[0]
            self._drop_before(lo)
        self._drop_before(lo)
        return self.first is not None and self.first <= t <= self.x[-1]

    def locate(self, t):
        """(i, j, w) for t inside the candidate's abscissae: its rows at t are i to j - 1;
        none (i == j), t lies between rows i - 1 and i, at the fraction w."""
        x = self.x
        i = bisect.bisect_left(x, t, self.start)
        j = bisect.bisect_right(x, t, self.start)
        return i, j, (0.0 if i < j else (t - x[i - 1]) / (x[i] - x[i - 1]))

    def sides(self, k, where):
        """The candidate's column k at the abscissa located: (left limit, right limit)."""
        i, j, w = where
        y = self.y[k]
        if i < j:
            return y[i], y[j - 1]
        c = y[i - 1] + w * (y[i] - y[i - 1])
        return c, c

    def middle(self, k, where, n):
        """The candidate's column k at its n-th row at the abscissa located (its last row
        there when it has fewer; the interpolation when it has none)."""
        i, j, w = where
        return self.y[k][min(i + n, j - 1)] if i < j else self.sides(k, where)[0]

    def tube_shift(self, k, t, r, band, time_tol):
        """The smallest |tau - t| with tau in [t - T, t + T] and |c(tau) - r| <= band, c the
        candidate's piecewise-linear curve; None where there is none."""
        x, y = self.x, self.y[k]
        lo, hi = max(t - time_tol, x[self.start]), min(t + time_tol, x[-1])
        if lo > hi:
            return None
        best = None
        k0 = max(bisect.bisect_right(x, lo, self.start) - 1, self.start)
        k1 = min(bisect.bisect_left(x, hi, self.start) + 1, len(x) - 1)
        for m in range(k0, k1):
            xa, xb = x[m], x[m + 1]
            if xb <= xa:
                continue
            a, b = max(xa, lo), min(xb, hi)
            if a > b:
                continue
            ya = y[m] + (a - xa) / (xb - xa) * (y[m + 1] - y[m])
            yb = y[m] + (b - xa) / (xb - xa) * (y[m + 1] - y[m])
            # the part of [a, b] where |ya + s (yb - ya) - r| <= band, s in [0, 1]
            if ya == yb:
                if abs(ya - r) > band:
                    continue
                s_lo, s_hi = 0.0, 1.0
            else:
                s1 = (r - band - ya) / (yb - ya)
                s2 = (r + band - ya) / (yb - ya)
                s_lo, s_hi = max(min(s1, s2), 0.0), min(max(s1, s2), 1.0)
                if s_lo > s_hi:
                    continue
            t_lo, t_hi = a + s_lo * (b - a), a + s_hi * (b - a)
            d = 0.0 if t_lo <= t <= t_hi else min(abs(t_lo - t), abs(t_hi - t))
            best = d if best is None else min(best, d)
        return best


class Measures:
    """The running measures of one compared column."""

    def __init__(self, atol):
        self.atol = atol
        self.points = self.failures = self.outside = 0
        self.max_abs = self.max_rel = self.max_shift = 0.0
        self.s_abs = self.s_ref = self.s_sq = self.s_refsq = 0.0
        self.first_fail = None

    def point(self, r, c, band):
        """One reference point r, c the candidate's value there (None outside its range):
        the sums; True when |c - r| <= band."""
        self.points += 1
        self.s_ref += abs(r)
        self.s_refsq += r * r
        if c is None:
            self.outside += 1
            return False
        err = abs(c - r)
        if err > self.max_abs:
            self.max_abs = err
        if r != 0.0 and err > self.max_rel * abs(r):
            self.max_rel = err / abs(r)
        self.s_abs += err
        self.s_sq += err * err
        return err <= band

    def miss(self, b, t, shift):
        """A point at t of block b outside the band: passed by the tube (shift: the shift
        it needed) or failed (shift None)."""
        if shift is not None:
            self.max_shift = max(self.max_shift, shift)
        else:
            self.failures += 1
            if self.first_fail is None:
                self.first_fail = f"{t:.6g}" + (f" (block {b})" if b > 1 else "")

    def result(self):
        s_abs, s_sq = self.s_abs, self.s_sq
        return {
            "points": self.points, "max_abs": self.max_abs, "max_rel": self.max_rel,
            "l1": s_abs / self.s_ref if self.s_ref > 0 else (0.0 if s_abs == 0 else math.inf),
            "l2": (math.sqrt(s_sq / self.s_refsq) if self.s_refsq > 0
                   else (0.0 if s_sq == 0 else math.inf)),
            "failures": self.failures, "first_fail": self.first_fail,
            "max_shift": self.max_shift, "outside": self.outside, "atol": self.atol,
        }


def default_atols(ref, cols, t_max):
    """ATOL_OF_SCALE of each column's largest |r| up to t_max (a first pass over ref)."""
    scale = [0.0] * len(cols)
    for _, group in reference_groups(ref.rows(), t_max):
        for row in group:
            scale = list(map(max, scale, map(abs, map(row.__getitem__, cols))))
    return [ATOL_OF_SCALE * s for s in scale]


def compare(ref, cand, pairs, rtol, atols, time_tol, t_max):
    """The measures (dicts) of each pair, the reference and the candidate merged row by row
    in abscissa order. A group of reference rows at one abscissa (a jump) meets the
    candidate from both sides: the first row its left limit, the last its right limit, those
    between its rows there in order; a single row the nearer side."""
    jr = [ref.names.index(r) for r, _ in pairs]
    jc = [cand.names.index(c) for _, c in pairs]
    measures = [Measures(a) for a in atols]
    for ref_block, cand_block in itertools.zip_longest(ref.blocks(), cand.blocks()):
        if ref_block and cand_block:      # else: read on, to count the blocks
            compare_block(ref_block[0], ref_block[1], Window(cand_block[1], jc), jr, measures,
                          rtol, time_tol, t_max)
    if ref.block != cand.block:
        raise BadInput(f"{ref.path} has {ref.block} blocks (profile times), {cand.path} "
                       f"{cand.block}; a block begins where the abscissa decreases after a '#' "
                       "line")
    if measures[0].points == 0:
        raise BadInput(f"--t-max {t_max:g}: no reference point up to it")
    return [m.result() for m in measures]


def compare_block(b, ref_rows, window, jr, measures, rtol, time_tol, t_max):
    """Add block b of the reference (its rows) to measures, the candidate's block in
    window."""
    for t, group in reference_groups(ref_rows, t_max):
        where = window.locate(t) if window.advance(t, time_tol) else None
        last = len(group) - 1
        for k, (j, m) in enumerate(zip(jr, measures)):
            left, right = window.sides(k, where) if where else (None, None)
            for n, row in enumerate(group):
                r = row[j]
                if where is None or n == 0 and (last > 0 or abs(left - r) <= abs(right - r)):
                    c = left
                elif n == last:
                    c = right
                else:
                    c = window.middle(k, where, n)
                band = m.atol + rtol * abs(r)
                if not m.point(r, c, band):
                    m.miss(b, t, window.tube_shift(k, t, r, band, time_tol)
                           if time_tol > 0.0 else None)
    for _ in window.rows:    # the rest of the candidate's block, checked
        pass


def writable(option, path):
    """Refuse, before anything is read or written, an output path that cannot be written."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise BadInput(f"{option} {path}: cannot write: no folder {folder}")
    if os.path.isdir(path):
        raise BadInput(f"{option} {path}: cannot write: it is a folder")
    if not os.access(path if os.path.exists(path) else folder, os.W_OK):
        raise BadInput(f"{option} {path}: cannot write: permission denied")


def report_lines(ref, cand, results, args):
    out = [f"# {PROG}: reference {ref}, candidate {cand}",
           f"# pass: |c - r| <= atol + rtol |r|, rtol = {args.rtol:g}, atol = "
           + (f"{args.atol:g}" if args.atol is not None
              else f"{ATOL_OF_SCALE:g} of each column's largest |r|")
           + (f"; tube +-{args.time_tol:g} in the abscissa" if args.time_tol > 0 else "")
           + (f"; up to {args.t_max:g}" if args.t_max is not None else ""),
           "| column | points | max abs error | max rel error | rel L1 | rel L2 | failures "
           "| largest time shift | first failure at |",
           "|---|---|---|---|---|---|---|---|---|"]
    for (r, c), m in results:
        name = r if r == c else f"{r}:{c}"
        first = m["first_fail"] or ""
        if m["outside"]:
            first += f" ({m['outside']} points outside the candidate's range)"
        out.append(f"| {name} | {m['points']} | {m['max_abs']:.3e} | {m['max_rel']:.3e} | "
                   f"{m['l1']:.3e} | {m['l2']:.3e} | {m['failures']} | "
                   f"{m['max_shift']:.3g} | {first} |")
    failed = [r if r == c else f"{r}:{c}" for (r, c), m in results if m["failures"]]
    if failed:
        out.append(f"FAIL: {len(failed)} of {len(results)} columns outside the tolerance: "
                   + " ".join(failed))
    else:
        out.append(f"PASS: {len(results)} columns within the tolerance")
    return out


def plot_module():
    """matplotlib.pyplot (Agg), or BadInput when matplotlib is missing."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise BadInput("--plot needs matplotlib (the project venv: .venv/bin/python "
                       "app/spallbar_compare.py ...)") from None
    return plt


def columns(table, names, t_max=None):
    """The abscissa and the named columns of table up to t_max, as lists (a pass over it);
    a NaN row between blocks, so that a plotted line breaks there."""
    js = [0] + [table.names.index(n) for n in names]
    out = [[] for _ in js]
    prev = None
    for row in table.rows():
        if t_max is not None and row[0] > t_max:
            continue
        if prev is not None and row[0] < prev:
            for col in out:
                col.append(math.nan)
        prev = row[0]
        for col, j in zip(out, js):
            col.append(row[j])
    return out


def plot(plt, path, ref, cand, results, t_max):
    """One panel a column: the candidate's curve, the reference's points (up to t_max)."""
    rx, *rcols = columns(ref, [r for (r, _), _ in results], t_max)
    cx, *ccols = columns(cand, [c for (_, c), _ in results])
    fig, axes = plt.subplots(len(results), 1, figsize=(8, 2.6 * len(results)), squeeze=False,
                             sharex=True)
    for ax, ((r, c), m), ry, cy in zip(axes[:, 0], results, rcols, ccols):
        ax.plot(cx, cy, "-", lw=1.0, color="tab:blue", label="candidate")
        ax.plot(rx, ry, "o", ms=2.5, color="black", label="reference")
        ax.set_ylabel(c)
        ax.set_title(f"{r if r == c else r + ' vs ' + c}: {m['failures']} of {m['points']} "
                     f"points outside, rel L1 {m['l1']:.2e}", fontsize=9)
        ax.legend(loc="best", fontsize=8, frameon=False)
    axes[-1, 0].set_xlabel(ref.names[0])
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=110)
    except OSError as e:
        raise BadInput(f"--plot {path}: cannot write: {e.strerror}") from None


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("reference")
    p.add_argument("candidate")
    p.add_argument("--column", action="append", default=[], metavar="NAME[:CAND_NAME]")
    p.add_argument("--rtol", type=float, default=1e-6)
    p.add_argument("--atol", type=float, default=None)
    p.add_argument("--time-tol", type=float, default=0.0)
    p.add_argument("--t-max", type=float, default=None,
                   help="compare the reference's points up to this abscissa only")
    p.add_argument("--report", metavar="FILE")
    p.add_argument("--plot", metavar="FILE.png")
    p.add_argument("--quiet", action="store_true", help="no table on stdout, only the status")

    def usage_error(message):
        sys.stderr.write(f"{PROG}: {message}\n")
        sys.exit(2)
    p.error = usage_error
    args = p.parse_args(argv)
    try:
        for name, v in (("--rtol", args.rtol), ("--atol", args.atol),
                        ("--time-tol", args.time_tol)):
            if v is not None and (not math.isfinite(v) or v < 0):
                raise BadInput(f"{name} must be a finite number >= 0, got {v}")
        for option, path in (("--report", args.report), ("--plot", args.plot)):
            if path:
                writable(option, path)
        plt = plot_module() if args.plot else None
        files = [open_rewindable(args.reference), open_rewindable(args.candidate)]
        ref, cand = (Table(path, f) for path, f in zip((args.reference, args.candidate), files))
        pairs = pairs_to_compare(ref.names, cand.names, args.column)
        atols = ([args.atol] * len(pairs) if args.atol is not None else
                 default_atols(ref, [ref.names.index(r) for r, _ in pairs], args.t_max))
        ref = Table(args.reference, files[0])
        results = list(zip(pairs, compare(ref, cand, pairs, args.rtol, atols, args.time_tol,
                                          args.t_max)))
        lines = report_lines(args.reference, args.candidate, results, args)
        if plt:
            plot(plt, args.plot, *(Table(path, f) for path, f in
                                   zip((args.reference, args.candidate), files)),
                 results, args.t_max)
    except BadInput as e:
        sys.stderr.write(f"{PROG}: {e}\n")
        return 2
    if args.report:
        try:
            with open(args.report, "w") as f:
                f.write("\n".join(lines) + "\n")
        except OSError as e:
            sys.stderr.write(f"{PROG}: --report {args.report}: cannot write: {e.strerror}\n")
            return 2
    if not args.quiet:
        print("\n".join(lines))
    return 1 if any(m["failures"] for _, m in results) else 0


if __name__ == "__main__":
    sys.exit(main())
