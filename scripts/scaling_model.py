#!/usr/bin/python3
"""A model, not a measurement: the expected strong and weak scaling of one run spread over MPI
ranks (mpirun -np N hvi run), from the per-point cost and the bytes per point measured on this
machine (docs/verification/benchmarks.md, "One run on two ranks"), for the two ways of sharing the
nodes near a rank's edge:

  ghost points (the first version): each rank copies its neighbours' points within 2 blocks
                        (8 cells, MUSL) and recomputes their transfers; whole points (284 bytes)
                        cross the network.
  shared blocks (today): each rank scatters its own points only and sends the per-colour sums of
                        the blocks it shares (mpm/shared_blocks.hpp), twice a step (scatter,
                        remap): one block layer of nodes, 4 nodes deep, 7 doubles a node, no
                        recomputation.

and for two ways of writing: every point gathered on rank 0 for output (the driver until
collective output), or each rank writing the rows of its slab of ids into one file collectively
(today, parallel HDF5): every point's snapshot values go once to the rank of its slab; the file
system's own time is not counted.

Usage: scripts/scaling_model.py   (prints the Markdown tables of docs/verification/scaling_model.md)
"""

# --- assumptions (each stated in docs/verification/scaling_model.md) -----------------------------
POINTS = 28.5e6             # the paper's 20 g model
POINTS_PER_CELL = 8         # 2 x 2 x 2 points in a filled cell
RATE_PER_CORE = 2.7e6       # point-steps/s per core (5.4 M on 2 cores, demo physics, 0.2 mm cells)
CORES_PER_RANK = 32         # one rank per node of 32 cores ...
THREAD_EFFICIENCY = 0.5     # ... that runs at half the per-core rate on each (memory-bound step)
LINK = 12.5e9               # bytes/s: 100 Gb/s
LATENCY = 2e-6              # s per message
NEIGHBOURS = 26             # messages a rank sends per exchange
BYTES_PER_POINT = 284       # measured: 10.3 MB a step for 36,315 ghost points
GHOST_CELLS = 8             # 2 blocks of 4 cells (MUSL)
NODE_LAYER = 4              # a shared block layer, nodes
BYTES_PER_NODE = 7 * 8      # mass, momentum, force (the remap: 4 doubles; counted as 7)
STEPS_PER_OUTPUT = 100      # a snapshot or an energy row with probes every 100 steps
MIGRATING = 0.002           # share of a rank's points that change rank in a step
SNAPSHOT_BYTES = 232        # measured: the demo's snapshot, 29.3 MB for 126,327 points


def piece_edge(points_per_rank):
    """Edge of a rank's piece, cells, taken as a cube filled with material."""
    return (points_per_rank / POINTS_PER_CELL) ** (1.0 / 3.0)


def step_time(ranks, points_per_rank, ghost_nodes, gathered, slabs=False):
    rate = RATE_PER_CORE * CORES_PER_RANK * THREAD_EFFICIENCY
    L = piece_edge(points_per_rank)
    surface = 6 * L * L if ranks > 1 else 0.0  # cells on the piece's faces
    if ghost_nodes:
        work = points_per_rank
        sent = 2 * surface * NODE_LAYER * BYTES_PER_NODE
    else:
        ghosts = POINTS_PER_CELL * surface * GHOST_CELLS
        work = points_per_rank + ghosts
        sent = ghosts * BYTES_PER_POINT
    sent += MIGRATING * points_per_rank * BYTES_PER_POINT
    messages = (2 if ghost_nodes else 1) + 1  # the exchanges, and the migration
    network = sent / LINK + (messages * NEIGHBOURS * LATENCY if ranks > 1 else 0.0)
    # Output gathered on rank 0: every point through its link, there and back, once per output.
    gather = 0.0
    if gathered and ranks > 1:
        gather = 2 * ranks * points_per_rank * BYTES_PER_POINT / LINK / STEPS_PER_OUTPUT
    # Written by slabs of ids: each rank's points' values to their slab's rank, once per output.
    if slabs and ranks > 1:
        gather = points_per_rank * SNAPSHOT_BYTES / LINK / STEPS_PER_OUTPUT
    return work / rate + network + gather, work / points_per_rank - 1.0


def table(title, rows):
    print(f"\n{title}\n")
    print("| ranks | points per rank | step time | speed-up | efficiency | recomputed ghosts |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]:.3g} | {r[2] * 1e3:.3g} ms | {r[3]:.3g} | {100 * r[4]:.0f}% | "
              f"{100 * r[5]:.0f}% |")


def main():
    counts = [1, 2, 4, 8, 16, 32, 64, 128, 256]
    variants = ((False, True, "ghost points, output gathered on rank 0 (the first version)"),
                (True, True, "shared blocks, output gathered on rank 0 (the second version)"),
                (True, False, "shared blocks, output written collectively by slabs of ids (today)"))
    for ghost_nodes, gathered, name in variants:
        t1, _ = step_time(1, POINTS, ghost_nodes, gathered, not gathered)
        strong = []
        for p in counts:
            t, g = step_time(p, POINTS / p, ghost_nodes, gathered, not gathered)
            strong.append((p, POINTS / p, t, t1 / t, t1 / t / p, g))
        table(f"Strong scaling, {name}: {POINTS:.3g} points", strong)
        n = POINTS / 16
        tw, _ = step_time(1, n, ghost_nodes, gathered, not gathered)
        weak = []
        for p in counts:
            t, g = step_time(p, n, ghost_nodes, gathered, not gathered)
            weak.append((p, n, t, p * tw / t, tw / t, g))
        table(f"Weak scaling, {name}: {n:.3g} points per rank", weak)


if __name__ == "__main__":
    main()
