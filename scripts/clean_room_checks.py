"""What scripts/clean-room.sh checks inside the bare Debian root, with the
wheel installed there offline and no compiler, SUNDIALS, SuiteSparse or
BLAS on the system:

1. the seed pendulum under every method lagmb lists, against its closed
   form (energy: thetadot^2 = 3 g sin(theta) / L for a rod pinned at one end);
2. a redundant joint (a parallelogram's third link) found and run;
3. a static equilibrium (a mass on a spring: x = m g / k);
4. every shared object the process has mapped comes from the wheel (lagmb's
   own folder), the interpreter or the C/C++ runtime.

Prints one line per check and exits 1 on the first failure.
Usage: python clean_room_checks.py
"""

import math
import os
import sys
import warnings

import lagmb as mb

G = 9.81


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what, flush=True)
    if not ok:
        sys.exit(1)


def seed_pendulum():
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m


package = os.path.dirname(os.path.abspath(mb.__file__))
check(package.startswith(sys.prefix), f"lagmb {mb.__version__} imported from the installed wheel ({package})")

for method in mb.methods():
    name = method["name"]
    options = {"step": 1e-4} if method["fixed_step"] else {"rtol": 1e-8, "atol": 1e-10}
    if method["baumgarte"] and name != "index1":
        options["baumgarte"] = (10.0, 10.0)
    r = mb.simulate(seed_pendulum(), t_end=0.5, n_out=51, method=name, **options)
    theta = -r.body("rod").angle[-1]  # below the horizontal
    omega = r.body("rod").angular_velocity[-1]
    error = abs(omega**2 - 3.0 * G * math.sin(theta)) / (3.0 * G)
    check(abs(r.t[-1] - 0.5) < 1e-12 and error < 1e-4, f"seed pendulum, {name}: thetadot^2 within {error:.1e} of 3 g sin(theta) / L")

# a parallelogram: the coupler's second pin repeats what the first and the
# cranks already impose (one dependent row), found and dropped
m = mb.Model(gravity=(0.0, -G))
left = m.add_body("left", mass=1.0, inertia=0.1, position=(0.0, -0.5), angle=-math.pi / 2)
right = m.add_body("right", mass=1.0, inertia=0.1, position=(1.0, -0.5), angle=-math.pi / 2)
bar = m.add_body("bar", mass=1.0, inertia=0.1, position=(0.5, -1.0))
mid = m.add_body("mid", mass=1.0, inertia=0.1, position=(2.0, -0.5), angle=-math.pi / 2)
m.add_revolute("a", m.ground, left, at=(0.0, 0.0))
m.add_revolute("b", m.ground, right, at=(1.0, 0.0))
m.add_revolute("c", m.ground, mid, at=(2.0, 0.0))
m.add_revolute("d", left, bar, at=(0.0, -1.0))
m.add_revolute("e", right, bar, at=(1.0, -1.0))
m.add_revolute("f", mid, bar, at=(2.0, -1.0))
with warnings.catch_warnings(record=True):
    warnings.simplefilter("always")
    rank = m.rank()
    r = mb.simulate(m, t_end=0.2, rtol=1e-8, atol=1e-10, n_out=11)
check(len(rank["dependent_rows"]) == 1 and rank["degrees_of_freedom"] == 1
      and abs(r.t[-1] - 0.2) < 1e-12,
      f"redundant parallelogram: {rank['dependent_rows']} dependent, {rank['degrees_of_freedom']} degree of freedom, run")

m = mb.Model(gravity=(0.0, -G))
mass = m.add_body("mass", mass=2.0, inertia=0.1, position=(0.0, -1.0))
m.add_translational("slide", m.ground, mass, at=(0.0, 0.0), axis=(0.0, 1.0))
m.add_spring_damper("spring", m.ground, (0.0, 1.0), mass, (0.0, -1.0), stiffness=100.0, free_length=1.5)
y = mb.equilibrium(m).body("mass").position[1]
check(abs(y - (1.0 - 1.5 - 2.0 * G / 100.0)) < 1e-9,
      f"equilibrium of a mass on a spring: y = {y:.9f} m (m g / k below the rest length)")

mapped = set()
with open("/proc/self/maps") as f:
    for line in f:
        path = line.split()[-1]
        if ".so" in os.path.basename(path):
            mapped.add(path)
foreign = []
for path in sorted(mapped):
    base = os.path.basename(path)
    if path.startswith(package + os.sep):
        continue  # the wheel's own (liblagmb.so, _core)
    if path.startswith((sys.prefix, sys.base_prefix, "/usr/lib/python3", "/usr/local/lib/python3")):
        continue  # the interpreter's extension modules and what pip installed (numpy)
    if base.startswith(("libc.so", "libm.so", "libstdc++.so", "libgcc_s.so", "ld-linux", "libpthread", "libdl.",
                        "librt.", "libz.so", "libexpat.so", "libffi.so", "liblzma.so", "libbz2.so", "libcrypto.so",
                        "libssl.so", "libuuid.so", "libmpdec.so", "libsqlite3.so", "libtinfo.so", "libncursesw.so",
                        "libreadline.so")):
        continue  # the C/C++ runtime and the interpreter's own libraries
    foreign.append(path)
lagmb_libs = sorted(p for p in mapped if p.startswith(package + os.sep))
check(not foreign, f"{len(mapped)} shared objects mapped, lagmb's: {[os.path.basename(p) for p in lagmb_libs]}; "
                   f"from elsewhere: {foreign or 'none'}")
