#!/usr/bin/env python3
"""Write the decks of the paper's Example 3, case 2 (input/example3_case2/): every timing
rule x shift policy at dx = h/19, h/95, h/190, and the full-mass comparison model of
Fig. 12. Run from the repository root: python3 scripts/make_case2_decks.py
"""
import os

HEAD = """! Seed Example 3, case 2 (Bak & Szczesniak 1988, section 7B, Figs. 11-12): the bar of
! case 1 (h = 0.95 m, E = 20 MPa, rho = 1765.8 kg/m^3, a = 106.43 m/s, on a rigid base,
! loaded on its top by p = 0.1 (1 - t/0.5 s)^3 MPa, with gravity, in self-weight
! equilibrium at t = 0) made of a material with ZERO tensile strength: every section
! can open and close, thousands of times. Unknown: the base reaction (reaction_bottom).
! {what}
! Written by scripts/make_case2_decks.py.
"""

BODY = """&run
  title         = "Example 3, case 2: zero tensile strength, {title}"
  t_end         = 0.6
  gravity       = 9.81
  timing        = '{timing}'
  shift         = '{shift}'
  model         = '{model}'
  profile_times = 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5
/
&mesh
  cells = {cells}
/
&segments
  n        = 1
  length   = 0.95
  young    = 20.0e6
  density  = 1765.8
  strength = 0.0
/
&ends
  top    = 'free'
  bottom = 'base'
/
&load
  kind     = 'power'
  face     = 'top'
  p0       = 0.1e6
  t_k      = 0.5
  exponent = 3.0
  t_cut    = 0.5
/
&initial
  state = 'static'
/
"""


def write(path, what, **kw):
    with open(path, "w") as f:
        f.write(HEAD.format(what=what) + BODY.format(**kw))


def main():
    out = os.path.join("input", "example3_case2")
    os.makedirs(out, exist_ok=True)
    for cells in (19, 95, 190):
        for timing in ("accelerate", "delay", "min"):
            for shift in ("above", "fragment"):
                name = f"{timing}_{shift}_h{cells}.nml"
                what = (f"Timing rule '{timing}', shift policy '{shift}', dx = h/{cells}"
                        + (" (the paper's choice for Figs. 11-12: accelerate, corrections for"
                           "\n! the colliding fragment only)." if (timing, shift) ==
                           ("accelerate", "fragment") else "."))
                write(os.path.join(out, name), what, timing=timing, shift=shift,
                      model="half-mass", cells=cells,
                      title=f"{timing}/{shift}, h/{cells}")
    write(os.path.join(out, "fullmass_accelerate_fragment_h19.nml"),
          "The paper's comparison model of Fig. 12: no half masses at free faces, full\n"
          "! masses with one-sided springs (doc/method.md), accelerate / fragment, dx = h/19.",
          timing="accelerate", shift="fragment", model="full-mass", cells=19,
          title="full-mass model, accelerate/fragment, h/19")


if __name__ == "__main__":
    main()
