#!/usr/bin/env python3
"""The dynamics model's equations in Python, integrated with SciPy's solve_ivp: the speed
baseline for bench_dynamics_virtual, on the same flight.

It replays the rotor commands that went over the bus in a C++ run (the CSV written by
`bench_dynamics_virtual --csv`), holding each for its 10 ms step as the dynamics node does,
from the C++ state at --from-s, and prints the real-time factor and how far the Python
trajectory ends from the C++ one. Same equations as dynamics/quadrotor_model.cpp (rigid body,
X rotors with k_f w^2 thrust and k_m w^2 drag torque, first-order motor lag faster up than
down, linear plus quadratic drag, angular drag, |q| pull-back term, induced-power energy),
same parameters (read from dynamics/airframes/iris.json), same tolerances as the CVODE
integrator, the quaternion renormalised after a step as the C++ integrator does.

Usage: scipy_model.py FLIGHT.csv [--from-s 12] [--duration-s 60] [--methods RK45,DOP853,LSODA]
                       [--rtol 1e-8] [--cpp-rtf N] [--cpp-cpu-rtf N]
Debian packages: python3-scipy python3-numpy.
"""
import argparse
import csv
import json
import math
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665
RHO = 1.225
SPIN = (1.0, 1.0, -1.0, -1.0)  # 0 front-right CCW, 1 rear-left CCW, 2 front-left CW, 3 rear-right CW


class Model:
    def __init__(self, airframe):
        a = airframe
        self.m = a["mass_kg"]
        self.I = (a["inertia_kgm2"]["xx"], a["inertia_kgm2"]["yy"], a["inertia_kgm2"]["zz"])
        r = a["rotor"]
        self.kf = r["thrust_coeff_N_per_radps2"]
        self.km = r["drag_torque_coeff_Nm_per_radps2"]
        self.tau_up = r["time_constant_up_s"]
        self.tau_down = r["time_constant_down_s"]
        self.lin = a["aero"]["linear_drag_Ns_per_m"]
        self.cda = a["aero"]["drag_cdA_m2"]
        self.ang = a["aero"]["angular_drag_Nms_per_rad"]
        b = a["battery"]
        self.eff = b["powertrain_efficiency"]
        self.avionics = b["avionics_power_W"]
        disk = math.pi * r["radius_m"] ** 2
        self.induced = 1.0 / (r["figure_of_merit"] * math.sqrt(2.0 * RHO * disk))
        h = a["arm_length_m"] / math.sqrt(2.0)
        self.rx = (h, -h, h, -h)  # rotor positions, body FLU
        self.ry = (-h, h, h, -h)
        self.wind = (0.0, 0.0, 0.0)

    def rhs(self, t, y, cmd):
        (px, py, pz, vx, vy, vz, qw, qx, qy, qz, wx, wy, wz, r0, r1, r2, r3, _e) = y.tolist()
        rot = (r0, r1, r2, r3)
        d_rot = []
        power = 0.0
        thrust = tx = ty = tz = 0.0
        for i in range(4):
            c = cmd[i]
            d_rot.append((c - rot[i]) / (self.tau_up if c >= rot[i] else self.tau_down))
            s = rot[i] if rot[i] > 0.0 else 0.0
            w2 = s * s
            f = self.kf * w2
            power += f * math.sqrt(f) * self.induced
            thrust += f
            tx += self.ry[i] * f
            ty -= self.rx[i] * f
            tz -= SPIN[i] * self.km * w2
        power = power / self.eff + self.avionics
        tx -= self.ang * wx
        ty -= self.ang * wy
        tz -= self.ang * wz
        # Thrust along body z rotated to the world by the normalised quaternion.
        n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
        a, b, c, d = qw / n, qx / n, qy / n, qz / n
        zx = 2.0 * (b * d + a * c)
        zy = 2.0 * (c * d - a * b)
        zz = 1.0 - 2.0 * (b * b + c * c)
        ax_, ay_, az_ = vx - self.wind[0], vy - self.wind[1], vz - self.wind[2]
        quad = 0.5 * RHO * self.cda * math.sqrt(ax_ * ax_ + ay_ * ay_ + az_ * az_)
        k = self.lin + quad
        m = self.m
        acc_x = (thrust * zx - k * ax_) / m
        acc_y = (thrust * zy - k * ay_) / m
        acc_z = (thrust * zz - k * az_ - m * G) / m
        ix, iy, iz = self.I
        # Euler's equations: I dw = tau - w x (I w)
        dwx = (tx - (wy * iz * wz - wz * iy * wy)) / ix
        dwy = (ty - (wz * ix * wx - wx * iz * wz)) / iy
        dwz = (tz - (wx * iy * wy - wy * ix * wx)) / iz
        ne = 1.0 - (qw * qw + qx * qx + qy * qy + qz * qz)
        dqw = 0.5 * (-qx * wx - qy * wy - qz * wz) + ne * qw
        dqx = 0.5 * (qw * wx + qy * wz - qz * wy) + ne * qx
        dqy = 0.5 * (qw * wy - qx * wz + qz * wx) + ne * qy
        dqz = 0.5 * (qw * wz + qx * wy - qy * wx) + ne * qz
        return [vx, vy, vz, acc_x, acc_y, acc_z, dqw, dqx, dqy, dqz, dwx, dwy, dwz] + d_rot + [power]


