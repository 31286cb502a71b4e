"""Analytic reference solutions used by the tmfdem verification tests and
the case plots (python3 + numpy). Tension positive, temperatures in C."""
import numpy as np


def plate_transient(x, t, kappa=0.005, length=1.0, t_left=0.0, t_right=100.0,
                    t_initial=0.0, n_terms=4000):
    """Slab 0 < x < length, T(0) = t_left, T(length) = t_right, T(x, 0) =
    t_initial (Carslaw & Jaeger, Sec. 3.4; the paper's Eq. 47 corrected:
    the sin(n pi x / l) factor restored and the initial-value series
    separated)."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    T = t_left + (t_right - t_left) * x / length
    if t <= 0:
        return np.where(x < length, t_initial, t_right) if t_initial == 0 else T
    n = np.arange(1, n_terms + 1)[:, None]
    decay = np.exp(-kappa * n**2 * np.pi**2 * t / length**2)
    T = T + (2 / np.pi) * np.sum((t_right * np.cos(n * np.pi) - t_left) / n
                                 * np.sin(n * np.pi * x / length) * decay, axis=0)
    m = np.arange(0, n_terms)[:, None]
    odd = 2 * m + 1
    T = T + (4 * t_initial / np.pi) * np.sum(
        np.sin(odd * np.pi * x / length) / odd
        * np.exp(-kappa * odd**2 * np.pi**2 * t / length**2), axis=0)
    return T


def cylinder_temperature(r, a=0.03, b=0.15, t_a=100.0, t_b=0.0):
    """Steady temperature in a hollow cylinder a < r < b (paper Eq. 49)."""
    r = np.asarray(r, dtype=float)
    return t_a * np.log(b / r) / np.log(b / a) + t_b * np.log(a / r) / np.log(a / b)


def read_csv(path):
    """lines.csv / probes.csv -> dict name -> dict time -> (x, y, {col: values})."""
    import csv
    data = {}
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        fields = header[4:]
        for row in reader:
            t, name, x, y = float(row[0]), row[1], float(row[2]), float(row[3])
            entry = data.setdefault(name, {}).setdefault(t, ([], [], {c: [] for c in fields}))
            entry[0].append(x)
            entry[1].append(y)
            for c, v in zip(fields, row[4:]):
                entry[2][c].append(float(v))
    out = {}
    for name, by_time in data.items():
        out[name] = {}
        for t, (xs, ys, cols) in by_time.items():
            out[name][t] = (np.array(xs), np.array(ys), {c: np.array(v) for c, v in cols.items()})
    return out


def cylinder_stress(r, E=20e9, nu=0.2, alpha=1.8e-5, a=0.03, b=0.15, t_a=100.0, t_b=0.0,
                    idealisation="plane strain"):
    """Steady thermal stress in a hollow cylinder with traction-free walls,
    TENSION POSITIVE: (sigma_r, sigma_theta) [Pa].

    Plane strain (eps_zz = 0) is minus the paper's Eq. 49 (printed
    compression positive; Noda 2018, Timoshenko & Goodier Sec. 151). Plane
    stress follows from it by the substitution E -> E (1 + 2 nu)/(1 + nu)^2,
    nu -> nu/(1 + nu), alpha -> alpha (1 + nu)/(1 + 2 nu) that maps the
    plane-stress equations onto the plane-strain ones: the same bracket with
    E alpha dT / 2 in place of E alpha dT / (2 (1 - nu))."""
    r = np.asarray(r, dtype=float)
    if idealisation == "plane strain":
        C = E * alpha * (t_a - t_b) / (2 * (1 - nu))
    elif idealisation == "plane stress":
        C = E * alpha * (t_a - t_b) / 2
    else:
        raise ValueError(idealisation)
    L = np.log(b / a)
    k = b**2 / a**2 - 1
    s_r = C * (np.log(b / r) / L - (b**2 / r**2 - 1) / k)
    s_t = C * ((np.log(b / r) - 1) / L + (b**2 / r**2 + 1) / k)
    return -s_r, -s_t


def in_plane_constants(E, nu, idealisation):
    """(lambda, mu, beta/alpha) of the 2D idealisation: plane-stress or
    plane-strain Lame constants and the in-plane expansion factor."""
    mu = E / (2 * (1 + nu))
    if idealisation == "plane strain":
        return E * nu / ((1 + nu) * (1 - 2 * nu)), mu, 1 + nu
    return E * nu / (1 - nu**2), mu, 1.0


def restrained_sheet_stress(E, nu, alpha, dT, idealisation, finite):
    """sigma_xx = sigma_yy [Pa] of a sheet held at F = I and heated by dT.
    Small strain: -2 (lambda + mu) beta dT, i.e. -E alpha dT/(1 - nu) in plane
    stress and -E alpha dT/(1 - 2 nu) in plane strain. Finite strain: the
    paper's Eq. 44 with F_e = I/(1 + s), s = beta dT:
    mu (1 - (1 + s)^2) + lambda/2 ((1 + s)^-2 - (1 + s)^2)."""
    lam, mu, factor = in_plane_constants(E, nu, idealisation)
    s = factor * alpha * dT
    if not finite:
        return -2 * (lam + mu) * s
    return mu * (1 - (1 + s)**2) + 0.5 * lam * ((1 + s)**-2 - (1 + s)**2)


def quenched_disc_roots(biot, n_terms=60):
    """The first n_terms roots lambda_n of lambda J1(lambda) = Bi J0(lambda),
    one in each interval (j_{1,n-1}, j_{0,n}) (j_{1,0} = 0)."""
    from scipy.optimize import brentq
    from scipy.special import j0, j1, jn_zeros
    z0 = jn_zeros(0, n_terms)
    z1 = np.concatenate(([0.0], jn_zeros(1, n_terms - 1)))
    f = lambda x: x * j1(x) - biot * j0(x)
    return np.array([brentq(f, lo + 1e-12, hi - 1e-12) for lo, hi in zip(z1, z0)])


def quenched_disc(r, t, radius, conductivity, diffusivity, h, t_initial, t_ambient,
                  n_terms=60):
    """Temperature [C] of a long cylinder / thin disc of the given radius [m],
    initially at t_initial and cooled from t = 0 by convection h [W/(m^2 K)]
    into t_ambient (Carslaw & Jaeger 7.6): theta = sum C_n exp(-lambda_n^2 Fo)
    J0(lambda_n r/R), C_n = 2 J1(lambda_n) / (lambda_n (J0^2 + J1^2)).
    Returns (T(r, t), area-mean T(t)) for scalar t, array r."""
    from scipy.special import j0, j1
    lam = quenched_disc_roots(h * radius / conductivity, n_terms)
    c = 2 * j1(lam) / (lam * (j0(lam) ** 2 + j1(lam) ** 2))
    decay = c * np.exp(-lam**2 * diffusivity * t / radius**2)
    r = np.atleast_1d(np.asarray(r, dtype=float))
    theta = (decay[None, :] * j0(np.outer(r / radius, lam))).sum(axis=1)
    theta_mean = (decay * 2 * j1(lam) / lam).sum()
    dT = t_initial - t_ambient
    return t_ambient + dT * theta, t_ambient + dT * theta_mean


def quenched_disc_rim_hoop_stress(t, E, alpha, **kw):
    """Hoop stress at the rim of a free thin disc (plane stress), tension
    positive [Pa]: sigma_theta(R) = E alpha (T_mean - T(R)) (Timoshenko &
    Goodier Sec. 150)."""
    T_rim, T_mean = quenched_disc([kw["radius"]], t, **kw)
    return E * alpha * (T_mean - T_rim[0])


def quenched_disc_first_crack_time(f_t, E, alpha, t_max=10.0, **kw):
    """The first time [s] at which the rim hoop stress reaches f_t, or None
    if its maximum stays below."""
    return quenched_disc_hoop_stress_time(f_t, E, alpha, kw["radius"], t_max, **kw)


def quenched_disc_hoop_stress(r, t, E, alpha, **kw):
    """Hoop stress at radius r [m] of the quenched thin disc (plane stress,
    tension positive) [Pa]: E alpha (T_mean / 2 + (1/r^2) int_0^r T r' dr' - T(r))."""
    radius = kw["radius"]
    rr = np.linspace(0., r, 801)
    T, T_mean = quenched_disc(rr, t, **kw)
    inner = np.trapz(T * rr, rr) / r**2
    return E * alpha * (T_mean / 2 + inner - T[-1])


def quenched_disc_hoop_stress_time(f_t, E, alpha, r, t_max=10.0, **kw):
    """The first time [s] at which the hoop stress at radius r reaches f_t, or
    None."""
    from scipy.optimize import brentq
    times = np.geomspace(1e-7, t_max, 400)
    s = np.array([quenched_disc_hoop_stress(r, t, E, alpha, **kw) for t in times])
    above = np.nonzero(s >= f_t)[0]
    if len(above) == 0:
        return None
    i = above[0]
    if i == 0:
        return times[0]
    g = lambda t: quenched_disc_hoop_stress(r, t, E, alpha, **kw) - f_t
    return brentq(g, times[i - 1], times[i])


def read_csv_xyz(path):
    """lines.csv / probes.csv of a 3D run (columns time,name,x,y,z,...) ->
    dict name -> dict time -> (points (n x 3), {col: values})."""
    import csv
    data = {}
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        if header[:5] != ["time", "name", "x", "y", "z"]:
            raise ValueError(f"{path}: not a 3D monitor file (header {header[:5]})")
        fields = header[5:]
        for row in reader:
            entry = data.setdefault(row[1], {}).setdefault(float(row[0]), ([], {c: [] for c in fields}))
            entry[0].append([float(v) for v in row[2:5]])
            for c, v in zip(fields, row[5:]):
                entry[1][c].append(float(v))
    return {name: {t: (np.array(p), {c: np.array(v) for c, v in cols.items()})
                   for t, (p, cols) in by_time.items()}
            for name, by_time in data.items()}


def sphere_quench(r, t, radius, diffusivity, t_initial, t_surface, n_terms=2000):
    """Sphere 0 <= r < radius at t_initial, its surface held at t_surface
    from t = 0 (Carslaw & Jaeger 9.3): T = Ts + (T0 - Ts) (2 R / (pi r))
    sum (-1)^(n+1) / n sin(n pi r / R) exp(-kappa n^2 pi^2 t / R^2); at
    r = 0 the limit 2 sum (-1)^(n+1) exp(...)."""
    r = np.atleast_1d(np.asarray(r, dtype=float))
    n = np.arange(1, n_terms + 1)[:, None]
    decay = np.exp(-diffusivity * n**2 * np.pi**2 * t / radius**2)
    sign = np.where(n % 2 == 1, 1.0, -1.0)
    rho = np.maximum(r, 1e-300)[None, :]
    series = np.where(r[None, :] > 0,
                      sign / n * np.sin(n * np.pi * rho / radius) * 2 * radius / (np.pi * rho),
                      2 * sign) * decay
    return t_surface + (t_initial - t_surface) * np.sum(series, axis=0)


def sphere_quench_heat_lost(t, radius, diffusivity, rho_c, t_initial, t_surface, n_terms=2000):
    """Heat that left the sphere of sphere_quench by time t [J]:
    rho c V (T0 - Ts) (1 - 6 / pi^2 sum exp(-kappa n^2 pi^2 t / R^2) / n^2)."""
    n = np.arange(1, n_terms + 1)
    volume = 4.0 / 3.0 * np.pi * radius**3
    remaining = 6 / np.pi**2 * np.sum(np.exp(-diffusivity * n**2 * np.pi**2 * t / radius**2) / n**2)
    return rho_c * volume * (t_initial - t_surface) * (1 - remaining)


def spherical_shell_temperature(r, a, b, t_a, t_b):
    """Steady conduction between spheres r = a (T_a) and r = b (T_b):
    T = T_b + (T_a - T_b) (1/r - 1/b) / (1/a - 1/b)."""
    r = np.asarray(r, dtype=float)
    return t_b + (t_a - t_b) * (1 / r - 1 / b) / (1 / a - 1 / b)


def spherical_shell_stress(r, E, nu, alpha, a, b, t_a, t_b, t_ref=0.0):
    """Thermal stresses in a thick-walled sphere a < r < b with free
    surfaces under the steady radial temperature of
    spherical_shell_temperature (Timoshenko & Goodier, Sec. 152), TENSION
    POSITIVE: (sigma_r, sigma_t) [Pa], sigma_t the hoop stress (both
    tangential directions), with I(r) = int_a^r (T - t_ref) r^2 dr:
    sigma_r = 2 alpha E / (1 - nu) [(r^3 - a^3) I(b) / ((b^3 - a^3) r^3) - I(r) / r^3],
    sigma_t = alpha E / (1 - nu) [(2 r^3 + a^3) I(b) / ((b^3 - a^3) r^3) + I(r) / r^3 - (T - t_ref)].
    T = c0 + c1 / r gives I(r) = c0 (r^3 - a^3) / 3 + c1 (r^2 - a^2) / 2."""
    r = np.asarray(r, dtype=float)
    c1 = (t_a - t_b) / (1 / a - 1 / b)
    c0 = t_b - c1 / b - t_ref

    def integral(x):
        return c0 * (x**3 - a**3) / 3 + c1 * (x**2 - a**2) / 2

    T = c0 + c1 / r
    k = alpha * E / (1 - nu)
    s_r = 2 * k * ((r**3 - a**3) * integral(b) / ((b**3 - a**3) * r**3) - integral(r) / r**3)
    s_t = k * ((2 * r**3 + a**3) * integral(b) / ((b**3 - a**3) * r**3) + integral(r) / r**3 - T)
    return s_r, s_t


def spherical_shell_heat_flow(k, a, b, t_a, t_b):
    """Steady heat flow from r = a to r = b: 4 pi k (T_a - T_b) / (1/a - 1/b) [W]."""
    return 4 * np.pi * k * (t_a - t_b) / (1 / a - 1 / b)
