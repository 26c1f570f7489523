#!/usr/bin/env python3
# Independent reference values for tests/models, written from the published formulas (papers, as
# collected in docs/physics.md and docs/models.md), not from the C++ code. Run: python3 tests/models/reference_values.py
# The printed numbers are pasted as literals into the tests.
import math
def brentq(f,a,b,**kw):
    # plain bisection on a log scale (scipy is not installed here)
    import math
    fa=f(a)
    for _ in range(3000):
        m=math.sqrt(a*b)
        if m==a or m==b: break
        fm=f(m)
        if (fm>0)==(fa>0): a,fa=m,fm
        else: b=m
    return math.sqrt(a*b)
mu=1.8e-5; rho=1.12; d=300e-6; cg=5.0; min_eps=0.35
pts=[(1.0,0.0),(0.9,0.05),(0.6,0.5),(0.4,2.0),(0.45,10.0),(0.75,30.0),(0.99,1.0),(0.9,100.0),(0.2,1.0)]
def Re_of(eps,w): return rho*eps*d*w/mu
def stokesK(): return cg**3*3*math.pi*mu*d
def sn_cdre24(Re): return 1+0.15*Re**0.687 if Re<1000 else 0.44*Re/24
def K_sn(eps,Re): return stokesK()*sn_cdre24(Re)
def K_difelice(eps,Re,dalla=False):
    chi = 3.7 if Re==0 else 3.7-0.65*math.exp(-(1.5-math.log10(Re))**2/2)
    # F = Cd rho pi d^2/8 eps^2 w^2 eps^-chi ; K=F/w
    w = Re*mu/(rho*eps*d)
    if Re==0: cdRe = 23.04 if dalla else 24.0
    else:
        Cd = (0.63+4.8/math.sqrt(Re))**2 if dalla else (24/Re*(1+0.15*Re**0.687) if Re<1000 else 0.44)
        cdRe=Cd*Re
    # K = Cd rho pi d^2 eps^(2-chi) w /8 = CdRe mu pi d eps^(1-chi)/8
    return cg**3*cdRe*mu*math.pi*d*eps**(1-chi)/8
def K_gidaspow(eps,Re):
    # beta (per volume) / phi, so that phi = 0 is well defined; K = (beta/phi) Vp
    phi=1-eps; w=Re*mu/(rho*eps*d); Vp=math.pi*d**3/6
    if eps<0.8:
        bphi=150*phi*mu/(eps*d*d)+1.75*rho*w/d
    else:
        Cdw = 24*mu/(rho*eps*d)*(1+0.15*Re**0.687) if Re<1000 else 0.44*w   # Cd*w
        bphi=0.75*Cdw*eps*rho*eps**-2.65/d
    return cg**3*bphi*Vp
def kh_F(phis,Re):
    # Benyahia et al. 2006 fit of Hill-Koch-Ladd; Re here is half the usual one
    ww=math.exp(-10*(0.4-phis)/phis) if phis>0 else 0.0
    pl = phis*math.log(phis) if phis>0 else 0.0
    if phis<0.4:
        F0=(1-ww)*(1+3*math.sqrt(phis/2)+135/64*pl+17.14*phis)/(1+0.681*phis-8.48*phis**2+8.16*phis**3)+ww*10*phis/(1-phis)**3
        F2=(1-ww)*(1+3*math.sqrt(phis/2)+135/64*pl+17.89*phis)/(1+0.681*phis-11.03*phis**2+15.41*phis**3)+ww*10*phis/(1-phis)**3
    else:
        F0=F2=10*phis/(1-phis)**3
    if phis>0.01 and phis<=0.1: F1=math.sqrt(2/phis)/40
    elif phis>0.1: F1=0.11+5.1e-4*math.exp(11.6*phis)
    else: F1=None
    F3 = 0.9351*phis+0.03667 if phis<0.0953 else 0.0673+0.212*phis+0.0232/(1-phis)**5
    if phis<=0.01:
        t1=(F2-1)/(3/8-F3)
        return 1+3/8*Re if Re<=t1 else F2+F3*Re
    t2=(F3+math.sqrt(F3*F3-4*F1*(F0-F2)))/(2*F1)
    return F0+F1*Re*Re if Re<=t2 else F2+F3*Re
def K_kh(eps,Re):
    # beta_vol = F * 18 mu eps^2/d^2 * phi ; per particle K = beta_vol Vp/phi
    return cg**3*kh_F(1-eps,Re/2)*18*mu*eps**2/d**2*math.pi*d**3/6
def beet_F(eps,Re):
    phi=1-eps
    F=10*phi/eps**2+eps**2*(1+1.5*math.sqrt(phi))
    if Re>0:
        F+=0.413*Re/(24*eps**2)*(1/eps+3*eps*phi+8.4*Re**-0.343)/(1+10**(3*phi)*Re**(-(1+4*phi)/2))
    return F
def K_beet(eps,Re): return cg**3*3*math.pi*mu*d*eps*beet_F(eps,Re)
def a_rs(p):
    if p<0.016: return 21.51
    if p<0.10: return 1.96+29.40*p+164.91*p**2-1923*p**3
    if p<0.18: x=p-0.10; return 4.63+4.68*x-412.04*x**2+2254*x**3
    if p<0.25: x=p-0.18; return 3.52-17.99*x+128.80*x**2-603*x**3
    if p<0.40: x=p-0.25; return 2.68-8.20*x+2.18*x**2+112.33*x**3
    return 1.79
