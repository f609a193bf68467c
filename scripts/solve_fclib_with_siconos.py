#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Solves an FCLIB local problem written by `frictopt export-fclib` with Siconos' fc3d/fc2d
solvers (NSGS) and compares the reactions with frictopt's stored solution.

Debian's Siconos (python3-siconos 4.5) is built without FCLIB support (no
frictionContact_fclib_read), so the file is read with h5py and the problem built from arrays:
W (dense, stored as compressed columns), q, mu and spacedim (docs/contact.md, "FCLIB export").

    /usr/bin/python3 scripts/solve_fclib_with_siconos.py OUT.hdf5 [--tolerance 1e-10] [--check 1e-6]

--check TOL exits 1 unless Siconos reports convergence and max|r - r_frictopt| <= TOL·max|r_frictopt|.
"""

import argparse
import sys

import h5py
import numpy as np
import scipy.sparse
import siconos.numerics as sn


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("file")
    parser.add_argument("--tolerance", type=float, default=1e-10, help="Siconos' SICONOS_DPARAM_TOL")
    parser.add_argument("--check", type=float, default=None)
    args = parser.parse_args()
    with h5py.File(args.file, "r") as f:
        local = f["fclib_local"]
        W = local["W"]
        m = int(np.asarray(W["m"]).ravel()[0])
        dense_W = scipy.sparse.csc_matrix((np.asarray(W["x"]), np.asarray(W["i"]), np.asarray(W["p"])),
                                          shape=(m, m)).toarray()
        q = np.asarray(local["vectors/q"], dtype=float)
        mu = np.asarray(local["vectors/mu"], dtype=float)
        d = int(np.asarray(local["spacedim"]).ravel()[0])
        ours = np.asarray(f["solution/r"], dtype=float) if "solution" in f else None
        units = str(np.asarray(local["info/description"]).astype(str))
    problem = sn.FrictionContactProblem(d, m // d, dense_W, q, mu)
    options = sn.SolverOptions(sn.SICONOS_FRICTION_3D_NSGS if d == 3 else sn.SICONOS_FRICTION_2D_NSGS)
    options.dparam[sn.SICONOS_DPARAM_TOL] = args.tolerance
    options.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
    r, u = np.zeros(m), np.zeros(m)
    info = (sn.fc3d_driver if d == 3 else sn.fc2d_driver)(problem, r, u, options)
    print("%s: spacedim %d, %d contacts, %s units; Siconos NSGS info %d, error %.3e, %d iterations" % (
        args.file, d, m // d, "normalized" if "Units: normalized" in units else "SI", info,
        options.dparam[sn.SICONOS_DPARAM_RESIDU], options.iparam[sn.SICONOS_IPARAM_ITER_DONE]))
    difference = None
    if ours is not None:
        difference = np.abs(r - ours).max() / max(np.abs(ours).max(), np.finfo(float).tiny)
        print("max|r - r_frictopt| / max|r_frictopt| = %.3e" % difference)
    if args.check is not None:
        if info != 0 or difference is None or not difference <= args.check:
            print("check failed: expected convergence and a difference <= %g" % args.check)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
