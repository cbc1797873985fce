"""The joints' values in the configuration load_urdf builds: the positions
given, the limits' middles, and the chains of mimics (which joint follows
which, and where its leader puts it).
"""

import warnings

from .. import _checks
from .._model_files import LARGEST
from .reader import MOVING, UrdfError, UrdfWarning, checked_argument


def mimics_of(followers):
    """{leader: [the joints whose chains of mimics end at it]}."""
    out = {}
    for name, (leader, _) in chain_leaders(followers).items():
        out.setdefault(leader, []).append(name)
    return out


def chain_leaders(followers):
    """{follower: (the joint its chain of mimics ends at, the product of the
    multipliers along it)}, each chain walked once (linear in the number of
    followers, where walking each follower's chain would be quadratic)."""
    out = {}
    for name in followers:
        path, at = [], name
        while at in followers and at not in out:
            path.append(at)
            at = followers[at]["joint"]
        leader, factor = out.get(at, (at, 1.0))
        for joint in reversed(path):  # (nearest the leader first)
            factor *= followers[joint]["multiplier"]
            out[joint] = (leader, factor)
    return out


def leader_of(followers, name):
    """The joint a chain of mimics from `name` ends at."""
    while name in followers:
        name = followers[name]["joint"]
    return name


def checked_positions(reader, joints, positions):
    """{URDF joint: finite value} of the argument `positions`, each naming
    a joint with one coordinate."""
    out = {}
    for name, value in positions.items():
        joint = joints.get(name) if isinstance(name, str) else None
        if joint is not None and joint.get("moves_as"):
            raise UrdfError(f"{reader.path}: positions: joint '{name}' is locked at {joint['locked']!r} by its equal "
                            "limits (load with limits=False to move it)")
        if joint is None or joint["type"] not in MOVING:
            movable = [j["name"] for j in joints.values() if j["type"] in MOVING]
            raise UrdfError(f"{reader.path}: positions: {_checks.show(name)} is not a revolute, continuous or "
                            f"prismatic joint of the file (those are: {', '.join(movable)})")
        out[name] = checked_argument(_checks.real, value, f"{reader.path}: positions: joint '{name}'")
        if abs(out[name]) > LARGEST:
            raise UrdfError(f"{reader.path}: positions: joint '{name}' = {out[name]:g} is beyond what a model can "
                            f"hold (at most {LARGEST:g})")
    return out


def mimic_followers(reader, joints):
    """{joint: its <mimic>} for the joints that mimic another: both must
    have a coordinate (revolute, continuous, prismatic). A mimic of a joint
    the file does not have is left out with one UrdfWarning naming each
    (the joint moves freely), or with strict refused. A fixed joint's
    <mimic> couples nothing (it has no coordinate) and is passed over
    (Talos's gripper has such elements); a joint locked by its limits
    cannot mimic nor be mimicked."""
    out, unknown = {}, []
    for joint in joints.values():
        m = joint["mimic"]
        owner = f"joint '{joint['name']}'"
        if m is None or (joint["type"] == "fixed" and not joint.get("moves_as")):
            continue
        if joint.get("moves_as"):
            reader.fail(m["element"], f"is locked at {joint['locked']!r} by its equal limits and mimics "
                        f"'{m['joint']}' (load with limits=False or mimic=False)", owner)
        if joint["type"] not in MOVING:
            reader.fail(m["element"], f"a {joint['type']} joint cannot mimic (only revolute, continuous and "
                        "prismatic joints have one coordinate)", owner)
        leader = joints.get(m["joint"])
        if leader is None:
            if reader.strict:
                reader.fail(m["element"], f"mimics '{m['joint']}', which is not a joint of the file (load with "
                            "strict=False to read it as a joint of its own)", owner)
            unknown.append(f"{owner}, line {m['element'].line}: mimics '{m['joint']}'")
            continue
        if leader.get("moves_as"):
            reader.fail(m["element"], f"mimics '{m['joint']}', which is locked at {leader['locked']!r} by its equal "
                        "limits (load with limits=False or mimic=False)", owner)
        if leader["type"] not in MOVING:
            reader.fail(m["element"], f"mimics '{m['joint']}', a {leader['type']} joint (a leader must be revolute, "
                        "continuous or prismatic)", owner)
        if leader["name"] == joint["name"]:
            reader.fail(m["element"], "mimics itself", owner)
        out[joint["name"]] = m
    done = set()  # followers known to lead, through their leaders, to a joint that mimics none
    for name in out:  # a cycle of mimics has no leader (each follower walked once: linear)
        path, on_path, at = [], set(), name
        while at in out and at not in done:
            if at in on_path:
                cycle = path[path.index(at):] + [at]
                shown = cycle if len(cycle) <= 12 else cycle[:6] + ["..."] + cycle[-3:]
                size = f" of {len(cycle) - 1} joints" if len(cycle) > 12 else ""
                reader.fail(out[at]["element"], f"mimics in a cycle{size} ({' -> '.join(shown)})", f"joint '{at}'")
            path.append(at)
            on_path.add(at)
            at = out[at]["joint"]
        done.update(path)
    if unknown:
        warnings.warn(UrdfWarning(
            f"{reader.path}: {len(unknown)} mimic{'s' if len(unknown) > 1 else ''} of a joint the file does not "
            f"have, each joint read as a joint of its own that moves freely (not coupled; strict=True refuses "
            f"such a mimic): {'; '.join(unknown)}"), stacklevel=4)  # (load_urdf's caller)
    return out


def joint_values(reader, joints, positions, followers, limits):
    """Each joint's angle or slide in the configuration the model is built
    in: `positions`; where not given 0, or with `limits` the middle of the
    joint's limits if 0 lies outside them (the Panda's fourth joint), or
    where equal limits lock it; a mimic's multiplier x + offset of its
    leader's value (a chain of mimics followed without recursion)."""
    def own(name):
        joint = joints[name]
        if name in positions:
            return positions[name]
        if joint.get("moves_as"):
            return joint["locked"]
        limit = joint["limit"]
        if limits and limit is not None and not limit[0] <= 0.0 <= limit[1]:
            return 0.5 * (limit[0] + limit[1])
        return 0.0

    value = {}
    for name in joints:
        chain, at = [], name
        while at not in value and at in followers:
            chain.append(at)
            at = followers[at]["joint"]
        if at not in value:
            value[at] = own(at)
        for follower in reversed(chain):
            m = followers[follower]
            x = m["multiplier"] * value[m["joint"]] + m["offset"]  # (floats: inf past a double, no error)
            if not abs(x) <= LARGEST:
                reader.fail(m["element"], f"puts it at {x:g} (multiplier x the value {value[m['joint']]:g} of "
                            f"'{m['joint']}' + offset): beyond what a model can hold (at most {LARGEST:g})",
                            f"joint '{follower}'")
            value[follower] = x
    for name, joint in joints.items():  # (a locked joint's value is its limits', not bounded by the reader)
        if joint.get("moves_as") and abs(value[name]) > LARGEST:
            reader.fail(joint["elements"]["limit"], f"locks the joint at {value[name]:g}: beyond what a model can "
                        f"hold (at most {LARGEST:g})", f"joint '{name}'")
    return value
