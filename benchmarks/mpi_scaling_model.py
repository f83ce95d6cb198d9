#!/usr/bin/python3
"""Scale on paper (issue 37 item 6): the time per increment of a distributed run of N C3D8R
elements on P ranks (one core each), from what was measured here and assumed networks.
Prints the markdown tables of benchmarks/RESULTS.md, "Scale on paper".

Model, per rank and increment (the slowest rank sets the pace):
  compute   = (N / P) * T_EL * imbalance(P)
  halo      = K * alpha + bytes / beta, with the subdomain a cube of m = (N / P)^(1/3)
              elements a side and bytes = FACES * SLOTS_PER_NODE * m^2 * 24 (one force slot
              per element corner at a shared node, exchange_plan.hpp); exposed in full
              (no overlap) and, with item 3's overlap, only beyond the interior elements' time
  allreduce = 2 * alpha * log2(P) (recursive doubling of the increment and energies)
  imbalance = (1 + r / phi) / (1 + r) with contact: contact work r (relative to the
              elements) on the fraction phi = P^(-1/3) of the ranks a plane contact zone
              crosses; 1.03 (METIS' tolerance) without contact or with a second balance
              constraint for contact.
Usage: benchmarks/mpi_scaling_model.py
"""

import math

T_EL = 130e-9  # s per C3D8R element increment, one core (7.7 M element-cycles/s, RESULTS.md)
SLOTS_PER_NODE = 3.8  # slots per shared node of a hex interface (measured plans: 3.60-3.84)
FACES = 6  # faces of an interior cube subdomain
K = 14  # neighbour messages per increment (METIS on 3-D meshes; 26 for cubes, 7 measured at 8)
CONTACT_R = 0.3  # contact work / element work (block impact: 29-36 %, RESULTS.md)
BALANCE = 1.03  # METIS' default tolerance

NETWORKS = {
    # name: (alpha s, beta B/s)
    "here (shared memory, measured)": (0.35e-6, 10e9),
    "InfiniBand HDR100 (assumed)": (1.5e-6, 11e9),
    "25 GbE TCP (assumed)": (20e-6, 2.5e9),
}


def halo_bytes(elements_per_rank):
    m = elements_per_rank ** (1.0 / 3.0)
    return FACES * SLOTS_PER_NODE * m * m * 24.0


def increment(n, p, alpha, beta, contact=False, overlap=False, balanced_contact=False):
    """Seconds per increment of the slowest rank: (total, compute, exposed halo, allreduce)."""
    e = n / p
    if p == 1:
        t = e * T_EL * (1.0 + (CONTACT_R if contact else 0.0))
        return t, t, 0.0, 0.0
    imbalance = BALANCE
    if contact and not balanced_contact:
        phi = min(1.0, p ** (-1.0 / 3.0))
        imbalance = max(BALANCE, (1.0 + CONTACT_R / phi) / (1.0 + CONTACT_R))
    work = 1.0 + (CONTACT_R if contact else 0.0)
    compute = e * T_EL * work * imbalance
    halo = K * alpha + halo_bytes(e) / beta
    if overlap:
        m = e ** (1.0 / 3.0)
        interior = max(0.0, (m - 2.0) / m) ** 3 * e * T_EL
        halo = max(0.0, halo - interior)
    allreduce = 2.0 * alpha * math.log2(p)
    return compute + halo + allreduce, compute, halo, allreduce


def strong_scaling_table():
    print("| N elements | P ranks | elements / rank | halo kB / rank | network | compute ms | "
          "halo µs (exposed, no overlap) | allreduce µs | efficiency | efficiency, overlap |")
    print("|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|")
    for n in (1e6, 1e7, 1e8):
        for p in (64, 128, 256, 512, 1024):
            for name in ("InfiniBand HDR100 (assumed)", "25 GbE TCP (assumed)"):
                alpha, beta = NETWORKS[name]
                t, c, h, a = increment(n, p, alpha, beta)
                t_ov = increment(n, p, alpha, beta, overlap=True)[0]
                serial = n * T_EL
                print(f"| {n:.0e} | {p} | {n / p:,.0f} | {halo_bytes(n / p) / 1e3:.0f} | "
                      f"{name.split(' (')[0]} | {c * 1e3:.3f} | {h * 1e6:.1f} | {a * 1e6:.1f} | "
                      f"{serial / (p * t):.2f} | {serial / (p * t_ov):.2f} |")


def contact_table():
    print("| P ranks | contact zone ranks φ | imbalance, one constraint | efficiency (IB, 1e7 "
          "elements) | with contact as 2nd constraint |")
    print("|---:|---:|---:|---:|---:|")
    alpha, beta = NETWORKS["InfiniBand HDR100 (assumed)"]
    n = 1e7
    for p in (8, 64, 128, 256, 512, 1024):
        phi = min(1.0, p ** (-1.0 / 3.0))
        imb = max(BALANCE, (1.0 + CONTACT_R / phi) / (1.0 + CONTACT_R))
        serial = n * T_EL * (1.0 + CONTACT_R)
        t = increment(n, p, alpha, beta, contact=True, overlap=True)[0]
        tb = increment(n, p, alpha, beta, contact=True, overlap=True, balanced_contact=True)[0]
        print(f"| {p} | {phi:.3f} | {imb:.2f} | {serial / (p * t):.2f} | {serial / (p * tb):.2f} |")


def second_machine():
    """Smallest N at which 2 machines of C cores beat one by SPEEDUP (slowest rank's whole
    halo and the allreduce at network cost on two machines, shared-memory cost on one)."""
    print("| cores per machine | network | break-even N (2 machines = 1) | elements / rank there | "
          "N for speed-up 1.5 | elements / rank there | N for speed-up 1.8 | elements / rank |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|")
    here_a, here_b = NETWORKS["here (shared memory, measured)"]
    for cores in (2, 64):
        for name in ("InfiniBand HDR100 (assumed)", "25 GbE TCP (assumed)"):
            alpha, beta = NETWORKS[name]
            row = [str(cores), name.split(" (")[0]]
            for target in (1.0, 1.5, 1.8):
                n = 1e3
                while n < 1e10:
                    one = increment(n, cores, here_a, here_b, overlap=True)[0]
                    two = increment(n, 2 * cores, alpha, beta, overlap=True)[0]
                    if one / two >= target:
                        break
                    n *= 1.05
                row += [f"{n:,.0f}", f"{n / (2 * cores):,.0f}"]
            print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    print("Assumptions: T_EL = %.0f ns per C3D8R element increment; %.1f slots per shared node; "
          "%d neighbour messages; networks (alpha, beta): %s\n" % (
              T_EL * 1e9, SLOTS_PER_NODE, K,
              "; ".join(f"{k}: {a * 1e6:.2f} µs, {b / 1e9:.1f} GB/s"
                        for k, (a, b) in NETWORKS.items())))
    strong_scaling_table()
    print()
    contact_table()
    print()
    second_machine()
