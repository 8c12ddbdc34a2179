#!/usr/bin/python3
"""The Hertz benchmark with GetFEM, as an independent peer of the crate.

The same problem as `benchmarks::Hertz`: the right half (x >= 0) of the
disk of radius R = 0.2 centred at (0, R), plane strain, E = 2e7, nu = 0.1,
body force (0, -1.3e6), u_x = 0 on the symmetry line x = 0, and the rigid
floor y = 0 below, with frictionless contact by GetFEM's Nitsche brick
(`add_Nitsche_contact_with_rigid_obstacle_brick`) on the 45-degree arc
from the lowest point (the crate's contact side), solved by GetFEM's
Newton with MUMPS.

The mesh is an isoparametric Q1 or Q2 mesh of N x N elements: a Coons
(transfinite) map of the unit square onto the half disk whose four sides
are the diameter and the three arcs of the crate's half-disk patch
(bottom 45-degree arc, right 90-degree arc, top 45-degree arc), with the
nodes placed on the map, so every boundary node lies on the exact circle.

The penalty. GetFEM's Nitsche contact brick forms gamma = gamma0 /
element_size (src/getfem_contact_and_friction_integral.cc), with
element_size GetFEM's diameter estimate of the element (sqrt(2) h on a
square of side h); the crate's Eq. (11) is gamma = F 0.1 E (p+1)(p+2) / h_b
with h_b the length of the slave boundary element. The script passes gamma0
as a field constant per element, gamma * element_size of that element, with
gamma = F 0.1 E (p+1)(p+2) / h_b (h_b = contact length / number of contact
faces: the faces of the Coons mesh span equal angles), so that the brick's
gamma is the crate's at the same factor F (`--factor`). It checks this at
the contact sample points (gamma_deviation: the largest relative difference
of the brick's gamma0 / element_size from gamma) and reports element_size /
h_b over the faces (r_min, r_max), the factor by which a single gamma0
would have missed Eq. (11).

Measured per run (one line of the CSV):
  - p0: the largest contact pressure, max of -sigma_yy (the floor's normal
    stress) sampled at 20 points per boundary element along the contact
    arc (points of the element faces, so inside the mesh);
  - a: the contact half-width, the x where the deformed gap y + u_y first
    turns positive along the arc going outwards from x = 0 (linear
    interpolation between the two samples around the change);
  - dofs: displacement DOFs (GetFEM's, before the x = 0 multipliers);
  - newton_iterations, converged;
  - setup_seconds: the model set-up (regions, finite element spaces,
    integration method, model, bricks), mesh generation excluded;
  - solve_seconds: GetFEM's Newton with MUMPS (md.solve);
  - factor, gamma, gamma_deviation, r_min, r_max: the penalty, as above.

Usage:
  /usr/bin/python3 scripts/getfem_hertz.py [--out data/getfem/hertz_getfem.csv]
      [--ladder q1:4,8,16,32,64 q2:4,8,16,32,64] [--theta 0] [--factor 1 10]

One run per rung and factor; the CSV holds every run, converged or not.
Needs Debian's python3-getfem (the system interpreter /usr/bin/python3);
without it the script says so and exits with status 3.
"""

import argparse
import datetime
import math
import sys
import time

R = 0.2
E = 2e7
NU = 0.1
BODY_FORCE = -1.3e6
SAMPLES = 20
PENALTY = 1.0


def coons(s, t):
    """The Coons map of the unit square onto the half disk x >= 0."""
    c = (0.0, R)

    def arc(angle):
        return (c[0] + R * math.cos(angle), c[1] + R * math.sin(angle))

    deg = math.pi / 180.0
    bottom = arc((270.0 + 45.0 * s) * deg)
    top = arc((90.0 - 45.0 * s) * deg)
    left = (0.0, 2.0 * R * t)
    right = arc((-45.0 + 90.0 * t) * deg)
    p00, p10 = (0.0, 0.0), arc(315.0 * deg)
    p01, p11 = (0.0, 2.0 * R), arc(45.0 * deg)
    out = []
    for k in range(2):
        v = ((1 - t) * bottom[k] + t * top[k] + (1 - s) * left[k] + s * right[k]
             - ((1 - s) * (1 - t) * p00[k] + s * (1 - t) * p10[k]
                + (1 - s) * t * p01[k] + s * t * p11[k]))
        out.append(v)
    return out


def mesh(gf, np, degree, n):
    """N x N isoparametric Q_degree elements (GT_QK node order: the first
    reference coordinate runs fastest)."""
    m = gf.Mesh('empty', 2)
    gt = gf.GeoTrans('GT_QK(2,%d)' % degree)
    for j in range(n):
        for i in range(n):
            pts = []
            for b in range(degree + 1):
                for a in range(degree + 1):
                    pts.append(coons((i + a / degree) / n, (j + b / degree) / n))
            m.add_convex(gt, np.array(pts).T)
    return m


