"""Small helpers shared by the command-line tests (cli_*.py)."""
import os
import shutil
import subprocess


class Checks:
    """Counts checks, prints each failure, ends with the plain 'N passed, N failed' line."""

    def __init__(self):
        self.checks = 0
        self.failures = 0

    def __call__(self, cond, what):
        self.checks += 1
        if not cond:
            self.failures += 1
            print("FAIL:", what)

    def finish(self):
        print(f"{self.checks - self.failures} passed, {self.failures} failed")
        return 1 if self.failures else 0


def fresh_work(work, name):
    """WORK/name, emptied (made if missing): a test's own folder."""
    path = os.path.join(work, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def run(exe, args, cwd, timeout=600):
    """Run spallbar; text output, nothing on stdin."""
    return subprocess.run([exe] + args, cwd=cwd, capture_output=True, text=True,
                          errors="replace", timeout=timeout, stdin=subprocess.DEVNULL)


def run_deck(check, exe, work, name, text):
    """Write text as WORK/name.nml and run it with --quiet in WORK; whether it exited 0
    (checked)."""
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(text)
    r = run(exe, [name + ".nml", "--quiet"], work)
    check(r.returncode == 0, f"spallbar {name}: exit {r.returncode}: {r.stderr.strip()!r}")
    return r.returncode == 0


def run_decks(check, exe, work, decks):
    """run_deck for each (name, text) of decks, up to the first that fails; whether all
    exited 0."""
    return all(run_deck(check, exe, work, name, text) for name, text in decks)


def _value(word):
    """A field of a text output: a float, or the word itself."""
    try:
        return float(word)
    except ValueError:
        return word


def history(path):
    """The columns of a text output (PREFIX.his, ...) by name, as lists of floats (a word, as
    .spl's end or .imp's kind, stays text; NaN, no value, is a float): the names are those of
    the last '#' header line, the rows the lines that start with a blank."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
            elif line.startswith(" ") and line.strip():
                rows.append([_value(x) for x in line.split()])
    return {name: [r[k] for r in rows] for k, name in enumerate(names)}


def expect_refused(check, exe, work, what, text, needles):
    """Write text as WORK/bad.nml and run it: exit 2 with one stderr line that holds every
    one of needles, and no output file left (checked)."""
    with open(os.path.join(work, "bad.nml"), "w") as f:
        f.write(text)
    p = run(exe, ["bad.nml", "-q"], work)
    lines = p.stderr.strip().splitlines()
    check(p.returncode == 2, f"{what}: exit 2 (got {p.returncode})")
    check(len(lines) == 1 and all(n in p.stderr for n in needles),
          f"{what}: one line naming {needles} ({p.stderr.strip()})")
    left = [f for f in os.listdir(work) if f.startswith("bad.") and f not in ("bad.nml",
                                                                              "bad.lock")]
    check(not left, f"{what}: no output file ({left})")
