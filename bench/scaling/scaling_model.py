#!/usr/bin/env python3
"""The share of a coupled step spent outside the two solvers, for beds and clusters this machine
cannot hold: a model whose inputs (bench/scaling/inputs.json) are measured here or named as
assumptions. docs/performance.md, "Scaling past one node", explains it.

  python3 bench/scaling/scaling_model.py [inputs.json]   # the tables
  python3 bench/scaling/scaling_model.py --self-test      # the model against hand calculations

Two data paths:
- central: every per-parcel array passes through the orchestrator, one process on one node. Its
  work (models, checks, ledger: serial_us_per_parcel; packing and the messages:
  wire_us_per_parcel_by_size at messages of all N parcels) is done for all N parcels on one core
  while both solvers wait, and its bytes cross its one network link (the larger direction, half of
  bytes_per_parcel, at the link's rate).
- rank to rank: both solvers partition the vessel alike among the nodes, so a parcel's cell lives
  on its own node; each particle rank exchanges with the gas ranks of its node (for its own
  parcels, all ranks at once, in messages of its own parcels: N over the particle ranks, the DEM's
  share of the cores by the solvers' work), and only the step's round trips with the orchestrator
  (its schedule, the ledger's totals; peer_messages_per_step) cross the network. Its coupling
  work per parcel is peer_us_per_parcel_by_size where the inputs have it (measured on the peer
  path itself: the laws, packing, the wire between the two ranks and the checks, by the parcels a
  message carries), else the central path's serial_us_per_parcel plus its wire.
As built, the rank-to-rank path (coupling.data_path: peer) keeps the coating ledger and the zone
passes with the particles (their own parcels'; the orchestrator keeps the totals), and the
orchestrator still writes every closed zone pass to zone_passes.csv as it comes, on one core
while both solvers wait: peer_orchestrator_us_per_pass_row for passes_per_parcel_step rows per
parcel and step. The tables give the path as built and without those rows (records by rank).
The wire's cost per parcel depends on the parcels a message carries (measured at a few sizes):
log-log between the measured sizes; below the smallest and beyond the largest the nearest
measured value is held, beyond the largest an optimistic bound (the cost per parcel grew 27 times
from 65,536 to 2^20 parcels a message, and 10^7 was not answered in the bench's time).
The solvers: the cores split between the DEM and the gas in proportion to their work (rank to
rank: the particle ranks' with their coupling work), each at its parallel efficiency, so both
finish together; the step is solver time plus the coupling work, none of it overlapped (an upper
bound on the share).
"""
import json
import math
import sys
from pathlib import Path


def values(inputs):
    return {k: v["value"] for k, v in inputs.items() if not k.startswith("_")}


def wire_us_per_parcel(table, message_parcels):
    """The wire's cost per parcel for messages of message_parcels parcels, from the measured table
    (entries {"parcels", "us_per_parcel"}): log-log between measured sizes, the nearest measured
    value held outside them. Returns (us, held): held is None, "below" or "above"."""
    points = sorted((e["parcels"], e["us_per_parcel"]) for e in table)
    if message_parcels <= points[0][0]:
        return points[0][1], ("below" if message_parcels < points[0][0] else None)
    if message_parcels >= points[-1][0]:
        return points[-1][1], ("above" if message_parcels > points[-1][0] else None)
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= message_parcels < x1:
            slope = math.log(y1 / y0) / math.log(x1 / x0)
            return y0 * (message_parcels / x0) ** slope, None
    raise AssertionError("unreachable")


def solver_us_per_parcel(p):
    """The DEM's and the gas solver's work per parcel at their parallel efficiencies."""
    dem = p["dem_us_per_parcel"] / p["dem_efficiency"]
    cfd = p["cfd_us_per_cell"] / p["parcels_per_cell"] / p["cfd_efficiency"]
    return dem, cfd


