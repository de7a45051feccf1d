"""Issue 17 landing exploration (see ex8.py): the lattice run with lift-off and landing."""
import os, sys; sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
import numpy as np
from held_gravity import *
from explore import step
rng = np.random.default_rng(5)
def run(b,uf,duf,deltas,nsteps=3):
    """free trial (uf,duf); bottom node positions u^n+deltas[k] at t^{n+1+k}, then held; returns row losses"""
    un=uf-duf
    Ms=[measure(b.Z,b.m,uf,duf,b.dt,b.g,False,True)]
    u=uf.copy(); du=duf.copy(); u[-1]=un[-1]+deltas[0]; du[-1]=deltas[0]
    Ms.append(held_M(b,u,du,True))
    for k in range(1,len(deltas)+nsteps):
        u2,du2=step(b,u,du,True)
        tgt=un[-1]+deltas[min(k,len(deltas)-1)]
        du2[-1]=tgt-u[-1]; u2[-1]=tgt
        u,du=u2,du2
        Ms.append(held_M(b,u,du,True))
    return -np.diff(Ms)
N=5; Z=rng.uniform(0.5,2,N); dt=0.3; g=1.0
b=Bar(Z,dt,g); C=np.sum(1/Z); c=Z[-1]**2*C/(2*dt); K=g*g*dt**3/(8*C); dstar=g*dt*dt/(Z[-1]*C)
uf=rng.normal(size=N+1); duf=rng.normal(size=N+1); uf[0]=duf[0]=0
_,d=landing(b,uf,duf,True); fn2=duf[-1]-d
# set d=dstar/2
duf[-1]=fn2+dstar/2; uf=uf-duf; uf[-1]+=0; 
un=(uf).copy(); uf=un+duf
_,d=landing(b,uf,duf,True)
if 0: print("d/d*",d/dstar,"2fn",fn2,"K",K)
if __name__=="__main__": print(run(b,uf,duf,[0.0]))
# quadratic in (d1,d2) total
def T(x): return run(b,uf,duf,[x[0],x[0]+x[1]]).sum()
e=1e-2; H=np.zeros((2,2)); G=np.zeros(2); T0=T([0,0])
for i in (range(2) if __name__=="__main__" else []):
    ei=np.eye(2)[i]*e; G[i]=(T(ei)-T(-ei))/(2*e)
    for j in range(2):
        ej=np.eye(2)[j]*e; H[i,j]=(T(ei+ej)-T(ei-ej)-T(-ei+ej)+T(-ei-ej))/(4*e*e)
if __name__=="__main__": print("T0",T0,"G",G,"H",H, np.linalg.eigvalsh(H))
