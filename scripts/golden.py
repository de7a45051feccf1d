#!/usr/bin/env python3
"""Golden comparison: every observable output of two spallbar programs, byte for byte.

    golden.py --exe NEW (--ref-exe OLD | --ref-rev GIT_REV) [--work DIR] [--long]
              [--fuzz N] [--ranks 1,3] [--added] [--variants]

A refactoring that claims "no change in behaviour" (issue 18) runs this against the program
it started from. For each case both programs run in the same directory with the same
relative paths (the outputs name the deck's path), one after the other; then:

  * every output file (PREFIX.his/.prf/.evt/.frg, sweep tables, the decks' own output
    files) must be identical byte for byte;
  * HDF5 files (PREFIX.h5, PREFIX_sweep.h5, checkpoints) must show no difference under
    h5diff (data and attributes) and list the same objects (h5ls -r);
  * stdout must be identical but for the run time ("N steps in T s"), stderr (but for the
    progress lines of a batch log, which come with the seconds) and the exit
    status identical (the program's identity, version and sources' digest, is masked
    wherever it is written: a refactor changes it by definition), and the same set of files left behind (empty PREFIX.lock files aside).

--added: for a change that adds outputs and claims to change nothing else (issue 31: new
history and sweep columns, a new deck variable echoed in every header, new event kinds): the
text outputs are compared without their '#' header lines, a table with a column-name line
by the old program's columns only (the new one may have more, anywhere), each value's text
exactly; HDF5 files by every dataset and attribute of the old file, to the bit, in the new
one (h5py). Exit status, stdout and stderr as always.

--variants: every deck of input/ also under the paper's event rules (events = 'paper'), in
the full-mass comparison model (model = 'full-mass') and in both: the decks of input/ use the
default rules and, but for one, the half-mass model, so a change to the rule sets
(src/model/spb_rules_*.f90) or to the full-mass model (spb_full_mass.f90) wants these too.

Cases: every deck under input/ (input/long/ with --long), HDF5 and x-t field variants of
four of them, a checkpointed run and each program's restart from its own checkpoint, a run the energy guard stops, the sweeps of input/sweeps/ on each rank count
(MPI ranks > 1 where the program was built with MPI), bad command lines, and N hostile
decks from tests/fuzz_decks.py (seeded). --ref-rev builds that revision's Release program
in DIR/ref-build first (a git worktree). Prints one line per difference and a summary;
exit 0 when there is none, 1 otherwise.
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tests"))

TIME_RE = re.compile(rb"steps in +[-+0-9.Ee]+ s")
# The program's identity (doc/build.md "Program identity"): a refactor changes the sources'
# digest by definition, so headers, stdout, --version and the HDF5 attributes that name the
# program are compared with it masked; everything else byte for byte.
IDENTITY_RE = re.compile(rb"spallbar \d+\.\d+\.\d+(?: \(source [0-9a-f]{12}\))?"
                         rb"(?: built from [^\n]*?(?= -- ))?")
SOURCES_RE = re.compile(rb"^  sources:  [^\n]*\n", re.MULTILINE)
# a progress line in a batch log (stderr not a terminal) comes after seconds of stepping: how
# many a run prints depends on the machine's speed, so stderr is compared without them
PROGRESS_RE = re.compile(rb"^spallbar: +[0-9.]+%  [^\n]* wall\)\n", re.MULTILINE)
IDENTITY_ATTRS = {"/": ("program", "revision", "checksum"), "/identity": ("program", "revision")}


def masked(data):
    """data with the program's identity replaced by 'spallbar IDENTITY'."""
    return SOURCES_RE.sub(b"", IDENTITY_RE.sub(b"spallbar IDENTITY", data))


def h5_attr_text(path):
    """The attributes of an HDF5 file as h5dump -A prints them, without the blocks of the
    attributes that name the program (IDENTITY_ATTRS): for a Python without h5py."""
    text = subprocess.run(["h5dump", "-A", path], capture_output=True, text=True).stdout
    skip = {n for names in IDENTITY_ATTRS.values() for n in names}
    out, dropping = [], None
    for line in text.splitlines():
        indent = len(line) - len(line.lstrip())
        if dropping is not None:
            if indent == dropping and line.strip() == "}":
                dropping = None
            continue
        m = re.match(r'\s*ATTRIBUTE "([^"]+)" \{', line)
        if m and m.group(1) in skip:
            dropping = indent
            continue
        out.append(line)
    return "\n".join(out[1:])     # the first line names the file


