"""A cube sliding down a terrain with a rounded break (issue 34's check): a 25 deg slope
joined to a flat run-out by a circular arc of radius Rb, tangent at both ends, mu = 0.2 to
the terrain (fix wall/lsdem terrain, penalty and impulse mode).

Independent expectation: this script's own RK4 integration of the slide along the path of
the cube's centroid (arc length s, speed v = s'). For a point mass (HALF = 0) it is
s'' = g (sin theta(s) - mu cos theta(s)) - mu kappa(s) v^2, the normal force
m (g cos theta + kappa v^2) on the concave arc. The cube (half side a = HALF) differs:

  - its centroid runs a above the terrain: it drops a (1 - cos 25 deg) = 0.047 less than
    the contact point, which costs a (1 - cos theta) / mu = 0.23 of run-out on every radius;
    with the arc's terms below the ODE's cube stops 0.34, 0.26, 0.23 short of the point
    mass at Rb = 4, 8, 16 (2.5-3.8 % of the travel);
  - on the arc its bottom face is a chord touching the arc at two edges, at angles
    +-alpha (sin alpha = a / Rb) from the centroid's radius r_c = sqrt(Rb^2 - a^2) - a,
    and it turns about the arc's centre: (1 + k^2 / r_c^2) v' = g sin phi
    - mu (Rb / r_c) (g cos phi + v^2 / r_c) / cos alpha, k^2 = 2 a^2 / 3 (the cube's
    rotational inertia; its spin-up on entering the arc and spin-down on leaving it are
    taken as instant and lossless), Rb / r_c because the edges slide Rb / r_c times as far
    as the centroid moves; with a = 0 this is the point mass's equation.

The cube released from rest with its bottom face's centre at height HS above the run-out
stops where this ODE says within 2 % of the travel, and its H/L agrees within 2 %, for
Rb = 4, 8 and 16 cube sides, in penalty mode (pair_style zero, fix nve/lsdem, as
test_wall_lsdem_band; measured +0.63, +0.17, +0.02 % of the travel) and in impulse mode
(fix impulse/lsdem, e = 0, at 4 times the penalty step; +0.32, +0.06, -0.00 %). The ODE's
model needs the arc longer than the cube: at Rb = 2 sides (arc 0.87, side 1) the cube
runs 2.3 % (penalty) and 1.5 % (impulse) farther than it says. In both modes and in the
ODE H/L falls towards mu = 0.2 as Rb grows (0.2259, 0.2214, 0.2156 by the ODE; the
centripetal friction mu kappa v^2 is spread over a flatter arc, whose lower end the cube
reaches slower). The point mass's own stop (a = 0) is printed beside: H/L 0.2176, 0.2152,
0.2104. About 9 s on one core."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, write_data, quat_axis_angle, GRAIN1, THERMO_FULL
from impulse_decks import header as impulse_header
from terrain_decks import HALF, G, cube_library, terrain_band, slide

THETA = math.radians(25.0)
MU = 0.2
HS = 2.0                       # release height of the bottom face's centre above the run-out
RADII = (4.0, 8.0, 16.0)       # break radii: 4, 8, 16 cube sides


def profile(rb):
    """The terrain's height z(x): flat (z = 0) for x <= 0, the arc of radius rb centred at
    (0, rb) for 0 <= x <= rb sin(theta), the 25 deg slope beyond (downhill is -x)."""
    xa = rb * math.sin(THETA)
    za = rb * (1.0 - math.cos(THETA))

    def z(x, y=0.0):
        if x <= 0.0:
            return 0.0
        if x <= xa:
            return rb - math.sqrt(rb * rb - x * x)
        return za + (x - xa) * math.tan(THETA)
    return z


def start_x(rb):
    """The release point's x on the slope, at height HS."""
    return rb * math.sin(THETA) + (HS - rb * (1.0 - math.cos(THETA))) / math.tan(THETA)


def slide_ode(rb, a, dt=2e-4):
    """The stop position x (of the centroid, = the contact point's on the flat) and time of a
    slider of half side a (0: a point mass on the profile) released at HS; RK4 in time."""
    if a > 0.0:
        rc = math.sqrt(rb * rb - a * a) - a           # the centroid's radius on the arc
        cos_alpha = math.sqrt(rb * rb - a * a) / rb
        spin = 1.0 + (2.0 / 3.0) * a * a / (rc * rc)  # 1 + k^2 / r_c^2
    else:
        rc, cos_alpha, spin = rb, 1.0, 1.0
    s1 = (HS - rb * (1.0 - math.cos(THETA))) / math.sin(THETA)   # the slope's length
    s2 = s1 + rc * THETA                                          # the flat starts

    def f(s, v):
        if s < s1:
            return v, G * (math.sin(THETA) - MU * math.cos(THETA))
        phi = THETA - (s - s1) / rc
        return v, (G * math.sin(phi)
                   - MU * (rb / rc) * (G * math.cos(phi) + v * v / rc) / cos_alpha) / spin

    s = v = t = 0.0
    on_arc = False
    while s < s2:
        if not on_arc and s >= s1:                    # spin-up: the kinetic energy shared
            on_arc = True
            v /= math.sqrt(spin)
        k1 = f(s, v)
        k2 = f(s + dt / 2 * k1[0], v + dt / 2 * k1[1])
        k3 = f(s + dt / 2 * k2[0], v + dt / 2 * k2[1])
        k4 = f(s + dt * k3[0], v + dt * k3[1])
        s += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += dt
        if v <= 0.0:
            raise RuntimeError("the slider stops before the flat")
    v *= math.sqrt(spin)                              # spin-down onto the flat
    # on the flat (entered within one step: s - s2 < v dt) it decelerates at mu g
    return -(s - s2 + v * v / (2 * MU * G)), t + v / (MU * G)


