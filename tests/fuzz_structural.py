#!/usr/bin/env python3
"""Structural deck fuzzer (issue 19), independent of fuzz_decks.py.

fuzz_decks.py mutates decks at random; this one enumerates. It reads the list of every deck
variable from `spallbar --deck-help` (group, name) and injects into EACH of them EACH of:
+-huge (1e308, DBL_MAX), +-tiny (1e-308, DBL_MIN), denormals (4.9e-324, 1e-310), NaN,
+-Inf, 0, -0, an integer where a real belongs and a real where an integer belongs, an empty
value, a repeat count (3*x), subscripts beyond the array (or on a scalar); into every string
variable strings holding '&', '/', '&run ... /', doubled and unbalanced quotes of both kinds,
'!', a newline, TAB, BEL, 511/512/5000 characters. Then whole-deck mutations on every base:
a group repeated, a group inside a string or a comment, a '/' missing, '&end' and '$end'
terminators, '!' comments in odd places, CRLF and CR line ends, a UTF-8 BOM, garbage before
the first and after the last group, NUL bytes, an empty deck. &sweep variables go through
`spallbar --sweep` on a sweep base.

The contract (README, doc/deck.md) for every deck:
  exit 0   a valid deck, a full run;
  exit 2   exactly one stderr line 'spallbar: &group: ...' naming the group (and, for a
           one-variable mutation whose value the doc says is refused, the variable), and no
           file left behind (not even PREFIX.lock);
  exit 3   a run that went wrong, with a message.
Never another status, a signal, a gfortran runtime message, a hang. Some cases also have
an outcome the doc fixes (NaN in a real is refused; a title holding '&mesh ... /' is just a
title; '!' starts a comment): a different outcome is a violation too.

Outcomes are counted (exit 0 / exit 2 / exit 3 / violation); each violation is printed with
its deck, which is kept under WORKDIR/violations/. The test fails on any violation.

usage: fuzz_structural.py SPALLBAR WORKDIR [--count N] [--seed S] [--jobs J] [--timeout T]
  --count N   run N of the enumerated cases (a seeded sample; 0 or more than there are: all)
"""
import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import threading
import time

from clitools import Checks

RUNTIME_TEXT = ("Fortran runtime error", "Error allocating", "Program received signal",
                "Backtrace", "Fortran runtime warning", "Operating system error")

# Kind of every deck variable (group, name): real, int, logical, word (a keyword with a
# list of choices), text (free text or a path). Arrays are marked. --deck-help must not
# list a variable that is missing here (the fuzzer would silently skip it).
KINDS = {
    ("run", "title"): "text", ("run", "t_end"): "real", ("run", "gravity"): "real",
    ("run", "timing"): "word", ("run", "shift"): "word", ("run", "events"): "word",
    ("run", "eps_rel"): "real", ("run", "history_every"): "int",
    ("run", "profile_times"): "real", ("run", "hdf5"): "logical",
    ("run", "field_every"): "int", ("run", "model"): "word", ("run", "energy_guard"): "real",
    ("run", "checkpoint"): "text", ("run", "checkpoint_every"): "int", ("run", "warnings"): "logical",
    ("run", "header"): "word",
    ("mesh", "cells"): "int", ("mesh", "ref_segment"): "int", ("mesh", "dt"): "real",
    ("mesh", "fit"): "word",
    ("segments", "n"): "int", ("segments", "length"): "real", ("segments", "young"): "real",
    ("segments", "density"): "real", ("segments", "area"): "real",
    ("segments", "strength"): "real", ("segments", "fracture_energy"): "real",
    ("segments", "damage_integral"): "real", ("segments", "damage_exponent"): "real",
    ("segments", "interface"): "word", ("segments", "velocity"): "real",
    ("segments", "gap"): "real",
    ("ends", "top"): "word", ("ends", "bottom"): "word", ("ends", "base_gap"): "real",
    ("ends", "base_gap_top"): "real",
    ("load", "kind"): "word", ("load", "face"): "word", ("load", "p0"): "real",
    ("load", "t_k"): "real", ("load", "exponent"): "real", ("load", "t_cut"): "real",
    ("load", "table"): "text",
    ("initial", "state"): "word", ("initial", "strain_rate"): "real",
    ("strength_field", "kind"): "word", ("strength_field", "modulus"): "real",
    ("strength_field", "scale"): "real", ("strength_field", "seed"): "int",
    ("sweep", "realizations"): "int", ("sweep", "seed"): "int", ("sweep", "vary"): "text",
    ("sweep", "values"): "real", ("sweep", "distribution"): "word", ("sweep", "bins"): "int",
    ("sweep", "perturb"): "text", ("sweep", "spread"): "real",
    ("sweep", "ensemble_columns"): "text", ("sweep", "horizon_tol"): "real",
    ("gauges", "x"): "real", ("gauges", "every"): "int", ("gauges", "side"): "word",
    ("impactor", "face"): "word", ("impactor", "mass"): "real", ("impactor", "velocity"): "real",
    ("impactor", "gap"): "real", ("impactor", "cushion"): "real",
}
ARRAYS = {("run", "profile_times"): 100, ("segments", "length"): 100,
          ("segments", "young"): 100, ("segments", "density"): 100, ("segments", "area"): 100,
          ("segments", "strength"): 100, ("segments", "interface"): 100,
          ("segments", "fracture_energy"): 100, ("segments", "damage_integral"): 100,
          ("segments", "damage_exponent"): 100,
          ("segments", "velocity"): 100, ("segments", "gap"): 100, ("sweep", "values"): 1000,
          ("sweep", "ensemble_columns"): 16,
          ("gauges", "x"): 100, ("gauges", "side"): 100}

