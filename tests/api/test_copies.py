"""Models and results copied and pickled with their shapes (issue 56).

`pickle.loads` of a model or a Result with collision shapes raised
"Shape.__new__() missing 6 required positional arguments", and
`copy.deepcopy(model)` the same: every `load_urdf(..., ground=)` model and
every contact run sent to another process (a process pool, a Dask worker)
was hit. Here every kind of shape (plane, sphere, capsule, box, cylinder,
an STL mesh; visual ones and frames too) travels with a copy, a deep copy
and a pickle; the copy simulates to the same numbers bit for bit, an
unpickled Result answers as the original, a mesh travels with its hull (the
copy reads no file), and a contact scene goes through a process pool."""

import copy
import os
import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import lagmb as mb
from builders import ARM_URDF

G = 9.81
CUBE = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
FACES = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
         (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]


def write_cube_stl(path):
    """A binary STL of the unit cube (12 triangles)."""
    with open(path, "wb") as f:
        f.write(b"lagmb test cube".ljust(80, b" ") + len(FACES).to_bytes(4, "little"))
        for face in FACES:
            f.write(np.zeros(3, "<f4").tobytes() + CUBE[list(face)].astype("<f4").tobytes() + b"\0\0")


def every_shape(stl):
    """Five bodies, each with a collision shape of its own kind (sphere,
    capsule, box, cylinder, the cube of `stl` scaled to 0.1 m), 1 mm above a
    floor (a plane) and dropped on it, a contact each; a visual box and a
    frame on one of them."""
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3, name="every shape")
    floor = m.add_shape("ground", "plane", (), role="collision")
    shapes = {"ball": ("sphere", (0.05,), 0.05), "pill": ("capsule", (0.03, 0.1), 0.03),
              "brick": ("box", (0.1, 0.1, 0.1), 0.05), "can": ("cylinder", (0.04, 0.1), 0.05),
              "gem": ("mesh", (0.1, 0.1, 0.1), 0.05)}
    for k, (name, (kind, size, half_height)) in enumerate(shapes.items()):
        centre = (0.3 * k, 0.0, half_height + 1e-3)
        m.add_body(name, mass=0.5, inertia=(1e-3, 1e-3, 1e-3), position=centre)
        shape = m.add_shape(name, kind, size, centre, mesh=str(stl) if kind == "mesh" else None, role="collision")
        m.add_contact(f"{name}_floor", shape, floor, stiffness=1e6, restitution=0.5, friction=0.5)
    m.add_shape("brick", "box", (0.12, 0.12, 0.12), (0.6, 0.0, 0.051))  # (visual)
    m.add_frame("brick_top", "brick", (0.6, 0.0, 0.101))
    return m


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    stl = tmp_path_factory.mktemp("mesh") / "cube.stl"
    write_cube_stl(stl)
    m = every_shape(stl)
    return m, mb.simulate(m, 0.1, n_out=11)


def same_model(a, b):
    assert a.to_text() == b.to_text()  # (every element, numbers to 17 digits)
    assert a.shapes == b.shapes and {s.kind for s in a.shapes} == {"plane", "sphere", "capsule", "box", "cylinder",
                                                                  "mesh"}
    assert a.frames.keys() == b.frames.keys() and a.name == b.name == "every shape"
    np.testing.assert_array_equal(b.frames["brick_top"].position, a.frames["brick_top"].position)


def test_a_model_with_every_kind_of_shape_copies_and_pickles_and_runs_the_same(scene):
    m, r = scene
    for other in (pickle.loads(pickle.dumps(m)), copy.deepcopy(m), copy.copy(m), m.copy()):
        same_model(m, other)
        again = mb.simulate(other, 0.1, n_out=11)
        assert np.array_equal(again.q, r.q) and np.array_equal(again.v, r.v)
        assert again.events == r.events
    # each shape alone too (a Shape and a Frame are tuples whose __new__ takes their fields)
    for shape in m.shapes:
        assert pickle.loads(pickle.dumps(shape)) == shape == copy.deepcopy(shape)
    frame = pickle.loads(pickle.dumps(m.frames["brick_top"]))
    assert frame.body == "brick" and np.array_equal(frame.rotation, m.frames["brick_top"].rotation)


def test_a_result_of_contacts_pickles_and_answers_as_the_original(scene):
    m, r = scene
    for other in (pickle.loads(pickle.dumps(r)), copy.deepcopy(r)):
        assert np.array_equal(other.q, r.q) and other.events == r.events
        same_model(r.model, other.model)
        for name in ("ball", "pill", "brick", "can", "gem"):
            mine, theirs = r.contact(f"{name}_floor"), other.contact(f"{name}_floor")
            assert np.array_equal(theirs.normal_force, mine.normal_force)
            assert list(theirs.state) == list(mine.state)
        # the bodies rest on the floor at the end: each contact carries its body's weight
        assert other.contact("brick_floor").normal_force[-1] == pytest.approx(0.5 * G, rel=1e-3)


def test_a_mesh_travels_with_its_hull_and_the_copy_reads_no_file(tmp_path):
    stl = tmp_path / "cube.stl"
    write_cube_stl(stl)
    m = every_shape(stl)
    text = pickle.dumps(m)
    os.remove(stl)
    other = pickle.loads(text)  # (its contact's hull from the pickle: no file to read)
    assert np.array_equal(mb.simulate(other, 0.05, n_out=3).q, mb.simulate(m, 0.05, n_out=3).q)


def test_a_robot_on_a_floor_pickles(tmp_path):
    """load_urdf(..., ground=z): a contact for each collision shape of the
    file (the arm's link a box here) with a floor at z."""
    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF.replace(
        "</inertial></link>", "</inertial><collision><origin xyz=\"0.5 0 0\"/><geometry><box size=\"1 0.1 0.1\"/>"
        "</geometry></collision></link>", 1))
    robot = mb.load_urdf(str(path), ground=-0.3)
    assert [kw["name"] for kind, kw in robot.elements if kind == "add_contact"]
    for other in (pickle.loads(pickle.dumps(robot)), copy.deepcopy(robot)):
        assert other.to_text() == robot.to_text() and other.shapes == robot.shapes
        assert np.array_equal(mb.simulate(other, 0.2, n_out=5).q, mb.simulate(robot, 0.2, n_out=5).q)


def test_a_contact_scene_runs_in_a_process_pool(scene):
    """The model is pickled to the worker and its Result back."""
    m, r = scene
    with ProcessPoolExecutor(max_workers=1) as pool:
        there = pool.submit(mb.simulate, m, 0.1, n_out=11).result(timeout=300)
    assert np.array_equal(there.q, r.q) and there.events == r.events
    assert np.array_equal(there.contact("gem_floor").normal_force, r.contact("gem_floor").normal_force)