def slide_impulse(name, band, x_start, t_end, box, dt=2e-3, every=250):
    """The cube of slide() released at the same pose, in impulse mode (fix impulse/lsdem,
    e = 0, the wall's mu): thermo rows."""
    lib = cube_library()
    th = THETA
    n = (-math.sin(th), 0.0, math.cos(th))
    base = (x_start, 0.0, HS)
    x = tuple(b + (HALF + 1e-4) * c for b, c in zip(base, n))
    write_data(name + ".data", box, [Grain(x, q=quat_axis_angle((0, 1, 0), -th))])
    deck = (impulse_header(lib, name + ".data")
            + "fix w all wall/lsdem terrain %s 1.0e4 0 %r\n" % (band, MU)
            + "fix grav all gravity %r vector 0 0 -1\n" % G
            + "fix imp all impulse/lsdem 0.0 %r\n" % MU + GRAIN1
            + "thermo_style custom step time v_px v_py v_pz v_vx v_vz\n" + THERMO_FULL
            + "thermo %d\ntimestep %r\nrun %d\n" % (every, dt, int(round(t_end / dt))))
    rc, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


def stop(tag, rows, x0, x_ode, hl_ode):
    """The cube's stop against the ODE's; its H/L, or None."""
    if not check(len(rows) > 10, "%s: no thermo output" % tag):
        return None
    end = rows[-1]
    moving = math.hypot(end["v_vx"], end["v_vz"])
    check(moving < 1e-3, "%s: the cube still moves at %g at t = %g" % (tag, moving, end["Time"]))
    x_sim = end["v_px"]                    # on the flat the centroid is above the contact
    check(abs(end["v_pz"] - HALF) < 0.01, "%s: the cube ends at z %g, not on the flat"
          % (tag, end["v_pz"]))
    hl_sim = HS / (x0 - x_sim)
    print("%-16s stop x: cube %.4f, ODE %.4f (travel %.4f: %+.2f %%); H/L cube %.4f, ODE %.4f "
          "(%+.2f %%)" % (tag + ":", x_sim, x_ode, x0 - x_ode,
                          100 * ((x0 - x_sim) / (x0 - x_ode) - 1), hl_sim, hl_ode,
                          100 * (hl_sim / hl_ode - 1)))
    near(x0 - x_sim, x0 - x_ode, rtol=0.02, msg="%s: horizontal travel" % tag)
    near(hl_sim, hl_ode, rtol=0.02, msg="%s: H/L" % tag)
    return hl_sim


results = {"ODE": [], "penalty": [], "impulse": []}
for rb in RADII:
    x0 = start_x(rb)
    x_ode, t_ode = slide_ode(rb, HALF)
    hl_ode = HS / (x0 - x_ode)
    x_pm, t_pm = slide_ode(rb, 0.0)
    print("Rb %g: point mass (a = 0) stops at x %.4f, H/L %.4f; the cube's ODE at %.4f, H/L "
          "%.4f" % (rb, x_pm, HS / (x0 - x_pm), x_ode, hl_ode))
    results["ODE"].append(hl_ode)
    name = "break%g" % rb
    band = terrain_band(name, profile(rb), x0=x_ode - 3.0, x1=x0 + 3.0, y0=-2.0, y1=2.0,
                        cell=0.1)
    box = (x_ode - 6.0, x0 + 6.0, -4, 4, -3, HS + 4.0)
    rows = slide(name, "terrain " + band, 25.0, MU, t_ode + 1.0, x0, every=500,
                 z_start=HS, box=box)
    results["penalty"].append(stop("Rb %g penalty" % rb, rows, x0, x_ode, hl_ode))
    rows = slide_impulse(name + "_impulse", band, x0, t_ode + 1.0, box)
    results["impulse"].append(stop("Rb %g impulse" % rb, rows, x0, x_ode, hl_ode))

for tag, hls in results.items():
    if check(None not in hls, "%s: not every radius ran" % tag):
        check(all(a > b > MU for a, b in zip(hls, hls[1:])), "%s: H/L %s at Rb %s does not "
              "fall towards mu = %g" % (tag, hls, RADII, MU))

finish()
