#!/usr/bin/python3
"""The liquid's force on every crust node of an ocean checkpoint against the node's weight
(docs/ocean.md, "What the probe's blow-up comes from"). Usage: ocean_shell_forces.py CHECKPOINT.h5
Debian's python3-h5py and python3-numpy. Work in progress on branch ocean."""
import h5py, numpy as np, sys
f=h5py.File(sys.argv[1],'r')
x=f['/particles/body/position/value'][0]; sp=f['/particles/body/species'][:]
m=f['/particles/body/mass/value'][:] if 'value' in f['/particles/body/mass'] else f['/particles/body/mass'][:]
g=f['/checkpoint/liquid']; K=g.attrs['bulk_modulus']; T=g['tetrahedra'][:]; V0=g['rest_volume'][:]
liq=sp==2
P=x[T]
a=P[:,1]-P[:,0]; b=P[:,2]-P[:,0]; d=P[:,3]-P[:,0]
vol=np.einsum('ij,ij->i',a,np.cross(b,d))/6
mt=liq[T].sum(1)
V=np.zeros(len(sp)); 
for k in range(4): np.add.at(V,T[:,k],vol/mt)
Pa=np.where(liq,-K*(V-V0)/np.where(liq,V0,1),0)
pt=Pa[T].sum(1)/mt
g1=np.cross(b,d)/6; g2=np.cross(d,a)/6; g3=np.cross(a,b)/6; g0=-(g1+g2+g3)
F=np.zeros_like(x)
for k,gk in enumerate([g0,g1,g2,g3]): np.add.at(F,T[:,k],pt[:,None]*gk)
c=(x*m[:,None]).sum(0)/m.sum(); r=x-c; rn=np.linalg.norm(r,axis=1); rh=r/rn[:,None]
sh=sp==1
Fr=(F*rh).sum(1)
# weight ~ m * M(<r)/r^2 ~ m * 1 (G M / r^2 with M~0.93 inside)
w=m*(1-m[sh].sum())/rn**2
print('min tet vol',vol.min(),'neg',(vol<0).sum(),'of',len(vol))
print('liquid P min/mean/max',Pa[liq].min(),Pa[liq].mean(),Pa[liq].max())
ratio=Fr[sh]/w[sh]
print('shell radial liquid force / weight: mean %.3f sd %.3f min %.3f max %.3f'%(ratio.mean(),ratio.std(),ratio.min(),ratio.max()))
Ft=F[sh]-Fr[sh,None]*rh[sh]
print('tangential/weight rms %.3f'%(np.linalg.norm(Ft,axis=1)/w[sh]).mean())
print('shell nodes touching no tet', (np.bincount(T.ravel(),minlength=len(sp))[sh]==0).sum())
