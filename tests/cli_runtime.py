#!/usr/bin/env python3
"""Run-time contract (INTERFACE.md): a run that goes wrong stops with exit status 3 and one
message, and what was written until then stays readable.

The case (issue 17): two one-cell bars meeting at t = 0 with the paper's literal event rules
(events = 'paper'): the stage-1 correction of their separation leaves a component along the
zig-zag mode's Jordan partner, whose energy grows as n^2; the scheme's own measure cannot see
it, the wave measure the guard uses does (2.25 times the impact's energy one step after the
break). The default guard (0.5) stops it; with energy_guard = 0 the same deck runs to its
end; with the admissible rules it runs to its end with the energy of the impact.

usage: cli_runtime.py SPALLBAR INPUT_DIR WORKDIR
"""
import os
import shutil
import sys

from clitools import Checks, run


def main():
    exe, indir, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    deck = ("&run t_end = 2e-3, events = 'paper', history_every = 1 /\n"
            "&mesh dt = 1e-5 /\n"
            "&segments n = 2, length = 0.01, 0.01, young = 2e9, 2e9, density = 2000, 2000,\n"
            "          strength = 0, 0, velocity = 1, -1 /\n")
    check = Checks()

    with open(os.path.join(work, "blowup.nml"), "w") as f:
        f.write(deck)
    r = run(exe, ["blowup.nml", "-q"], work)
    lines = r.stderr.splitlines()
    check(r.returncode == 3, f"exit status {r.returncode}, expected 3")
    check(len(lines) == 1 and "mechanical energy exceeds" in lines[0], f"stderr {r.stderr!r}")
    rows = [l.split() for l in open(os.path.join(work, "blowup.his")) if l.startswith(" ")]
    check(len(rows) >= 3 and all(len(x) == len(rows[0]) for x in rows), "history rows complete")
    t_last = float(rows[-1][0])
    check(0.0 < t_last < 2e-3, f"history ends at t = {t_last}, before t_end")
    for ext in (".prf", ".evt", ".frg"):
        check(os.path.getsize(os.path.join(work, "blowup" + ext)) > 0, f"{ext} written")
    print(f"ok   guard stopped the run at t = {t_last}: {lines[0] if lines else ''}")

    with open(os.path.join(work, "noguard.nml"), "w") as f:
        f.write(deck.replace("events = 'paper'", "events = 'paper', energy_guard = 0"))
    r = run(exe, ["noguard.nml", "-q"], work)
    check(r.returncode == 0, f"energy_guard = 0: exit {r.returncode} {r.stderr}")
    with open(os.path.join(work, "admissible.nml"), "w") as f:
        f.write(deck.replace("events = 'paper'", "events = 'admissible'"))
    r = run(exe, ["admissible.nml", "-q"], work)
    check(r.returncode == 0, f"admissible rules: exit {r.returncode} {r.stderr}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
