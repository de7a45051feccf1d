#!/usr/bin/env python3
"""spallbar-compare: compare a candidate curve table with a reference, with tolerances.

    spallbar-compare REFERENCE CANDIDATE [--column NAME[:CAND_NAME]]... [--rtol R] [--atol A]
                     [--time-tol T] [--t-max T] [--report FILE] [--plot FILE.png] [--quiet]

REFERENCE and CANDIDATE are spallbar column outputs (.his, .gau, .sweep: `#` header lines,
the last one naming the columns) or plain tables `t value ...` (`#` or `!` comments, blanks
or commas between numbers, an optional first line naming the columns, Fortran `D`
exponents read): a digitised curve, a legacy printout. The first column is the abscissa.
A plain table without a header names its columns by position: 1 (the abscissa), 2, 3, ...

Each compared column (default: every column the two tables share but the abscissa; a
headerless two-column reference against a named candidate needs --column NAME, which maps
the reference's one value column to the candidate's NAME; --column 2:reaction_bottom maps
explicitly) is evaluated at the reference's abscissae, the candidate interpolated linearly
(at a repeated abscissa -- a jump -- the later row). A point passes when
    |c - r| <= atol + rtol |r|
(atol default: 1e-9 of the column's largest |r|, so round-off near a zero passes); with
--time-tol T it also passes when the candidate curve comes within that band somewhere within
+-T of the point's abscissa (a tube: timing differences within T pass; for curves read off a
figure), and the shift it needed is reported. A reference point outside the candidate's
abscissa range fails (unless the tube reaches it). --t-max T compares the reference's
points up to abscissa T only.

Prints per column: points, max absolute and relative error, relative L1 and L2 norms
(sum |c - r| / sum |r|, sqrt(sum (c - r)^2 / sum r^2)), failures, the largest time shift
used, and the first failing abscissa. Exit 0: every point of every column passes; 1: some
fail (the columns are named); 2: bad input (one line on stderr, nothing written).

Only the Python standard library is needed; --plot needs matplotlib (the project venv).
"""
import argparse
import bisect
import math
import sys

PROG = "spallbar-compare"


class BadInput(Exception):
    """Bad input: one line on stderr, exit 2."""


def _number(word):
    return float(word.replace("D", "E").replace("d", "e"))


def read_table(path):
    """(names, columns) of a spallbar column output or a plain table; columns are lists."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise BadInput(f"{path}: cannot read: {e.strerror}") from None
    names, rows, last_comment = None, [], None
    for k, line in enumerate(lines, 1):
        text = line.strip()
        if not text:
            continue
        if text[0] in "#!":
            last_comment = text[1:].strip()
            continue
        words = text.replace(",", " ").split()
        try:
            values = [_number(w) for w in words]
        except ValueError:
            if rows or names is not None:
                raise BadInput(f"{path}: line {k}: not a row of numbers: {text[:60]!r}") from None
            names = words            # a plain table's header line
            continue
        if not rows and names is None and last_comment:
            cand = last_comment.split()
            if len(cand) == len(values) and all(not _is_number(w) for w in cand):
                names = cand         # a spallbar output: the last '#' line names the columns
        if rows and len(values) != len(rows[0]):
            raise BadInput(f"{path}: line {k}: {len(values)} numbers, the first row has "
                           f"{len(rows[0])}")
        if not all(math.isfinite(v) for v in values):
            raise BadInput(f"{path}: line {k}: a value is not finite")
        rows.append(values)
    if not rows:
        raise BadInput(f"{path}: no rows of numbers")
    ncol = len(rows[0])
    if ncol < 2:
        raise BadInput(f"{path}: one column only; a table is 'abscissa value ...'")
    if names is None:
        names = [str(j + 1) for j in range(ncol)]
    if len(names) != ncol:
        raise BadInput(f"{path}: {len(names)} column names for {ncol} columns")
    if len(set(names)) != len(names):
        raise BadInput(f"{path}: a column name is repeated")
    columns = [[r[j] for r in rows] for j in range(ncol)]
    x = columns[0]
    if any(b < a for a, b in zip(x, x[1:])):
        raise BadInput(f"{path}: the abscissa ({names[0]}) decreases; the first column must "
                       "be non-decreasing")
    return names, columns


def _is_number(word):
    try:
        _number(word)
        return True
    except ValueError:
        return False


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
    return [(n, n) for n in common]


def interpolate(x, y, t):
    """y at t, linear between the rows around t; at a repeated abscissa the later row; None
    outside [x[0], x[-1]]."""
    if t < x[0] or t > x[-1]:
        return None
    k = bisect.bisect_right(x, t)
    if k >= len(x):
        return y[-1]
    if k == 0:
        return y[0]
    x0, x1 = x[k - 1], x[k]
    if x1 == x0:
        return y[k]
    w = (t - x0) / (x1 - x0)
    return y[k - 1] + w * (y[k] - y[k - 1])


def tube_shift(x, y, t, r, band, time_tol):
    """The smallest |tau - t| with tau in [t - T, t + T] and |c(tau) - r| <= band, c the
    candidate's piecewise-linear curve; None where there is none."""
    lo, hi = max(t - time_tol, x[0]), min(t + time_tol, x[-1])
    if lo > hi:
        return None
    best = None
    k0 = max(bisect.bisect_right(x, lo) - 1, 0)
    k1 = min(bisect.bisect_left(x, hi) + 1, len(x) - 1)
    for k in range(k0, k1):
        xa, xb = x[k], x[k + 1]
        if xb <= xa:
            continue
        a, b = max(xa, lo), min(xb, hi)
        if a > b:
            continue
        ya = y[k] + (a - xa) / (xb - xa) * (y[k + 1] - y[k])
        yb = y[k] + (b - xa) / (xb - xa) * (y[k + 1] - y[k])
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