def rank_message_parcels(p, n_parcels, nodes):
    """One particle rank's parcels: N over the particle ranks, the DEM's share of the cores by the
    solvers' work (the coupling work, a few per cent of it, left out of this split)."""
    dem, cfd = solver_us_per_parcel(p)
    return n_parcels / (nodes * p["cores_per_node"] * dem / (dem + cfd))


def solver_seconds(p, n_parcels, nodes):
    """Both solvers' step on nodes x cores, the cores split so that both finish together."""
    dem = n_parcels * p["dem_us_per_parcel"] / p["dem_efficiency"]
    cfd = n_parcels / p["parcels_per_cell"] * p["cfd_us_per_cell"] / p["cfd_efficiency"]
    return (dem + cfd) * 1e-6 / (nodes * p["cores_per_node"])


def central_seconds(p, n_parcels, net):
    wire, _ = wire_us_per_parcel(p["wire_us_per_parcel_by_size"], n_parcels)
    work = n_parcels * (p["serial_us_per_parcel"] + wire) * 1e-6
    link = n_parcels * 0.5 * p["bytes_per_parcel"] / (net["gb_per_s"] * 1e9)
    return work + link + p["messages_per_step"] * net["latency_us"] * 1e-6


def rank_to_rank_work_us(p, message_parcels):
    """The coupling work per parcel of a particle rank whose messages carry message_parcels:
    measured on the peer path (peer_us_per_parcel_by_size) or, without it, the central path's
    serial work and wire. Returns (us, held) as wire_us_per_parcel."""
    if "peer_us_per_parcel_by_size" in p:
        return wire_us_per_parcel(p["peer_us_per_parcel_by_size"], message_parcels)
    wire, held = wire_us_per_parcel(p["wire_us_per_parcel_by_size"], message_parcels)
    return p["serial_us_per_parcel"] + wire, held


def rank_to_rank_seconds(p, n_parcels, nodes, net, rows_central=False):
    """The coupling work, done by the particle ranks for their own parcels, with the cores split so
    that the particle ranks (with that work) and the gas ranks finish together: the work spreads
    over all cores. rows_central: the orchestrator writing the closed zone passes of the path as
    built, serial, on top."""
    cores = nodes * p["cores_per_node"]
    w, _ = rank_to_rank_work_us(p, rank_message_parcels(p, n_parcels, nodes))
    work = n_parcels * w * 1e-6 / cores
    messages = p.get("peer_messages_per_step", p["messages_per_step"])
    serial = 0.0
    if rows_central and "peer_orchestrator_us_per_pass_row" in p:
        serial = (n_parcels * p["passes_per_parcel_step"] * p["peer_orchestrator_us_per_pass_row"]
                  * 1e-6)
    return work + serial + messages * net["latency_us"] * 1e-6


def share(outside, solvers):
    return outside / (outside + solvers)


def ms(x, digits):
    """x to the given significant digits, from 1,000 up with its thousands grouped (not in
    exponent form)."""
    text = f"{x:.{digits}g}"
    return f"{float(text):,.0f}" if abs(float(text)) >= 1000 else text


def percent(x):
    """One decimal, two where one would round a share below 100 % up to it."""
    text = f"{100 * x:.1f}"
    return f"{100 * x:.2f}" if text == "100.0" and x < 1 else text


