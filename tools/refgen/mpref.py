"""High-precision reference distributions for mcstat's tests (mpmath).

Independent of libmcstat: tails from the incomplete beta/gamma functions at
mp precision (prefactors from loggamma, where 50 digits absorb any
cancellation), quantiles by Newton's method in mp from SciPy's double
precision values.  Used by make_reference.py.
"""
import mpmath as mp

mp.mp.dps = 50


def _beta_cf(a, b, x):
    """Continued fraction (modified Lentz) of I_x(a, b) * a / prefactor."""
    tiny = mp.mpf(10) ** (-4 * mp.mp.dps)
    eps = mp.mpf(10) ** (-mp.mp.dps + 5)
    c = mp.mpf(1)
    d = 1 - (a + b) * x / (a + 1)
    d = 1 / (d if abs(d) > tiny else tiny)
    h = d
    m = 1
    while True:
        m2 = 2 * m
        aa = m * (b - m) * x / ((a - 1 + m2) * (a + m2))
        d = 1 + aa * d; c = 1 + aa / c; d = 1 / d; h *= d * c
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1 + m2))
        d = 1 + aa * d; c = 1 + aa / c; d = 1 / d; de = d * c; h *= de
        if abs(de - 1) < eps:
            return h
        m += 1


def _beta_lower(a, b, x, y):
    lpre = a * mp.log(x) + b * mp.log(y) - (mp.loggamma(a) + mp.loggamma(b) - mp.loggamma(a + b))
    return mp.exp(lpre) * _beta_cf(a, b, x) / a


def beta_tails(a, b, x, y=None):
    """(I_x(a,b), 1 - I_x(a,b)), each computed directly where it is small;
    y = 1 - x may be given separately when it is too small to form."""
    a, b, x = mp.mpf(a), mp.mpf(b), mp.mpf(x)
    y = 1 - x if y is None else mp.mpf(y)
    if x <= 0:
        return mp.mpf(0), mp.mpf(1)
    if y <= 0:
        return mp.mpf(1), mp.mpf(0)
    if x < (a + 1) / (a + b + 2):
        p = _beta_lower(a, b, x, y)
        return p, 1 - p
    q = _beta_lower(b, a, y, x)
    return 1 - q, q


def gamma_tails(a, x):
    """(P(a,x), Q(a,x)): series for P below a+1, Legendre's fraction for Q above."""
    a, x = mp.mpf(a), mp.mpf(x)
    if x <= 0:
        return mp.mpf(0), mp.mpf(1)
    lpre = a * mp.log(x) - x - mp.loggamma(a)
    eps = mp.mpf(10) ** (-mp.mp.dps + 5)
    if x < a + 1:
        s = term = 1 / a
        n = 1
        while True:
            term *= x / (a + n)
            s += term
            if term < s * eps:
                break
            n += 1
        p = mp.exp(lpre) * s
        return p, 1 - p
    tiny = mp.mpf(10) ** (-4 * mp.mp.dps)
    b = x + 1 - a
    c = 1 / tiny
    d = 1 / b
    h = d
    i = 1
    while True:
        an = -i * (i - a)
        b += 2
        d = an * d + b
        d = d if abs(d) > tiny else tiny
        c = b + an / c
        c = c if abs(c) > tiny else tiny
        d = 1 / d
        de = d * c
        h *= de
        if abs(de - 1) < eps:
            break
        i += 1
    q = mp.exp(lpre) * h
    return 1 - q, q


def t_tails(t, df):
    t, df = mp.mpf(t), mp.mpf(df)
    if t == 0:
        return mp.mpf(0.5), mp.mpf(0.5)
    p, _ = beta_tails(df / 2, mp.mpf(0.5), df / (df + t * t), t * t / (df + t * t))
    up = p / 2
    return (1 - up, up) if t > 0 else (up, 1 - up)


def chisq_tails(x, df):
    return gamma_tails(mp.mpf(df) / 2, mp.mpf(x) / 2)


def f_tails(x, df1, df2):
    x, df1, df2 = mp.mpf(x), mp.mpf(df1), mp.mpf(df2)
    return beta_tails(df1 / 2, df2 / 2, df1 * x / (df1 * x + df2), df2 / (df1 * x + df2))


