"""A cube sliding down a terrain with a rounded break (issue 34's check): a 25 deg slope
joined to a flat run-out by a circular arc of radius Rb, tangent at both ends, mu = 0.2 to
the terrain (fix wall/lsdem terrain, penalty mode).

Independent expectation: this script's own RK4 integration of the slide along the path of
the cube's centroid (arc length s, speed v = s'). For a point mass (HALF = 0) it is
s'' = g (sin theta(s) - mu cos theta(s)) - mu kappa(s) v^2, the normal force
m (g cos theta + kappa v^2) on the concave arc. The cube (half side a = HALF) differs:

  - its centroid runs a above the terrain: it drops a (1 - cos 25 deg) = 0.047 less than
    the contact point, which costs a (1 - cos theta) / mu = 0.23 of run-out on every radius
    (3.5-4 % of the travel: the cube stops short of the point mass by about that);
  - on the arc its bottom face is a chord touching the arc at two edges, at angles
    +-alpha (sin alpha = a / Rb) from the centroid's radius r_c = sqrt(Rb^2 - a^2) - a,
    and it turns about the arc's centre: (1 + k^2 / r_c^2) v' = g sin phi
    - mu (Rb / r_c) (g cos phi + v^2 / r_c) / cos alpha, k^2 = 2 a^2 / 3 (the cube's
    rotational inertia; its spin-up on entering the arc and spin-down on leaving it are
    taken as instant and lossless), Rb / r_c because the edges slide Rb / r_c times as far
    as the centroid moves; with a = 0 this is the point mass's equation.

The cube released from rest with its bottom face's centre at height HS above the run-out
stops where this ODE says within 2 % of the travel, and its H/L agrees within 2 %, for
Rb = 4, 8 and 16 cube sides (the ODE's model needs the arc longer than the cube: at
Rb = 2 sides, arc 0.87 < side 1, the cube runs 2.6 % farther than it says); both H/L fall
towards mu = 0.2 as Rb grows (the centripetal friction mu kappa v^2 is spread over a
flatter arc). The point mass's own stop (a = 0) is printed beside."""
import math
import os

from lsdemtest import check, near, finish
from terrain_decks import HALF, G, terrain_band, slide

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


results = []
for rb in RADII:
    x0 = start_x(rb)
    x_ode, t_ode = slide_ode(rb, HALF)
    hl_ode = HS / (x0 - x_ode)
    x_pm, t_pm = slide_ode(rb, 0.0)
    name = "break%g" % rb
    band = terrain_band(name, profile(rb), x0=x_ode - 3.0, x1=x0 + 3.0, y0=-2.0, y1=2.0,
                        cell=0.1)
    rows = slide(name, "terrain " + band, 25.0, MU, t_ode + 1.0, x0, every=500,
                 z_start=HS, box=(x_ode - 6.0, x0 + 6.0, -4, 4, -3, HS + 4.0))
    if not check(len(rows) > 10, "Rb %g: no thermo output" % rb):
        continue
    end = rows[-1]
    moving = math.hypot(end["v_vx"], end["v_vz"])
    check(moving < 1e-3, "Rb %g: the cube still moves at %g at t = %g" % (rb, moving, end["Time"]))
    x_sim = end["v_px"]                    # on the flat the centroid is above the contact
    check(abs(end["v_pz"] - HALF) < 0.01, "Rb %g: the cube ends at z %g, not on the flat"
          % (rb, end["v_pz"]))
    hl_sim = HS / (x0 - x_sim)
    print("Rb %4g: stop x: cube %.4f, ODE %.4f (travel %.4f: %+.2f %%); H/L cube %.4f, ODE %.4f "
          "(%+.2f %%); point mass (a = 0): stop x %.4f, H/L %.4f" % (
              rb, x_sim, x_ode, x0 - x_ode, 100 * ((x0 - x_sim) / (x0 - x_ode) - 1), hl_sim,
              hl_ode, 100 * (hl_sim / hl_ode - 1), x_pm, HS / (x0 - x_pm)))
    near(x0 - x_sim, x0 - x_ode, rtol=0.02, msg="Rb %g: horizontal travel" % rb)
    near(hl_sim, hl_ode, rtol=0.02, msg="Rb %g: H/L" % rb)
    results.append((rb, hl_sim, hl_ode))

if check(len(results) == len(RADII), "not every radius ran"):
    for (ra, sa, oa), (rb, sb, ob) in zip(results, results[1:]):
        check(oa > ob > MU, "ODE: H/L %.4f at Rb %g, %.4f at Rb %g: not falling towards "
              "mu" % (oa, ra, ob, rb))
        check(sa > sb > MU, "cube: H/L %.4f at Rb %g, %.4f at Rb %g: not falling towards mu"
              % (sa, ra, sb, rb))

finish()
