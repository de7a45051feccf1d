"""Issue 17, the landing of an odd bar held by a fixed top on the base (doc/method.md, "Still
open: the landing"): an exploration on the lattice model of bench/held_gravity.py, kept so
the numbers can be reproduced. ex8.py prints the counterexample (2 f_n = 0, gap 0,
d = d*/2): the best held landing and the best clipped free face both add up to K; ex7.py
also tries candidate rules on 400 random sag states per bar."""
import numpy as np
from ex7 import setup, held_rows, free_loss, Bar
rng=np.random.default_rng(8)
for N in (3,5,9,21):
  for hom in (True,False):
    Z=np.ones(N) if hom else rng.uniform(0.5,2,N); b=Bar(Z,0.3,1.0); C=np.sum(1/Z); K=b.g**2*b.dt**3/(8*C)
    for gf in (0.0,0.5,0.99):
      uf,duf,un,fn2,gap,dstar=setup(b,0.5,gf,True)
      ds=np.concatenate([-np.logspace(-8,2,200)*dstar,np.linspace(0,gap,50)])
      bh=max(min(held_rows(b,uf,duf,un,dl)) for dl in ds)
      bf=max(free_loss(b,uf,duf,xp) for xp in ds)
      print(f"N{N} {'homog' if hom else 'layered'} ZnC={Z[-1]*C:5.2f} 2fn=0 d=d*/2 gap={gf:.2f}x: best held landing row+next /K {bh/K:+.4f}; best free (face clipped to <= gap) /K {bf/K:+.4f}; bound 1-2/(ZnC)={1-2/(Z[-1]*C):.3f}")
