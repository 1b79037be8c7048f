#!/usr/bin/env python3
"""Writes the Kuhn mesh of [-1, 1]^3 with n^3 cubes (six tetrahedra each, positively oriented)
and the 004 star's level set u = |x| - rho(theta, phi), rho = 0.45 + 0.3 cos 6theta cos^2 3phi,
at its vertices: the input `mmg3d_O3 -ls` adapts in docs/star3d.md.

usage: star3d_cube.py N OUT_STEM   (writes OUT_STEM.mesh and OUT_STEM.sol)
"""
import itertools
import sys

import numpy as np


def star(p):
    r = np.linalg.norm(p, axis=1)
    theta = np.arctan2(p[:, 1], p[:, 0])
    phi = np.arcsin(np.clip(np.where(r > 0, p[:, 2] / np.maximum(r, 1e-300), 0.0), -1, 1))
    return r - (0.45 + 0.3 * np.cos(6 * theta) * np.cos(3 * phi) ** 2)


def main():
    n, stem = int(sys.argv[1]), sys.argv[2]
    g = np.linspace(-1.0, 1.0, n + 1)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    pts = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    idx = lambda i, j, k: (k * (n + 1) + j) * (n + 1) + i
    i, j, k = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    tets = []
    for perm in itertools.permutations(range(3)):
        c = [np.zeros_like(i)] * 3
        vs = [idx(i, j, k)]
        off = [0, 0, 0]
        for d in perm:
            off[d] += 1
            vs.append(idx(i + off[0], j + off[1], k + off[2]))
        tets.append(np.stack(vs, axis=1))
    tets = np.concatenate(tets)
    a, b, c, d = (pts[tets[:, m]] for m in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)
    neg = vol < 0
    tets[neg, 2], tets[neg, 3] = tets[neg, 3].copy(), tets[neg, 2].copy()
    u = star(pts)
    with open(stem + ".mesh", "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % len(pts))
        np.savetxt(f, np.hstack([pts, np.zeros((len(pts), 1))]), fmt="%.17g %.17g %.17g %d")
        f.write("Tetrahedra\n%d\n" % len(tets))
        np.savetxt(f, np.hstack([tets + 1, np.ones((len(tets), 1), dtype=int)]), fmt="%d")
        f.write("End\n")
    with open(stem + ".sol", "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n%d\n1 1\n" % len(pts))
        np.savetxt(f, u, fmt="%.17g")
        f.write("End\n")


if __name__ == "__main__":
    main()
