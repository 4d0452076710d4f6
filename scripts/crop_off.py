#!/usr/bin/env python3
"""Cut the faces within RINGS vertex rings of vertex SEED of REF.off out of each of several
meshes with the connectivity of REF (the outputs of one scheme with different options), for a
close-up picture: crop_off.py REF.off SEED RINGS IN1.off OUT1.off [IN2.off OUT2.off ...]"""
import sys
def read(p):
    t=open(p).read().split()
    assert t[0]=='OFF'; nv,nf=int(t[1]),int(t[2]); i=4
    V=[tuple(map(float,t[i+3*k:i+3*k+3])) for k in range(nv)]; i+=3*nv
    F=[]
    for _ in range(nf):
        n=int(t[i]); F.append(list(map(int,t[i+1:i+1+n]))); i+=1+n
    return V,F
def crop(V,F,seed,rings):
    vf={}
    for fi,f in enumerate(F):
        for v in f: vf.setdefault(v,[]).append(fi)
    vs={seed}; fs=set()
    for _ in range(rings):
        nf=set(x for v in vs for x in vf[v]); fs|=nf
        vs=set(v for fi in fs for v in F[fi])
    return sorted(fs)
V,F=read(sys.argv[1]); seed=int(sys.argv[2]); rings=int(sys.argv[3])
fs=crop(V,F,seed,rings)
for src,dst in zip(sys.argv[4::2],sys.argv[5::2]):
    V2,F2=read(src)
    used=sorted(set(v for fi in fs for v in F2[fi])); idx={v:k for k,v in enumerate(used)}
    with open(dst,'w') as o:
        o.write("OFF\n%d %d 0\n"%(len(used),len(fs)))
        for v in used: o.write("%.17g %.17g %.17g\n"%V2[v])
        for fi in fs: o.write("%d %s\n"%(len(F2[fi])," ".join(str(idx[v]) for v in F2[fi])))
