"""Generate the lane loops of ``benchmarks/lanes_kernel.py`` (``burst2``, ``burst4``): one slot's state in local scalars each.

Numba keeps scalars in registers but per-lane arrays in memory; a loop over lanes would load and store every
lane's state each sample (the interleaved kernels dropped in git 2fe4145 did, and ran 1.6-3x slower). So the
lanes are written out, one ``lane_sample`` call per lane. Run ``python benchmarks/gen_lanes.py``
and paste its output between the markers in ``benchmarks/lanes_kernel.py``.
"""

from __future__ import annotations


def burst(lanes: int) -> str:
    """Source of ``burst<lanes>``."""
    r = range(lanes)
    o = [
        "@njit(cache=True, nogil=True)",
        f"def burst{lanes}(m, hs, st, hist, tail, ks, mus, sigmas, peaks, delay, quantize, bound, tail_start, whys):",
        f'    """Advance the {lanes} slots by up to ``m`` samples each in one loop; stop after a sample where one exits.',
        "",
        "    Each slot's state lives in local scalars; its sample is :func:`lane_sample`. Returns the loop",
        "    count ``i``: every slot ran ``i`` samples, the last of them an exit (``whys[l]`` 1: at rest,",
        "    not integrated; 2: past the bound) for the slots that exit.",
        '    """',
    ]
    for j in r:
        o.append(f"    x{j}, v{j}, p{j} = st[{j}, SX], st[{j}, SV], int(st[{j}, SPOS])")
        o.append(f"    n{j}, t{j}, e{j}, h{j}, w{j} = st[{j}, STMIN], st[{j}, STMAX], peaks[{j}], hs[{j}], 0")
        o.append(f"    mu{j}, sg{j}, hi{j}, ta{j} = mus[{j}], sigmas[{j}], hist[{j}], tail[{j}]")
        o.append(f"    k{j} = (ks[{j}, 0], ks[{j}, 1], ks[{j}, 2], ks[{j}, 3], ks[{j}, 4], ks[{j}, 5])")
    o.append("    i = 0")
    o.append("    while i < m:")
    for j in r:
        o.append(f"        x{j}, v{j}, p{j}, n{j}, t{j}, e{j}, w{j} = lane_sample(")
        o.append(
            f"            h{j} + i, x{j}, v{j}, p{j}, n{j}, t{j}, e{j}, hi{j}, ta{j}, tail_start, "
            f"mu{j}, sg{j}, delay, quantize, bound, k{j}"
        )
        o.append("        )")
    o.append("        i += 1")
    o.append("        if " + " | ".join(f"w{j}" for j in r) + ":")
    o.append("            break")
    for j in r:
        o.append(
            f"    st[{j}, SX], st[{j}, SV], st[{j}, SPOS], st[{j}, STMIN], st[{j}, STMAX] = x{j}, v{j}, p{j}, n{j}, t{j}"
        )
        o.append(f"    peaks[{j}], whys[{j}] = e{j}, w{j}")
    o.append("    return i")
    return "\n".join(o) + "\n"


def burst_free(lanes: int) -> str:
    """Source of ``burst<lanes>_free``: the slots all before their tail, no delay (the hot path)."""
    r = range(lanes)
    o = [
        "@njit(cache=True, nogil=True)",
        f"def burst{lanes}_free(m, st, ks, mus, sigmas, peaks, quantize, bound, whys):",
        f'    """:func:`burst{lanes}` for slots before their tail, without delay: each sample is',
        "    :func:`dfa.core.kernel.free_sample` (no ring, no tail).",
        '    """',
    ]
    for j in r:
        o.append(
            f"    x{j}, v{j}, e{j}, w{j}, mu{j}, sg{j} = st[{j}, SX], st[{j}, SV], peaks[{j}], 0, mus[{j}], sigmas[{j}]"
        )
        o.append(f"    k{j} = (ks[{j}, 0], ks[{j}, 1], ks[{j}, 2], ks[{j}, 3], ks[{j}, 4], ks[{j}, 5])")
    o.append("    i = 0")
    o.append("    while i < m:")
    for j in r:
        o.append(
            f"        x{j}, v{j}, e{j}, w{j}, _, _ = free_sample(x{j}, v{j}, e{j}, mu{j}, sg{j}, quantize, bound, k{j})"
        )
    o.append("        i += 1")
    o.append("        if " + " | ".join(f"w{j}" for j in r) + ":")
    o.append("            break")
    for j in r:
        o.append(f"    st[{j}, SX], st[{j}, SV], peaks[{j}], whys[{j}] = x{j}, v{j}, e{j}, w{j}")
    o.append("    return i")
    return "\n".join(o) + "\n"


def generated(lanes: int = 4) -> str:
    """Everything between the markers of ``benchmarks/lanes_kernel.py``."""
    return burst(lanes) + "\n\n" + burst_free(lanes)


if __name__ == "__main__":
    print(generated(), end="")
