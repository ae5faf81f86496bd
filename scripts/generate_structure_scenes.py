#!/usr/bin/env python3
"""Writes the structure scenes of issue 8 into samples/scenes/*.json, built exactly as
docs/scene-specifications.md specifies them: B2 card_house (mu 0.6 stands, 0.2 must collapse) and
B3 masonry_arch (mu 0.6 stands, 0.2 and 0.1 must collapse), one JSON per friction coefficient
(card_house_mu0_6.json, ...). Positions, orientations and hull vertices are computed in double
precision and written with repr() (exact round trip), so the designed contacts touch exactly.

Usage: python3 scripts/generate_structure_scenes.py [output_dir]   (default: samples/scenes)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from generate_contact_scenes import ground, rot_y, scene, write  # noqa: E402

# B2 card: box half extents (T/2, w/2, L/2) = (0.001, 0.1, 0.2), 0.01 kg, 25 degree lean.
CARD_T, CARD_W, CARD_L, CARD_M = 0.002, 0.2, 0.4, 0.01
PSI = math.radians(25.0)


def card(name, x, z, angle):
    half = [CARD_T / 2, CARD_W / 2, CARD_L / 2]
    inertia = [CARD_M / 3 * (half[1] ** 2 + half[2] ** 2), CARD_M / 3 * (half[0] ** 2 + half[2] ** 2),
               CARD_M / 3 * (half[0] ** 2 + half[1] ** 2)]
    return {"name": name, "position": [x, 0.0, z], "orientation": rot_y(angle), "mass": CARD_M,
            "inertia": inertia,
            "shapes": [{"type": "box", "half_extents": half, "material": "scene"}]}


def a_frame(prefix, x_apex, z_base):
    """docs/scene-specifications.md B2: two cards leaning on each other, each on its bottom inner edge."""
    dx = (CARD_L / 2) * math.sin(PSI) + (CARD_T / 2) * math.cos(PSI)
    z = z_base + (CARD_L / 2) * math.cos(PSI) + (CARD_T / 2) * math.sin(PSI)
    return [card(prefix + "_left", x_apex - dx, z, PSI), card(prefix + "_right", x_apex + dx, z, -PSI)]


def card_house(mu, tag):
    z_flat = CARD_L * math.cos(PSI) + CARD_T * math.sin(PSI)  # top outer edges of the low frames
    bodies = [ground()]
    bodies += a_frame("low1", -0.175, 0.0) + a_frame("low2", 0.175, 0.0)
    bodies.append(card("flat", 0.0, z_flat + CARD_T / 2, math.pi / 2))
    bodies += a_frame("top", 0.0, z_flat + CARD_T)
    verdict = "stands" if mu > 0.3292 else "must collapse"
    return scene(f"card_house_mu{tag}",
                 f"docs/scene-specifications.md B2 card_house mu={mu}: two A-frames, a flat card and a top frame of "
                 f"0.2 x 0.4 m cards leaning at 25 deg; {verdict} (static mu_min 0.3292).",
                 0.01, 10.0, mu, 0.0, bodies)


# B3 arch: 17 voussoirs, centre-line radius 1 m, t = 0.25 m, depth 0.5 m, 2000 kg/m^3.
ARCH_N, ARCH_A, ARCH_B, ARCH_D, ARCH_RHO = 17, 0.875, 1.125, 0.5, 2000.0
ARCH_O = (0.0, 0.5)  # centre (x, z)


def voussoir_properties():
    """Mass, COM radius r_c and principal inertia (x radial, y depth, z tangential) of one sector."""
    alpha = math.pi / (2 * ARCH_N)  # half angle
    a, b, d = ARCH_A, ARCH_B, ARCH_D
    area = alpha * (b * b - a * a)
    r_c = (2.0 / 3.0) * (b ** 3 - a ** 3) / (b * b - a * a) * math.sin(alpha) / alpha
    quartic = (b ** 4 - a ** 4) / 4.0
    s_tt = quartic * (alpha - math.sin(2 * alpha) / 2)  # int w^2 dA, w tangential
    s_rr = quartic * (alpha + math.sin(2 * alpha) / 2) - r_c * r_c * area  # int u^2 dA about COM
    mass = ARCH_RHO * d * area
    depth2 = area * d ** 3 / 12.0  # int y^2 dV / rho
    inertia = [ARCH_RHO * (d * s_tt + depth2), ARCH_RHO * d * (s_rr + s_tt),
               ARCH_RHO * (d * s_rr + depth2)]
    return mass, r_c, inertia, alpha


def voussoir(k):
    mass, r_c, inertia, alpha = voussoir_properties()
    phi_c = (k + 0.5) * math.pi / ARCH_N
    points = [[r * math.cos(beta) - r_c, y, r * math.sin(beta)]
              for r in (ARCH_A, ARCH_B) for beta in (-alpha, alpha) for y in (-ARCH_D / 2, ARCH_D / 2)]
    return {"name": f"voussoir{k}",
            "position": [ARCH_O[0] + r_c * math.cos(phi_c), 0.0, ARCH_O[1] + r_c * math.sin(phi_c)],
            "orientation": rot_y(-phi_c), "mass": mass, "inertia": inertia,
            "shapes": [{"type": "convex_hull", "points": points, "material": "scene"}]}


def masonry_arch(mu, tag):
    bodies = [ground()]
    for side, x in (("right", 1.0), ("left", -1.0)):
        bodies.append({"name": f"abutment_{side}", "type": "static", "position": [x, 0.0, 0.25],
                       "shapes": [{"type": "box", "half_extents": [0.375, 0.35, 0.25],
                                   "material": "scene"}]})
    bodies += [voussoir(k) for k in range(ARCH_N)]
    verdict = "stands" if mu > 0.3086 else "must collapse"
    return scene(f"masonry_arch_mu{tag}",
                 f"docs/scene-specifications.md B3 masonry_arch mu={mu}: 17 convex-hull voussoirs (R 1 m, t 0.25 m, "
                 f"46.2 kg each) on two abutments; {verdict} (thrust-line mu_min 0.3086).",
                 0.01, 10.0, mu, 0.0, bodies)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "samples", "scenes")
    documents = [card_house(0.6, "0_6"), card_house(0.2, "0_2"), masonry_arch(0.6, "0_6"),
                 masonry_arch(0.2, "0_2"), masonry_arch(0.1, "0_1")]
    for document in documents:
        write(directory, document)


if __name__ == "__main__":
    main()
