#!/usr/bin/env python3
"""Largest eigenvalue of M^-1 (K_elem + K_contact) dt^2 for the two-block deck (issue 20 diagnosis).

Linear, all contacts closed: one-point hex V B^T C B plus the stiffness hourglass term
(kappa 2G sum(b.b)/(8V) sum_a gamma_a gamma_a^T), lumped mass rho V/8 per node, node-to-face
springs as contact_engine.cpp builds them (both views, w = 1/2, k = alpha m_eff/dt^2, corner
shares N_I). Central differences are stable for the printed value < 4 (undamped) or
< (2(sqrt(1+xi^2)-xi))^2 = 3.56 with the linear bulk viscosity xi = 0.06. numpy only.
  python3 benchmarks/contact_eigen.py [--unz 2] [--shift 0.5] [--alpha 0.125] [--free]
import numpy as np, itertools, sys, argparse
E, NU, RHO = 200e9, 0.3, 7850.0
lam = E*NU/((1+NU)*(1-2*NU)); mu = E/(2*(1+NU))
cd = np.sqrt((lam+2*mu)/RHO)
SIGNS = np.array([[-1,-1,-1],[1,-1,-1],[1,1,-1],[-1,1,-1],[-1,-1,1],[1,-1,1],[1,1,1],[-1,1,1]],float)
GAMMA = np.array([[1,1,-1,-1,-1,-1,1,1],[1,-1,-1,1,-1,1,1,-1],[1,-1,1,-1,1,-1,1,-1],[-1,1,-1,1,1,-1,1,-1]],float)

def hex_K(h, kappa=0.05):
    V = h**3
    b = SIGNS * h*h/4  # dV/dx_I
    B = np.zeros((6, 24))
    for I in range(8):
        bx, by, bz = b[I]/V
        B[0,3*I]=bx; B[1,3*I+1]=by; B[2,3*I+2]=bz
        B[3,3*I]=by; B[3,3*I+1]=bx
        B[4,3*I]=bz; B[4,3*I+2]=bx
        B[5,3*I+1]=bz; B[5,3*I+2]=by
    C = np.zeros((6,6)); C[:3,:3]=lam; C[range(3),range(3)]+=2*mu; C[3:,3:]=np.eye(3)*mu
    K = V*B.T@C@B
    khg = kappa*2*mu*(b*b).sum()/(8*V)
    G = sum(np.outer(g,g) for g in GAMMA)
    K += khg*np.kron(G, np.eye(3))
    return K

def block(nx, ny, nz, h, x0, y0, z0, base, nodes):
    ids = {}
    for k in range(nz+1):
        for j in range(ny+1):
            for i in range(nx+1):
                ids[i,j,k] = len(nodes); nodes.append((x0+i*h, y0+j*h, z0+k*h))
    els = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                els.append([ids[i,j,k],ids[i+1,j,k],ids[i+1,j+1,k],ids[i,j+1,k],ids[i,j,k+1],ids[i+1,j,k+1],ids[i+1,j+1,k+1],ids[i,j+1,k+1]])
    return ids, els

def run(a):
    h=a.h; nodes=[]
    lid, lel = block(a.lnx,a.lnx,a.lnz,h,0,0,-a.lnz*h,0,nodes)
    off = -0.5*(a.unx-a.lnx)*h + a.shift*h
    uid, uel = block(a.unx,a.unx,a.unz,h,off,off,0.0,0,nodes)
    X = np.array(nodes); n=len(X)
    K = np.zeros((3*n,3*n)); m = np.zeros(n)
    Ke = hex_K(h, a.kappa)
    for e in lel+uel:
        dofs = np.array([[3*i,3*i+1,3*i+2] for i in e]).ravel()
        K[np.ix_(dofs,dofs)] += Ke
        m[e] += RHO*h**3/8
    dt = a.dt if a.dt else 0.9*0.9417*h/cd
    # contact faces: lower top (outward +z), upper bottom (outward -z); nodes 0..3 CCW
    ltop = [[lid[i,j,a.lnz],lid[i+1,j,a.lnz],lid[i+1,j+1,a.lnz],lid[i,j+1,a.lnz]] for i in range(a.lnx) for j in range(a.lnx)]
    ubot = [[uid[i,j,0],uid[i+1,j,0],uid[i+1,j+1,0],uid[i,j+1,0]] for i in range(a.unx) for j in range(a.unx)]
    lnodes = sorted({q for f in ltop for q in f}); unodes = sorted({q for f in ubot for q in f})
    Kc = np.zeros_like(K); cons=[]
    def view(slaves, faces, w):
        for s in slaves:
            p = X[s,:2]
            for f in faces:
                lo = X[f[0],:2]; hi = X[f[2],:2]
                if np.all(p >= lo-1e-12) and np.all(p <= hi+1e-12):
                    xi = (p-lo)/(hi-lo)
                    N = np.array([(1-xi[0])*(1-xi[1]), xi[0]*(1-xi[1]), xi[0]*xi[1], (1-xi[0])*xi[1]])
                    mm = N@m[f]; ms = m[s]
                    meff = ms*mm/(ms+mm)
                    k = w*a.alpha*meff/dt**2
                    if a.rule == 'sumN2':   # k from the true single-spring frequency
                        k = w*a.alpha/ (dt**2 * (1/ms + (N**2/m[f]).sum()))
                    cons.append((s,f,N,k)); break
    if a.views in ('both','lower'): view(lnodes, ubot, a.w)
    if a.views in ('both','upper'): view(unodes, ltop, a.w)
    for s,f,N,k in cons:
        Bv = np.zeros(n); Bv[s]=1; 
        for I,q in enumerate(f): Bv[q]-=N[I]
        idx = np.nonzero(Bv)[0]
        for i in idx:
            for j in idx:
                Kc[3*i+2,3*j+2] += k*Bv[i]*Bv[j]
    fixed = set()
    if not a.free:
        for i in range(a.lnx+1):
            for j in range(a.lnx+1):
                fixed |= {3*lid[i,j,0]+d for d in range(3)}
    free = np.array([d for d in range(3*n) if d not in fixed])
    Minv = 1/np.sqrt(np.repeat(m,3))[free]
    def lmax(KK):
        A = (KK[np.ix_(free,free)]*Minv[:,None])*Minv[None,:]
        w, v = np.linalg.eigh(A)
        return w[-1]*dt**2, v[:,-1]
    le,_ = lmax(K); lc,_ = lmax(Kc); lt,vt = lmax(K+Kc)
    # per node Gershgorin of contact part
    A = (Kc[np.ix_(free,free)]*Minv[:,None])*Minv[None,:]
    gers = np.abs(A).sum(1).max()*dt**2
    print(f"{a.tag:30s} dt={dt:.4e} elem={le:.3f} contact={lc:.3f} (gersh {gers:.3f}) total={lt:.3f}  (limit 4)  ncons={len(cons)}")
    if a.verbose:
        top = np.argsort(-np.abs(vt))[:6]
        for t in top:
            d = free[t]; print("   dof", d//3, "xyz"[d%3], X[d//3], f"{vt[t]:.3f}", f"m={m[d//3]/(RHO*h**3/8):.0f}m0")
    return le, lc, lt

p = argparse.ArgumentParser()
p.add_argument('--lnx',type=int,default=3); p.add_argument('--lnz',type=int,default=2)
p.add_argument('--unx',type=int,default=4); p.add_argument('--unz',type=int,default=1)
p.add_argument('--h',type=float,default=1e-3); p.add_argument('--shift',type=float,default=0.0)
p.add_argument('--alpha',type=float,default=0.5); p.add_argument('--w',type=float,default=0.5)
p.add_argument('--views',default='both'); p.add_argument('--rule',default='meff')
p.add_argument('--kappa',type=float,default=0.05); p.add_argument('--dt',type=float,default=0)
p.add_argument('--free',action='store_true'); p.add_argument('--verbose',action='store_true')
p.add_argument('--tag',default='')
run(p.parse_args())