def compare_column(xr, yr, xc, yc, rtol, atol, time_tol):
    """The measures of one column (a dict)."""
    scale = max(abs(v) for v in yr)
    if atol is None:
        atol = 1e-9 * scale
    n = len(xr)
    max_abs = max_rel = 0.0
    s_abs = s_ref = s_sq = s_refsq = 0.0
    failures, first_fail, max_shift, outside = 0, None, 0.0, 0
    for t, r in zip(xr, yr):
        c = interpolate(xc, yc, t)
        band = atol + rtol * abs(r)
        ok = c is not None and abs(c - r) <= band
        if c is None:
            outside += 1
        else:
            err = abs(c - r)
            max_abs = max(max_abs, err)
            if r != 0.0:
                max_rel = max(max_rel, err / abs(r))
            s_abs += err
            s_sq += err * err
        s_ref += abs(r)
        s_refsq += r * r
        if not ok and time_tol > 0.0:
            shift = tube_shift(xc, yc, t, r, band, time_tol)
            if shift is not None:
                ok = True
                max_shift = max(max_shift, shift)
        if not ok:
            failures += 1
            if first_fail is None:
                first_fail = t
    return {
        "points": n, "max_abs": max_abs, "max_rel": max_rel,
        "l1": s_abs / s_ref if s_ref > 0 else (0.0 if s_abs == 0 else math.inf),
        "l2": math.sqrt(s_sq / s_refsq) if s_refsq > 0 else (0.0 if s_sq == 0 else math.inf),
        "failures": failures, "first_fail": first_fail, "max_shift": max_shift,
        "outside": outside, "atol": atol,
    }


def report_lines(ref, cand, results, args):
    out = [f"# {PROG}: reference {ref}, candidate {cand}",
           f"# pass: |c - r| <= atol + rtol |r|, rtol = {args.rtol:g}, atol = "
           + (f"{args.atol:g}" if args.atol is not None else "1e-9 of each column's largest |r|")
           + (f"; tube +-{args.time_tol:g} in the abscissa" if args.time_tol > 0 else "")
           + (f"; up to {args.t_max:g}" if args.t_max is not None else ""),
           "| column | points | max abs error | max rel error | rel L1 | rel L2 | failures "
           "| largest time shift | first failure at |",
           "|---|---|---|---|---|---|---|---|---|"]
    for (r, c), m in results:
        name = r if r == c else f"{r}:{c}"
        first = "" if m["first_fail"] is None else f"{m['first_fail']:.6g}"
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


def plot(path, ref, cand, results, pairs):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise BadInput("--plot needs matplotlib (the project venv: .venv/bin/python "
                       "app/spallbar_compare.py ...)") from None
    (rn, rcols), (cn, ccols) = ref, cand
    fig, axes = plt.subplots(len(pairs), 1, figsize=(8, 2.6 * len(pairs)), squeeze=False,
                             sharex=True)
    for ax, ((r, c), m) in zip(axes[:, 0], results):
        ax.plot(ccols[0], ccols[cn.index(c)], "-", lw=1.0, color="tab:blue", label="candidate")
        ax.plot(rcols[0], rcols[rn.index(r)], "o", ms=2.5, color="black", label="reference")
        ax.set_ylabel(c)
        ax.set_title(f"{r if r == c else r + ' vs ' + c}: {m['failures']} of {m['points']} "
                     f"points outside, rel L1 {m['l1']:.2e}", fontsize=9)
        ax.legend(loc="best", fontsize=8, frameon=False)
    axes[-1, 0].set_xlabel(rn[0])
    fig.tight_layout()
    fig.savefig(path, dpi=110)


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
        ref = read_table(args.reference)
        cand = read_table(args.candidate)
        if args.t_max is not None:
            keep = [k for k, x in enumerate(ref[1][0]) if x <= args.t_max]
            if not keep:
                raise BadInput(f"--t-max {args.t_max:g}: no reference point up to it")
            ref = (ref[0], [[col[k] for k in keep] for col in ref[1]])
        pairs = pairs_to_compare(ref[0], cand[0], args.column)
        results = []
        for r, c in pairs:
            m = compare_column(ref[1][0], ref[1][ref[0].index(r)], cand[1][0],
                               cand[1][cand[0].index(c)], args.rtol, args.atol, args.time_tol)
            results.append(((r, c), m))
        lines = report_lines(args.reference, args.candidate, results, args)
        if args.plot:
            plot(args.plot, ref, cand, results, pairs)
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