# Valid base decks, small and short (a few steps of 20-40 cells). The units are scaled so
# that a wave speed is ~1 m/s and a step ~0.1 s: an integer put into any real (t_end = 1)
# still means a handful of steps, never a run that would look like a hang.
# (name, [(group, [(variable, value text), ...]), ...], files, extra arguments)
BASES = [
    ("power_two", [
        ("run", [("title", "'structural power'"), ("t_end", "0.3"), ("gravity", "0.0"),
                 ("timing", "'accelerate'"), ("shift", "'fragment'"), ("events", "'admissible'"),
                 ("eps_rel", "1e-9"), ("history_every", "1"), ("profile_times", "0.1, 0.2"),
                 ("hdf5", ".false."), ("field_every", "0"), ("model", "'half-mass'"),
                 ("energy_guard", "0.5"), ("checkpoint", "''"), ("checkpoint_every", "0")]),
        ("mesh", [("cells", "20"), ("ref_segment", "1"), ("fit", "'strict'")]),
        ("segments", [("n", "2"), ("length", "1.0, 0.5"), ("young", "250.0, 250.0"),
                      ("density", "1000.0, 1000.0"), ("area", "1.0, 0.5"),
                      ("strength", "5.0, -1.0"), ("damage_integral", "0.5, 0.0"),
                      ("damage_exponent", "2.0, 1.5"),
                      ("interface", "'bonded'"), ("velocity", "0.0, 0.0"), ("gap", "0.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'free'"), ("base_gap", "0.0")]),
        ("load", [("kind", "'power'"), ("face", "'top'"), ("p0", "10.0"), ("t_k", "0.2"),
                  ("exponent", "1.0"), ("t_cut", "0.2")]),
        ("initial", [("state", "'unstressed'"), ("strain_rate", "0.0")]),
        ("strength_field", [("kind", "'uniform'"), ("seed", "1")]),
        ("gauges", [("x", "0.5, 1.0, 1.2"), ("every", "1"), ("side", "'above', 'below', 'above'")]),
    ], {}, []),
    ("table_base_hdf5", [
        ("run", [("title", "'structural table'"), ("t_end", "0.4"), ("gravity", "9.81"),
                 ("timing", "'delay'"), ("events", "'paper'"), ("hdf5", ".true."),
                 ("field_every", "2"), ("checkpoint", "'run.ck.h5'"), ("checkpoint_every", "2"),
                 ("profile_times", "0.2")]),
        ("mesh", [("dt", "0.1"), ("fit", "'stretch'")]),
        ("segments", [("n", "1"), ("length", "2.02"), ("young", "250.0"), ("density", "1000.0"),
                      ("strength", "50.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'base'"), ("base_gap", "0.0")]),
        ("load", [("kind", "'table'"), ("face", "'top'"), ("table", "'load.txt'")]),
        ("initial", [("state", "'static'")]),
        ("strength_field", [("kind", "'weibull'"), ("modulus", "6.0"), ("scale", "60.0"),
                            ("seed", "12345")]),
    ], {"load.txt": "# t [s]  p [Pa]\n0 0\n0.1 5\n0.3 0\n"}, []),
    ("exp_dry_transmit", [
        ("run", [("title", "\"structural exp\""), ("t_end", "0.5"), ("timing", "'min'"),
                 ("shift", "'above'"), ("energy_guard", "0.0"), ("history_every", "2")]),
        ("mesh", [("cells", "10"), ("ref_segment", "2")]),
        ("segments", [("n", "3"), ("length", "0.5, 1.0, 0.5"), ("young", "250.0, 1000.0, 250.0"),
                      ("density", "1000.0, 1000.0, 1000.0"), ("strength", "-1.0, 20.0, 20.0"),
                      ("interface", "'dry', 'bonded'"), ("gap", "0.01, 0.0"),
                      ("velocity", "0.1, 0.0, 0.0")]),
        ("ends", [("top", "'transmit'"), ("bottom", "'free'")]),
        ("load", [("kind", "'exponential'"), ("face", "'top'"), ("p0", "8.0"), ("t_k", "0.3"),
                  ("t_cut", "0.3")]),
        ("initial", [("strain_rate", "0.01")]),
    ], {}, []),
    ("none_full_mass", [
        ("run", [("t_end", "0.3"), ("model", "'full-mass'"), ("gravity", "1.0")]),
        ("mesh", [("cells", "20")]),
        ("segments", [("length", "1.0"), ("young", "250.0"), ("density", "1000.0"),
                      ("strength", "1.0"), ("velocity", "0.2")]),
        ("ends", [("top", "'fixed'"), ("bottom", "'fixed'")]),
        ("load", [("kind", "'none'")]),
    ], {}, []),
    # a striking mass (issue 33): a cushioned mass falling onto the top of a bar on the base
    ("impactor_cushion", [
        ("run", [("title", "'structural impactor'"), ("t_end", "0.4"), ("gravity", "9.81"),
                 ("history_every", "1")]),
        ("mesh", [("cells", "20")]),
        ("segments", [("length", "1.0"), ("young", "250.0"), ("density", "1000.0"),
                      ("strength", "5.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'base'")]),
        ("initial", [("state", "'static'")]),
        ("impactor", [("face", "'top'"), ("mass", "200.0"), ("velocity", "1.0"),
                      ("gap", "0.01"), ("cushion", "1.0e4")]),
    ], {}, []),
    ("sweep", [
        ("run", [("title", "'structural sweep'"), ("t_end", "0.3")]),
        ("mesh", [("cells", "20")]),
        ("segments", [("n", "2"), ("length", "1.0, 0.5"), ("young", "250.0, 250.0"),
                      ("density", "1000.0, 1000.0"), ("strength", "5.0, 5.0")]),
        ("load", [("kind", "'power'"), ("p0", "10.0"), ("t_k", "0.2"), ("exponent", "1.0")]),
        ("strength_field", [("kind", "'weibull'"), ("modulus", "6.0"), ("scale", "5.0"),
                            ("seed", "3")]),
        ("sweep", [("realizations", "2"), ("seed", "7"), ("vary", "'p0'"),
                   ("values", "10.0, 20.0"), ("distribution", "'static'"), ("bins", "10")]),
    ], {}, ["--sweep"]),
    # an ensemble (issue 34): p0 perturbed, two history columns sampled
    ("sweep_perturb", [
        ("run", [("title", "'structural ensemble'"), ("t_end", "0.3")]),
        ("mesh", [("cells", "20")]),
        ("segments", [("length", "1.0"), ("young", "250.0"), ("density", "1000.0"),
                      ("strength", "5.0")]),
        ("load", [("kind", "'power'"), ("p0", "10.0"), ("t_k", "0.2"), ("exponent", "1.0")]),
        ("sweep", [("perturb", "'p0'"), ("spread", "1.0e-3"), ("realizations", "2"),
                   ("seed", "7"), ("ensemble_columns", "'reaction_bottom', 'e_wave'"),
                   ("horizon_tol", "0.01")]),
    ], {}, ["--sweep"]),
]
BASE = {b[0]: b for b in BASES}

