#!/usr/bin/env python3
"""The share of a coupled step spent outside the two solvers, for beds and clusters this machine
cannot hold: a model whose inputs (bench/scaling/inputs.json) are measured here or named as
assumptions. docs/performance.md, "Scaling past one node", explains it.

  python3 bench/scaling/scaling_model.py [inputs.json]   # the tables
  python3 bench/scaling/scaling_model.py --self-test      # the model against hand calculations

Two data paths:
- central: every per-parcel array passes through the orchestrator, one process on one node. Its
  work (models, checks, ledger: serial_us_per_parcel; packing and the messages:
  wire_us_per_parcel) is done for all N parcels on one core while both solvers wait, and its bytes
  cross its one network link (the larger direction, half of bytes_per_parcel, at the link's rate).
- rank to rank: both solvers partition the vessel alike among the nodes, so a parcel's cell lives
  on its own node; each particle rank exchanges with the gas ranks of its node (the same
  per-parcel work and packing, for its own parcels, all ranks at once), and only the step's round
  trips with the orchestrator (its schedule, the ledger's totals) cross the network.
The solvers: the cores split between the DEM and the gas in proportion to their work (rank to
rank: the particle ranks' with their coupling work), each at its parallel efficiency, so both
finish together; the step is solver time plus the coupling work, none of it overlapped (an upper
bound on the share).
"""
import json
import sys
from pathlib import Path


def values(inputs):
    return {k: v["value"] for k, v in inputs.items() if not k.startswith("_")}


def solver_seconds(p, n_parcels, nodes):
    """Both solvers' step on nodes x cores, the cores split so that both finish together."""
    dem = n_parcels * p["dem_us_per_parcel"] / p["dem_efficiency"]
    cfd = n_parcels / p["parcels_per_cell"] * p["cfd_us_per_cell"] / p["cfd_efficiency"]
    return (dem + cfd) * 1e-6 / (nodes * p["cores_per_node"])


def central_seconds(p, n_parcels, net):
    work = n_parcels * (p["serial_us_per_parcel"] + p["wire_us_per_parcel"]) * 1e-6
    link = n_parcels * 0.5 * p["bytes_per_parcel"] / (net["gb_per_s"] * 1e9)
    return work + link + p["messages_per_step"] * net["latency_us"] * 1e-6


def rank_to_rank_seconds(p, n_parcels, nodes, net):
    """The coupling work, done by the particle ranks for their own parcels, with the cores split so
    that the particle ranks (with that work) and the gas ranks finish together: the work spreads
    over all cores."""
    cores = nodes * p["cores_per_node"]
    work = n_parcels * (p["serial_us_per_parcel"] + p["wire_us_per_parcel"]) * 1e-6 / cores
    return work + p["messages_per_step"] * net["latency_us"] * 1e-6


def share(outside, solvers):
    return outside / (outside + solvers)


def tables(p):
    lines = []
    for name, net in p["networks"].items():
        lines.append(f"\n{name}: {net['gb_per_s']:g} GB/s, {net['latency_us']:g} us a message\n")
        lines.append("| parcels | nodes | solvers [ms/step] | central: outside [ms] | share "
                     "| rank to rank: outside [ms] | share |")
        lines.append("|---:|---:|---:|---:|---:|---:|---:|")
        for n in p["parcels"]:
            for nodes in p["nodes"]:
                s = solver_seconds(p, n, nodes)
                c = central_seconds(p, n, net)
                r = rank_to_rank_seconds(p, n, nodes, net)
                lines.append(f"| {n:,} | {nodes} | {1e3 * s:.4g} | {1e3 * c:.4g} | "
                             f"{100 * share(c, s):.1f} % | {1e3 * r:.3g} | {100 * share(r, s):.1f} % |")
    dem = p["dem_us_per_parcel"] / p["dem_efficiency"]
    cfd = p["cfd_us_per_cell"] / p["parcels_per_cell"] / p["cfd_efficiency"]
    w = p["serial_us_per_parcel"] + p["wire_us_per_parcel"]
    # rank to rank, large beds: share = w / (w + the solvers' work per parcel); 2 % needs
    # w <= 0.02 / 0.98 of that work
    lines.append(f"\nRank to rank, on large beds the share tends to w / (w + {dem + cfd:.3g} us), "
                 f"w the coupling work per parcel (now {w:.3g} us) and {dem + cfd:.3g} us the "
                 f"solvers' per parcel (DEM {dem:.3g}, gas {cfd:.3g}, at their efficiencies): "
                 f"2 % needs w <= {0.02 / 0.98 * (dem + cfd):.3g} us.")
    return "\n".join(lines)


def self_test():
    p = {"dem_us_per_parcel": 4.0, "cfd_us_per_cell": 2.0, "parcels_per_cell": 2.0,
         "serial_us_per_parcel": 0.5, "wire_us_per_parcel": 0.5, "bytes_per_parcel": 300,
         "dem_efficiency": 1.0, "cfd_efficiency": 1.0, "cores_per_node": 10,
         "messages_per_step": 4}
    net = {"gb_per_s": 1.0, "latency_us": 10}
    # 10^6 parcels on 2 nodes of 10 cores: (4 + 2 / 2) us x 10^6 / 20 = 0.25 s
    assert abs(solver_seconds(p, 1e6, 2) - 0.25) < 1e-12
    # central: 1 us x 10^6 = 1 s of work, 150 MB at 1 GB/s = 0.15 s, 40 us of latency
    assert abs(central_seconds(p, 1e6, net) - 1.15004) < 1e-9
    # rank to rank: 10^6 x 1 us over 20 cores = 50 ms, plus 40 us
    assert abs(rank_to_rank_seconds(p, 1e6, 2, net) - 0.05004) < 1e-9
    assert abs(share(1.0, 3.0) - 0.25) < 1e-15
    print("scaling model: self-test passed")


def main(argv):
    if "--self-test" in argv:
        self_test()
        return 0
    path = Path(argv[1]) if len(argv) > 1 else Path(__file__).with_name("inputs.json")
    inputs = json.loads(path.read_text())
    p = values(inputs)
    print(f"inputs: {path}")
    for k, v in inputs.items():
        if not k.startswith("_") and k not in ("networks", "parcels", "nodes"):
            print(f"  {k} = {v['value']}: {v['source']}")
    print(tables(p))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