def tables(p):
    lines = []
    for name, net in p["networks"].items():
        lines.append(f"\n{name}: {net['gb_per_s']:g} GB/s, {net['latency_us']:g} us a message\n")
        built = "peer_orchestrator_us_per_pass_row" in p
        lines.append("| parcels | nodes | solvers [ms/step] | central: outside [ms] | share "
                     + ("| rank to rank as built: outside [ms] | share " if built else "")
                     + "| rank to rank, records by rank: outside [ms] | share |")
        lines.append("|---:|---:|---:|---:|---:|" + ("---:|---:|" if built else "")
                     + "---:|---:|")
        for n in p["parcels"]:
            for nodes in p["nodes"]:
                s = solver_seconds(p, n, nodes)
                c = central_seconds(p, n, net)
                r = rank_to_rank_seconds(p, n, nodes, net)
                b = rank_to_rank_seconds(p, n, nodes, net, rows_central=True)
                lines.append(f"| {n:,} | {nodes} | {ms(1e3 * s, 4)} | {ms(1e3 * c, 4)} | "
                             f"{percent(share(c, s))} % | "
                             + (f"{ms(1e3 * b, 3)} | {percent(share(b, s))} % | " if built else "")
                             + f"{ms(1e3 * r, 3)} | {percent(share(r, s))} % |")
    table = p["wire_us_per_parcel_by_size"]
    sizes = sorted(e["parcels"] for e in table)
    lines.append(f"\nThe wire's cost per parcel at the parcels a message carries (log-log between "
                 f"the measured {sizes[0]:,} to {sizes[-1]:,}; \"held\": outside them, the "
                 f"nearest measured value, an optimistic bound, the cost per parcel rising "
                 f"toward both ends):\n")
    rank_column = ("coupling work, measured on the peer path [us/parcel]"
                   if "peer_us_per_parcel_by_size" in p else "serial work + wire [us/parcel]")
    lines.append("| parcels | nodes | central: a message [parcels] | wire [us/parcel] "
                 f"| rank to rank: a message [parcels] | {rank_column} |")
    lines.append("|---:|---:|---:|---:|---:|---:|")

    def cost(us_held):
        us, held = us_held
        return f"{us:.3g}" + (f", held ({held} the measured sizes)" if held else "")

    for n in p["parcels"]:
        for nodes in p["nodes"]:
            r = rank_message_parcels(p, n, nodes)
            lines.append(f"| {n:,} | {nodes} | {n:,} | {cost(wire_us_per_parcel(table, n))} | "
                         f"{r:,.0f} | {cost(rank_to_rank_work_us(p, r))} |")
    dem, cfd = solver_us_per_parcel(p)
    n = max(p["parcels"])
    ws = "/".join(f"{rank_to_rank_work_us(p, rank_message_parcels(p, n, nodes))[0]:.3g}"
                  for nodes in p["nodes"])
    # rank to rank, large beds: share = w / (w + the solvers' work per parcel); 2 % needs
    # w <= 0.02 / 0.98 of that work
    source = ("measured on the peer path" if "peer_us_per_parcel_by_size" in p
              else "the central path's serial work and wire")
    lines.append(f"\nRank to rank, on large beds the share tends to w / (w + {dem + cfd:.3g} us), "
                 f"w the coupling work per parcel ({source}; at {n:,} parcels on "
                 f"{'/'.join(str(nodes) for nodes in p['nodes'])} nodes: {ws} us) and "
                 f"{dem + cfd:.3g} us the solvers' per parcel (DEM {dem:.3g}, gas {cfd:.3g}, at "
                 f"their efficiencies): 2 % needs w <= {0.02 / 0.98 * (dem + cfd):.3g} us.")
    return "\n".join(lines)