# Numbers put into every variable, whatever its kind: (label, text, refused for a real).
NUMBERS = [
    ("huge", "1e308", True), ("-huge", "-1e308", True),
    ("dbl_max", "1.7976931348623157e308", True), ("-dbl_max", "-1.7976931348623157e308", True),
    ("tiny", "1e-308", True), ("-tiny", "-1e-308", True),
    ("dbl_min", "2.2250738585072014e-308", True), ("-dbl_min", "-2.2250738585072014e-308", True),
    ("denormal", "4.9e-324", True), ("-denormal", "-4.9e-324", True),
    ("denormal2", "1e-310", True), ("nan", "NaN", True), ("-nan", "-NaN", True),
    ("inf", "Inf", True), ("-inf", "-Inf", True), ("infinity", "+Infinity", True),
    ("zero", "0", False), ("-zero", "-0", False), ("-zero_real", "-0.0", False),
    ("underflow", "1e-400", True), ("-underflow", "-1e-400", True),
    ("d_exponent", "1d308", True), ("below_range", "9.99e-61", True),
    ("above_range", "1.01e60", True),
]
# the numbers also put into logicals and strings (the others only add digits there)
NUMBERS_ANY_KIND = {"huge", "-huge", "tiny", "-tiny", "denormal", "nan", "inf", "-inf", "zero",
                    "-zero"}