def face_points(degree, n):
    """Points on the contact arc: the bottom faces (t = 0) of the first
    element row, SAMPLES per face, mapped like the elements (Lagrange
    interpolation of the face's nodes)."""
    pts = []
    for i in range(n):
        nodes = [coons((i + a / degree) / n, 0.0) for a in range(degree + 1)]
        for k in range(SAMPLES):
            xi = (k + 0.5) / SAMPLES
            ref = [a / degree for a in range(degree + 1)]
            w = []
            for a in range(degree + 1):
                l = 1.0
                for b in range(degree + 1):
                    if b != a:
                        l *= (xi - ref[b]) / (ref[a] - ref[b])
                w.append(l)
            pts.append([sum(w[a] * nodes[a][d] for a in range(degree + 1)) for d in range(2)])
    return pts


def solve(gf, np, degree, n, theta, factor):
    m = mesh(gf, np, degree, n)
    t0 = time.perf_counter()
    border = m.outer_faces()
    normals = m.normal_of_faces(border)
    CONTACT, SYMMETRY = 1, 2
    # the contact arc: outward normal within 45 degrees of -y
    m.set_region(CONTACT, border[:, np.nonzero(normals[1] < -math.cos(math.pi / 4) + 1e-9)[0]])
    m.set_region(SYMMETRY, border[:, np.nonzero(normals[0] < -1.0 + 1e-9)[0]])
    mfu = gf.MeshFem(m, 2)
    mfu.set_fem(gf.Fem('FEM_QK(2,%d)' % degree))
    mfd = gf.MeshFem(m, 1)
    mfd.set_fem(gf.Fem('FEM_QK(2,%d)' % degree))
    mim = gf.MeshIm(m, gf.Integ('IM_GAUSS_PARALLELEPIPED(2,%d)' % (2 * degree + 2)))
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    md = gf.Model('real')
    md.add_fem_variable('u', mfu)
    md.add_initialized_data('lambda', [lam])
    md.add_initialized_data('mu', [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, 'u', 'lambda', 'mu')
    md.add_initialized_data('f', [0.0, BODY_FORCE])
    md.add_source_term_brick(mim, 'u', 'f')
    md.add_normal_Dirichlet_condition_with_multipliers(mim, 'u', degree, SYMMETRY)
    # Only contact holds the disk vertically, and GetFEM's Newton starts
    # from u = 0 where no point touches: a weak elastic foundation (a mass
    # term, as in GetFEM's own contact demos) keeps the first tangent
    # regular. Its force, PENALTY * |u| * area ~ 1e-3 N/m, is 1e-8 of the load.
    md.add_initialized_data('penalty', [PENALTY])
    md.add_mass_brick(mim, 'u', 'penalty')
    md.add_initialized_fem_data('obstacle', mfd, mfd.eval('y'))
    # the crate's gamma of Eq. (11) at factor F: gamma0 per element (a
    # piecewise constant field) times that element's element_size, so that
    # the brick's gamma0 / element_size is F 0.1 E (p+1)(p+2) / h_b
    faces = m.region(CONTACT).shape[1]
    length = gf.asm_generic(mim, 0, '1', CONTACT, md)
    h_b = length / faces
    mfg = gf.MeshFem(m, 1)
    mfg.set_fem(gf.Fem('FEM_QK(2,0)'))
    sizes_model = gf.Model('real')
    sizes_model.add_fem_variable('g', mfg)
    sizes = (gf.asm_generic(mim, 1, 'element_size*Test_g', -1, sizes_model)
             / gf.asm_generic(mim, 1, 'Test_g', -1, sizes_model))
    gamma = factor * 0.1 * E * (degree + 1) * (degree + 2) / h_b
    md.add_initialized_fem_data('gamma0', mfg, gamma * sizes)
    # the check: the brick's gamma at the contact points, against Eq. (11)
    pts = np.array(face_points(degree, n)).T
    formed = np.asarray(md.interpolation('gamma0/element_size', pts, m)).reshape(-1)
    deviation = float(np.max(np.abs(formed / gamma - 1.0)))
    on_faces = np.asarray(md.interpolation('element_size', pts, m)).reshape(-1) / h_b
    neumann = md.Neumann_term('u', CONTACT)
    md.add_Nitsche_contact_with_rigid_obstacle_brick(
        mim, 'u', neumann, 'obstacle', 'gamma0', CONTACT, theta)
    t1 = time.perf_counter()
    # MUMPS explicitly: for large systems 'auto' picks GMRES with ILUT,
    # which fails here (tiny pivots) and runs for tens of minutes
    iterations, converged = md.solve('max_res', 1e-8, 'max_iter', 50, 'lsolver', 'mumps')
    t2 = time.perf_counter()
    pts = np.array(face_points(degree, n)).T
    syy = md.interpolation('(lambda*Trace(Grad_u)*Id(2) + 2*mu*Sym(Grad_u))(2,2)', pts, m)
    gap = md.interpolation('X(2) + u(2)', pts, m)
    order = np.argsort(pts[0])
    x = pts[0][order]
    p = -np.asarray(syy).reshape(-1)[order]
    g = np.asarray(gap).reshape(-1)[order]
    p0 = float(np.max(p))
    a = float(x[-1])
    for k in range(1, len(x)):
        if g[k - 1] <= 0.0 < g[k]:
            a = float(x[k - 1] + (x[k] - x[k - 1]) * (-g[k - 1]) / (g[k] - g[k - 1]))
            break
    return {
        'dofs': mfu.nbdof(),
        'p0': p0,
        'half_width': a,
        'newton_iterations': int(iterations),
        'converged': bool(converged),
        'setup_seconds': t1 - t0,
        'solve_seconds': t2 - t1,
        'factor': factor,
        'gamma': gamma,
        'deviation': deviation,
        'r_min': float(np.min(on_faces)),
        'r_max': float(np.max(on_faces)),
    }


COLUMNS = ('code,element,degree,elements,dofs,factor,gamma,gamma_deviation,r_min,r_max,p0,half_width,'
           'newton_iterations,converged,setup_seconds,solve_seconds,getfem_version,date')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--out', default='data/getfem/hertz_getfem.csv')
    ap.add_argument('--ladder', nargs='*', default=['q1:4,8,16,32,64', 'q2:4,8,16,32,64'])
    # the paper's non-symmetric variant
    ap.add_argument('--theta', type=float, default=0.0)
    # the penalty factors F of Eq. (11): 1 is the paper's
    ap.add_argument('--factor', type=float, nargs='*', default=[1.0, 10.0])
    args = ap.parse_args()
    try:
        import getfem as gf
        import numpy as np
    except ImportError:
        print('getfem_hertz: GetFEM is not installed (apt-get install python3-getfem, '
              'run with /usr/bin/python3)', file=sys.stderr)
        return 3
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    version = gf.getfem_env('release')
    date = datetime.datetime.now(datetime.timezone.utc).date().isoformat()
    rows = []
    for factor in args.factor:
        for rung in args.ladder:
            name, meshes = rung.split(':')
            degree = {'q1': 1, 'q2': 2}[name.lower()]
            for n in (int(v) for v in meshes.split(',')):
                r = solve(gf, np, degree, n, args.theta, factor)
                print('F = %g, Q%d %4d^2: %7d DOFs, p0 = %.6e, a = %.6e, %d Newton iterations%s, '
                      'set-up %.3f s, solve %.3f s'
                      % (factor, degree, n, r['dofs'], r['p0'], r['half_width'],
                         r['newton_iterations'], '' if r['converged'] else ' (NOT converged)',
                         r['setup_seconds'], r['solve_seconds']), file=sys.stderr, flush=True)
                rows.append((degree, n, r))
    import os
    os.makedirs(os.path.dirname(args.out) or '.', exist_ok=True)
    tmp = args.out + '.tmp'
    with open(tmp, 'w') as f:
        f.write('# GetFEM %s, %s; Hertz half disk R = 0.2, E = 2e7, nu = 0.1, plane strain, '
                'body force (0, -1.3e6); Nitsche contact brick, theta = %g, '
                'gamma0 = gamma element_size per element, gamma = F 0.1 E (p+1)(p+2) / h_b '
                '(the crate\'s Eq. (11) at factor F); '
                'p0 = max(-sigma_yy) and a = first zero of the deformed gap y + u_y, sampled at '
                '%d points per contact face\n' % (version, date, args.theta, SAMPLES))
        f.write(COLUMNS + '\n')
        for degree, n, r in rows:
            f.write('getfem,Q%d,%d,%d,%d,%g,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%d,%s,%.6f,%.6f,%s,%s\n'
                    % (degree, degree, n, r['dofs'], r['factor'], r['gamma'], r['deviation'],
                       r['r_min'], r['r_max'], r['p0'], r['half_width'],
                       r['newton_iterations'], 'true' if r['converged'] else 'false',
                       r['setup_seconds'], r['solve_seconds'], version, date))
    os.replace(tmp, args.out)
    print('written to %s' % args.out, file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
