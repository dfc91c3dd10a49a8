"""A small, slow, obvious reference implementation of ../shared/LDEM_SPEC.md.

Written from the spec alone (numpy + scipy), to test the C++ engine against
(tests/py/test_reference.py). Nothing here is taken from pkg/ldem. Where the
spec leaves a convention open and a step-by-step comparison needs the engine's
choice, the place says "OPEN:" and where the choice comes from:
- the drive's smooth start (1 - cos over two fundamental periods) and the time
  step (0.4 x 2/omega_max): README.md, "Choices where the study is silent";
- the triangular load's axis (x): the engine's prescribed_dofs(), checked;
- the energy bookkeeping over a step (which velocity the kinetic energy uses,
  whether prescribed DOFs count, the quadrature of the external work): the
  spec only names the energies. Several consistent discretisations exist; the
  one here is derived below (Reference) and is the one whose numbers the
  engine reproduces (candidates tried: reaction at x(k) times x(k+1) - x(k),
  trapezoid of the reactions, reaction with the prescribed nodes' inertia and
  their kinetic energy counted: on a 600-step run to rupture these differ from
  the engine by 1e-4 to 3e-3 of W at the end, by percents early; this one by 2e-11).
Clamped bars (eps_r < eps_p) follow the spec literally: eps_r = eps_p.

Units: SI. Vectors of nodes are arrays (n_nodes, 3); bars are parallel arrays.

    lat = Lattice(2, 2, 2, 0.02, Material())
    sim = Reference(lat, Material(), gf=..., load="uniform", ...)
    sim.compute_forces(); sim.measure(); sim.advance()
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.optimize

# -- kinds of bar (LDEM_SPEC section 1) ---------------------------------------
EDGE, CENTRE, DIAGONAL = 0, 1, 2
KIND_NAMES = {EDGE: "edge", CENTRE: "centre-centre", DIAGONAL: "diagonal"}

# -- damage states (section 3) -------------------------------------------------
UNDAMAGED, DAMAGED, BROKEN = 0, 1, 2


@dataclass
class Material:
    """Table 2 of the study (LDEM_SPEC section 6), c_a of section 3."""
    E: float = 3.5e10
    nu: float = 0.25
    rho: float = 2400.0
    Gf_mean: float = 100.0
    Gf_cv: float = 1.0
    eps_p: float = 6.3e-5
    c_a: float = 0.1385


# -- section 2: Nayfeh and Hefzy ------------------------------------------------
def nayfeh_delta(nu):
    return 9.0 * nu / (4.0 - 8.0 * nu)


def nayfeh_phi(nu):
    d = nayfeh_delta(nu)
    return (9.0 + 8.0 * d) / (18.0 + 24.0 * d)


def normal_area(mat, L0):
    """A_n = phi L0^2: area of a normal bar (edge or centre-centre) of the infinite lattice."""
    return nayfeh_phi(mat.nu) * L0 ** 2


def diagonal_area(mat, L0):
    """A_d = (2 delta / sqrt 3) A_n."""
    return 2.0 * nayfeh_delta(mat.nu) / math.sqrt(3.0) * normal_area(mat, L0)


def fracture_area(kind, mat, L0):
    """A_f of a bar not shared with fewer modules than in the bulk: c_a L0^2 for
    normal bars, c_a (1.15 L0)^2 for diagonals (the spec's 1.15, literally)."""
    return mat.c_a * (1.15 * L0) ** 2 if kind == DIAGONAL else mat.c_a * L0 ** 2


def ca_from_module_split():
    """c_a from the study's condition that one crack splitting a module dissipates
    G_f L0^2: 1 = 4 x 0.25 c_a + c_a + 4 c_a 1.15^2 (the study then uses 0.1385)."""
    return 1.0 / (4 * 0.25 + 1.0 + 4 * 1.15 ** 2)


# -- section 1: the lattice ------------------------------------------------------
class Lattice:
    """nx x ny x nz cubic modules of side L0, a centre node in each.

    Built module by module, the obvious way: every module lists its 12 edges
    (an edge met k times is shared by k modules and gets k/4 of the bulk area and
    of the bulk fracture area), its 8 centre-corner diagonals, and a bar from its
    centre to the centre of each face neighbour (listed once per pair).
    """

    def __init__(self, nx, ny, nz, L0, mat):
        self.nx, self.ny, self.nz, self.L0 = nx, ny, nz, L0
        self.size = np.array([nx, ny, nz]) * L0
        nodes, index = [], {}

        def node(key, pos):
            if key not in index:
                index[key] = len(nodes)
                nodes.append(pos)
            return index[key]

        corner = lambda i, j, k: node(("c", i, j, k), (i * L0, j * L0, k * L0))  # noqa: E731
        centre = lambda i, j, k: node(("m", i, j, k), ((i + .5) * L0, (j + .5) * L0, (k + .5) * L0))  # noqa: E731

        modules = [(i, j, k) for k in range(nz) for j in range(ny) for i in range(nx)]
        edge_count = {}     # (n1, n2) -> number of modules sharing the edge
        diagonals, centres = [], []
        mass = {}
        m_module = mat.rho * L0 ** 3
        for (i, j, k) in modules:
            c = centre(i, j, k)
            corners = [corner(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
            # lumped mass: half to the centre, 1/16 to each corner
            mass[c] = mass.get(c, 0.0) + m_module / 2
            for n in corners:
                mass[n] = mass.get(n, 0.0) + m_module / 16
            # the 12 edges: corner pairs that differ in one index
            for p in range(8):
                for q in range(p + 1, 8):
                    if bin(p ^ q).count("1") == 1:
                        key = (corners[p], corners[q])
                        edge_count[key] = edge_count.get(key, 0) + 1
            for n in corners:
                diagonals.append((c, n))
            for (a, b, d) in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):  # face neighbour in +x, +y, +z
                if i + a < nx and j + b < ny and k + d < nz:
                    centres.append((c, centre(i + a, j + b, k + d)))

        self.X = np.array(nodes, dtype=float)
        self.mass = np.array([mass[n] for n in range(len(nodes))])
        self.index = index

        n1, n2, kind, share = [], [], [], []
        for (a, b), k in edge_count.items():
            n1.append(a), n2.append(b), kind.append(EDGE), share.append(k / 4.0)
        for (a, b) in centres:
            n1.append(a), n2.append(b), kind.append(CENTRE), share.append(1.0)
        for (a, b) in diagonals:
            n1.append(a), n2.append(b), kind.append(DIAGONAL), share.append(1.0)
        self.n1, self.n2 = np.array(n1), np.array(n2)
        self.kind, self.share = np.array(kind), np.array(share)
        self.L = np.linalg.norm(self.X[self.n2] - self.X[self.n1], axis=1)
        self.direction = (self.X[self.n2] - self.X[self.n1]) / self.L[:, None]
        An, Ad = normal_area(mat, L0), diagonal_area(mat, L0)
        self.area = np.where(self.kind == DIAGONAL, Ad, An) * self.share
        self.EA = mat.E * self.area
        self.Af = np.array([fracture_area(k, mat, L0) for k in self.kind]) * self.share

    @property
    def n_nodes(self):
        return len(self.X)

    @property
    def n_bars(self):
        return len(self.n1)

    @staticmethod
    def count_nodes(nx, ny, nz):
        return (nx + 1) * (ny + 1) * (nz + 1) + nx * ny * nz

    @staticmethod
    def count_bars(nx, ny, nz):
        """Edges: x-edges nx(ny+1)(nz+1) and the same by symmetry; centre-centre:
        (nx-1)ny nz and so on; diagonals 8 per module."""
        edges = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz
        centres = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1)
        return edges + centres + 8 * nx * ny * nz

    def stiffness(self):
        """Linear stiffness matrix (3N x 3N) of the undamaged lattice, dense."""
        N = self.n_nodes
        K = np.zeros((3 * N, 3 * N))
        for b in range(self.n_bars):
            n = self.direction[b]
            k = self.EA[b] / self.L[b] * np.outer(n, n)
            i, j = 3 * self.n1[b], 3 * self.n2[b]
            K[i:i + 3, i:i + 3] += k
            K[j:j + 3, j:j + 3] += k
            K[i:i + 3, j:j + 3] -= k
            K[j:j + 3, i:i + 3] -= k
        return K


# -- section 3: Hillerborg's triangle ---------------------------------------------
def limit_strain(Af, Gf, EA, eps_p, L):
    """eps_r = 2 A_f G_f / (EA eps_p L), clamped to eps_p (perfectly brittle) when
    smaller; returns (eps_r, clamped)."""
    eps_r = 2.0 * Af * Gf / (EA * eps_p * L)
    clamped = eps_r < eps_p
    return np.where(clamped, eps_p, eps_r), clamped


def envelope(eps, EA, eps_p, eps_r):
    """The tension envelope: EA eps up to eps_p, then linear to 0 at eps_r, then 0."""
    eps, EA, eps_r = np.broadcast_arrays(np.asarray(eps, float), EA, eps_r)
    out = np.zeros(eps.shape)
    rising = eps <= eps_p
    out[rising] = EA[rising] * eps[rising]
    soft = (eps > eps_p) & (eps < eps_r)
    out[soft] = EA[soft] * eps_p * (eps_r[soft] - eps[soft]) / (eps_r[soft] - eps_p)
    return out


def bar_force(eps, kappa, EA, eps_p, eps_r):
    """Axial force (tension > 0) at strain eps once the damage is kappa (the
    largest strain reached, eps included): elastic in compression; in tension
    on the envelope while eps = kappa, on the secant to the origin below it."""
    eps, kappa, EA, eps_r = np.broadcast_arrays(np.asarray(eps, float), kappa, EA, eps_r)
    F = EA * eps                                    # compression, or never past eps_p
    tens = (eps > 0) & (kappa > eps_p)
    secant = np.zeros(eps.shape)
    secant[tens] = envelope(kappa[tens], EA[tens], eps_p, eps_r[tens]) / kappa[tens]
    F = np.where(tens, secant * eps, F)
    return F


def damage_state(kappa, eps_p, eps_r):
    return np.where(kappa <= eps_p, UNDAMAGED, np.where(kappa < eps_r, DAMAGED, BROKEN))


def dissipated_energy(kappa, EA, eps_p, eps_r, L):
    """Work along the envelope up to kappa minus the secant energy at kappa,
    integrated piece by piece (no closed form used): A_f G_f at kappa = eps_r;
    1/2 L EA eps_p^2 for a bar clamped to perfectly brittle (eps_r = eps_p),
    whose envelope drops from EA eps_p to zero at eps_p."""
    kappa, EA, eps_r, L = np.broadcast_arrays(np.asarray(kappa, float), EA, eps_r, L)
    k = np.minimum(kappa, eps_r)
    w_rise = 0.5 * EA * eps_p * eps_p                          # the elastic branch, once past eps_p
    f_k = envelope(k, EA, eps_p, eps_r)
    # trapezoid under the straight softening branch from (eps_p, EA eps_p) to (k, f(k)): exact
    w_soft = np.where(k > eps_p, 0.5 * (EA * eps_p + f_k) * (k - eps_p), 0.0)
    stored = 0.5 * envelope(kappa, EA, eps_p, eps_r) * kappa  # on the secant at kappa (0 once broken)
    return np.where(kappa <= eps_p, 0.0, L * (w_rise + w_soft - stored))


# -- section 4: Weibull G_f ----------------------------------------------------------
def weibull_from_mean_cv(mean, cv):
    """Weibull (location 0): shape k from CV^2 = G(1+2/k)/G(1+1/k)^2 - 1, scale
    lambda = mean / G(1+1/k)."""
    if cv == 0:
        return math.inf, mean
    lg = math.lgamma

    def f(logk):
        k = math.exp(logk)
        return math.sqrt(math.expm1(lg(1 + 2 / k) - 2 * lg(1 + 1 / k))) - cv

    k = math.exp(scipy.optimize.brentq(f, math.log(0.05), math.log(500.0), xtol=1e-15, rtol=1e-15))
    return k, mean / math.gamma(1 + 1 / k)


def weibull_cdf(x, shape, scale):
    return 1.0 - np.exp(-(np.asarray(x) / scale) ** shape)


# -- sections 5 and 6: boundary conditions, drive, frequencies ------------------------
def drive_displacement(t, velocity, ramp_time):
    """OPEN (README, "Smooth start"): the drive velocity rises as (1 - cos) over
    ramp_time to `velocity`, so velocity and acceleration start at zero:
        V(t) = velocity (1 - cos(pi t / T)) / 2,  t < T;  velocity after.
    Integrated: U(t) = velocity (t/2 - T/(2 pi) sin(pi t/T)) for t < T,
    velocity (t - T/2) after."""
    T = ramp_time
    if T > 0 and t < T:
        return velocity * (t / 2 - T / (2 * math.pi) * math.sin(math.pi * t / T))
    return velocity * (t - T / 2)


class Boundary:
    """The cube test: lower face fixed (all DOFs), upper face a prescribed
    vertical displacement weight * U(t), its lateral DOFs free (default) or fixed.
    uniform: weight 1. triangular: weight x / W, zero at the edge x = 0, one at
    x = W (OPEN: the spec says "from one edge to the opposite"; the x axis is
    the engine's, checked in the tests)."""

    def __init__(self, lat, load="uniform", top_lateral_free=True):
        z, H = lat.X[:, 2], lat.size[2]
        tol = 1e-9 * lat.L0
        self.bottom = np.flatnonzero(np.abs(z) < tol)
        self.top = np.flatnonzero(np.abs(z - H) < tol)
        self.height = H
        self.face_area = lat.size[0] * lat.size[1]
        if load == "uniform":
            self.weight = np.ones(len(self.top))
        elif load == "triangular":
            self.weight = lat.X[self.top, 0] / lat.size[0]
        else:
            raise ValueError(load)
        self.prescribed = np.zeros((lat.n_nodes, 3), bool)   # displacement given (zero or driven)
        self.prescribed[self.bottom, :] = True
        self.prescribed[self.top, 2] = True
        if not top_lateral_free:
            self.prescribed[self.top, :2] = True
        self.free = ~self.prescribed


def frequencies(lat, bc):
    """omega_1 and omega_max of the undamaged lattice with every prescribed DOF
    held: K v = omega^2 M v on the free DOFs, dense."""
    free = bc.free.reshape(-1)
    K = lat.stiffness()[np.ix_(free, free)]
    m = np.repeat(lat.mass, 3)[free]
    s = 1.0 / np.sqrt(m)
    w2 = scipy.linalg.eigh(K * s[:, None] * s[None, :], eigvals_only=True)
    return math.sqrt(psd_eigenvalue(w2[0], w2)), math.sqrt(w2[-1])


def drive_frequency(lat, bc):
    """omega_d, the drive's own frequency: sqrt(u'Ku / u'Mu) of the elastic field u of
    a unit drive (the upper face's z at its weight, the other prescribed DOFs at 0, the
    free ones in equilibrium, K_ff u_f = -K_fp u_p), over every DOF; dense. It times the
    smooth start (two periods)."""
    K = lat.stiffness()
    u = np.zeros((lat.n_nodes, 3))
    u[bc.top, 2] = bc.weight
    u = u.reshape(-1)
    free = bc.free.reshape(-1)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], -K[np.ix_(free, ~free)] @ u[~free])
    return math.sqrt(u @ K @ u / (u @ (np.repeat(lat.mass, 3) * u)))