def self_test():
    flat = [{"parcels": 1e3, "us_per_parcel": 0.5}, {"parcels": 1e7, "us_per_parcel": 0.5}]
    p = {"dem_us_per_parcel": 4.0, "cfd_us_per_cell": 2.0, "parcels_per_cell": 2.0,
         "serial_us_per_parcel": 0.5, "wire_us_per_parcel_by_size": flat, "bytes_per_parcel": 300,
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
    # the wire by message size: 1 us at 10^3, 0.25 us at 10^5: at 10^4 the log-log middle, 0.5 us;
    # the nearest measured value held outside
    sloped = [{"parcels": 1e5, "us_per_parcel": 0.25}, {"parcels": 1e3, "us_per_parcel": 1.0}]
    assert abs(wire_us_per_parcel(sloped, 1e4)[0] - 0.5) < 1e-12
    assert wire_us_per_parcel(sloped, 10) == (1.0, "below")
    assert wire_us_per_parcel(sloped, 1e7) == (0.25, "above")
    p["wire_us_per_parcel_by_size"] = sloped
    # central at 1.6 x 10^5 parcels: wire held at 0.25 us, (0.5 + 0.25) us x 1.6 x 10^5 = 0.12 s,
    # 24 MB at 1 GB/s = 0.024 s, 40 us of latency
    assert abs(central_seconds(p, 1.6e5, net) - 0.14404) < 1e-9
    # rank to rank at 1.6 x 10^5 parcels on 2 nodes: the DEM's share of the cores 4 / (4 + 1),
    # 16 particle ranks of 10^4 parcels, the wire 0.5 us there: 1.6 x 10^5 x 1 us over 20 cores
    # = 8 ms, plus 40 us
    assert abs(rank_message_parcels(p, 1.6e5, 2) - 1e4) < 1e-6
    assert abs(rank_to_rank_seconds(p, 1.6e5, 2, net) - 0.00804) < 1e-9
    # the peer path's own measured work replaces serial + wire for rank to rank, and its round
    # trips with the orchestrator: 10^4 parcels a message at 0.2 us: 1.6 x 10^5 x 0.2 us over 20
    # cores = 1.6 ms, plus 2 x 10 us; the central path unchanged
    p["peer_us_per_parcel_by_size"] = [{"parcels": 1e4, "us_per_parcel": 0.2}]
    p["peer_messages_per_step"] = 2
    assert abs(rank_to_rank_seconds(p, 1.6e5, 2, net) - 0.00162) < 1e-9
    # as built: the orchestrator writes 10^-4 closed passes per parcel and step, 16 rows for 1.6 x
    # 10^5 parcels, at 0.5 us each: 8 us on top
    p["passes_per_parcel_step"] = 1e-4
    p["peer_orchestrator_us_per_pass_row"] = 0.5
    assert abs(rank_to_rank_seconds(p, 1.6e5, 2, net, rows_central=True) - 0.001628) < 1e-9
    assert abs(rank_to_rank_seconds(p, 1.6e5, 2, net) - 0.00162) < 1e-9
    assert abs(central_seconds(p, 1.6e5, net) - 0.14404) < 1e-9
    # the measured tables of inputs.json: their own values at their measured sizes
    inputs = json.loads(Path(__file__).with_name("inputs.json").read_text())
    for key in ("wire_us_per_parcel_by_size", "peer_us_per_parcel_by_size"):
        for e in inputs[key]["value"]:
            us, held = wire_us_per_parcel(inputs[key]["value"], e["parcels"])
            assert held is None and abs(us - e["us_per_parcel"]) < 1e-12, (e, us, held)
    print("scaling model: self-test passed")


def main(argv):
    if "-h" in argv or "--help" in argv:
        print(__doc__)
        return 0
    if "--self-test" in argv:
        self_test()
        return 0
    path = Path(argv[1]) if len(argv) > 1 else Path(__file__).with_name("inputs.json")
    try:
        inputs = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as e:
        print(f"{path}: {e}; give an inputs file like bench/scaling/inputs.json "
              f"(--help says more)", file=sys.stderr)
        return 2
    if "wire_us_per_parcel" in inputs and "wire_us_per_parcel_by_size" not in inputs:
        print(f"{path}: wire_us_per_parcel is now wire_us_per_parcel_by_size, a list of "
              f"{{\"parcels\", \"us_per_parcel\", \"source\"}} (see bench/scaling/inputs.json); "
              f"one entry keeps the cost the same at every size", file=sys.stderr)
        return 2
    p = values(inputs)
    print(f"inputs: {path}")
    for k, v in inputs.items():
        if k in ("wire_us_per_parcel_by_size", "peer_us_per_parcel_by_size"):
            print(f"  {k}: {v['source']}")
            for e in sorted(v["value"], key=lambda e: e["parcels"]):
                print(f"    {e['parcels']:,} parcels a message: {e['us_per_parcel']} us: "
                      f"{e['source']}")
        elif not k.startswith("_") and k not in ("networks", "parcels", "nodes"):
            print(f"  {k} = {v['value']}: {v['source']}")
    print(tables(p))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