# Strings put into every string variable: (label, text, a title holding it is valid).
LONG = 5000
STRINGS = [
    ("amp", "'a & b'", True), ("slash", "'a / b'", True), ("amp_run", "'&run'", True),
    ("group_text", "'&run t_end = 1 /'", True), ("group_text2", "'see &mesh cells = 3 /'", True),
    ("end_text", "'x &end'", True), ("doubled_single", "'it''s'", True),
    ("doubled_double", '"say ""hi"""', True), ("other_quote_in_single", "'say \"hi\"'", True),
    ("other_quote_in_double", "\"it's\"", True), ("only_doubled", "''''", True),
    ("unbalanced_single", "'open", False), ("unbalanced_double", '"open', False),
    ("mixed_quotes", "'open\"", False), ("bang", "'wow! not a comment'", True),
    ("bang_slash", "'! /'", True), ("empty", "''", True), ("blank", "'   '", True),
    ("newline", "'line one\nline two'", None), ("crlf_in_string", "'a\r\nb'", None),
    ("tab", "'a\tb'", None), ("bel", "'a\x07b'", False), ("esc", "'a\x1bb'", False),
    ("del", "'a\x7fb'", False), ("nul", "'a\x00b'", False),
    ("len511", "'" + "x" * 511 + "'", True), ("len512", "'" + "x" * 512 + "'", False),
    ("len5000", "'" + "y" * LONG + "'", False), ("len5000_dq", '"' + "&/'" * (LONG // 3) + '"',
                                                   False),
    ("unquoted", "free", None), ("unquoted_slash", "a/b", False),
    ("unquoted_amp", "a&b", None), ("two_strings", "'a' 'b'", None),
    ("utf8", "'\u00e9t\u00e9 \u2013 \u03c3'", None),
]
# strings put only into free-text variables (title, paths, vary): a keyword refuses them all
TEXT_ONLY = {"esc", "del", "nul", "crlf_in_string", "blank", "only_doubled", "len5000_dq",
             "two_strings", "utf8", "other_quote_in_double", "end_text", "len511"}
# strings also put into numeric and logical variables (they must not confuse the scanner)
STRINGS_IN_NUMBERS = {"group_text", "unbalanced_single", "unbalanced_double", "unquoted_slash",
                      "amp", "bang_slash"}


def render(groups, eol="\n"):
    out = []
    for g, items in groups:
        out.append(f"&{g}")
        out += [f"  {v} = {t}" for v, t in items]
        out.append("/")
    return eol.join(out) + eol


def deck_variables(exe):
    """[(group, name)] in the order --deck-help lists them."""
    r = subprocess.run([exe, "--deck-help"], capture_output=True, text=True, timeout=60,
                       stdin=subprocess.DEVNULL)
    out, group = [], None
    for line in r.stdout.splitlines():
        m = re.match(r"^&(\w+)\s*$", line)
        if m:
            group = m.group(1).lower()
            continue
        if line.strip() == "/":
            group = None
            continue
        m = re.match(r"^\s+(\w+)\s+=", line)
        if m and group:
            out.append((group, m.group(1).lower()))
    return r.returncode, out


def unquote(text):
    """The value of a quoted Fortran string: outer quotes off, the doubled one undoubled."""
    q = text[0]
    return text[1:-1].replace(q + q, q)


class Case:
    def __init__(self, label, base, text, group=None, var=None, expect=None, files=None,
                 why=""):
        self.label = label          # mutation family and details
        self.base = base            # base deck name
        self.text = text            # the deck (str or bytes)
        self.group = group          # the group a refusal must name (None: any, or 'deck')
        self.var = var              # the variable a refusal must name (None: not checked)
        self.expect = expect        # None, 0 or 2: the outcome the doc fixes
        self.files = BASE[base][2] if files is None else files
        self.args = BASE[base][3]
        self.why = why              # the doc's reason for expect
        self.title = None           # on exit 0: the title the outputs must echo


def base_holding(rng, group, var):
    """A base deck that gives var (or at least has its group)."""
    has = [b for b in BASES if any(g == group and any(v == var for v, _ in items)
                                   for g, items in b[1])]
    if group != "sweep":
        has = [b for b in has if "--sweep" not in b[3]]
    if not has:
        has = [b for b in BASES if any(g == group for g, _ in b[1])
               and (group == "sweep") == ("--sweep" in b[3])]
    return rng.choice(has)


def with_value(groups, group, var, lhs, value):
    """The base with `var = ...` replaced by `lhs = value` (added if the base lacks it)."""
    out, done = [], False
    for g, items in groups:
        new = []
        for v, t in items:
            if g == group and v == var:
                new.append((lhs, value))
                done = True
            else:
                new.append((v, t))
        if g == group and not done:
            new.append((lhs, value))
            done = True
        out.append((g, new))
    return out


def current(groups, group, var):
    for g, items in groups:
        for v, t in items:
            if g == group and v == var:
                return t
    return None


def variable_cases(rng, variables):
    """Every injection into every variable, each on one base that gives the variable."""
    cases = []
    for group, var in variables:
        kind = KINDS[(group, var)]
        array = (group, var) in ARRAYS
        name, groups, _, _ = base_holding(rng, group, var)
        old = current(groups, group, var)
        rest = ""
        if array and old is not None and "," in old:
            rest = old[old.index(",") :]          # keep the other elements valid

        def add(label, value, expect=None, strict=False, why="", lhs=None):
            g = with_value(groups, group, var, lhs or var, value)
            named = strict or expect == 2
            cases.append(Case(f"{label} -> &{group} {lhs or var}", name, render(g),
                              group if named else None, var if named else None, expect,
                              why=why))

        for label, text, refused in NUMBERS:
            if kind not in ("real", "int") and label not in NUMBERS_ANY_KIND:
                continue
            if kind == "real":
                exp = 2 if refused else None
                why = "doc: every real is finite and 0 or 1e-60..1e60 in magnitude"
            elif kind == "int":
                exp = None if label in ("zero", "-zero") else 2
                why = "doc: wrong types are refused (not an integer)"
            elif kind == "word":
                exp, why = 2, "doc: choices outside their lists are refused"
            else:
                exp, why = None, ""
            add(f"number {label}", text + rest, exp, why=why)
        # a type of the neighbouring kind
        if kind == "real":
            add("integer for a real", "1" + rest)
            add("integer for a real (2**32)", "4294967296" + rest)
        if kind == "int":
            add("real for an integer", "1.0", 2, why="doc: wrong types are refused")
            add("real for an integer (fraction)", "20.5", 2, why="doc: wrong types are refused")
            add("integer beyond int32", "2147483648", 2, why="doc: wrong types are refused")
            add("integer beyond int64", "99999999999999999999", 2,
                why="doc: wrong types are refused")
        if kind == "logical":
            add("integer for a logical", "1", 2, why="doc: wrong types are refused")
            add("real for a logical", "1.0", 2, why="doc: wrong types are refused")
        if kind in ("word", "text"):
            add("integer for a string", "1")
        add("empty value", rest.lstrip(", ") and (", " + rest.lstrip(", ")) or "")
        # repeat counts
        one = {"real": "1.0", "int": "1", "logical": "T", "word": "'x'", "text": "'x'"}[kind]
        if kind == "word" and old:
            one = old.split(",")[0].strip()
        add("repeat count 3*", f"3*{one}", 2 if not array else None,
            why="a scalar cannot take three values")
        add("repeat count 1*", f"1*{one}")
        add("repeat count 0*", f"0*{one}")
        add("repeat count null 3*", "3*")
        add("repeat count huge", f"2147483647*{one}", 2,
            why="more values than any variable holds")
        # subscripts
        if array:
            size = ARRAYS[(group, var)]
            for sub in ("0", "-1", str(size + 1), "100000", "2147483648", f"1:{size + 50}",
                        f"{size}:{size + 1}"):
                add(f"subscript ({sub})", one, 2, lhs=f"{var}({sub})",
                    why="doc: values beyond the arrays are refused")
        else:
            for sub in ("1", "2"):
                add(f"subscript on a scalar ({sub})", one, 2, lhs=f"{var}({sub})",
                    why="a scalar has no elements")
        # strings
        for label, text, title_ok in STRINGS:
            if kind not in ("word", "text") and label not in STRINGS_IN_NUMBERS:
                continue
            if kind != "text" and label in TEXT_ONLY:
                continue
            if kind in ("real", "int", "logical"):
                exp, why = 2, "doc: wrong types are refused"
            elif label in ("bel", "esc", "del", "nul"):
                exp, why = 2, "doc: control characters anywhere are refused"
            elif label in ("len512", "len5000", "len5000_dq"):
                exp, why = 2, "doc: strings longer than 511 characters are refused"
            elif label in ("unbalanced_single", "unbalanced_double", "mixed_quotes"):
                exp, why = 2, "doc: unterminated strings are refused"
            elif (group, var) == ("run", "title") and title_ok:
                exp, why = 0, "doc: a group's text ends at '/' outside strings; any title runs"
            elif (group, var) in (("segments", "interface"), ("gauges", "side")) and \
                    label == "empty":
                # an interface element left empty is one not given: 'bonded' (doc/deck.md);
                # a side left empty is one not given: a hole, or the default 'above'
                exp, why = None, "doc: an empty element is one not given"
            elif kind == "word" and label not in ("unquoted",):
                exp, why = 2, "doc: choices outside their lists are refused"
            else:
                exp, why = None, ""
            # an unquoted '&' or '/' ends the group, an unbalanced quote the deck: those
            # refusals rightly name the group's text, not the variable
            strict = exp == 2 and label not in ("unbalanced_single", "unbalanced_double",
                                                "mixed_quotes", "unquoted_slash",
                                                "unquoted_amp")
            g = with_value(groups, group, var, var, text + (rest if kind != "text" else ""))
            cases.append(Case(f"string {label} -> &{group} {var}", name, render(g),
                              group if strict else None, var if strict else None, exp,
                              why=why))
            if (group, var) == ("run", "title") and exp == 0:
                cases[-1].title = unquote(text)
    return cases


def deck_cases(rng):
    """Whole-deck structure on every base."""
    cases = []
    for name, groups, _, _ in BASES:
        first = len(cases)
        text = render(groups)
        gnames = [g for g, _ in groups]

        def add(label, t, group=None, expect=None, why=""):
            cases.append(Case(label, name, t, group, None, expect, why=why))

        add("valid base", text, None, 0, "a base deck is valid")
        for k, (g, items) in enumerate(groups):
            add(f"group &{g} repeated", render(groups[:k + 1] + [groups[k]] + groups[k + 1:]),
                g, 2, "doc: a group given twice is refused")
            add(f"group &{g} repeated empty", render(groups) + f"&{g} /\n", g, 2,
                "doc: a group given twice is refused")
            lines = render([(g, items)]).splitlines()
            nosl = "\n".join(lines[:-1]) + "\n"
            add(f"'/' of &{g} missing", render(groups[:k]) + nosl + render(groups[k + 1:]), g, 2,
                "doc: a group not terminated is refused")
            add(f"&{g} in a comment", render(groups[:k]) + f"! &{g} x = 1 /\n" +
                render(groups[k:]), None, 0, "doc: '!' starts a comment")
        add("group inside the title", render(with_value(
            groups, "run", "title", "title", "'&mesh cells = 3 /'")), None, 0,
            "doc: title = 'see &mesh cells = 3 /' is a title and nothing else")
        cases[-1].title = "&mesh cells = 3 /"
        add("&end terminators", text.replace("\n/\n", "\n&end\n"))
        add("$group $end style", re.sub(r"(?m)^&", "$", text).replace("\n/\n", "\n$end\n"))
        add("'/' on the last value's line", re.sub(r"\n/\n", " /\n", text), None, 0,
            "namelist syntax")
        add("all on one line", text.replace("\n", " ") + "\n", None, 0, "namelist syntax")
        add("no newline at the end", text.rstrip("\n"), None, 0, "namelist syntax")
        add("uppercase", text.upper().replace(".TRUE.", ".true.").replace(".FALSE.", ".false."))
        add("comment before the first group", "! deck & / ' \" \n" + text, None, 0,
            "doc: '!' starts a comment")
        add("comment after each group name", re.sub(r"(?m)^(&\w+)$", r"\1 ! name", text), None,
            0, "doc: '!' starts a comment")
        add("comment after each value", re.sub(r"(?m)^(  \w+ = .*)$", r"\1 ! it's a/b &x",
                                               text), None, 0, "doc: '!' starts a comment")
        add("comment on each '/' line", text.replace("\n/\n", "\n/ ! end 'q\n"), None, 0,
            "doc: '!' starts a comment")
        add("comment lines with quotes", re.sub(r"(?m)^(  \w+ = )", r"! don't\n\1", text),
            None, 0, "doc: '!' starts a comment")
        add("comment after the last group", text + "! the end &run /\n", None, 0,
            "doc: '!' starts a comment")
        add("comment between name and '='", re.sub(r"(?m)^  (\w+) = ", r"  \1 ! c\n = ", text,
                                                   count=2))
        add("comment between '=' and value", re.sub(r"(?m)^  (\w+) = ", r"  \1 = ! c\n ", text,
                                                    count=2))
        add("'!' inside a group name", text.replace("&" + gnames[0], "&" + gnames[0][:1] + "!"
                                                    + gnames[0][1:], 1), None, 2,
            "the group's name is broken")
        add("CRLF line ends", text.replace("\n", "\r\n"))
        add("CR line ends", text.replace("\n", "\r"))
        add("UTF-8 BOM", "\ufeff" + text, None, 0, "doc: a UTF-8 BOM is read as nothing")
        add("UTF-8 BOM + CRLF", "\ufeff" + text.replace("\n", "\r\n"), None, 0,
            "doc: a UTF-8 BOM is read as nothing")
        for junk in ("junk", "/", "&", "x = 1", "'str'", "&run", "1e308", "!\x07", "\x00",
                     "&" + gnames[-1] + " /junk"):
            add(f"trailing garbage {junk!r}", text + junk + "\n", None, 2,
                "doc: text outside groups is refused")
        add("trailing garbage, no newline", text + "junk", None, 2,
            "doc: text outside groups is refused")
        add("leading garbage", "junk\n" + text, None, 2, "doc: text outside groups is refused")
        add("stray word after a group name", text.replace("&" + gnames[0], "&" + gnames[0]
                                                          + " stray", 1), gnames[0], 2,
            "doc: stray words between a group's name and its first assignment are refused")
        add("nested group", text.replace("\n/\n", "\n&" + gnames[0] + "\n/\n", 1), None, 2,
            "a group opened inside another")
        add("lone '&' inside a group", re.sub(r"(?m)^(  \w+ = .*)$", r"\1 &", text, count=1),
            None, 2, "a bare '&' is no value")
        add("NUL byte inside a group", text.replace("\n/\n", "\n\x00\n/\n", 1), None, 2,
            "doc: control characters anywhere are refused")
        add("only comments", "! nothing\n! here\n", "run", 2, "doc: &run is required")
        add("only a BOM", "\ufeff", None, 2, "doc: &run is required")
        add("group names only", "".join(f"&{g}\n/\n" for g in gnames), None, 2,
            "doc: t_end is required")
        add("very long line", text.replace("\n/\n", "\n" + " " * 200000 + "\n/\n", 1))
        add("deck of 5000 groups", text + "&gizmo /\n" * 5000, None, 2,
            "doc: unknown groups are refused")
        if "--sweep" in BASE[name][3]:
            # --sweep starts MPI (~0.4 s a run): on the sweep base only what concerns &sweep
            # and the text as a whole
            cases[first:] = [c for c in cases[first:] if "&sweep" in c.label or c.label in (
                "valid base", "group inside the title", "&end terminators", "CRLF line ends",
                "UTF-8 BOM", "comment after each value", "trailing garbage 'junk'",
                "all on one line")]
            # the sweep deck without --sweep, and an ordinary deck with it
            cases.append(Case("sweep deck without --sweep", name, text, "sweep", None, 2,
                              files={}, why="doc: an ordinary run of a sweep deck is refused"))
            cases[-1].args = []
        else:
            c = Case("--sweep without &sweep", name, text, "sweep", None, 2,
                     why="doc: --sweep without &sweep is refused")
            c.args = ["--sweep"]
            cases.append(c)
    return cases


def table_cases():
    """The load table is a deck input as well: its structure."""
    tables = {"ok": "0 0\n0.1 5\n0.3 0\n", "crlf": "0 0\r\n0.1 5\r\n0.3 0\r\n",
              "bom": "\ufeff0 0\n0.1 5\n", "nan": "0 0\n0.1 NaN\n", "huge": "0 0\n0.1 1e308\n",
              "tiny": "0 0\n0.1 1e-308\n", "denormal": "0 0\n0.1 4.9e-324\n",
              "inf_time": "0 0\nInf 5\n", "slash": "0 0\n0.1 5 /\n", "repeat": "0 0\n2*0.1\n",
              "amp": "&load\n0 0\n", "quote": "'0' 0\n", "tab": "0\t0\n0.1\t5\n",
              "bel": "0 0\n0.1 5\x07\n", "long_row": "0 " + "0" * 2000 + "\n",
              "empty": "", "comma": "0,0\n0.1,5\n", "three": "0 0 0\n", "minus_zero": "-0 -0\n",
              "tab_line": "0 0\n\t\n0.1 5\n"}
    valid = {"ok", "crlf", "tab", "comma", "minus_zero", "bom", "tab_line"}
    cases = []
    for label, t in tables.items():
        cases.append(Case(f"load table {label}", "table_base_hdf5",
                          render(BASE["table_base_hdf5"][1]),
                          "load" if label not in valid else None,
                          "table" if label not in valid else None,
                          None if label in valid | {"crlf", "bom"} else 2,
                          files={"load.txt": t}, why="doc: a malformed load table is refused"))
    return cases


def run_case(exe, work, idx, case, timeout, slots):
    with slots["--sweep" in case.args]:
        return run_one(exe, work, idx, case, timeout)


def run_one(exe, work, idx, case, timeout):
    folder = os.path.join(work, f"case{idx:05d}")
    os.makedirs(folder)
    for f, t in case.files.items():
        with open(os.path.join(folder, f), "w", encoding="utf-8", newline="") as fh:
            fh.write(t)
    data = case.text if isinstance(case.text, bytes) else case.text.encode("utf-8")
    with open(os.path.join(folder, "deck.nml"), "wb") as fh:
        fh.write(data)
    before = set(os.listdir(folder))
    t0 = time.monotonic()
    env = None
    if "--sweep" in case.args:
        # one rank (an MPI singleton): Open MPI starts faster without its network layers
        env = dict(os.environ)
        env.setdefault("OMPI_MCA_pml", "ob1")
        env.setdefault("OMPI_MCA_btl", "self")
    try:
        r = subprocess.run([exe] + case.args + ["deck.nml", "-q"], cwd=folder, env=env,
                           capture_output=True, timeout=timeout, stdin=subprocess.DEVNULL)
        rc, out, err = r.returncode, r.stdout.decode("utf-8", "replace"), \
            r.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        rc, out = None, (e.stdout or b"").decode("utf-8", "replace")
        err = (e.stderr or b"").decode("utf-8", "replace")
    left = sorted(set(os.listdir(folder)) - before)
    return folder, rc, out, err, left, time.monotonic() - t0


def names(line, word):
    return re.search(r"(?<![a-z0-9_])" + re.escape(word.lower()) + r"(?![a-z0-9_])",
                     line.lower()) is not None


def echoed_title(folder):
    """The title in the header of PREFIX.his (None: no such line)."""
    try:
        with open(os.path.join(folder, "deck.his"), encoding="utf-8", errors="replace") as fh:
            for line in fh:
                if line.startswith("# title: "):
                    return line[len("# title: "):].rstrip("\n")
                if line.startswith(" "):
                    break
    except OSError:
        pass
    return None


def judge(case, rc, out, err, left, folder):
    """(outcome, [problems]); outcome in 'exit 0', 'exit 2', 'exit 3', 'violation'."""
    bad = []
    if rc == 0 and case.title is not None and "--sweep" not in case.args:
        got = echoed_title(folder)
        if got is None or got.rstrip(" ") != case.title.rstrip(" "):   # Fortran trims
            bad.append(f"PREFIX.his echoes the title as {got!r}, the deck gives {case.title!r}")
    lines = err.splitlines()
    for t in RUNTIME_TEXT:
        if t in err or t in out:
            bad.append(f"gfortran runtime text {t!r}")
    if rc is None:
        bad.append("timed out (hang)")
    elif rc < 0:
        bad.append(f"killed by signal {-rc}")
    elif rc not in (0, 2, 3):
        bad.append(f"exit status {rc}")
    if rc == 2:
        if len(lines) != 1:
            bad.append(f"{len(lines)} stderr lines, expected exactly 1")
        first = lines[0] if lines else ""
        m = re.match(r"^spallbar: &(\w+)", first)
        if not m and not (case.group is None and first.startswith("spallbar: deck")):
            bad.append("the stderr line does not start with 'spallbar: &group:'")
        if case.group is not None and not (m and m.group(1).lower() == case.group):
            bad.append(f"the stderr line does not name &{case.group}")
        if case.var is not None and not names(first, case.var):
            bad.append(f"the stderr line does not name {case.var}")
        if left:
            bad.append(f"files left behind: {left}")
    if rc == 3 and not err.strip():
        bad.append("exit 3 without a message")
    if rc in (0, 2) and case.expect is not None and rc != case.expect:
        bad.append(f"exit {rc}, expected {case.expect} ({case.why})")
    if bad:
        return "violation", bad
    return f"exit {rc}", []


def snippet(case):
    """The mutated line(s) of the deck, shortened."""
    text = case.text if isinstance(case.text, str) else case.text.decode("utf-8", "replace")
    m = re.search(r"-> &(\w+) (\S+)", case.label)
    if m:
        var = re.escape(m.group(2).split("(")[0])
        hit = re.search(r"(?m)^  " + var + r"\b.*$", text)
        if hit:
            s = text[hit.start():hit.start() + 160]
            return repr(s if len(s) < 160 else s + "...")
    return repr(text[:300] + ("..." if len(text) > 300 else ""))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("exe")
    p.add_argument("work")
    p.add_argument("--count", type=int, default=0, help="cases to run (0: all)")
    p.add_argument("--seed", type=int, default=19)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--timeout", type=float, default=60.0, help="seconds per case")
    args = p.parse_args()
    exe = os.path.abspath(args.exe)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    check = Checks()
    rng = random.Random(args.seed)
    t_start = time.monotonic()

    rc, variables = deck_variables(exe)
    check(rc == 0 and variables, f"--deck-help: exit {rc}, {len(variables)} variables")
    unknown = [gv for gv in variables if gv not in KINDS]
    check(not unknown, f"--deck-help lists variables this fuzzer does not know: {unknown}")
    variables = [gv for gv in variables if gv in KINDS]
    missing = sorted(set(KINDS) - set(variables))
    check(not missing, f"variables not listed by --deck-help: {missing}")
    groups_seen = sorted({g for g, _ in variables})

    cases = variable_cases(rng, variables) + deck_cases(rng) + table_cases()
    total = len(cases)
    if 0 < args.count < total:
        keep = [c for c in cases if c.label == "valid base"]
        rest = [c for c in cases if c.label != "valid base"]
        cases = keep + random.Random(args.seed).sample(rest, max(0, args.count - len(keep)))
    print(f"fuzz_structural: {len(variables)} variables in {len(groups_seen)} groups "
          f"({', '.join(groups_seen)}), {total} cases enumerated, running {len(cases)} "
          f"(seed {args.seed}, {args.jobs} jobs)", flush=True)

    tally, by_family, violations, timing, log = {}, {}, [], [], []
    # a --sweep run mostly waits for MPI to start (little CPU): more of them at a time
    slots = {False: threading.Semaphore(args.jobs), True: threading.Semaphore(3 * args.jobs)}
    with concurrent.futures.ThreadPoolExecutor(max_workers=4 * args.jobs) as pool:
        futs = {pool.submit(run_case, exe, args.work, k, c, args.timeout, slots): (k, c)
                for k, c in enumerate(cases)}
        for fut in concurrent.futures.as_completed(futs):
            k, case = futs[fut]
            folder, rc, out, err, left, secs = fut.result()
            outcome, bad = judge(case, rc, out, err, left, folder)
            tally[outcome] = tally.get(outcome, 0) + 1
            timing.append((secs, k, case.label, case.base))
            first = err.strip().splitlines()[0] if err.strip() else ""
            log.append(f"{k}\t{outcome}\t{rc}\t{case.base}\t{case.label}\t{first[:200]}")
            fam = case.label.split(" -> ")[0].split(" (")[0]
            fam = re.sub(r"^(number|string|load table) .*", r"\1", fam)
            by_family.setdefault(fam, {}).setdefault(outcome, 0)
            by_family[fam][outcome] += 1
            if bad:
                keep = os.path.join(args.work, "violations", f"case{k:05d}")
                os.makedirs(os.path.dirname(keep), exist_ok=True)
                shutil.move(folder, keep)
                with open(os.path.join(keep, "what.txt"), "w") as fh:
                    fh.write(f"{case.label}\nbase: {case.base}\nargs: {case.args}\n"
                             f"exit: {rc}\nproblems: {bad}\nstderr:\n{err}\n")
                violations.append((k, case, rc, err, bad, keep))
            else:
                shutil.rmtree(folder, ignore_errors=True)

    # every case's outcome and first stderr line, for a look at what the program says
    with open(os.path.join(args.work, "outcomes.tsv"), "w") as fh:
        fh.write("\n".join(sorted(log, key=lambda l: int(l.split("\t")[0]))) + "\n")
    for k, case, rc, err, bad, keep in sorted(violations, key=lambda v: v[0]):
        check(False, f"case {k}: {case.label} (base {case.base}{' ' + ' '.join(case.args) if case.args else ''}): "
              f"{'; '.join(bad)}\n    deck: {snippet(case)}\n    exit {rc}, stderr: "
              f"{err.strip()[:400]!r}\n    kept: {keep}")
    print("fuzz_structural: outcomes by family:")
    for fam in sorted(by_family):
        print(f"  {fam:42s} " + ", ".join(f"{o} {n}" for o, n in sorted(by_family[fam].items())))
    timing.sort(reverse=True)
    print("fuzz_structural: slowest: " + "; ".join(
        f"{t:.2f} s case {k} {lab} ({b})" for t, k, lab, b in timing[:3]) +
        f"; --sweep runs {sum(t for t, _, _, b in timing if b == 'sweep'):.1f} s, others "
        f"{sum(t for t, _, _, b in timing if b != 'sweep'):.1f} s (summed)")
    order = ["exit 0", "exit 2", "exit 3", "violation"]
    print(f"fuzz_structural: {len(cases)} decks (seed {args.seed}): " +
          ", ".join(f"{o}: {tally.get(o, 0)}" for o in order) +
          f"  [{time.monotonic() - t_start:.1f} s]")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