def psd_eigenvalue(value, eigenvalues):
    """An eigenvalue of a positive semi-definite matrix, round-off removed.
    A backward-stable solver (any correct LAPACK) returns the eigenvalues of
    K + E with ||E|| <~ n eps ||K||: a zero one (a mechanism) may come out as
    -1e-12 on one BLAS and +1e-12 on another. Values within that bound are
    zero; a value below it is a real negative eigenvalue, a bug in K."""
    bound = len(eigenvalues) * np.finfo(float).eps * max(abs(eigenvalues[0]), abs(eigenvalues[-1]))
    if value < -bound:
        raise ValueError(f"negative eigenvalue {value:.3e} of a positive semi-definite matrix (bound {bound:.1e})")
    return value if value > bound else 0.0


# -- section 5: central differences, and the energies ----------------------------------
class Reference:
    """The cube test integrated by the spec's central differences (section 5):

        v(n+1/2) = [(1 - D dt/2) v(n-1/2) + dt (P - F_int(x(n)))/m] / (1 + D dt/2)
        x(n+1)   = x(n) + dt v(n+1/2)

    on the free DOFs (P = 0 in the cube test), D = 2 zeta omega_1. A prescribed
    DOF is set to its value weight * U(t(n+1)) (zero on the lower face); it is
    not integrated (OPEN: the spec only says "prescribed").

    Use: compute_forces() (bar forces and damage at x(n)), measure() (state n),
    advance() (to n+1). The energies at state n, a bookkeeping of the scheme
    derived here (OPEN in the spec; these are the conventions the engine's
    numbers follow, found by comparing candidate forms, see the tests):
      - elastic: sum over the bars of 1/2 F eps L at x(n) (secant energy);
      - fracture: sum of dissipated_energy(kappa_n);
      - kinetic: 1/2 m v(n-1/2)^2 over the FREE DOFs (the last velocity known;
        a prescribed DOF's inertia is the drive's business: it is in neither
        the kinetic energy nor the external work);
      - damping: the scheme is exactly
            m (v(k+1/2) - v(k-1/2)) / dt = P - F_int(x(k)) - D m vbar_k,
            vbar_k = (v(k-1/2) + v(k+1/2)) / 2,
        so the damping force of step k works over the displacement dt vbar_k:
        dW_damp = D m vbar_k^2 dt, summed over the free DOFs and the steps k < n;
      - external work: the support of a prescribed DOF applies R_k = F_int(x(k))
        (its bars' pull, the same force that enters the free DOFs' equation at
        step k), and the midpoint rule that matches the velocity-centred
        kinetic energy takes it over the same centred interval,
            dW_ext = R_k (x(k+1) - x(k-1)) / 2,   summed over k < n
        (x(-1) = x(0): the specimen starts at rest). With this pairing
        W - K - E_el - E_frac - W_damp is a second-order (O(dt^2)) residual.
    """

    def __init__(self, lat, mat, gf, dt, damping, load="uniform", strain_rate=0.02, ramp_time=0.0,
                 top_lateral_free=True, eps_r=None):
        self.lat, self.mat = lat, mat
        self.bc = Boundary(lat, load, top_lateral_free)
        self.dt, self.D = dt, damping
        self.velocity = strain_rate * self.bc.height      # of the most-pulled upper node
        self.ramp_time = ramp_time
        self.gf = np.asarray(gf, float)
        er, self.clamped = limit_strain(lat.Af, self.gf, lat.EA, mat.eps_p, lat.L)
        self.eps_r = er if eps_r is None else np.asarray(eps_r, float)
        N = lat.n_nodes
        self.u = np.zeros((N, 3))       # x(n) - X
        self.u_prev = np.zeros((N, 3))  # x(n-1) - X
        self.v = np.zeros((N, 3))       # v(n-1/2)
        self.kappa = np.zeros(lat.n_bars)
        self.step = 0
        self.time = 0.0
        self.external_work = 0.0
        self.damping_work = 0.0
        self.f_int = None

    def set_state(self, step, u, u_prev, kappa, external_work=0.0, damping_work=0.0):
        """Start from a given state n (e.g. the engine's): x(n), x(n-1) (which
        gives v(n-1/2) = (x(n) - x(n-1))/dt) and the damage reached before step n."""
        self.step, self.time = step, step * self.dt
        self.u, self.u_prev = np.array(u, float), np.array(u_prev, float)
        self.v = (self.u - self.u_prev) / self.dt
        self.kappa = np.array(kappa, float)
        self.external_work, self.damping_work = external_work, damping_work

    def drive(self, t):
        return drive_displacement(t, self.velocity, self.ramp_time)

    def strains(self, u=None):
        """eps = (l - L)/L with l the current length; also the current unit vectors."""
        u = self.u if u is None else u
        x = self.lat.X + u
        d = x[self.lat.n2] - x[self.lat.n1]
        l = np.linalg.norm(d, axis=1)
        return (l - self.lat.L) / self.lat.L, d / l[:, None]

    def compute_forces(self):
        """Bar forces at x(n); damage kappa = max(kappa, eps)."""
        eps, e = self.strains()
        self.kappa = np.maximum(self.kappa, eps)
        self.eps = eps
        self.F = bar_force(eps, self.kappa, self.lat.EA, self.mat.eps_p, self.eps_r)
        f = np.zeros_like(self.u)
        # F_int: minus the force a node's bars exert on it (a tension pulls n1 towards n2)
        np.add.at(f, self.lat.n1, -self.F[:, None] * e)
        np.add.at(f, self.lat.n2, self.F[:, None] * e)
        self.f_int = f

    def states(self):
        return damage_state(self.kappa, self.mat.eps_p, self.eps_r)

    def measure(self):
        """State n (after compute_forces): the records of LDEM_SPEC section 6.
        stress_bottom: the sum of the vertical reactions of the lower nodes over
        the face area, tension > 0 (the support pulls them down, the bars up);
        stress_top: the same on the upper face; mean_strain: the mean vertical
        displacement of the upper nodes over the height."""
        lat, mat, bc = self.lat, self.mat, self.bc
        state = self.states()
        return dict(
            step=self.step,
            time=self.time,
            mean_strain=self.u[bc.top, 2].mean() / bc.height,
            stress_bottom=-self.f_int[bc.bottom, 2].sum() / bc.face_area,
            stress_top=self.f_int[bc.top, 2].sum() / bc.face_area,
            kinetic=0.5 * (lat.mass[:, None] * self.v ** 2)[bc.free].sum(),
            elastic=0.5 * (self.F * self.eps * lat.L).sum(),
            fracture=dissipated_energy(self.kappa, lat.EA, mat.eps_p, self.eps_r, lat.L).sum(),
            damping=self.damping_work,
            external_work=self.external_work,
            damaged=int((state == DAMAGED).sum()),
            broken=int((state == BROKEN).sum()),
        )

    def advance(self):
        """From x(n) to x(n+1) (compute_forces() first)."""
        bc, dt, D = self.bc, self.dt, self.D
        m = self.lat.mass[:, None]
        a = D * dt / 2
        v_new = ((1 - a) * self.v + dt * (-self.f_int) / m) / (1 + a)
        u_new = self.u + dt * v_new
        presc = np.zeros_like(self.u)
        presc[bc.top, 2] = bc.weight * self.drive((self.step + 1) * dt)
        u_new[bc.prescribed] = presc[bc.prescribed]
        v_new[bc.prescribed] = (u_new[bc.prescribed] - self.u[bc.prescribed]) / dt
        vbar = 0.5 * (self.v + v_new)
        self.damping_work += dt * D * (m * vbar ** 2)[bc.free].sum()
        self.external_work += 0.5 * (self.f_int * (u_new - self.u_prev))[bc.prescribed].sum()
        self.u_prev, self.u, self.v = self.u, u_new, v_new
        self.step += 1
        self.time = self.step * dt
