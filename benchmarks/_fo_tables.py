"""The tables benchmarks/bench_fo.py prints: lo against its own transforms and the fastest floor
for each size and method (ms, ratios, D1 error, load, rounds, target), the transforms alone, and the
peers against lo on the same cases."""

from __future__ import annotations

from _fo_references import THREADS


def fmt_ms(t):
    return f"{t * 1e3:8.2f}" if t is not None else f"{'-':>8}"


def print_tables(rows, added):
    print(
        f"\nlo against its own transforms and the fastest floor, {added} busy processes added "
        f"(ms, {THREADS} threads; own = the library's FFT pair (AS) or forward FFT (Fresnel), no "
        "copies; floor = least of own, system FFTW measured, pyFFTW measured; med = median "
        "per-round ratio, against each floor and the largest; null = own timed again, against own "
        "(med) and against the least floor of its round (rl); D1 err = |1 - w_D1 / w|)"
    )
    header = (
        f"{'N':>5} {'case':9} {'own':>8} {'floor':>8} {'from':>6} {'lo':>8} {'x own':>6} "
        f"{'x floor':>7} {'med own':>7} {'med fl':>6} {'null':>5} {'null rl':>7} {'native':>8} "
        f"{'cold':>8} {'new z':>8} "
        f"{'D1 err':>8} {'load':>5} {'rounds':>6}  target"
    )
    print(header)
    print("-" * len(header))
    for r in rows:
        for m, c in r["cases"].items():
            print(
                f"{r['n']:5d} {m[:9]:9} {fmt_ms(c['own_s'])} {fmt_ms(c['floor_s'])} "
                f"{c['floor_source']:>6} {fmt_ms(c['lo_s'])} {c['ratio_to_own']:5.2f}x "
                f"{c['ratio_to_floor']:6.2f}x {c['ratio_to_own_median']:6.2f}x "
                f"{c['ratio_to_floor_median']:5.2f}x {c['null_ratio_to_own_median']:4.2f}x "
                f"{c['null_ratio_to_round_least_floor_median']:6.2f}x {fmt_ms(c['lo_native_s'])} "
                f"{c['lo_cold_s'] * 1e3:8.1f} {fmt_ms(c['lo_new_distance_s'])} "
                f"{c['lo_d1_rel_error']:8.1e} {r['load_average_1min']:5.1f} {r['rounds']:6d}  "
                f"{'met' if c['target_met'] else 'NOT met'} (<= {c['target_own']:g}x own, "
                f"{c['target_floor']:g}x floor, on {c['target_judged_on']})"
            )
    print(
        "transforms alone (ms): "
        + "; ".join(
            f"{r['n']}: "
            + ", ".join(
                f"{name} " + " ".join(f"{src} {t * 1e3:.2f}" for src, t in srcs.items())
                for name, srcs in r["transforms_s"].items()
            )
            for r in rows
        )
    )


def print_peers(rows):
    print(
        "\npeers (ms; x lo = peer time / lo warm time, x new z = peer time / lo new-z time; D1 err "
        "of the peer and of lo on the same case)"
    )
    header = (
        f"{'N':>5} {'case':9} {'peer':10} {'routine':34} {'time':>9} {'x lo':>7} {'x new z':>7} "
        f"{'D1 err':>8} {'lo err':>8}"
    )
    print(header)
    print("-" * len(header))
    for r in rows:
        for m, c in r["cases"].items():
            for p in c["peers"]:
                routine = p["routine"] + (" os=1" if "num_oversampling=1" in p["settings"] else "")
                if p["s"] is None:
                    print(f"{r['n']:5d} {m[:9]:9} {p['peer']:10} {routine:34} failed: {p['error']}")
                    continue
                print(
                    f"{r['n']:5d} {m[:9]:9} {p['peer']:10} {routine:34} {p['s'] * 1e3:9.2f} "
                    f"{p['ratio_to_lo']:6.1f}x {p['ratio_to_lo_new_distance']:6.1f}x "
                    f"{p['d1_rel_error']:8.1e} {c['lo_d1_rel_error']:8.1e}"
                )
