#!/usr/bin/env python3
"""IAS15 on the race's two N-body scenes, measured by REBOUND itself.

REBOUND's IAS15 (Rein and Spiegel 2015, MNRAS 446, 1424) is the reference
integrator of N-body work: a 15th-order Gauss-Radau predictor-corrector with
adaptive steps. This script runs it on the same initial states as the race
(the Pleiades to t = 3, the outer solar system to 2 sqrt(2) Jupiter periods,
both from their published data, in physical coordinates, no change of frame)
at a ladder of its accuracy parameter `epsilon`, and writes each run's end
state and cost to ias15.json beside it. The lab judges those end states
against its references exactly as it judges its own contenders.

Cost: REBOUND has no counter of force evaluations, so a force that adds
nothing is registered as `additional_forces`, which REBOUND calls once per
evaluation of the gravity, and it is counted (velocity independent, so that
IAS15 iterates exactly as without it). `steps_done` is REBOUND's own count of
steps.

Run (REBOUND 5.x from PyPI, outside the crate's build):
    python3 -m venv venv && venv/bin/pip install rebound==5.2.2
    venv/bin/python lab/ias15/ias15.py
"""

import json
import math
import os

import rebound

EPSILONS = [10.0 ** -k for k in range(1, 13)]


def pleiades():
    x = [3, 3, -1, -3, 2, -2, 2]
    y = [3, -3, 2, 0, 0, -4, 4]
    vx = [0, 0, 0, 0, 0, 1.75, -1.5]
    vy = [0, 0, 0, -1.25, 1, 0, 0]
    bodies = [(float(i + 1), (x[i], y[i], 0.0), (vx[i], vy[i], 0.0)) for i in range(7)]
    return 1.0, bodies, 3.0, 2


G_OUTER = 2.95912208286e-4
M_OUTER = [1.00000597682, 0.000954786104043, 0.000285583733151, 0.0000437273164546,
           0.0000517759138449, 1.0 / 1.3e8]
Q_OUTER = [(0.0, 0.0, 0.0), (-3.5023653, -3.8169847, -1.5507963),
           (9.0755314, -3.0458353, -1.6483708), (8.3101420, -16.2901086, -7.2521278),
           (11.4707666, -25.7294829, -10.8169456), (-15.5387357, -25.2225594, -3.1902382)]
V_OUTER = [(0.0, 0.0, 0.0), (0.00565429, -0.00412490, -0.00190589),
           (0.00168318, 0.00483525, 0.00192462), (0.00354178, 0.00137102, 0.00055029),
           (0.00288930, 0.00114527, 0.00039677), (0.00276725, -0.00170702, -0.00136504)]


def outer_solar_system():
    # Jupiter about the Sun, as the scene computes its period: vis-viva
    mu = G_OUTER * (M_OUTER[0] + M_OUTER[1])
    r = math.sqrt(sum(c * c for c in Q_OUTER[1]))
    v = math.sqrt(sum(c * c for c in V_OUTER[1]))
    a = 1.0 / (2.0 / r - v * v / mu)
    period = 2.0 * math.pi * math.sqrt(a ** 3 / mu)
    t_end = 2.0 * math.sqrt(2.0) * period
    return G_OUTER, list(zip(M_OUTER, Q_OUTER, V_OUTER)), t_end, 3


def run(scene, epsilon):
    g, bodies, t_end, dims = scene
    sim = rebound.Simulation()
    sim.G = g
    sim.integrator = "ias15"
    sim.integrator.epsilon = epsilon
    for m, q, v in bodies:
        sim.add(m=m, x=q[0], y=q[1], z=q[2], vx=v[0], vy=v[1], vz=v[2])
    count = [0]

    def nothing(reb_sim):
        count[0] += 1

    sim.additional_forces = nothing
    sim.force_is_velocity_dependent = 0
    sim.integrate(t_end, exact_finish_time=1)
    ps = sim.particles
    return {
        "epsilon": epsilon,
        "t": sim.t,
        "evaluations": count[0],
        "steps": sim.steps_done,
        "positions": [[p.x, p.y, p.z][:dims] for p in ps],
        "velocities": [[p.vx, p.vy, p.vz][:dims] for p in ps],
    }


if __name__ == "__main__":
    out = {
        "rebound": rebound.__version__,
        "command": "venv/bin/python lab/ias15/ias15.py",
        "pleiades": [run(pleiades(), e) for e in EPSILONS],
        "outer-solar-system": [run(outer_solar_system(), e) for e in EPSILONS],
    }
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ias15.json")
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    for scene in ("pleiades", "outer-solar-system"):
        for r in out[scene]:
            print(scene, f"eps {r['epsilon']:.0e}", "evaluations", r["evaluations"],
                  "steps", r["steps"], "t", r["t"])
