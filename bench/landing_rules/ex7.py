"""Issue 17 landing exploration (see ex8.py): candidate landing rules on random sag states."""
import numpy as np
from ex5 import run, Bar, landing, measure, held_M, step
rng = np.random.default_rng(7)
def setup(b, d_over, gap_frac, fn_zero=False):
    N=b.N; C=np.sum(1/b.Z); dstar=b.g*b.dt**2/(b.Z[-1]*C)
    while True:
        uf=rng.normal(size=N+1); duf=rng.normal(size=N+1); uf[0]=duf[0]=0
        un=uf-duf
        if fn_zero:  # adjust du of node n-1 so that 2 f_n = 0 (f_n is affine in it)
            def fn(v):
                du2=duf.copy(); du2[N-1]=v; u2=un+du2
                _,d=landing(b,u2,du2,True); return du2[-1]-d
            a0=fn(0.0); a1=fn(1.0); duf[N-1]=-a0/(a1-a0)
        u2=un+duf; _,d=landing(b,u2,duf,True); fn2=duf[-1]-d
        x=fn2+d_over*dstar
        if x>0: break
    duf[-1]=x; uf=un+duf
    gap=gap_frac*x   # base - u_n^n, in [0, x): the trial penetrates
    return uf,duf,un,fn2,gap,dstar
def held_rows(b,uf,duf,un,delta):
    return run(b,uf,duf,[delta],2)[:2]
def free_loss(b,uf,duf,xp):
    u2=uf.copy(); du2=duf.copy(); du2[-1]=xp; u2[-1]=uf[-1]-duf[-1]+xp
    return measure(b.Z,b.m,uf,duf,b.dt,b.g,False,True)-measure(b.Z,b.m,u2,du2,b.dt,b.g,False,True)
for N in (3,5,9,21):
  Z=rng.uniform(0.5,2,N); b=Bar(Z,0.3,1.0); C=np.sum(1/Z); K=b.g**2*b.dt**3/(8*C)
  # explicit counterexample: 2 f_n = 0, gap = 0, d = d*/2
  uf,duf,un,fn2,gap,dstar=setup(b,0.5,0.0,True)
  deltas=np.concatenate([-np.logspace(-6,1,60),[0.0]])*dstar
  bh=max(min(held_rows(b,uf,duf,un,dl)) for dl in deltas)
  bf=max(free_loss(b,uf,duf,xp) for xp in deltas)
  print(f"N{N}: 2fn={fn2:.1e} gap=0 d=d*/2: best held (min row loss)/K {bh/K:+.4f}, best free-clipped loss/K {bf/K:+.4f}")
  stats={k:[0,0.0] for k in ("held delta=0","held delta=gap","held best in [0,gap]","free x'=gap")}
  M=400
  for t in range(M):
    uf,duf,un,fn2,gap,dstar=setup(b,rng.uniform(0,1),rng.uniform(0,1))
    cands={"held delta=0":[min(held_rows(b,uf,duf,un,0.0))],
           "held delta=gap":[min(held_rows(b,uf,duf,un,gap))],
           "held best in [0,gap]":[max(min(held_rows(b,uf,duf,un,dl)) for dl in np.linspace(0,gap,41))],
           "free x'=gap":[free_loss(b,uf,duf,gap)]}
    for k,v in cands.items():
        l=v[0]
        if l< -1e-12*max(1,K): stats[k][0]+=1; stats[k][1]=min(stats[k][1],l/K)
  print("   random sag states (d in (0,d*), gap in [0,x)): "+"; ".join(f"{k}: gains in {v[0]}/{M}, worst {-v[1]:.3f} K" for k,v in stats.items()))