def h_rs(p):
    T=[(0.03,0.08,(0.239,4.64,-4.41,253.63)),(0.08,0.12,(0.492,6.10,33.63,-789.6)),(0.12,0.18,(0.739,5.01,-61.1,310.8)),
       (0.18,0.34,(0.887,1.03,-5.17,5.99)),(0.34,0.48,(0.943,-0.17,-2.29,-9.12)),(0.48,0.55,(0.850,-1.35,-6.13,-132.6))]
    if p<0.03: return 7.97*p
    for lo,hi,c in T:
        if p<hi: x=p-lo; return c[0]+c[1]*x+c[2]*x*x+c[3]*x**3
    x=p-0.55; return max(0.0,0.680-2.34*x-225.2*x*x)
def u_terminal(dd,rhop,rhof,muf,g):
    # balance (rhop-rhof) g pi d^3/6 = 3 pi mu d u F(1,Re), brentq on u
    f=lambda u: (rhop-rhof)*g*math.pi*dd**3/6 - 3*math.pi*muf*dd*u*beet_F(1.0,rhof*dd*u/muf)
    return brentq(f,1e-30,1e6,xtol=1e-300,rtol=1e-15,maxiter=500)
def K_beet_filtered(eps,Re,cell,rhop=1750.0,g=9.81,k=0.05):
    ut=u_terminal(d,rhop,rho,mu,g)
    Fr=ut**2/(g*d); Lc=ut**2/g*Fr**(-2/3)
    phi=1-eps
    corr=1-h_rs(phi)/(a_rs(phi)*Lc/cell+1)
    return K_beet(eps,Re)*corr*math.exp(k*(1-cg))
def sh_deen(eps,Re,Sc=1.0): return (7-10*eps+5*eps**2)*(1+0.17*Re**0.2*Sc**(1/3))+(1.33-2.31*eps+1.16*eps**2)*Re**0.7*Sc**(1/3)
def sh_gunn(eps,Re,Sc=1.0): return (7-10*eps+5*eps**2)*(1+0.7*Re**0.2*Sc**(1/3))+(1.33-2.4*eps+1.2*eps**2)*Re**0.7*Sc**(1/3)
def sh_rm(eps,Re,Sc=1.0): return 2+0.6*Re**0.5*Sc**(1/3)
def k_mass(sh,eps,Re,Sc=1.0):
    D=mu/(rho*Sc); Km=sh(eps,Re,Sc)*D/d
    return cg**3*Km*rho*math.pi*d*d
def tenneti_K(eps,Re):
    phi=1-eps
    F=(1+0.15*Re**0.687)/eps**3+5.81*phi/eps**3+0.48*phi**(1/3)/eps**4+phi**3*Re*(0.95+0.61*phi**3/eps**2)
    return cg**3*3*math.pi*mu*d*eps*F

def fmt(x): return "%.17g"%x
laws={'schiller_naumann':K_sn,'di_felice':K_difelice,'dallavalle':lambda e,R:K_difelice(e,R,True),'gidaspow':K_gidaspow,
      'koch_hill':K_kh,'beetstra':K_beet,'deen_gunn':lambda e,R:k_mass(sh_deen,e,R),'gunn':lambda e,R:k_mass(sh_gunn,e,R),
      'ranz_marshall':lambda e,R:k_mass(sh_rm,e,R),'tenneti':tenneti_K}
print("// points (eps, slip):", pts)
for name,f in laws.items():
    vals=[]
    for eps,w in pts:
        e=max(eps,min_eps); Re=Re_of(e,w); vals.append(f(e,Re))
    print("%s: {%s}"%(name,", ".join(fmt(v) for v in vals)))
print("stokesK", fmt(stokesK()))
cells=[1e-4,1e-3,4e-3,1e-2,0.1]
fp=[(0.6,0.5),(0.4,2.0),(0.95,1.0),(0.75,0.2),(0.5,5.0)]
print("filtered points", fp, "cells", cells)
print("beetstra_filtered: {%s}"%", ".join(fmt(K_beet_filtered(e,Re_of(e,w),c)) for (e,w),c in zip(fp,cells)))
ut=u_terminal(d,1750.0,rho,mu,9.81); print("u_t", fmt(ut), "Re_t", fmt(rho*d*ut/mu))
print("u_t d=1e-7", fmt(u_terminal(1e-7,1750.0,rho,mu,9.81)), "d=5e-3", fmt(u_terminal(5e-3,1750.0,rho,mu,9.81)))
print("Sc=0.7 deen eps0.6 w0.5:", fmt(k_mass(sh_deen,0.6,Re_of(0.6,0.5),0.7)/1.0))
# filtered Beetstra with the terminal velocity from the reference gas (1.12, 1.8e-5) while the
# parcel's local gas is rho 1.5, mu 2.0e-5: eps 0.6, slip 0.5, cell 4e-3, cg 5, k 0.05
rl,ml=1.5,2.0e-5
eps,w,cell=0.6,0.5,4e-3
Re=rl*eps*d*w/ml
Fb=beet_F(eps,Re)
ut=u_terminal(d,1750.0,rho,mu,9.81); Fr=ut**2/(9.81*d); Lc=ut**2/9.81*Fr**(-2/3)
corr=1-h_rs(0.4)/(a_rs(0.4)*Lc/cell+1)
print("reference filtered:", fmt(cg**3*3*math.pi*ml*d*eps*Fb*corr*math.exp(0.05*(1-cg))))
ut2=u_terminal(d,1750.0,rl,ml,9.81); Fr=ut2**2/(9.81*d); Lc2=ut2**2/9.81*Fr**(-2/3)
corr2=1-h_rs(0.4)/(a_rs(0.4)*Lc2/cell+1)
print("local filtered:", fmt(cg**3*3*math.pi*ml*d*eps*Fb*corr2*math.exp(0.05*(1-cg))))