# The CVODE integrator's tolerances (dynamics/cvode_integrator.cpp).
RTOL = 1e-8
ATOL = np.array([1e-6] * 6 + [1e-9] * 4 + [1e-8] * 3 + [1e-3] * 4 + [1e-3])


def read_flight(path):
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows.append(row)
    return rows


def state_of(row):
    keys = ["px", "py", "pz", "vx", "vy", "vz", "qw", "qx", "qy", "qz", "wx", "wy", "wz", "r0", "r1", "r2", "r3"]
    return np.array([float(row[k]) for k in keys] + [0.0])


def fly(model, rows, first, steps, method, rtol, atol):
    y = state_of(rows[first])
    t0, c0 = time.perf_counter(), time.process_time()
    for k in range(first, first + steps):
        cmd = tuple(float(rows[k]["cmd%d" % i]) for i in range(4))
        t = float(rows[k]["t_s"])
        sol = solve_ivp(model.rhs, (t, t + 0.01), y, method=method, rtol=rtol, atol=atol, args=(cmd,))
        if sol.status != 0:
            raise RuntimeError("solve_ivp failed at t=%.2f: %s" % (t, sol.message))
        y = sol.y[:, -1].copy()
        n = math.sqrt(float(np.dot(y[6:10], y[6:10])))
        if abs(n - 1.0) > 1e-9:
            y[6:10] /= n
    return y, time.perf_counter() - t0, time.process_time() - c0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("flight_csv")
    ap.add_argument("--airframe", default=os.path.join(here, "..", "..", "dynamics", "airframes", "iris.json"))
    ap.add_argument("--from-s", type=float, default=12.0, help="start of the replayed segment (airborne)")
    ap.add_argument("--duration-s", type=float, default=60.0)
    ap.add_argument("--methods", default="RK45,DOP853,LSODA")
    ap.add_argument("--rtol", type=float, default=RTOL,
                    help="relative tolerance (default CVODE's 1e-8; absolute ones scale with it)")
    ap.add_argument("--cpp-rtf", type=float, default=0.0, help="the C++ figure to compare with (wall)")
    ap.add_argument("--cpp-cpu-rtf", type=float, default=0.0, help="the C++ figure to compare with (CPU)")
    args = ap.parse_args()

    with open(args.airframe) as f:
        model = Model(json.load(f))
    rows = read_flight(args.flight_csv)
    first = int(round(args.from_s * 100))
    steps = int(round(args.duration_s * 100))
    if first + steps >= len(rows):
        sys.exit("scipy_model.py: %s holds %.1f s; need %.1f s (pass --csv-s to the benchmark)"
                 % (args.flight_csv, len(rows) / 100.0, args.from_s + args.duration_s))
    ref = state_of(rows[first + steps])
    print("SciPy %s solve_ivp on the same flight: %.0f s from t = %.0f s, commands held 10 ms each, "
          "rtol %g, the CVODE integrator's absolute tolerances x %g" % (
              __import__("scipy").__version__, args.duration_s, args.from_s, args.rtol, args.rtol / RTOL))
    print("%-8s %8s %10s %10s %22s %11s %11s" % ("method", "wall s", "xRT", "(CPU)", "final |dp| vs C++ (mm)",
                                                "C++/Python", "(CPU)"))
    for method in args.methods.split(","):
        y, wall, cpu = fly(model, rows, first, steps, method, args.rtol, ATOL * (args.rtol / RTOL))
        dp = float(np.linalg.norm(y[0:3] - ref[0:3])) * 1000.0
        rtf, cpu_rtf = args.duration_s / wall, args.duration_s / cpu
        ratio = ("%10.0fx" % (args.cpp_rtf / rtf)) if args.cpp_rtf > 0 else "%11s" % "-"
        cpu_ratio = ("%10.0fx" % (args.cpp_cpu_rtf / cpu_rtf)) if args.cpp_cpu_rtf > 0 else "%11s" % "-"
        print("%-8s %8.2f %9.1fx %9.1fx %22.3f %s %s" % (method, wall, rtf, cpu_rtf, dp, ratio, cpu_ratio))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
