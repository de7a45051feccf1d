#!/usr/bin/env python3
"""Long-run soak (issue 9): the paper's Example 3 case 2 (zero tensile strength, on the
rigid base, gravity) at h/19, loaded by 940 pressure pulses (0.1 MPa, every 0.5 s) for
470 s: 1.0e6 steps and ~9e5 events (fractures, collisions, separations, landings).

Checks over every history row: the energy ledger stays at its initial value (drift
<= 1e-9 of the largest energy term), the momentum balance closes (momentum - momentum0 =
i_gravity + i_ends + i_support + p_shift to 1e-9 of the largest impulse), the run reaches
its last step; and memory is flat: the peak resident size of the 1e6-step run exceeds that
of a 1e5-step run of the same deck by less than 1 MiB.

usage: cli_soak.py SPALLBAR INPUT_DIR WORKDIR
"""
import os
import shutil
import subprocess
import sys

from clitools import Checks

COL = {"ledger": 15, "momentum": 9, "step": 10, "e_kin": 4, "e_strain": 5, "e_pot": 6,
       "w_ext": 7, "i_gravity": 20, "i_ends": 21, "i_support": 22, "p_shift": 23}


def deck_text(indir, t_end):
    text = open(os.path.join(indir, "example3_case2", "accelerate_fragment_h19.nml")).read()
    out = []
    for line in text.splitlines():
        key = line.strip().split("=")[0].strip()
        if key == "t_end":
            line = f"  t_end = {t_end}"
        elif key == "profile_times":
            line = "  history_every = 1000"
        elif key == "kind":
            line = "  kind = 'table'\n  table = 'pulses.txt'"
        elif key in ("p0", "t_k", "exponent", "t_cut"):
            continue
        out.append(line)
    return "\n".join(out) + "\n"


def run(exe, work, name):
    """Run a deck; exit status and peak resident size [KiB] of that process alone."""
    with open(os.path.join(work, name + ".log"), "w") as log:
        p = subprocess.Popen([exe, name + ".nml", "-q"], cwd=work, stdout=log,
                             stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        _, status, usage = os.wait4(p.pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_maxrss


def main():
    exe, indir, work = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    with open(os.path.join(work, "pulses.txt"), "w") as f:
        f.write("# t [s]  p [Pa]: a 0.1 MPa triangle every 0.5 s\n")
        for k in range(940):
            t0 = 0.5 * k
            f.write(f"{t0:.6f} 0\n{t0 + 0.05:.6f} 1.0e5\n{t0 + 0.1:.6f} 0\n")
    for name, t_end in (("short", 47.0), ("soak", 470.0)):
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(deck_text(indir, t_end))
    rc_s, rss_short = run(exe, work, "short")
    rc, rss = run(exe, work, "soak")
    check(rc_s == 0 and rc == 0, f"exit {rc_s}, {rc}: see {work}/*.log")
    rows = [list(map(float, line.split())) for line in open(os.path.join(work, "soak.his"))
            if line.startswith(" ")]
    events = sum(1 for line in open(os.path.join(work, "soak.evt")) if line.startswith(" "))
    steps = int(rows[-1][COL["step"]])
    r0 = rows[0]
    e_scale = max(max(abs(r[COL[k]]) for k in ("e_kin", "e_strain", "e_pot", "w_ext"))
                  for r in rows)
    drift = max(abs(r[COL["ledger"]] - r0[COL["ledger"]]) for r in rows)
    p_scale = max(max(abs(r[COL[k]]) for k in ("i_gravity", "i_ends", "i_support"))
                  for r in rows)
    p_err = max(abs(r[COL["momentum"]] - r0[COL["momentum"]]
                    - sum(r[COL[k]] for k in ("i_gravity", "i_ends", "i_support", "p_shift")))
                for r in rows)
    print(f"soak: {steps} steps, {events} events, {len(rows)} history rows")
    print(f"soak: ledger drift {drift:.3e} J/m^2 = {drift / e_scale:.2e} of {e_scale:.4g}")
    print(f"soak: momentum balance {p_err:.3e} kg/(m s) = {p_err / p_scale:.2e} of {p_scale:.4g}")
    print(f"soak: peak resident size {rss_short} KiB (1e5 steps), {rss} KiB (1e6 steps)")
    check(steps >= 1000000, f"only {steps} steps")
    check(events > 500000, f"only {events} events")
    check(drift <= 1e-9 * e_scale, "energy ledger drift")
    check(p_err <= 1e-9 * p_scale, "momentum balance")
    check(rss - rss_short < 1024, f"memory grew by {rss - rss_short} KiB")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
