"""Issue 17 landing exploration (see ex8.py): the intact step of the lattice model."""
import os, sys; sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
import numpy as np
from held_gravity import *

def step(b, u, du, held_bot):
    """one step of the lumped-mass scheme, fixed top; returns (u, du) at n+2"""
    Z, dt, g = b.Z, b.dt, b.g
    s = (Z/dt)*(u[:-1]-u[1:])
    f = np.zeros(b.N+1)
    f[1:] += s; f[:-1] -= s
    du2 = du + dt*dt/b.m*f + dt*dt*g
    du2[0] = 0
    if held_bot: du2[-1] = 0
    return u+du2, du2

if __name__ != "__main__": pass
rng = np.random.default_rng(1)
N=5; Z=rng.uniform(0.5,2,N); dt=0.3; g=1.0
b=Bar(Z,dt,g)
# check conservation of held measure and free measure
u=rng.normal(size=N+1); du=rng.normal(size=N+1); u[0]=du[0]=0; du[-1]=0
M0=held_M(b,u,du,True); u1,du1=step(b,u,du,True); print("held cons", held_M(b,u1,du1,True)-M0)
u=rng.normal(size=N+1); du=rng.normal(size=N+1); u[0]=du[0]=0
M0=measure(b.Z,b.m,u,du,dt,g,False,True); u1,du1=step(b,u,du,False); print("free cons", measure(b.Z,b.m,u1,du1,dt,g,False,True)-M0)
u=rng.normal(size=N+1); du=rng.normal(size=N+1); u[0]=du[0]=0
M0=held_M(b,u,du,True); u1,du1=step(b,u,du,True); print("held cons du_n!=0", held_M(b,u1,du1,True)-M0, du[-1])
u2,du2=step(b,u1,du1,True); print("  next", held_M(b,u2,du2,True)-held_M(b,u1,du1,True))