def h5_attrs_differ(a, b):
    """'' when the root and /identity attributes of two HDF5 files agree but for the
    program's identity (and the checkpoint's checksum, which counts it), else what differs."""
    try:
        import h5py
        import numpy as np
    except ImportError:
        return "" if h5_attr_text(a) == h5_attr_text(b) else "the attributes differ (h5dump -A)"
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        for path, skip in IDENTITY_ATTRS.items():
            if (path in fa) != (path in fb):
                return f"{path} in one file only"
            if path not in fa:
                continue
            ka = {k for k in fa[path].attrs if k not in skip}
            kb = {k for k in fb[path].attrs if k not in skip}
            if ka != kb:
                return f"{path} attributes {sorted(ka ^ kb)} in one file only"
            for k in ka:
                if not np.array_equal(np.asarray(fa[path].attrs[k]), np.asarray(fb[path].attrs[k])):
                    return f"{path} attribute {k} differs"
    return ""
HDF5_SUFFIXES = (".h5",)


def build_rev(rev, work):
    """Release build of a git revision of this repository; returns its executable."""
    src = os.path.join(work, "ref-src")
    build = os.path.join(work, "ref-build")
    if os.path.exists(src):
        subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", src],
                       capture_output=True)
        shutil.rmtree(src, ignore_errors=True)
    subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", src, rev], check=True,
                   capture_output=True)
    subprocess.run(["cmake", "-S", src, "-B", build, "-G", "Ninja",
                    "-DCMAKE_Fortran_COMPILER=gfortran", "-DCMAKE_BUILD_TYPE=Release",
                    "-DSPALLBAR_BUILD_TESTING=OFF"], check=True, capture_output=True)
    subprocess.run(["cmake", "--build", build, "-j", str(os.cpu_count() or 2)], check=True,
                   capture_output=True)
    # the program is built: the worktree goes (the repository keeps no trace of it)
    subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", src], capture_output=True)
    return os.path.join(build, "bin", "spallbar")


def snapshot(folder):
    """Relative paths of the files under folder (but the empty PREFIX.lock a run holds
    while it writes its outputs, issue 19: it carries no result)."""
    out = set()
    for d, _, files in os.walk(folder):
        for f in files:
            path = os.path.join(d, f)
            if f.endswith(".lock") and os.path.getsize(path) == 0:
                continue
            out.add(os.path.relpath(path, folder))
    return out


class Golden:
    def __init__(self, new, old, work, added=False):
        self.new, self.old, self.work = new, old, work
        self.added = added
        self.cases = 0
        self.diffs = []
        self.files_compared = 0

    def differ(self, case, what):
        self.diffs.append(f"{case}: {what}")
        print(f"DIFF {case}: {what}", flush=True)

    def run_both(self, case, setup, argv, cwd_rel=".", env=None, restart_from=None):
        """Run argv (the program first, as the placeholder EXE) in a fresh copy made by
        setup(folder) for each program; compare what each leaves."""
        self.cases += 1
        results = {}
        for tag, exe in (("old", self.old), ("new", self.new)):
            folder = os.path.join(self.work, "run")
            shutil.rmtree(folder, ignore_errors=True)
            os.makedirs(folder)
            self.current = exe   # a setup that runs the program itself reads it here
            setup(folder)
            if restart_from:
                restart_from(folder)
            before = snapshot(folder)
            cwd = os.path.join(folder, cwd_rel)
            cmd = [exe if a == "EXE" else a for a in argv]
            p = subprocess.run(cmd, cwd=cwd, capture_output=True, env=env, timeout=3600,
                               stdin=subprocess.DEVNULL)
            keep = os.path.join(self.work, tag)
            shutil.rmtree(keep, ignore_errors=True)
            shutil.move(folder, keep)
            results[tag] = (p.returncode, masked(TIME_RE.sub(b"steps in T s", p.stdout)),
                            masked(PROGRESS_RE.sub(b"", p.stderr)), snapshot(keep) - before)
        (rc_o, out_o, err_o, files_o), (rc_n, out_n, err_n, files_n) = results["old"], results["new"]
        if rc_o != rc_n:
            self.differ(case, f"exit status {rc_o} -> {rc_n}")
        if err_o != err_n:
            self.differ(case, f"stderr {err_o[:200]!r} -> {err_n[:200]!r}")
        if out_o != out_n:
            self.differ(case, f"stdout differs ({first_diff(out_o, out_n)})")
        if files_o != files_n:
            self.differ(case, f"files left: only old {sorted(files_o - files_n)}, only new "
                              f"{sorted(files_n - files_o)}")
        for rel in sorted(files_o & files_n):
            self.compare_file(case, rel)
        return results

    def compare_file(self, case, rel):
        a = os.path.join(self.work, "old", rel)
        b = os.path.join(self.work, "new", rel)
        self.files_compared += 1
        if self.added:
            why = added_only(a, b, rel.endswith(HDF5_SUFFIXES) or rel.endswith(".h5.part"))
            if why:
                self.differ(case, f"{rel}: {why}")
            return
        if rel.endswith(HDF5_SUFFIXES) or rel.endswith(".h5.part"):
            p = subprocess.run(["h5diff", "-c", "--exclude-attribute", "/", "--exclude-attribute",
                                "/identity", a, b], capture_output=True, text=True)
            if p.returncode != 0:
                self.differ(case, f"{rel}: h5diff: {p.stdout.strip()[:300]}")
            why = h5_attrs_differ(a, b)
            if why:
                self.differ(case, f"{rel}: {why}")
            la = subprocess.run(["h5ls", "-r", a], capture_output=True, text=True).stdout
            lb = subprocess.run(["h5ls", "-r", b], capture_output=True, text=True).stdout
            if la != lb:
                self.differ(case, f"{rel}: the objects differ (h5ls -r)")
            return
        with open(a, "rb") as fa, open(b, "rb") as fb:
            da, db = masked(fa.read()), masked(fb.read())
        if da != db:
            self.differ(case, f"{rel}: {first_diff(da, db)}")