def t_pdf(t, df):
    t, df = mp.mpf(t), mp.mpf(df)
    return mp.exp(mp.loggamma((df + 1) / 2) - mp.loggamma(df / 2) - mp.log(df * mp.pi) / 2
                  - (df + 1) / 2 * mp.log1p(t * t / df))


def chisq_pdf(x, df):
    x, a = mp.mpf(x), mp.mpf(df) / 2
    return mp.exp((a - 1) * mp.log(x) - x / 2 - a * mp.log(2) - mp.loggamma(a))


def f_pdf(x, df1, df2):
    x, a, b = mp.mpf(x), mp.mpf(df1) / 2, mp.mpf(df2) / 2
    return mp.exp(a * mp.log(df1 / df2 * 1) + (a - 1) * mp.log(x) - (a + b) * mp.log1p(df1 * x / df2)
                  - (mp.loggamma(a) + mp.loggamma(b) - mp.loggamma(a + b)))


def quantile(tails, pdf, p, upper, x0):
    """Positive root of log T(x) = log p (T the chosen tail), by Newton's
    method in z = log x at mp precision; x0 > 0 is a starting value."""
    p = mp.mpf(p)
    z = mp.log(mp.mpf(x0))
    for _ in range(200):
        x = mp.exp(z)
        P, Q = tails(x)
        T = Q if upper else P
        f = mp.log(T) - mp.log(p)
        slope = x * pdf(x) / T * (-1 if upper else 1)
        step = f / slope
        if abs(step) > 50:  # damp far from the root
            step = 50 * mp.sign(step)
        z -= step
        if abs(step) <= mp.mpf(10) ** (-mp.mp.dps + 15):
            return mp.exp(z)
    raise RuntimeError("quantile did not converge")


def chisq_tail_quad(x, df, upper):
    """A chi-squared tail by quadrature of the density (tanh-sinh, with break
    points every few standard deviations): an oracle independent of the
    series, fractions and asymptotic expansions, usable at any df."""
    a = mp.mpf(df) / 2
    g = mp.mpf(x) / 2
    s = mp.sqrt(a)
    lg = mp.loggamma(a)
    f = lambda t: mp.exp((a - 1) * mp.log(t) - t - lg)
    # break points on the tail's own scale (its e-folding length a/|g - a|
    # far from the centre) and every few standard deviations
    h = min(s, a / abs(g - a)) if g != a else s
    near = [h * c for c in (0.5, 1, 2, 4, 8, 16, 32, 64, 128)]
    if upper:
        pts = [g] + [g + d for d in near] + [a + k * s for k in (5, 10, 20, 40, 80) if a + k * s > g + near[-1]]
        pts = sorted(set(pts)) + [mp.inf]
    else:
        pts = [g - d for d in near if g - d > 0] + [a - k * s for k in (80, 40, 20, 10, 5) if 0 < a - k * s < g - near[-1]]
        pts = [mp.mpf(0)] + sorted(set(pts)) + [g]
    return mp.quad(f, pts)


def f_tail_quad(f, df1, df2, upper):
    """An F tail by quadrature of the beta density of x = df1 f/(df1 f + df2),
    with break points on the standard-deviation scale: independent of the
    continued fraction and of the asymptotic expansion.  For |z| <= 5."""
    a, b = mp.mpf(df1) / 2, mp.mpf(df2) / 2
    f = mp.mpf(f)
    x = df1 * f / (df1 * f + df2)
    r = a + b
    xi = a / r
    sd = mp.sqrt(xi * (1 - xi) / r)
    lb = mp.loggamma(a) + mp.loggamma(b) - mp.loggamma(r)
    dens = lambda t: mp.exp((a - 1) * mp.log(t) + (b - 1) * mp.log1p(-t) - lb)
    ks = [k / mp.mpf(4) for k in range(-160, 161)]
    grid = [xi + k * sd for k in ks if 0 < xi + k * sd < 1]
    if upper:
        pts = [x] + [g for g in grid if g > x] + [mp.mpf(1)]
    else:
        pts = [mp.mpf(0)] + [g for g in grid if g < x] + [x]
    return mp.quad(dens, pts)
