"""Chebyshev coefficients of exp(-x) I0(x) and exp(-x) I1(x) for cpp/src/core/special_functions.hpp
(standard library only).

Near, x in [0, 8]: f(t) = exp(-x) In(x) / x^n with x = 4 (t + 1). Far, x in [8, inf): g(t) = sqrt(x)
exp(-x) In(x) with x = 16 / (t + 1), analytic in 1/x. Each is interpolated at 40 Chebyshev nodes
(computed, like everything here,
to 50 digits: nodes rounded to doubles would alias the high coefficients to ~1e-15) with In from its
power series of positive terms, and printed up to the last coefficient above 1e-18.
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


def ine(order: int, x: Decimal) -> Decimal:
    """exp(-x) I_order(x), order 0 or 1: sum_k (x/2)^(2k + order) / (k! (k + order)!)."""
    q, term, k = x * x / 4, (x / 2) ** order, 0
    s = term
    while term >= s * Decimal(10) ** -45:
        k += 1
        term = term * q / (k * (k + order))
        s += term
    return s * (-x).exp()


def chebyshev(f, n=NODES):
    xs = [cos((2 * k + 1) * PI / (2 * n)) for k in range(n)]
    values = [f(x) for x in xs]
    table = []
    for x in xs:  # T_j at each node by the recurrence
        row = [Decimal(1), x]
        for _ in range(2, n):
            row.append(2 * x * row[-1] - row[-2])
        table.append(row)
    c = [2 * sum(v * table[k][j] for k, v in enumerate(values)) / n for j in range(n)]
    return [float(v) for v in c[: max(j for j, v in enumerate(c) if abs(v) > Decimal("1e-18")) + 1]]


if __name__ == "__main__":
    for order in (0, 1):
        # I1 near 0 is x / 2: its series is of exp(-x) I1(x) / x, which keeps the relative error
        # there.
        for name, f in (
            (
                f"kI{order}eNear",
                lambda t, order=order: ine(order, 4 * (t + 1)) / (4 * (t + 1)) ** order,
            ),
            (
                f"kI{order}eFar",
                lambda t, order=order: ine(order, 16 / (t + 1)) * (16 / (t + 1)).sqrt(),
            ),
        ):
            print(name, ", ".join(f"{v:.17e}" for v in chebyshev(f)))