def added_only(a, b, hdf5):
    """'' when b holds everything a holds (--added), else the first thing that differs."""
    if hdf5:
        import h5py
        import numpy as np
        with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
            names = []
            fa.visit(names.append)
            for name in [""] + names:
                obj = fa[name] if name else fa
                if name and name not in fb:
                    return f"/{name} is missing"
                other = fb[name] if name else fb
                for key, val in obj.attrs.items():
                    if key in IDENTITY_ATTRS.get("/" + name, ()):
                        continue
                    if key not in other.attrs:
                        return f"/{name} attribute {key} is missing"
                    if not np.array_equal(np.asarray(val), np.asarray(other.attrs[key])):
                        return f"/{name} attribute {key} differs"
                if isinstance(obj, h5py.Dataset):
                    va, vb = np.asarray(obj[()]), np.asarray(other[()])
                    same = va.dtype == vb.dtype and va.shape == vb.shape and \
                        va.tobytes() == vb.tobytes()
                    if not same:
                        return f"/{name} differs"
        return ""
    with open(a, "rb") as fa, open(b, "rb") as fb:
        la = [l for l in fa.read().splitlines() if not l.startswith(b"#")]
        lb = [l for l in fb.read().splitlines() if not l.startswith(b"#")]
    if len(la) != len(lb):
        return f"{len(la)} vs {len(lb)} lines without the headers"
    if not la:
        return ""
    ha, hb = la[0].split(), lb[0].split()
    named = ha and ha[0][:1].isalpha() and all(n in hb for n in ha)
    if not named:
        for k, (x, y) in enumerate(zip(la, lb)):
            if x != y:
                return f"line {k + 1} without the headers: {x[:100]!r} -> {y[:100]!r}"
        return ""
    cols = [hb.index(n) for n in ha]
    for k, (x, y) in enumerate(zip(la[1:], lb[1:])):
        wx, wy = x.split(), y.split()
        if len(wy) != len(hb) and len(wx) == len(ha):
            return f"row {k + 1}: {len(wy)} values, its header names {len(hb)}"
        if [wy[c] for c in cols if c < len(wy)] != wx:
            bad = [ha[i] for i, c in enumerate(cols) if c >= len(wy) or i >= len(wx) or wy[c] != wx[i]]
            return f"row {k + 1}: {', '.join(n.decode() for n in bad[:5])} differ"
    return ""


def first_diff(a, b):
    la, lb = a.splitlines(), b.splitlines()
    for k, (x, y) in enumerate(zip(la, lb)):
        if x != y:
            return f"line {k + 1}: {x[:120]!r} -> {y[:120]!r}"
    return f"{len(la)} vs {len(lb)} lines"


