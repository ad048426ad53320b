#!/usr/bin/python3
"""How well the liquid layer of an ocean checkpoint carries the crust (docs/ocean.md): for every
crust node and liquid particle, the layer's radial push against the node's weight and the net of
push and weight (self-gravity by direct sum), and the crust's radii.
Usage: ocean_shell_forces.py CHECKPOINT.h5   (Debian's python3-h5py and python3-numpy)"""
import sys

import h5py
import numpy as np

f = h5py.File(sys.argv[1], 'r')
x = f['/particles/body/position/value'][0]
species = f['/particles/body/species'][:]
mass_group = f['/particles/body/mass']
m = mass_group['value'][:] if 'value' in mass_group else mass_group[:]
layer = f['/checkpoint/liquid']
K = layer.attrs['bulk_modulus']
T = layer['tetrahedra'][:]
V0 = layer['rest_volume'][:]
softening = f['/checkpoint'].attrs['softening']

c = (x * m[:, None]).sum(0) / m.sum()
x = x - c
r = np.linalg.norm(x, axis=1)
rhat = x / r[:, None]
P = x[T]
a, b, d = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]
g1, g2, g3 = np.cross(b, d) / 6, np.cross(d, a) / 6, np.cross(a, b) / 6
g0 = -(g1 + g2 + g3)
vol = np.einsum('ij,ij->i', a, g1)
node = V0 > 0
V = np.zeros(len(x))
for k in range(4):
    np.add.at(V, T[:, k], vol / 4)
pressure = np.where(node, -K * (V - V0) / np.where(node, V0, 1), 0)
pt = pressure[T].mean(1)
F = np.zeros_like(x)
for k, gk in enumerate([g0, g1, g2, g3]):
    np.add.at(F, T[:, k], pt[:, None] * gk)
gravity = np.zeros_like(x)
for i in range(0, len(x), 512):
    dx = x[None, :, :] - x[i:i + 512, None, :]
    r2 = (dx ** 2).sum(2) + softening ** 2
    r2[r2 == softening ** 2] = np.inf
    gravity[i:i + 512] = (m[None, :, None] * dx / r2[:, :, None] ** 1.5).sum(1)
W = m[:, None] * gravity
print('tetrahedra %d, inverted %d; pressure nodes %d' % (len(T), (vol <= 0).sum(), node.sum()))
for name, s in (('crust', species == 1), ('liquid', species == 2)):
    w = np.linalg.norm(W[s], axis=1)
    push = (F[s] * rhat[s]).sum(1) / w
    net = np.linalg.norm(F[s] + W[s], axis=1) / w
    print('%-6s %4d: radial push / weight %.3f +- %.3f [%.3f, %.3f]; |push + weight| / weight rms %.3f, max %.3f'
          % (name, s.sum(), push.mean(), push.std(), push.min(), push.max(), np.sqrt((net ** 2).mean()), net.max()))
crust = species == 1
print('crust radius %.4f +- %.4f [%.4f, %.4f]; liquid r %.3f..%.3f; P liquid %.4f..%.4f e_g'
      % (r[crust].mean(), r[crust].std(), r[crust].min(), r[crust].max(), r[species == 2].min(), r[species == 2].max(),
         pressure[species == 2].min(), pressure[species == 2].max()))
