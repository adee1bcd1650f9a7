"""Chebyshev coefficients of exp(-x) I0(x) for cpp/src/core/special_functions.hpp (standard library only).

Near, x in [0, 8]: f(t) = exp(-x) I0(x) with x = 4 (t + 1). Far, x in [8, inf): g(t) = sqrt(x) exp(-x) I0(x) with
x = 16 / (t + 1), analytic in 1/x. Each is interpolated at 40 Chebyshev nodes (computed, like everything here,
to 50 digits: nodes rounded to doubles would alias the high coefficients to ~1e-15) with I0 from its power series
of positive terms, and printed up to the last coefficient above 1e-18.
"""

from decimal import Decimal, getcontext

getcontext().prec = 50
PI = Decimal("3.14159265358979323846264338327950288419716939937510582097494459")
NODES = 40


def cos(t: Decimal) -> Decimal:
    t2, term, s, k = t * t, Decimal(1), Decimal(1), 0
    while abs(term) > Decimal(10) ** -55:
        k += 2
        term = -term * t2 / (k * (k - 1))
        s += term
    return s


def i0e(x: Decimal) -> Decimal:
    q, term, s, k = x * x / 4, Decimal(1), Decimal(1), 0
    while term >= s * Decimal(10) ** -45:
        k += 1
        term = term * q / (k * k)
        s += term
    return s * (-x).exp()


def chebyshev(f, n=NODES):
    xs = [cos((2 * k + 1) * PI / (2 * n)) for k in range(n)]
    values = [f(x) for x in xs]
    table = []
    for x in xs:   # T_j at each node by the recurrence
        row = [Decimal(1), x]
        for _ in range(2, n):
            row.append(2 * x * row[-1] - row[-2])
        table.append(row)
    c = [2 * sum(v * table[k][j] for k, v in enumerate(values)) / n for j in range(n)]
    return [float(v) for v in c[:max(j for j, v in enumerate(c) if abs(v) > Decimal("1e-18")) + 1]]


if __name__ == "__main__":
    for name, f in (("kI0eNear", lambda t: i0e(4 * (t + 1))),
                    ("kI0eFar", lambda t: i0e(16 / (t + 1)) * (16 / (t + 1)).sqrt())):
        print(name, ", ".join(f"{v:.17e}" for v in chebyshev(f)))