def copy_input(folder):
    shutil.copytree(os.path.join(ROOT, "input"), os.path.join(folder, "input"))


def add_to_run(text, extra):
    """The deck with extra assignments at the start of its &run group."""
    m = re.search(r"&run\b", text, re.IGNORECASE)
    if not m:
        return "&run " + extra + " /\n" + text
    return text[:m.end()] + "\n  " + extra + "\n" + text[m.end():]


def set_in_run(text, var, value):
    """The deck with var = value in its &run group: an assignment it has is replaced (a second
    one would be refused), else one is added at the group's start."""
    pat = re.compile(r"(\b" + var + r"\s*=\s*)('[^']*'|\"[^\"]*\")", re.IGNORECASE)
    if pat.search(text):
        return pat.sub(lambda m: m.group(1) + value, text, count=1)
    return add_to_run(text, f"{var} = {value}")


# --variants: the assignments each variant of a deck gets
VARIANTS = (("paper", (("events", "'paper'"),)),
            ("full_mass", (("model", "'full-mass'"),)),
            ("paper_full_mass", (("events", "'paper'"), ("model", "'full-mass'"))))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--ref-exe")
    ap.add_argument("--ref-rev")
    ap.add_argument("--work", default="golden_work")
    ap.add_argument("--long", action="store_true")
    ap.add_argument("--fuzz", type=int, default=200)
    ap.add_argument("--ranks", default="1,3")
    ap.add_argument("--variants", action="store_true",
                    help="every deck of input/ also with events = 'paper', model = 'full-mass' "
                         "and both (see above)")
    ap.add_argument("--added", action="store_true",
                    help="the new program adds columns, variables, kinds: compare the old "
                         "outputs' data within the new ones (see above)")
    a = ap.parse_args(argv[1:])
    work = os.path.abspath(a.work)
    os.makedirs(work, exist_ok=True)
    if a.ref_rev:
        old = build_rev(a.ref_rev, work)
    elif a.ref_exe:
        old = os.path.abspath(a.ref_exe)
    else:
        ap.error("--ref-exe or --ref-rev")
    g = Golden(os.path.abspath(a.exe), old, work, added=a.added)

    # every deck of input/
    decks = []
    for d, _, files in os.walk(os.path.join(ROOT, "input")):
        rel = os.path.relpath(d, os.path.join(ROOT, "input"))
        if rel.startswith("sweeps") or (rel.startswith("long") and not a.long):
            continue
        decks += [os.path.normpath(os.path.join(rel, f)) for f in sorted(files) if f.endswith(".nml")]
    for deck in sorted(decks):
        d, f = os.path.split(deck)
        g.run_both(f"deck {deck}", copy_input, ["EXE", f, "--output", "out_" + f[:-4]],
                   cwd_rel=os.path.join("input", d))
        for tag, assignments in (VARIANTS if a.variants else ()):
            def var_setup(folder, deck=deck, assignments=assignments):
                copy_input(folder)
                path = os.path.join(folder, "input", deck)
                text = open(path).read()
                for var, value in assignments:
                    text = set_in_run(text, var, value)
                open(path, "w").write(text)
            g.run_both(f"deck {deck} ({tag})", var_setup,
                       ["EXE", f, "--output", f"{tag}_" + f[:-4]], cwd_rel=os.path.join("input", d))

    # HDF5, x-t fields
    for deck in ("example2.nml", "example3_case1_delay.nml", "expanding_bar.nml",
                 "example3_case2/accelerate_fragment_h19.nml"):
        def setup(folder, deck=deck):
            copy_input(folder)
            path = os.path.join(folder, "input", deck)
            text = open(path).read()
            open(path, "w").write(add_to_run(text, "hdf5 = .true., field_every = 7"))
        d, f = os.path.split(deck)
        g.run_both(f"hdf5 {deck}", setup, ["EXE", f, "--output", "h5_" + f[:-4]],
                   cwd_rel=os.path.join("input", d))

    # a checkpointed run, and each program's restart from its own checkpoint (a checkpoint
    # of another program is refused since issue 32: doc/outputs.md)
    def ck_setup(folder, t_end="1.0e-3"):
        copy_input(folder)
        path = os.path.join(folder, "input", "example2.nml")
        lines = []
        for line in open(path).read().splitlines():
            if re.match(r"\s*t_end\s*=", line):
                line = f"  t_end = {t_end}"
            if not re.match(r"\s*profile_times\s*=", line):
                lines.append(line)
        open(path, "w").write(add_to_run("\n".join(lines) + "\n", "checkpoint = 'restart.h5', "
                                         "checkpoint_every = 40, hdf5 = .true., field_every = 9"))
    g.run_both("checkpoint example2", ck_setup, ["EXE", "example2.nml", "--output", "ck"],
               cwd_rel="input")

    def restart_setup(folder):
        ck_setup(folder)
        inp = os.path.join(folder, "input")
        subprocess.run([g.current, "example2.nml", "--output", "ck", "-q"], cwd=inp,
                       capture_output=True)
        ck_setup_more = open(os.path.join(inp, "example2.nml")).read()
        open(os.path.join(inp, "example2.nml"), "w").write(
            ck_setup_more.replace("t_end = 1.0e-3", "t_end = 2.0e-3"))
    g.run_both("restart from its own checkpoint", restart_setup,
               ["EXE", "example2.nml", "--output", "ck", "--restart", "restart.h5"],
               cwd_rel="input")

    # sweeps
    mpi = shutil.which("mpirun")
    for sweep in sorted(os.listdir(os.path.join(ROOT, "input", "sweeps"))):
        if not sweep.endswith(".nml"):
            continue
        for ranks in [int(r) for r in a.ranks.split(",")]:
            cmd = ["EXE", "--sweep", sweep, "--output", f"sw_{sweep[:-4]}", "-q"]
            if ranks > 1:
                if not mpi:
                    continue
                cmd = [mpi, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
            g.run_both(f"sweep {sweep} on {ranks} rank(s)", copy_input, cmd,
                       cwd_rel=os.path.join("input", "sweeps"))
            if ranks > 1:
                # the same with cases handed out one at a time
                def dyn_setup(folder, sweep=sweep):
                    copy_input(folder)
                    path = os.path.join(folder, "input", "sweeps", sweep)
                    text = open(path).read()
                    m = re.search(r"&sweep\b", text, re.IGNORECASE)
                    open(path, "w").write(text[:m.end()] + "\n  distribution = 'dynamic'\n" +
                                          text[m.end():])
                g.run_both(f"sweep {sweep} on {ranks} ranks, dynamic", dyn_setup, cmd,
                           cwd_rel=os.path.join("input", "sweeps"))

    # runs that end early: the energy guard (exit 3), a progress line on a terminal-less stderr
    guard_deck = ("&run t_end = 0.04, timing = 'accelerate', events = 'paper', history_every = 7,\n"
                  "     profile_times = 1e-3, 2e-3 /\n&mesh dt = 1e-5 /\n"
                  "&segments n = 2, length = 0.01, 0.01, young = 2e9, 2e9, density = 2000, 2000,\n"
                  "  strength = 0, 0, velocity = 1, -1 /\n")

    def guard_setup(folder):
        open(os.path.join(folder, "guard.nml"), "w").write(guard_deck)
    g.run_both("energy guard stop", guard_setup, ["EXE", "guard.nml"])

    # command lines
    for args in ([], ["--help"], ["--version"], ["nothere.nml"], ["example2.nml", "--bogus"],
                 ["example2.nml", "--output"], ["--sweep"], ["example2.nml", "--restart",
                                                              "missing.h5"]):
        g.run_both(f"command line {args}", copy_input, ["EXE"] + args, cwd_rel="input")

    # hostile decks (the fuzzer's generator, seeded)
    import fuzz_decks
    rng = random.Random(20261123)
    for k in range(a.fuzz):
        base = fuzz_decks.BASES[rng.randrange(len(fuzz_decks.BASES))]
        label, text, files, _, _ = fuzz_decks.mutations(rng, base)

        def setup(folder, text=text, files=files):
            for f, t in files.items():
                with open(os.path.join(folder, f), "w", encoding="latin-1") as fh:
                    fh.write(t)
            with open(os.path.join(folder, "deck.nml"), "wb") as fh:
                fh.write(text)
        g.run_both(f"fuzz case {k} ({label})", setup, ["EXE", "deck.nml"])

    print(f"golden: {g.cases} cases, {g.files_compared} output files compared, "
          f"{len(g.diffs)} differences (old {old}, new {g.new})")
    return 1 if g.diffs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
